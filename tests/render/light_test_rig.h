#pragma once
/// @file light_test_rig.h
/// Test-only: one renderer shared by a light test's cases (shaders compile once), a frame of a
/// scene at a size, view and light path, the orthographic analytic scene and DESIGN.md's golden
/// rule (test_render_lights, test_render_light_paths). Needs a current GL 4.5 context.
#include "core/image.h"
#include "core/scene.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtGlobal>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace velvet::test {

/// One renderer for the whole file (shaders compile once).
struct Rig {
    render::Renderer renderer;
    render::OffscreenTarget target;
};
inline Rig* rig() {
    static std::unique_ptr<Rig> r;
    if (!r) {
        r = std::make_unique<Rig>();
        std::string error;
        if (!r->renderer.initialize(&error))
            qFatal("renderer: %s", error.c_str());
    }
    return r.get();
}

struct Frame {
    Image linear, display;
};

inline Frame renderFrame(const Scene& scene, int size,
                         render::DebugView view = render::DebugView::Final,
                         render::LightPath path = render::LightPath::Auto,
                         const std::optional<Material>& splitMaterial = std::nullopt) {
    Rig* r = rig();
    std::string error;
    if (!r->target.resize(size, size, &error))
        qFatal("target: %s", error.c_str());
    render::FrameSettings fs;
    fs.width = fs.height = size;
    fs.view = view;
    fs.lightPath = path;
    fs.splitMaterial = splitMaterial;
    r->renderer.setScene(scene);
    if (!r->renderer.render(fs, r->target.framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    return {r->renderer.readLinear(), r->renderer.readDisplay()};
}

/// Orthographic unit sphere, black environment, no lights yet.
inline Scene analyticScene() {
    Scene scene = test::blackOrthographicScene();
    Material& m = scene.material;
    m.setColor(ParamId::BaseColor, {0.8f, 0.3f, 0.2f});
    m.setScalar(ParamId::Roughness, 0.4f);
    return scene;
}

/// DESIGN.md's golden rule: pixels differing by more than 5/255 in any channel; returns the
/// fraction of such pixels.
inline double differingFraction(const Image& a, const Image& b, float* worst = nullptr) {
    int differing = 0;
    float w = 0.0f;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            float d = 0.0f;
            for (int k = 0; k < 3; ++k)
                d = std::max(d, std::abs(std::round(a.rgba(x, y)[k] * 255.0f) -
                                         std::round(b.rgba(x, y)[k] * 255.0f)));
            w = std::max(w, d);
            differing += d > 5.0f;
        }
    if (worst)
        *worst = w;
    return double(differing) / double(a.width * a.height);
}

} // namespace velvet::test
