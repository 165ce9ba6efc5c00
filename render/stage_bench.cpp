#include "render/stage_bench.h"

#include "core/document_io.h"
#include "core/light_rigs.h"
#include "render/offscreen.h"
#include "render/progressive_accumulation.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <epoxy/gl.h>
#include <sys/resource.h>
#include <vector>

namespace velvet::render {
namespace {

/// CPU time of the whole process (all threads) in milliseconds.
double processCpuMs() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 +
           double(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3;
}

/// How much more @p ms is than @p baseMs, as a fraction (0.25: a quarter more).
double overhead(double ms, double baseMs) {
    return ms / std::max(baseMs, 1e-6) - 1.0;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

} // namespace

bool measureStage(int width, int height, int frames, StageBenchReport& report, std::string* error) {
    Scene lit = defaultScene();
    lit.mesh.kind = PreviewMeshKind::ShaderBall;
    lit.lights = *lightRigLights("key"); // one directional key light with castShadows
    lit.environment.ground = GroundMode::ShadowCatcher;
    Scene off = lit, shadow = lit, full = lit;
    for (Light& l : off.lights)
        l.castShadows = false;
    full.environment.ambientOcclusion = true;

    Renderer renderer;
    OffscreenTarget target;
    if (!renderer.initialize(error) || !target.resize(width, height, error))
        return false;
    FrameSettings fs;
    fs.width = width;
    fs.height = height;
    // Every frame a step of an orbit (the camera's yaw), so none keeps the last frame's
    // occlusion (render/ao_pass.h) but the value edits', which keep the camera where it was.
    // The orbit's frames are the editor's while the mouse drags (FrameSettings::navigating: the
    // stage at a quarter); the same frames at half (the stage's resolution at rest) are timed
    // beside them, and the value edit is a slider's, at rest.
    Camera camera = lit.camera;
    fs.navigating = true;
    const auto frame = [&](const Scene& scene, ScenePart parts, double* wallMs,
                           double* cpuMs = nullptr) {
        camera.yawDeg += 0.5f;
        fs.camera = camera;
        renderer.update(scene, parts);
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        const double cpuStart = processCpuMs();
        if (!renderer.render(fs, target.framebuffer(), error))
            return false;
        glFinish();
        if (wallMs)
            *wallMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
        if (cpuMs)
            *cpuMs = processCpuMs() - cpuStart;
        return true;
    };
    renderer.setScene(full);
    renderer.finishEnvironment();
    renderer.finishGraph();
    if (!frame(full, ScenePart::All, nullptr) || !frame(off, ScenePart::All, nullptr))
        return false;
    // Interleaved, so the three see the same machine state; each variant's first frame after a
    // switch redraws the shadow map, so the second is timed (an orbit's frame).
    report.occlusionKeptFrames = 0;
    std::vector<double> offMs, shadowMs, fullMs, valueEditMs, mapMs, maskMs, occlusionMs, offCpu,
        shadowCpu, fullCpu, unsettledCpu, texels, filteredShare, shadowRestMs, fullRestMs,
        maskRestMs, occlusionRestMs, ownUpsampleMs;
    for (int i = 0; i < frames; ++i) {
        double ms = 0.0, cpu = 0.0;
        if (!frame(off, ScenePart::Lights | ScenePart::Environment, nullptr) ||
            !frame(off, ScenePart::None, &ms, &cpu))
            return false;
        offMs.push_back(ms);
        offCpu.push_back(cpu);
        if (!frame(shadow, ScenePart::Lights | ScenePart::Environment, nullptr))
            return false;
        mapMs.push_back(renderer.lastTimings().shadowMapsMs);
        if (!frame(shadow, ScenePart::None, &ms, &cpu))
            return false;
        shadowMs.push_back(ms);
        shadowCpu.push_back(cpu);
        const FrameTimings t = renderer.lastTimings();
        maskMs.push_back(t.shadowMaskMs);
        texels.push_back(double(t.shadowMaskTexels));
        filteredShare.push_back(double(t.shadowMaskFiltered) /
                                double(std::max(t.shadowMaskTexels, 1LL)));
        // The same frame filtering every texel (the maps are still the shadow frame's).
        fs.settleShadows = false;
        const bool unsettled = frame(shadow, ScenePart::None, nullptr, &cpu);
        fs.settleShadows = true;
        if (!unsettled)
            return false;
        unsettledCpu.push_back(cpu);
        if (!frame(full, ScenePart::Lights | ScenePart::Environment, nullptr) ||
            !frame(full, ScenePart::None, &ms, &cpu))
            return false;
        fullMs.push_back(ms);
        fullCpu.push_back(cpu);
        occlusionMs.push_back(renderer.lastTimings().occlusionMs);
        fs.packOcclusion = false;
        const bool ownUpsample = frame(full, ScenePart::None, &ms);
        fs.packOcclusion = true;
        if (!ownUpsample)
            return false;
        ownUpsampleMs.push_back(ms);
        // The same orbit steps with the stage at its resolution at rest.
        fs.navigating = false;
        if (!frame(shadow, ScenePart::Lights | ScenePart::Environment, nullptr) ||
            !frame(shadow, ScenePart::None, &ms))
            return false;
        shadowRestMs.push_back(ms);
        maskRestMs.push_back(renderer.lastTimings().shadowMaskMs);
        if (!frame(full, ScenePart::Lights | ScenePart::Environment, nullptr) ||
            !frame(full, ScenePart::None, &ms))
            return false;
        fullRestMs.push_back(ms);
        occlusionRestMs.push_back(renderer.lastTimings().occlusionMs);
        // A value edit: the base colour, the camera where the last frame left it.
        Scene edited = full;
        edited.material.setColor(ParamId::BaseColor, glm::vec3(0.2f + 0.05f * float(i % 2)));
        camera.yawDeg -= 0.5f; // frame() steps it: the same view as the frame before
        if (!frame(edited, ScenePart::MaterialValues, &ms))
            return false;
        valueEditMs.push_back(ms);
        report.occlusionKeptFrames += renderer.lastTimings().occlusionKept ? 1 : 0;
        fs.navigating = true;
    }
    // The refinement at rest: whole progressive means of the same view, traced and not,
    // alternated (a traced frame reads the light of the traced frame before it); frames 1..15
    // timed.
    std::vector<double> tracedMs, untracedMs;
    fs.navigating = false;
    fs.camera = camera;
    fs.reflectionSamples = kRefinementReflectionSamples;
    fs.reflectionSampleTotal = kRefinementReflectionSamples * kRefinementFrames;
    renderer.update(full, ScenePart::All);
    for (int round = 0; round < (frames >= 7 ? 2 : 1); ++round)
        for (bool traced : {true, false}) {
            fs.screenSpaceReflections = traced;
            for (int k = 0; k < kRefinementFrames; ++k) {
                fs.accumulation = k;
                fs.jitter = progressiveJitter(k);
                fs.reflectionSampleSet = k;
                glFinish();
                const auto start = std::chrono::steady_clock::now();
                if (!renderer.render(fs, target.framebuffer(), error))
                    return false;
                glFinish();
                const double ms = std::chrono::duration<double, std::milli>(
                                      std::chrono::steady_clock::now() - start)
                                      .count();
                if (k > 0)
                    (traced ? tracedMs : untracedMs).push_back(ms);
            }
        }
    report.refineTracedMs = median(tracedMs);
    report.refineUntracedMs = median(untracedMs);
    report.refineTracedOverhead = overhead(report.refineTracedMs, report.refineUntracedMs);
    report.frameOffMs = median(offMs);
    report.frameShadowMs = median(shadowMs);
    report.frameStageMs = median(fullMs);
    report.frameStageValueEditMs = median(valueEditMs);
    report.frameStageOwnUpsampleMs = median(ownUpsampleMs);
    report.stageOwnUpsampleOverhead = overhead(report.frameStageOwnUpsampleMs, report.frameOffMs);
    report.shadowOverhead = overhead(report.frameShadowMs, report.frameOffMs);
    report.stageOverhead = overhead(report.frameStageMs, report.frameOffMs);
    report.shadowMapMs = median(mapMs);
    report.occlusionMs = median(occlusionMs);
    report.shadowMaskMs = median(maskMs);
    report.cpuOffMs = median(offCpu);
    report.cpuShadowMs = median(shadowCpu);
    report.cpuStageMs = median(fullCpu);
    report.cpuShadowOverhead = overhead(report.cpuShadowMs, report.cpuOffMs);
    report.cpuStageOverhead = overhead(report.cpuStageMs, report.cpuOffMs);
    report.cpuShadowUnsettledMs = median(unsettledCpu);
    report.cpuShadowUnsettledOverhead = overhead(report.cpuShadowUnsettledMs, report.cpuOffMs);
    report.frameShadowRestMs = median(shadowRestMs);
    report.frameStageRestMs = median(fullRestMs);
    report.shadowRestOverhead = overhead(report.frameShadowRestMs, report.frameOffMs);
    report.stageRestOverhead = overhead(report.frameStageRestMs, report.frameOffMs);
    report.shadowMaskRestMs = median(maskRestMs);
    report.occlusionRestMs = median(occlusionRestMs);
    report.shadowMaskTexels = median(texels);
    report.shadowMaskFilteredShare = median(filteredShare);
    return true;
}

} // namespace velvet::render
