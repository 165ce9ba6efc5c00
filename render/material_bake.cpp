#include "render/material_bake.h"

#include "core/graph/graph_compiler.h"
#include "core/mapping_warnings.h"
#include "core/texture_cache.h"
#include "core/texture_set_lobes.h"
#include "render/gl_util.h"
#include "render/graph_texture.h"
#include "render/headless_context.h"
#include "render/material_table.h"
#include "render/shader_program.h"
#include "render/texture_set.h"

#include <array>
#include <epoxy/gl.h>
#include <memory>

namespace velvet::render {
namespace {

constexpr int kTargets = 8; ///< material_bake.frag's outputs (GL 4.5 guarantees 8 draw buffers)

/// The bake's GL objects, released with the context still current.
struct BakeObjects {
    GLuint fbo = 0, vao = 0, ubo = 0, fallback = 0;
    std::array<GLuint, kTargets> colour{};
    std::vector<GLuint> graphTextures;
    ~BakeObjects() {
        glDeleteFramebuffers(1, &fbo);
        glDeleteVertexArrays(1, &vao);
        glDeleteBuffers(1, &ubo);
        glDeleteTextures(1, &fallback);
        glDeleteTextures(kTargets, colour.data());
        if (!graphTextures.empty())
            glDeleteTextures(GLsizei(graphTextures.size()), graphTextures.data());
    }
};

Image readTarget(GLuint texture, int width, int height, int channels) {
    std::vector<float> rgba(size_t(width) * size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)),
                      rgba.data());
    // Row 0 of the target is v ~ 0, which is also row 0 of the Image (the top): no flip.
    Image out(width, height, channels);
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (int c = 0; c < channels; ++c)
            out.pixels[i * size_t(channels) + size_t(c)] = rgba[i * 4 + size_t(c)];
    return out;
}

bool bakeWithContext(const Material& material, int width, int height, MaterialMaps& out,
                     Problems* problems, std::string* error) {
    // The material's slots and values exactly as the renderer uploads them.
    TextureSet slots;
    slots.setMaterial(material, problems);
    GpuMaterial record = packMaterialRecord(material, slots, {}, /*compactGBuffer=*/true);
    // The bake samples every lobe slot per texel (material_bake.frag's readLobeInputs), so the
    // lobe factors are the parameters alone, not times the texture means the compact layout
    // folds in for the lighting pass.
    const GpuMaterial plain = packMaterial(material);
    record.specularColorWeight = plain.specularColorWeight;
    record.sheenColorRoughness = plain.sheenColorRoughness;
    record.clearcoat = plain.clearcoat;
    record.sheenWeightAnisotropy = plain.sheenWeightAnisotropy;
    MaterialTable table;
    table.upload({record});

    static const graph::Graph kEmpty;
    const graph::CompiledGraph compiled =
        graph::compileGraph(material.graph ? *material.graph : kEmpty, graphCompileOptions());
    if (!compiled.ok)
        return fail(error, "the material graph cannot be compiled: " + compiled.error);
    ShaderProgram program;
    std::string why;
    if (!program.build("fullscreen.vert", "material_bake.frag", {},
                       {{"material_graph.glsl", compiled.glsl}}, &why))
        return fail(error, "the bake program failed: " + why);

    BakeObjects gl;
    glCreateFramebuffers(1, &gl.fbo);
    glCreateTextures(GL_TEXTURE_2D, kTargets, gl.colour.data());
    std::array<GLenum, kTargets> buffers{};
    for (int i = 0; i < kTargets; ++i) {
        glTextureStorage2D(gl.colour[size_t(i)], 1, GL_RGBA32F, width, height);
        glNamedFramebufferTexture(gl.fbo, GLenum(GL_COLOR_ATTACHMENT0 + i), gl.colour[size_t(i)],
                                  0);
        buffers[size_t(i)] = GLenum(GL_COLOR_ATTACHMENT0 + i);
    }
    glNamedFramebufferDrawBuffers(gl.fbo, kTargets, buffers.data());
    const GLenum status = glCheckNamedFramebufferStatus(gl.fbo, GL_DRAW_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return fail(error, "the bake target of " + std::to_string(width) + "x" +
                               std::to_string(height) + " is incomplete");
    glCreateVertexArrays(1, &gl.vao);

    // The graph's value block and texture nodes, bound where the G-buffer pass binds them.
    const size_t slotsNeeded = std::max<size_t>(compiled.values.size(), 1);
    glCreateBuffers(1, &gl.ubo);
    glNamedBufferStorage(gl.ubo, GLsizeiptr(slotsNeeded * sizeof(glm::vec4)), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    if (!compiled.values.empty())
        glNamedBufferSubData(gl.ubo, 0, GLsizeiptr(compiled.values.size() * sizeof(glm::vec4)),
                             compiled.values.data());
    gl.fallback = createGraphFallbackTexture();
    for (const graph::SamplerBinding& b : compiled.samplers) {
        GLuint texture = gl.fallback;
        if (!b.file.empty()) {
            const Texture t = slots.sharedCache().get(b.file, TextureUsage::Color, b.colorSpace);
            if (problems)
                for (Problem p : t.problems) {
                    if (p.path.empty())
                        p.path = "graph.nodes (node " + std::to_string(b.node) + ")";
                    problems->items.push_back(std::move(p));
                }
            if (t.image && !t.image->empty()) {
                unsigned created = 0;
                int w = 0, h = 0;
                uploadGraphTexture(*t.image, created, w, h);
                gl.graphTextures.push_back(created);
                texture = created;
            }
        }
        glBindTextureUnit(GLuint(b.unit), texture);
    }

    GLint previousFbo = 0;
    GLint previousViewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_VIEWPORT, previousViewport);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gl.fbo);
    glViewport(0, 0, width, height);
    glBindVertexArray(gl.vao);
    table.bind();
    glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(graphCompileOptions().valuesBinding), gl.ubo);
    slots.bind(program.id());
    glUseProgram(program.id());
    glProgramUniform2f(program.id(), 0, float(width), float(height));
    glDrawArrays(GL_TRIANGLES, 0, 3);

    out.baseColor = readTarget(gl.colour[0], width, height, 4);
    out.normal = readTarget(gl.colour[1], width, height, 3);
    out.orm = readTarget(gl.colour[2], width, height, 3);
    out.emission = readTarget(gl.colour[3], width, height, 3);
    out.coat = readTarget(gl.colour[4], width, height, 2);
    out.sheen = readTarget(gl.colour[5], width, height, 4);
    out.specular = readTarget(gl.colour[6], width, height, 4);
    out.anisotropy = readTarget(gl.colour[7], width, height, 3);

    slots.unbind();
    for (const graph::SamplerBinding& b : compiled.samplers)
        glBindTextureUnit(GLuint(b.unit), 0);
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previousFbo));
    glViewport(previousViewport[0], previousViewport[1], previousViewport[2], previousViewport[3]);
    if (const std::string glError = takeGlErrors(); !glError.empty())
        return fail(error, "baking the material's maps failed: " + glError);
    return true;
}

