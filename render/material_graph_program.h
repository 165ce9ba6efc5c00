#pragma once
/// @file material_graph_program.h
/// Render-private: the G-buffer program with the scene material's graph compiled into it as the
/// generated include "material_graph.glsl" (core/graph/graph_compiler.h), and that graph's
/// lifecycle (render/renderer.h, "Material graph"): its value block (kGraphValuesUbo), its
/// texture nodes' textures, and a structural edit being built on the driver's threads while the
/// old program, with the old graph's values and textures, goes on drawing.

#include "core/diagnostics.h"
#include "core/graph/graph_compiler.h"
#include "core/material.h"
#include "render/lobe_channels.h"
#include "render/shader_program.h"

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace velvet {
class TextureCache;
} // namespace velvet

namespace velvet::render {

struct GpuMaterial;

/// What a G-buffer program can be specialised to (issue 16): the record's texture slots, atlas
/// slots and lobe-channel map (GpuMaterial::terms2.y, .z, .w), all fixed by the material's
/// structure (which slots hold a texture, what the graph writes), never by a value. Compiled in,
/// the slots the material leaves empty cost nothing and the lobe channels are written at constant
/// indices (llvmpipe runs both sides of every branch and indexes local arrays slowly).
struct GeometryFeatures {
    int textureSlots = 0, atlasSlots = 0, lobeMap = -1, iorEntry = kLobePerMaterial;
    /// Whether the mesh carries its visibility from itself (GpuMesh::hasVisibility): without,
    /// the specular occlusion's code is compiled out.
    bool meshVisibility = false;
    static GeometryFeatures of(const GpuMaterial& record, bool meshVisibility);
    /// gbuffer.frag's defines (FIXED_TEXTURE_SLOTS, FIXED_ATLAS_SLOTS, FIXED_LOBE_MAP,
    /// FIXED_IOR_ENTRY, FIXED_MESH_VISIBILITY).
    std::vector<std::string> defines() const;
    auto operator<=>(const GeometryFeatures&) const = default;
};

class MaterialGraphProgram {
public:
    MaterialGraphProgram() = default;
    /// Needs the renderer's context current (frees the value block and the textures).
    ~MaterialGraphProgram();
    MaterialGraphProgram(const MaterialGraphProgram&) = delete;
    MaterialGraphProgram& operator=(const MaterialGraphProgram&) = delete;

    /// Compiles @p material's graph to GLSL as the interface the first build() links (a graph
    /// that cannot compile, e.g. too many texture nodes, starts with the empty graph and sets
    /// error()). No GL.
    void start(const Material& material);
    /// Builds the G-buffer program from disk with the linked graph; false + message (the last
    /// good program is kept). A structure in flight is abandoned (it restarts next frame).
    bool build(std::string* error);

    /// Takes @p material's graph: a value or texture edit updates the block and the bindings now;
    /// a structural edit (different shader text) is built at the next buildPending(). A graph
    /// that fails to compile is reported to @p problems and the previous one kept.
    void setGraph(const Material& material, TextureCache& cache, Problems* problems);
    /// Starts the G-buffer program for a pending structure, and adopts it once the driver has
    /// finished (polled each frame; with @p wait, now). Until then the old program draws with
    /// the old interface. A failure keeps the old program and is reported by error().
    void buildPending(TextureCache& cache, bool wait = false);
    /// Uploads the linked graph's value block (a value edit: no shader is touched).
    void uploadValues();
    /// Loads (through @p cache) and uploads each texture node's image when its file, colour space
    /// or contents changed. Cheap when nothing did: one cache lookup each.
    void refreshTextures(TextureCache& cache, Problems* problems);
    /// Binds the value block and the texture nodes' units for the geometry pass / unbinds them.
    void bind();
    void unbind() const;

    /// The generic program: every texture slot and lobe map at run time.
    unsigned program() const { return m_program.id(); }
    /// The program specialised to @p features (with the linked graph), built now when
    /// @p mayBuild and not built yet; otherwise, or if that build fails, program().
    /// @p deferred (optional) is set when the specialised program was wanted but not built.
    unsigned programFor(const GeometryFeatures& features, bool mayBuild, bool* deferred = nullptr);
    /// Why the last graph was not compiled, or "" when the drawn program matches the scene.
    const std::string& error() const { return m_error; }
    /// A structural change is waiting for its program.
    bool pending() const { return m_hasPending; }

    /// The MaterialInputs fields the drawn program's graph writes (its lobe-channel map follows
    /// them: render/lobe_channels.h).
    const std::vector<std::string>& writtenFields() const { return m_linked.writtenFields; }

    /// Specialised builds that failed (program() drew instead), and the last one's message.
    int specialisationFailures() const { return m_specialisationFailures; }
    const std::string& lastSpecialisationError() const { return m_specialisationError; }
    /// G-buffer programs built (GL compiles) since construction.
    int compileCount() const { return m_compileCount; }
    /// Graph-to-GLSL compiles (start() and setGraph()) since construction.
    int graphCompiles() const { return m_graphCompiles; }
    /// Value-block uploads since construction.
    int valueUploads() const { return m_valueUploads; }

private:
    struct Texture {
        unsigned texture = 0;
        std::uint64_t generation = 0;
        int width = 0, height = 0;
    };
    graph::CompiledGraph compile(const Material& material);
    void release();

    ShaderProgram m_program;
    /// Specialisations of m_program (same graph); null after a failed build. Dropped whenever
    /// m_program is rebuilt or replaced.
    std::map<GeometryFeatures, std::unique_ptr<ShaderProgram>> m_specialised;
    graph::CompiledGraph m_linked;  ///< what m_program was built from
    graph::CompiledGraph m_pending; ///< a new structure, started at the next buildPending()
    bool m_hasPending = false;      ///< m_pending is waiting to start or being built
    ProgramBuild m_build;           ///< m_pending's program in flight
    std::string m_error;
    unsigned m_ubo = 0;
    size_t m_uboSlots = 0;
    std::vector<Texture> m_textures; ///< one per m_linked.samplers entry
    unsigned m_fallback = 0;         ///< 1x1 white for a texture node without an image
    int m_compileCount = 0, m_graphCompiles = 0, m_valueUploads = 0;
    int m_specialisationFailures = 0;
    std::string m_specialisationError;
};

} // namespace velvet::render
