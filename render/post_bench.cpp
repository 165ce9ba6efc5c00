#include "render/post_bench.h"

#include "core/document_io.h"
#include "core/image.h"
#include "core/post_effects.h"
#include "render/offscreen.h"
#include "render/post_chain.h"
#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <epoxy/gl.h>
#include <functional>

namespace velvet::render {
namespace {

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

double timeMs(int frames, const std::function<bool()>& body) {
    std::vector<double> ms;
    body(); // warm-up: compiles programs, fills the target pool
    for (int i = 0; i < frames; ++i) {
        glFinish();
        const auto start = std::chrono::steady_clock::now();
        if (!body())
            return -1.0;
        glFinish();
        ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
    }
    return median(ms);
}

} // namespace

bool measurePostChain(int width, int height, int lights, int frames, PostBenchReport& report,
                      std::string* error) {
    Scene scene = defaultScene();
    const int side = int(std::ceil(std::cbrt(double(std::max(lights, 1)))));
    for (int i = 0; i < lights; ++i) {
        Light l;
        l.type = LightType::Point;
        const int x = i % side, y = (i / side) % side, z = i / (side * side);
        l.position = glm::vec3(x, y, z) / float(side) * 3.2f - 1.6f;
        l.range = 1.0f;
        l.intensity = 0.05f;
        scene.lights.push_back(l);
    }
    Renderer renderer;
    if (!renderer.initialize(error))
        return false;
    OffscreenTarget target;
    if (!target.resize(width, height, error))
        return false;
    FrameSettings fs;
    fs.width = width;
    fs.height = height;
    auto frame = [&](const PostChain& chain) {
        scene.post = chain;
        renderer.setScene(scene);
        // Neither the IBL bake's slices nor first-use shader compilation belong to the figure.
        renderer.finishEnvironment();
        renderer.finishGraph();
        if (!renderer.render(fs, target.framebuffer(), error))
            return -1.0;
        return timeMs(frames, [&] { return renderer.render(fs, target.framebuffer(), error); });
    };
    report.frameNoPostMs = frame({});
    if (report.frameNoPostMs < 0 && error)
        *error = "no-post frame: " + *error;
    report.frameMs = frame(defaultPostChain());
    if (report.frameMs < 0 || report.frameNoPostMs < 0)
        return false;
    report.postChainShare = (report.frameMs - report.frameNoPostMs) / report.frameMs;

    // Effects alone on the renderer's lit HDR image stand-in: a float texture of the frame size.
    PostChainRenderer post;
    Image hdr(width, height, 4);
    for (size_t i = 0; i < hdr.pixels.size(); ++i)
        hdr.pixels[i] = float((i * 7919) % 1000) / 400.0f;
    GLuint tex = 0, fbo = 0, out = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA16F, width, height);
    glTextureSubImage2D(tex, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, hdr.pixels.data());
    glCreateTextures(GL_TEXTURE_2D, 1, &out);
    glTextureStorage2D(out, 1, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, out, 0);
    PostRunInputs in;
    in.hdrTexture = tex;
    in.width = width;
    in.height = height;
    in.finalFbo = fbo;
    auto chainMs = [&](const PostChain& chain) {
        PostRunResult r;
        return timeMs(frames, [&] { return post.run(chain, in, r, error); });
    };
    PostChain bloom, gauss;
    bloom.effects = {makeEffect("bloom")};
    gauss.effects = {makeEffect("gaussian_blur")};
    gauss.effects[0].params["sigma"] = {2.0f};  // < 3: full resolution
    gauss.effects[0].params["radius"] = {4.0f}; // 9 taps
    report.bloomMs = chainMs(bloom);
    report.gauss9Ms = chainMs(gauss);
    report.bloomVsGauss9 = report.gauss9Ms > 0 ? report.bloomMs / report.gauss9Ms : 0.0;

    post.setProfiling(true);
    for (const EffectMeta& m : postEffectCatalogue()) {
        PostChain c;
        c.effects = {makeEffect(m.type)};
        PostRunResult r;
        if (!post.run(c, in, r, error)) // warm-up (compile)
            break;
        std::vector<double> ms;
        for (int i = 0; i < frames && post.run(c, in, r, error); ++i)
            for (const PostStepTiming& t : post.lastTimings())
                if (t.name.find(m.type) != std::string::npos)
                    ms.push_back(t.ms);
        report.effectMs.emplace_back(std::string(m.type), median(ms));
    }
    post.endFrame();
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteTextures(1, &out);
    return true;
}

} // namespace velvet::render