/// What an engine texture set has no map for, one line each, when the material uses it: the
/// lobes the engine has no input for (core/texture_set_lobes.h), the IOR, the BRDF term choices.
std::vector<std::string> unmappedInSet(const Material& m, TextureSetTarget target) {
    std::vector<std::string> w = lobeGaps(m, target);
    const std::string to = "the " + std::string(textureSetTargetId(target)) + " texture set";
    auto add = [&](ParamId id, const std::string& what) {
        w.push_back(std::string(paramMeta(id).id) + ": " + what + "; " + to +
                    " has no map for it (set it in the engine's material)");
    };
    if (m.scalar(ParamId::Ior) != 1.5f)
        add(ParamId::Ior, "an index of refraction other than 1.5");
    // The BRDF term choices, as for glTF and MaterialX; the graph is baked here, so its line
    // (which says it is not exported) does not apply.
    for (std::string& line : mappingWarnings(m, to))
        if (line.rfind("graph:", 0) != 0)
            w.push_back(std::move(line));
    return w;
}

} // namespace

ExportOutcome exportTextureSet(const Material& material, const std::filesystem::path& folder,
                               std::string_view baseName, const TextureSetOptions& options,
                               bool force) {
    ExportOutcome outcome;
    auto failed = [&](ExportOutcome::Status status, std::string why) {
        outcome.status = status;
        outcome.error = std::move(why);
        return outcome;
    };
    if (const std::string why = checkTextureSetOptions(options); !why.empty())
        return failed(ExportOutcome::Status::BadInput, why);
    const std::string base = sanitizeFileStem(baseName);
    MaterialMaps maps;
    Problems problems;
    std::string error;
    if (!bakeMaterialMaps(material, options.size, options.size, maps, &problems, &error))
        return failed(ExportOutcome::Status::Failed, error);
    // A texture that cannot be read is bad input, as for the other formats: nothing is written.
    for (const Problem& p : problems.items) {
        if (p.severity == Problem::Severity::Error)
            return failed(ExportOutcome::Status::BadInput, p.toString());
        outcome.warnings.push_back(p.toString());
    }
    outcome.warnings = [&] {
        std::vector<std::string> all = unmappedInSet(material, options.target);
        all.insert(all.end(), outcome.warnings.begin(), outcome.warnings.end());
        return all;
    }();
    BuiltExport built;
    if (!buildTextureSet(maps, base, material.name, options, built, &error))
        return failed(ExportOutcome::Status::Failed, error);
    switch (writeExportFiles(folder, built.files, force, &error, &outcome.written)) {
    case ExportWriteError::None:
        return outcome;
    case ExportWriteError::Exists:
        return failed(ExportOutcome::Status::Exists, error);
    case ExportWriteError::Unsafe:
    case ExportWriteError::IoError:
        break;
    }
    return failed(ExportOutcome::Status::Failed, error);
}

bool bakeMaterialMaps(const Material& material, int width, int height, MaterialMaps& out,
                      Problems* problems, std::string* error) {
    if (width < 1 || height < 1 || width > 8192 || height > 8192)
        return fail(error, "the bake size must be 1 to 8192 a side");
    std::unique_ptr<HeadlessContext> context;
    if (!HeadlessContext::isAnyContextCurrent()) {
        context = HeadlessContext::create(error);
        if (!context)
            return false;
    }
    return bakeWithContext(material, width, height, out, problems, error);
}

} // namespace velvet::render
