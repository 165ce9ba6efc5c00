#pragma once
// Shared helpers of the render tests: one headless context per test process, scenes built in code.

#include "core/document_io.h"
#include "core/post_effects.h"
#include "core/scene.h"
#include "core/spherical_harmonics.h"
#include "render/headless_context.h"
#include "render/offscreen.h"
#include "render/renderer.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

namespace velvet::test {

/// Whether this run rewrites the golden images it compares against (VELVET_UPDATE_GOLDENS=1:
/// only after a deliberate change, reviewed by eye).
inline bool updateGoldens() {
    const char* v = std::getenv("VELVET_UPDATE_GOLDENS");
    return v && std::string(v) == "1";
}

inline render::HeadlessContext* headlessContext(std::string* error) {
    static std::string lastError;
    static std::unique_ptr<render::HeadlessContext> ctx =
        render::HeadlessContext::create(&lastError);
    if (!ctx && error)
        *error = lastError;
    return ctx.get();
}

/// The fixture of the render tests that draw frames and read them back: a renderer and a square
/// offscreen target on the process's headless context.
struct OffscreenRenderer {
    std::unique_ptr<render::Renderer> renderer;
    std::unique_ptr<render::OffscreenTarget> target;
    int size = 0;

    /// "" when the context, the renderer and the target are up; else why not.
    std::string start(int side) {
        std::string error;
        if (!headlessContext(&error))
            return error;
        size = side;
        renderer = std::make_unique<render::Renderer>();
        target = std::make_unique<render::OffscreenTarget>();
        if (!renderer->initialize(&error) || !target->resize(side, side, &error))
            return error;
        return {};
    }
    /// Frees both while the context is still current (cleanupTestCase).
    void stop() {
        target.reset();
        renderer.reset();
    }
    /// @p scene (when given; its problems into @p problems) drawn in @p view, linear.
    Image draw(const Scene* scene, render::DebugView view = render::DebugView::Final,
               Problems* problems = nullptr) {
        if (scene)
            renderer->setScene(*scene, problems);
        // Drawn with the bake complete, as `velvet render` draws: the same image whether the
        // environment and the DFG LUT came from the disk cache or were baked just now.
        renderer->finishEnvironment();
        render::FrameSettings fs;
        fs.width = fs.height = size;
        fs.view = view;
        std::string error;
        if (!renderer->render(fs, target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return renderer->readLinear();
    }
};

/// The test process's one OffscreenRenderer, started at @p side on first use (qFatal if it cannot
/// start); stopProcessRenderer() frees it while the context is still current (cleanupTestCase).
inline std::unique_ptr<OffscreenRenderer>& processRendererSlot() {
    static std::unique_ptr<OffscreenRenderer> renderer;
    return renderer;
}
inline OffscreenRenderer* processRenderer(int side) {
    auto& r = processRendererSlot();
    if (!r) {
        r = std::make_unique<OffscreenRenderer>();
        const std::string error = r->start(side);
        if (!error.empty())
            qFatal("renderer: %s", error.c_str());
    }
    return r.get();
}
/// The headless context, then processRenderer() with its target at @p width x @p height: a
/// render test's initTestCase. Null + @p error when either cannot start.
inline OffscreenRenderer* startProcessRenderer(int width, int height, std::string* error) {
    if (!headlessContext(error))
        return nullptr;
    OffscreenRenderer* r = processRenderer(std::max(width, height));
    return r->target->resize(width, height, error) ? r : nullptr;
}
inline void stopProcessRenderer() {
    if (auto& r = processRendererSlot())
        r->stop();
}

/// The shipped default scene (core/document_io.h), loaded exactly as `velvet render` and the editor
/// load it, so the golden image is the default scene and not a copy of it. Fails the test when the
/// default preset reports any problem.
inline Scene shippedDefaultScene() {
    Problems problems;
    Scene scene = defaultScene(&problems);
    for (const Problem& p : problems.items)
        qWarning("default scene: %s", p.toString().c_str());
    if (!problems.items.empty())
        QTest::qFail("the default scene reported problems", __FILE__, __LINE__);
    return scene;
}

/// The library preset @p name (resources/presets/NAME.json) of the source tree; nullopt, with
/// the first problem as a warning, when it does not load.
inline std::optional<Material> libraryPreset(const std::string& name) {
    Problems problems;
    std::optional<Material> m = loadMaterialFile(
        std::string(VELVET_SOURCE_DIR) + "/resources/presets/" + name + ".json", problems);
    if (!m && !problems.items.empty())
        qWarning("%s: %s", name.c_str(), problems.items[0].toString().c_str());
    return m;
}

/// A dim sky with a bright soft lamp up and behind the sphere (as the camera sees it), where the
/// sphere's upper rim reflects it at grazing angles.
inline float lampRadiance(glm::vec3 d) {
    const glm::vec3 lamp = glm::normalize(glm::vec3(0.0f, 1.0f, -1.0f));
    return 0.05f + 0.3f * std::max(d.y, 0.0f) +
           6.0f * std::exp(-12.0f * (1.0f - glm::dot(d, lamp)));
}

inline Image lampEnvironment() {
    Image img(512, 256, 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float l = lampRadiance(
                equirectDirection((float(x) + 0.5f) / img.width, (float(y) + 0.5f) / img.height));
            float* p = img.at(x, y);
            p[0] = p[1] = p[2] = l;
        }
    return img;
}

/// A test's start in its own cache (XDG_CACHE_HOME under @p dir: the IBL and DFG caches) with the
/// process's headless context; the message why not, or empty.
inline std::string startWithCacheIn(const QTemporaryDir& dir) {
    if (!dir.isValid())
        return "no temporary folder";
    qputenv("XDG_CACHE_HOME", (dir.path() + "/cache").toUtf8());
    std::string error;
    return headlessContext(&error) ? std::string() : error;
}

/// A frame's linear image and the same frame's normal view (DebugView::Normal, no reflection
/// samples): the known-answer tests read each pixel's normal from the second.
struct ImageWithNormals {
    Image color, normal;
};
inline ImageWithNormals renderWithNormals(const Scene& scene, render::FrameSettings fs) {
    ImageWithNormals r;
    std::string error;
    Problems problems;
    if (!render::renderSceneOffscreen(scene, fs, &r.color, nullptr, &error, &problems))
        qFatal("render failed: %s", error.c_str());
    fs.view = render::DebugView::Normal;
    fs.reflectionSamples = 0;
    if (!render::renderSceneOffscreen(scene, fs, &r.normal, nullptr, &error, &problems))
        qFatal("render failed: %s", error.c_str());
    return r;
}

/// The largest difference of two same-sized images' RGB channels, in 1/255 steps.
inline int maxDifference(const Image& a, const Image& b) {
    int worst = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int k = 0; k < 3; ++k)
                worst = std::max(
                    worst, int(std::lround(std::abs(a.at(x, y)[k] - b.at(x, y)[k]) * 255.0f)));
    return worst;
}

/// How many pixels of two same-sized images differ by at least @p steps 255ths in a channel.
inline int differingPixels(const Image& a, const Image& b, int steps = 1) {
    int count = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool differs = false;
            for (int k = 0; k < 3; ++k)
                differs |= std::lround(std::abs(a.at(x, y)[k] - b.at(x, y)[k]) * 255.0f) >= steps;
            count += differs;
        }
    return count;
}

/// Whether two images are the same size and the same pixels, bit for bit.
inline bool samePixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels == b.pixels;
}

