#include "render/graph_preview.h"

#include "core/graph/graph_compiler.h"
#include "core/image_ops.h"
#include "core/texture_cache.h"
#include "render/graph_texture.h"
#include "render/shader_program.h"

#include <algorithm>
#include <cctype>
#include <epoxy/gl.h>
#include <map>

namespace velvet::render {
namespace {

/// The include graph_preview.frag reads.
constexpr const char* kPreviewInclude = "graph_preview_nodes.glsl";
/// Distinct structures kept compiled; beyond this the cache starts over (a long editing session
/// must not keep every program it ever built).
constexpr size_t kMaxPrograms = 64;

bool isRaw(const std::string& colorSpace) {
    std::string lower = colorSpace;
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return lower == "raw";
}

/// Whether the previewed output is a colour to sRGB-encode: a Color output, except the colour of
/// a texture node sampled "Raw" (packed data, shown as stored).
bool encodesSrgb(const graph::Graph& g, const PreviewRequest& r, graph::PortType type) {
    if (type != graph::PortType::Color)
        return false;
    const graph::Node* n = g.node(r.node);
    if (n && n->type->samplesTexture) {
        const int cs = n->type->settingIndex("colorSpace");
        if (cs >= 0 && isRaw(n->settings[size_t(cs)]))
            return false;
    }
    return true;
}

} // namespace

struct GraphPreview::Impl {
    struct CachedTexture {
        GLuint texture = 0;
        std::uint64_t generation = 0;
        int width = 0, height = 0;
        bool used = false; ///< sampled by the current batch (the others are freed after it)
    };
    /// A 64x64 thumbnail needs no more texels than this per side: a 4K map is uploaded at 256
    /// (16 times fewer texels than the frame's own copy, mips included), not duplicated.
    static constexpr int kMaxPreviewTextureSide = 256;

    int side = 64;
    GLuint colour = 0, fbo = 0, vao = 0, ubo = 0, fallback = 0;
    size_t uboSlots = 0;
    std::map<std::string, std::unique_ptr<ShaderProgram>> programs; ///< by generated GLSL text
    std::map<std::string, CachedTexture> textures; ///< by file + '\n' + colour space
    int compiles = 0;

    ~Impl() {
        programs.clear();
        for (auto& [key, t] : textures)
            glDeleteTextures(1, &t.texture);
        glDeleteTextures(1, &colour);
        glDeleteTextures(1, &fallback);
        glDeleteFramebuffers(1, &fbo);
        glDeleteVertexArrays(1, &vao);
        glDeleteBuffers(1, &ubo);
    }

    void createTarget() {
        glCreateTextures(GL_TEXTURE_2D, 1, &colour);
        glTextureStorage2D(colour, 1, GL_RGBA8, side, side);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
        glCreateVertexArrays(1, &vao);
        fallback = createGraphFallbackTexture();
    }

    /// The program for @p glsl: cached, or built now (nullptr + problem on a build failure).
    ShaderProgram* program(const std::string& glsl, Problems* problems) {
        if (const auto it = programs.find(glsl); it != programs.end())
            return it->second.get();
        if (programs.size() >= kMaxPrograms)
            programs.clear();
        auto p = std::make_unique<ShaderProgram>();
        std::string error;
        if (!p->build("fullscreen.vert", "graph_preview.frag", {}, {{kPreviewInclude, glsl}},
                      &error)) {
            if (problems)
                problems->error("", "graph preview", error);
            return nullptr;
        }
        ++compiles;
        return programs.emplace(glsl, std::move(p)).first->second.get();
    }

    void uploadValues(const std::vector<glm::vec4>& values) {
        const size_t slots = std::max<size_t>(values.size(), 1);
        if (!ubo || uboSlots < slots) {
            glDeleteBuffers(1, &ubo);
            glCreateBuffers(1, &ubo);
            glNamedBufferStorage(ubo, GLsizeiptr(slots * sizeof(glm::vec4)), nullptr,
                                 GL_DYNAMIC_STORAGE_BIT);
            uboSlots = slots;
        }
        glNamedBufferSubData(ubo, 0, GLsizeiptr(values.size() * sizeof(glm::vec4)), values.data());
    }

