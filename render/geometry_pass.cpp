#include "render/geometry_pass.h"

#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "render/gbuffer_layout.h"
#include "render/material_graph_program.h"
#include "render/texture_set.h"

#include <algorithm>
#include <cmath>
#include <epoxy/gl.h>

namespace velvet::render {

bool materialEmits(const Material& m) {
    const glm::vec3 e = m.color(ParamId::EmissiveColor) * m.scalar(ParamId::EmissiveStrength);
    if (e.r > 0.0f || e.g > 0.0f || e.b > 0.0f)
        return true;
    const graph::Graph* g = m.graph.get();
    const graph::NodeId out = g ? g->outputNode() : graph::kInvalidNodeId;
    if (out == graph::kInvalidNodeId)
        return false;
    for (ParamId id : {ParamId::EmissiveColor, ParamId::EmissiveStrength})
        if (g->connectionTo(out, graph::PortIndex(graph::outputInputForParam(id))))
            return true;
    return false;
}

void drawGeometryPass(const GeometryPassInputs& in, const MeshCache::Entry& mesh,
                      MaterialGraphProgram& graph, const TextureSet& textures) {
    glBindFramebuffer(GL_FRAMEBUFFER, in.framebuffer);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    const float farDepth = 1.0f;
    // The G-buffer's colours are not cleared: every reader tests the depth first (the lighting,
    // catcher and debug passes by the depth test, the occlusion, shadow-mask and local-light
    // passes and the toon outline by comparing it with the far plane), so a background pixel's
    // colours are never used, and every fragment that writes depth writes every colour (about
    // 0.6 ms of a 1280x720 frame on llvmpipe, BENCHMARKS.md).
    const auto clearGeometry = [&] {
        if (in.emission)
            glClearBufferfv(GL_COLOR, gbufferColorAttachmentCount(), kNoEmission);
        glClearBufferfv(GL_DEPTH, 0, &farDepth);
    };
    clearGeometry();
    auto programOf = [&](MaterialGraphProgram& p, const GpuMaterial& record) {
        return in.specialise ? p.programFor(GeometryFeatures::of(record, mesh.gpu.hasVisibility()),
                                            in.mayBuild, in.deferred)
                             : p.program();
    };
    const unsigned program = programOf(graph, in.recordA);
    glUseProgram(program);
    glProgramUniform1i(program, 0, 0); // uMaterialId: the scene's material
    textures.bind(program);
    graph.bind();
    if (mesh.doubleSided)
        glDisable(GL_CULL_FACE);
    mesh.gpu.draw();
    MaterialGraphProgram* bound = &graph;
    if (in.split) {
        // A/B split: B's part again, from a cleared G-buffer, with material B (id 1).
        const int seam = std::clamp(
            int(std::lround(std::clamp(in.splitPosition, 0.0f, 1.0f) * in.width)), 0, in.width);
        glEnable(GL_SCISSOR_TEST);
        if (in.splitSwapped)
            glScissor(0, 0, seam, in.height);
        else
            glScissor(seam, 0, in.width - seam, in.height);
        clearGeometry();
        // B with a graph of its own draws with its own program (its graph's code, values and
        // texture nodes), not with A's graph under B's parameters.
        if (in.splitGraph && in.splitGraph != &graph) {
            graph.unbind();
            bound = in.splitGraph;
            bound->bind();
        }
        const unsigned programB = programOf(*bound, in.recordB);
        if (programB != program)
            glUseProgram(programB);
        // B's own slots (their units and per-program uniforms); A's when the caller has none.
        const TextureSet& slotsB = in.texturesB ? *in.texturesB : textures;
        if (programB != program || &slotsB != &textures)
            slotsB.bind(programB);
        glProgramUniform1i(programB, 0, 1);
        mesh.gpu.draw();
        glProgramUniform1i(programB, 0, 0);
        glDisable(GL_SCISSOR_TEST);
    }
    textures.unbind();
    bound->unbind();
}

} // namespace velvet::render