/// The known-answer tests' scene: an orthographic front view of the default unit sphere (each
/// pixel's normal and view direction known in closed form) under a black environment, no lights.
inline Scene blackOrthographicScene() {
    Scene scene;
    scene.camera.orthographic = true;
    scene.camera.pitchDeg = 0.0f;
    scene.camera.yawDeg = 0.0f;
    scene.environment.hdri.clear();
    scene.environment.color = glm::vec3(0.0f);
    scene.lights.clear();
    return scene;
}

/// The directional light the known-answer tests compare with the CPU twins (from the upper left,
/// in front of the sphere, warm).
/// A white material without sheen or coat: @p metallic 1 a white metal (F0 = 1), 0 a white
/// dielectric whose specular weight may be 0 (a pure Lambertian or Burley surface).
inline Material whiteMaterial(float metallic, float roughness, float specularWeight = 1.0f) {
    Material m;
    m.setColor(ParamId::BaseColor, glm::vec3(1.0f));
    m.setScalar(ParamId::Metallic, metallic);
    m.setScalar(ParamId::Roughness, roughness);
    m.setScalar(ParamId::SpecularWeight, specularWeight);
    m.setScalar(ParamId::SheenWeight, 0.0f);
    m.setScalar(ParamId::ClearcoatWeight, 0.0f);
    return m;
}

/// No lights, and a uniform environment of @p color (a white furnace for white).
inline Scene uniformEnvironmentScene(glm::vec3 color) {
    Scene scene;
    scene.lights.clear();
    scene.environment.hdri.clear();
    scene.environment.color = color;
    scene.environment.intensity = 1.0f;
    return scene;
}

inline Light analyticKeyLight() {
    Light light;
    light.type = LightType::Directional;
    light.intensity = 2.5f;
    light.color = {1.0f, 0.9f, 0.8f};
    light.direction = {-0.4f, -0.5f, -0.75f};
    return light;
}

/// Makes a resources root in @p root whose shaders/ folder is a copy (the rest links to the real
/// files) the one core::resources reads (VELVET_RESOURCES), so a test can break and mend shader
/// files. Returns the copy's shaders folder.
inline std::filesystem::path useShaderCopy(const std::filesystem::path& root) {
    namespace fs = std::filesystem;
    const fs::path real = fs::path(VELVET_SOURCE_DIR) / "resources";
    for (const auto& entry : fs::directory_iterator(real)) {
        const fs::path name = entry.path().filename();
        if (name == "shaders")
            fs::copy(entry.path(), root / name, fs::copy_options::recursive);
        else
            fs::create_directory_symlink(entry.path(), root / name);
    }
    qputenv("VELVET_RESOURCES", QByteArray::fromStdString(root.string()));
    return root / "shaders";
}

/// A whole text file (shader sources the reload tests break and mend); empty when unreadable.
inline std::string readText(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}
inline void writeText(const std::filesystem::path& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
}

} // namespace velvet::test