    /// The GL texture for a texture node's binding, (re)uploaded when the cache reloaded the file;
    /// the fallback while the file is unset, missing or broken.
    GLuint texture(const graph::SamplerBinding& b, TextureCache* cache, Problems* problems) {
        if (b.file.empty() || !cache)
            return fallback;
        const Texture tex = cache->get(b.file, TextureUsage::Color, b.colorSpace);
        if (problems)
            for (Problem p : tex.problems) {
                if (p.path.empty())
                    p.path = "graph.nodes (node " + std::to_string(b.node) + ")";
                problems->items.push_back(std::move(p));
            }
        if (!tex.image || tex.image->empty())
            return fallback;
        CachedTexture& t = textures[b.file + '\n' + b.colorSpace];
        t.used = true;
        if (!t.texture || t.generation != tex.generation) {
            Image small = *tex.image;
            fitToLimit(small, kMaxPreviewTextureSide, nullptr);
            uploadGraphTexture(small, t.texture, t.width, t.height);
            t.generation = tex.generation;
        }
        return t.texture;
    }

    Image readBack() const {
        std::vector<unsigned char> bytes(size_t(side) * side * 4);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_PACK_ROW_LENGTH, 0);
        glGetTextureImage(colour, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bytes.size()),
                          bytes.data());
        // Row 0 of the texture is v ~ 0, which is also row 0 of the Image: no flip (header).
        Image img(side, side, 4);
        std::transform(bytes.begin(), bytes.end(), img.pixels.begin(),
                       [](unsigned char b) { return float(b) / 255.0f; });
        return img;
    }
};

GraphPreview::GraphPreview(int side) : m_impl(std::make_unique<Impl>()) {
    m_impl->side = std::clamp(side, 1, 512);
    m_impl->createTarget();
}

GraphPreview::~GraphPreview() = default;

int GraphPreview::side() const {
    return m_impl->side;
}

int GraphPreview::compileCount() const {
    return m_impl->compiles;
}

std::vector<Image> GraphPreview::render(const graph::Graph& graph,
                                        std::span<const PreviewRequest> requests,
                                        TextureCache* textures, Problems* problems) {
    Impl& d = *m_impl;
    std::vector<Image> results(requests.size());
    if (requests.empty())
        return results;
    GLint previousFbo = 0, previousProgram = 0, previousVao = 0;
    GLint previousViewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_CURRENT_PROGRAM, &previousProgram);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previousVao);
    glGetIntegerv(GL_VIEWPORT, previousViewport);
    const GLboolean depth = glIsEnabled(GL_DEPTH_TEST), blend = glIsEnabled(GL_BLEND),
                    scissor = glIsEnabled(GL_SCISSOR_TEST), cull = glIsEnabled(GL_CULL_FACE),
                    srgb = glIsEnabled(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_FRAMEBUFFER_SRGB); // the shader encodes; RGBA8 stores the bytes as written
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, d.fbo);
    glViewport(0, 0, d.side, d.side);
    glBindVertexArray(d.vao);
    // The G-buffer pass's binding points: the same declarations, and nothing else disturbed.
    const graph::CompileOptions options = graphCompileOptions();

    std::vector<int> unitsUsed;
    for (auto& [key, t] : d.textures)
        t.used = false;
    for (size_t i = 0; i < requests.size(); ++i) {
        const graph::CompiledGraph c =
            graph::compileGraphPreview(graph, requests[i].node, requests[i].output, options);
        if (!c.ok) {
            if (problems)
                problems->error("", "graph preview", c.error);
            continue;
        }
        ShaderProgram* program = d.program(c.glsl, problems);
        if (!program)
            continue;
        d.uploadValues(c.values);
        glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(options.valuesBinding), d.ubo);
        for (const graph::SamplerBinding& b : c.samplers) {
            glBindTextureUnit(GLuint(b.unit), d.texture(b, textures, problems));
            unitsUsed.push_back(b.unit);
        }
        glUseProgram(program->id());
        glProgramUniform1f(program->id(), 0, float(d.side));
        glProgramUniform1i(program->id(), 1, encodesSrgb(graph, requests[i], c.previewType));
        glDrawArrays(GL_TRIANGLES, 0, 3);
        results[i] = d.readBack();
    }

    for (int unit : unitsUsed)
        glBindTextureUnit(GLuint(unit), 0);
    // A batch previews every node of the graph: files it did not sample left the graph.
    for (auto it = d.textures.begin(); it != d.textures.end();) {
        if (it->second.used) {
            ++it;
            continue;
        }
        glDeleteTextures(1, &it->second.texture);
        it = d.textures.erase(it);
    }
    glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(options.valuesBinding), 0);
    glBindVertexArray(GLuint(previousVao));
    glUseProgram(GLuint(previousProgram));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previousFbo));
    glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);
    const auto restore = [](GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); };
    restore(GL_DEPTH_TEST, depth);
    restore(GL_BLEND, blend);
    restore(GL_SCISSOR_TEST, scissor);
    restore(GL_CULL_FACE, cull);
    restore(GL_FRAMEBUFFER_SRGB, srgb);
    return results;
}

} // namespace velvet::render
