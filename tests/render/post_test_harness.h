#pragma once
/// @file post_test_harness.h
/// Test-only: runs a post chain (render/post_chain.h) on small synthetic float images and reads
/// the result back, so each effect's defining property can be checked on known inputs
/// (test_render_post_effects, test_render_post_grading, test_render_display_transform). Needs a current GL 4.5 context.

#include "core/image.h"
#include "core/post_chain.h"
#include "render/post_chain.h"

#include <glm/mat4x4.hpp>
#include <string>

namespace velvet::test {

/// Synthetic inputs: small float images, row 0 at the top (core/image.h).
struct PostTestInput {
    Image color;   ///< RGBA (or RGB) scene-linear
    Image depth;   ///< 1 channel hardware depth in [0, 1]; empty: everything at depth 1
    Image normals; ///< 3 channels world normals; empty: +Z
    glm::mat4 viewProj{1.0f}, prevViewProj{1.0f}, proj{1.0f};
    float time = 0.0f;
    /// The display encoding after built-in tone curves (null: the hand-written sRGB fallback).
    const render::DisplayEncoding* encoding = nullptr;
};

/// Uploads @p input (depth and octahedral normals at their G-buffer units), runs @p chain through
/// @p post and reads back RGBA float (row 0 at the top): display-encoded when the chain tone
/// maps, scene-linear otherwise. Saves and restores the framebuffer binding and viewport.
bool applyPostChain(render::PostChainRenderer& post, const PostChain& chain,
                    const PostTestInput& input, Image& output, std::string* error);

} // namespace velvet::test
