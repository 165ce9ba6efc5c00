#include "render/material_graph_program.h"

#include "core/texture_cache.h"
#include "render/graph_texture.h"
#include "render/material_table.h"
#include "render/renderer.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <glm/vec4.hpp>

namespace velvet::render {
namespace {

/// The generated include gbuffer.frag reads (graph_compiler.h's interface).
constexpr const char* kGraphInclude = "material_graph.glsl";

} // namespace

MaterialGraphProgram::~MaterialGraphProgram() {
    release();
}

void MaterialGraphProgram::release() {
    if (m_ubo)
        glDeleteBuffers(1, &m_ubo);
    m_ubo = 0;
    m_uboSlots = 0;
    for (Texture& t : m_textures)
        if (t.texture)
            glDeleteTextures(1, &t.texture);
    m_textures.clear();
    if (m_fallback)
        glDeleteTextures(1, &m_fallback);
    m_fallback = 0;
}

/// Compiles @p material's graph (an empty graph when it has none: a velvetGraph that changes
/// nothing), with the renderer's binding points.
graph::CompiledGraph MaterialGraphProgram::compile(const Material& material) {
    ++m_graphCompiles;
    const graph::CompileOptions options = graphCompileOptions();
    static const graph::Graph empty;
    return graph::compileGraph(material.graph ? *material.graph : empty, options);
}

void MaterialGraphProgram::start(const Material& material) {
    m_linked = compile(material);
    if (!m_linked.ok) { // too many texture nodes: start without the graph
        m_error = m_linked.error;
        m_linked = compile(Material{});
    }
}

GeometryFeatures GeometryFeatures::of(const GpuMaterial& record, bool meshVisibility) {
    return {record.terms2.y, record.terms2.z, record.terms2.w, iorLobeEntry(record),
            meshVisibility};
}

std::vector<std::string> GeometryFeatures::defines() const {
    return {"FIXED_TEXTURE_SLOTS " + std::to_string(textureSlots),
            "FIXED_ATLAS_SLOTS " + std::to_string(atlasSlots),
            "FIXED_LOBE_MAP (" + std::to_string(lobeMap) + ")",
            "FIXED_IOR_ENTRY " + std::to_string(iorEntry),
            "FIXED_MESH_VISIBILITY " + std::to_string(int(meshVisibility))};
}

bool MaterialGraphProgram::build(std::string* error) {
    m_build.abandon(); // a structure in flight restarts next frame, from the files on disk
    if (!m_program.build("gbuffer.vert", "gbuffer.frag", {}, {{kGraphInclude, m_linked.glsl}},
                         error))
        return false;
    m_specialised.clear();
    ++m_compileCount;
    return true;
}

unsigned MaterialGraphProgram::programFor(const GeometryFeatures& features, bool mayBuild,
                                          bool* deferred) {
    auto it = m_specialised.find(features);
    if (it == m_specialised.end()) {
        if (deferred && !mayBuild)
            *deferred = true;
        if (!mayBuild || m_program.id() == 0)
            return m_program.id();
        if (m_specialised.size() >= 8) // a handful of structures per graph; start afresh
            m_specialised.clear();
        auto program = std::make_unique<ShaderProgram>();
        // The generic program built from the same text: a failure is a bug (or a shader edited
        // under the reload), reported by the renderer as a warning; the generic one draws.
        std::string message;
        if (program->build("gbuffer.vert", "gbuffer.frag", features.defines(),
                           {{kGraphInclude, m_linked.glsl}}, &message)) {
            ++m_compileCount;
        } else {
            program.reset();
            ++m_specialisationFailures;
            m_specialisationError = message;
        }
        it = m_specialised.emplace(features, std::move(program)).first;
    }
    return it->second ? it->second->id() : m_program.id();
}

void MaterialGraphProgram::uploadValues() {
    ++m_valueUploads;
    const std::vector<glm::vec4>& values = m_linked.values;
    const size_t slots = std::max<size_t>(values.size(), 1);
    if (!m_ubo || m_uboSlots < slots) {
        if (m_ubo)
            glDeleteBuffers(1, &m_ubo);
        glCreateBuffers(1, &m_ubo);
        glNamedBufferStorage(m_ubo, GLsizeiptr(slots * sizeof(glm::vec4)), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        m_uboSlots = slots;
    }
    if (!values.empty())
        glNamedBufferSubData(m_ubo, 0, GLsizeiptr(values.size() * sizeof(glm::vec4)),
                             values.data());
}

void MaterialGraphProgram::refreshTextures(TextureCache& cache, Problems* problems) {
    const auto& samplers = m_linked.samplers;
    if (m_textures.size() > samplers.size()) {
        for (size_t i = samplers.size(); i < m_textures.size(); ++i)
            if (m_textures[i].texture)
                glDeleteTextures(1, &m_textures[i].texture);
    }
    m_textures.resize(samplers.size());
    for (size_t i = 0; i < samplers.size(); ++i) {
        Texture& t = m_textures[i];
        if (samplers[i].file.empty()) {
            t.generation = 0;
            continue;
        }
        const velvet::Texture tex =
            cache.get(samplers[i].file, TextureUsage::Color, samplers[i].colorSpace);
        if (problems)
            for (Problem p : tex.problems) {
                if (p.path.empty())
                    p.path = "graph.nodes (node " + std::to_string(samplers[i].node) + ")";
                problems->items.push_back(std::move(p));
            }
        if (!tex.image || tex.image->empty()) {
            t.generation = 0;
            continue;
        }
        if (t.texture && t.generation == tex.generation)
            continue;
        uploadGraphTexture(*tex.image, t.texture, t.width, t.height);
        t.generation = tex.generation;
    }
}

void MaterialGraphProgram::bind() {
    glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(graphCompileOptions().valuesBinding), m_ubo);
    if (!m_fallback)
        m_fallback = createGraphFallbackTexture();
    for (size_t i = 0; i < m_linked.samplers.size(); ++i) {
        const Texture* t = i < m_textures.size() ? &m_textures[i] : nullptr;
        glBindTextureUnit(GLuint(m_linked.samplers[i].unit),
                          t && t->texture && t->generation ? t->texture : m_fallback);
    }
}

void MaterialGraphProgram::unbind() const {
    for (const graph::SamplerBinding& s : m_linked.samplers)
        glBindTextureUnit(GLuint(s.unit), 0);
}

void MaterialGraphProgram::setGraph(const Material& material, TextureCache& cache,
                                    Problems* problems) {
    graph::CompiledGraph next = compile(material);
    if (!next.ok) {
        m_error = next.error;
        m_hasPending = false;
        m_build.abandon();
        if (problems)
            problems->error("", "graph", next.error + "; the previous graph is kept");
        return;
    }
    if (next.glsl == m_linked.glsl) { // back to the drawn structure: drop any build
        m_linked = std::move(next);
        m_hasPending = false;
        m_build.abandon();
        uploadValues();
        refreshTextures(cache, problems);
        return;
    }
    if (m_hasPending && next.glsl == m_pending.glsl) {
        // The structure in flight with new values: they are uploaded when it is adopted.
        m_pending = std::move(next);
        return;
    }
    m_pending = std::move(next);
    m_hasPending = true;
    m_build.abandon(); // an older structure in flight is no longer wanted
}

void MaterialGraphProgram::buildPending(TextureCache& cache, bool wait) {
    if (!m_hasPending)
        return;
    std::string message;
    if (!m_build.active() && !m_build.start("gbuffer.vert", "gbuffer.frag", {},
                                            {{kGraphInclude, m_pending.glsl}}, &message)) {
        m_hasPending = false;
        m_error = message;
        return;
    }
    if (!wait && !m_build.ready())
        return; // the driver's threads are still compiling: draw the old program
    m_hasPending = false;
    if (!m_build.finish(m_program, &message)) {
        m_error = message;
        return;
    }
    ++m_compileCount;
    m_specialised.clear(); // built from the old graph
    m_error.clear();
    m_linked = std::move(m_pending);
    m_pending = {};
    uploadValues();
    refreshTextures(cache, nullptr);
}

} // namespace velvet::render
