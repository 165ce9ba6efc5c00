#pragma once
/// @file graph_preview.h
/// Live thumbnails of material-graph nodes, rendered by the GPU through the graph compiler
/// (core/graph/graph_compiler.h, compileGraphPreview): the nodes feeding one output are compiled
/// into a full-screen fragment program that evaluates that output over UV in [0, 1]^2, drawn into
/// a small RGBA8 target and read back. So a thumbnail shows exactly what the G-buffer pass
/// computes — UV transforms, atlas rectangles, noise — with no second implementation on the CPU.
///
/// Display encoding (as the editor's image thumbnails): colour outputs are scene-linear and are
/// sRGB-encoded (IEC 61966-2-1) and clamped to [0, 1]; data (floats, vectors, normals as
/// n * 0.5 + 0.5, and the colour of a texture node sampled "Raw") is shown as is, clamped.
///
/// Programs are cached by their generated GLSL text, which depends only on the structure upstream
/// of the previewed node: a value edit re-uses the program and only uploads the value block.
/// Texture nodes' images come from the renderer's TextureCache and are uploaded as the renderer
/// uploads graph textures (RGBA16F, mipmapped, repeat), re-uploaded when the cache reloads them.

#include "core/diagnostics.h"
#include "core/graph/graph.h"
#include "core/image.h"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace velvet {
class TextureCache;
}

namespace velvet::render {

/// One thumbnail to render: output @ref output of node @ref node.
struct PreviewRequest {
    graph::NodeId node = graph::kInvalidNodeId;
    graph::PortIndex output = 0;
};

/// Renders node thumbnails. Needs one GL 4.5 context current for its whole life (construction,
/// every render(), destruction), the context whose TextureCache is passed in.
class GraphPreview {
public:
    /// Thumbnails of @p side x @p side pixels (1..512).
    explicit GraphPreview(int side = 64);
    ~GraphPreview();
    GraphPreview(const GraphPreview&) = delete;
    GraphPreview& operator=(const GraphPreview&) = delete;

    /// Renders each of @p requests from @p graph. Result i is the thumbnail of request i: RGBA
    /// float holding the 8-bit display values (byte / 255), row y showing v = (y + 0.5) / side
    /// (so an image texture appears as its file, first row on top), or an empty Image when the
    /// request could not be rendered (its reason is added to @p problems). @p textures loads
    /// texture nodes' files (null: they sample opaque white, as an unset file does in the
    /// renderer). Restores the draw framebuffer and viewport it found.
    std::vector<Image> render(const graph::Graph& graph, std::span<const PreviewRequest> requests,
                              TextureCache* textures, Problems* problems = nullptr);

    int side() const;
    /// Programs compiled since construction (tests: a value edit adds none).
    int compileCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet::render
