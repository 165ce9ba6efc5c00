#pragma once
/// @file graph_texture.h
/// Render-private: how a material-graph texture node's image becomes a GL texture, shared by the
/// G-buffer pass (renderer.cpp) and node thumbnails (graph_preview.cpp) so both sample the same.

#include "core/graph/graph_compiler.h"
#include "core/image.h"

namespace velvet::render {

/// The binding points of generated graph code, for the G-buffer pass and thumbnails alike: the
/// value block (VelvetGraphValues) on UBO 2 (0 is the frame, 3 the IBL block, 7 the post-effect
/// frame) and the texture nodes from unit binding::kMaterialTexFirst + kTextureSlotCount, above
/// the material slots, so the graph never rebinds a unit another pass relies on.
graph::CompileOptions graphCompileOptions();

/// Uploads @p image (scene-linear RGBA, row 0 first, so row 0 lies at t = 0) into @p texture:
/// RGBA16F with a full mip chain, trilinear, repeat wrap. (Re)creates the texture when it is 0 or
/// its size (@p width, @p height, updated) differs. Needs a current context.
void uploadGraphTexture(const Image& image, unsigned& texture, int& width, int& height);

/// A 1x1 opaque white RGBA16F texture: what a texture node samples while its file is unset or
/// broken. The caller owns it.
unsigned createGraphFallbackTexture();

} // namespace velvet::render
