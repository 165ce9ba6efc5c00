// Image-based lighting: what each case proves is stated on the case. Small cubemaps (the test
// environment is 128 x 64, so faces of 32 texels) keep the whole file to a few seconds on llvmpipe.
#include "core/diffuse_albedo.h"
#include "core/ibl.h"
#include "core/image.h"
#include "core/resources.h"
#include "core/spherical_harmonics.h"
#include "render/camera.h"
#include "render/environment_map.h"
#include "render/ibl_bake.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

struct Frame {
    Image linear, depth;
};

Frame renderScene(const Scene& scene, int size, render::FrameSettings fs = {}) {
    fs.width = fs.height = size;
    Frame f;
    std::string error;
    Problems problems;
    if (!render::renderSceneOffscreen(scene, fs, &f.linear, nullptr, &error, &problems))
        qFatal("render failed: %s", error.c_str());
    for (const Problem& p : problems.items)
        qWarning("%s", p.toString().c_str());
    fs.view = render::DebugView::Depth;
    if (!render::renderSceneOffscreen(scene, fs, &f.depth, nullptr, &error, &problems))
        qFatal("render failed: %s", error.c_str());
    return f;
}

bool onSphere(const Frame& f, int x, int y) {
    return f.depth.rgba(x, y).x > 0.0f;
}

/// Mean of the sphere's pixels (all channels).
double sphereMean(const Frame& f, int* count = nullptr) {
    double sum = 0.0;
    int n = 0;
    for (int y = 0; y < f.linear.height; ++y)
        for (int x = 0; x < f.linear.width; ++x)
            if (onSphere(f, x, y)) {
                const glm::vec4 c = f.linear.rgba(x, y);
                sum += (c.x + c.y + c.z) / 3.0;
                ++n;
            }
    if (count)
        *count = n;
    return n ? sum / n : 0.0;
}

/// A test environment whose radiance depends on the direction's x and y only (not z): a checker
/// on a gradient that is brighter towards +X. Rotating it by 180 degrees about Y, (x, z) ->
/// (-x, -z), therefore mirrors it in x.
std::string writeTestEnvironment(const QString& dir) {
    Image img(128, 64, 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const glm::vec3 d =
                equirectDirection((float(x) + 0.5f) / img.width, (float(y) + 0.5f) / img.height);
            const float checker =
                (std::sin(9.0f * d.x) * std::sin(9.0f * d.y) > 0.0f) ? 1.0f : 0.2f;
            float* p = img.at(x, y);
            p[0] = checker * (1.2f + d.x);
            p[1] = checker * (0.8f + 0.5f * d.y);
            p[2] = checker * (1.2f - 0.8f * d.x);
        }
    const std::string path = (dir + "/xy_environment.exr").toStdString();
    std::string error;
    if (!writeImage(path, img, PixelFormat::Half, &error))
        qFatal("cannot write the test environment: %s", error.c_str());
    return path;
}

} // namespace

class TestRenderIbl : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    std::string m_envPath;

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        // A fresh LUT cache: this process makes the DFG LUT on the GPU and writes it there.
        qputenv("XDG_CACHE_HOME", (m_dir.path() + "/cache").toUtf8());
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_envPath = writeTestEnvironment(m_dir.path());
    }

    // IblBaker reports the compute programs it builds (Renderer::shaderCompileCount adds its
    // count): one per ibl_*.comp shader the bake uses, at initialize() and again at reload().
    void compileCountIsWhatIsBuilt() {
        int files = 0;
        for (const auto& e : std::filesystem::directory_iterator(
                 std::filesystem::path(VELVET_SOURCE_DIR) / "resources/shaders")) {
            const std::string name = e.path().filename().string();
            files += name.rfind("ibl_", 0) == 0 && e.path().extension() == ".comp";
        }
        QCOMPARE(files, 4); // equirect to cube, downsample, prefilter, DFG
        render::IblBaker baker;
        QCOMPARE(baker.compileCount(), 0);
        std::string error;
        QVERIFY2(baker.initialize(&error), error.c_str());
        QCOMPARE(baker.compileCount(), files);
        int rebuilt = 0;
        QVERIFY2(baker.reload(&error, &rebuilt), error.c_str());
        QCOMPARE(rebuilt, files);
        QCOMPARE(baker.compileCount(), 2 * files);
    }

    // The DFG LUT made on the GPU (Hammersley importance sampling, ibl_dfg.comp) matches an
    // independent CPU integration (a double-precision product rule, core/ibl.cpp) within 1 % at
    // sampled texels, and the CPU twin of the GPU algorithm within 1e-3. A second baker reads the
    // LUT back from the disk cache without running a slice.
    void dfgLutMatchesCpuIntegration() {
        render::IblBaker baker;
        std::string error;
        QVERIFY2(baker.initialize(&error), error.c_str());
        QVERIFY(!baker.dfgReady());
        baker.finish();
        QVERIFY(baker.dfgReady());
        QVERIFY(baker.stats().slices > 1);
        const std::vector<glm::vec2> lut = baker.readDfgLut();
        constexpr int N = ibl::kDfgLutSize;
        double worstRel = 0.0, worstTwin = 0.0;
        QString where;
        int checked = 0;
        for (int j = 0; j < N; j += 7)
            for (int i = 0; i < N; i += 5) {
                const glm::vec2 p = ibl::dfgTexelParams(i, j);
                const glm::vec2 ref = ibl::integrateDfgQuadrature(p.x, p.y);
                const glm::vec2 gpu = lut[size_t(j) * N + i];
                const glm::vec2 twin = ibl::integrateDfg(p.x, p.y);
                // Relative to the albedo E = A + B (the quantity shading uses): B alone is tiny
                // at normal incidence and a relative error of it means nothing.
                const double scale = std::max(double(ref.x + ref.y), 1e-3);
                const double rel =
                    std::max(std::abs(gpu.x - ref.x), std::abs(gpu.y - ref.y)) / scale;
                if (rel > worstRel) {
                    worstRel = rel;
                    where = QString("n.v %1 roughness %2: GPU (%3, %4), CPU (%5, %6)")
                                .arg(p.x)
                                .arg(p.y)
                                .arg(gpu.x)
                                .arg(gpu.y)
                                .arg(ref.x)
                                .arg(ref.y);
                }
                worstTwin = std::max(worstTwin, double(glm::length(gpu - twin)));
                ++checked;
            }
        qInfo("DFG LUT %dx%d, %d samples: %d texels, worst error vs CPU quadrature %.4f %% of "
              "A + B (%s); worst |GPU - CPU twin| %.2e; made in %d slices, worst %.1f ms",
              N, N, ibl::kDfgLutSamples, checked, 100.0 * worstRel, qPrintable(where), worstTwin,
              baker.stats().slices, baker.stats().worstSliceMs);
        QVERIFY2(worstRel <= 0.01, qPrintable(where));
        QVERIFY2(worstTwin <= 1e-3, qPrintable(QString::number(worstTwin)));

        QVERIFY(std::filesystem::exists(render::IblBaker::dfgCacheFile()));
        render::IblBaker cached;
        QVERIFY2(cached.initialize(&error), error.c_str());
        QVERIFY(cached.dfgReady());
        QCOMPARE(cached.progress(), 1.0f);
        QVERIFY(cached.readDfgLut() == lut);
    }

    // A uniform environment prefilters to the same uniform value in every level and face (±1 %):
    // the importance-sampled GGX convolution is normalised and the PDF-based source mips of a
    // constant are that constant.
    void uniformEnvironmentPrefiltersToItself() {
        const glm::vec3 c(0.8f, 0.5f, 0.25f);
        render::EnvironmentCache cache;
        Environment env;
        env.color = c;
        const render::GpuEnvironment& gpu = cache.get(env, nullptr);
        render::IblBaker baker;
        std::string error;
        QVERIFY2(baker.initialize(&error), error.c_str());
        render::IblBakeOptions options;
        options.faceSize = 64;
        baker.setOptions(options);
        baker.request(gpu);
        baker.finish();
        QVERIFY(baker.specularReady());
        QCOMPARE(baker.faceSize(), 64);
        double worst = 0.0;
        for (int level = 0; level < baker.specularLevels(); ++level)
            for (int face = 0; face < 6; ++face) {
                const Image img = baker.readSpecularFace(level, face);
                QVERIFY(img.width == std::max(64 >> level, 1));
                for (int y = 0; y < img.height; ++y)
                    for (int x = 0; x < img.width; ++x)
                        for (int k = 0; k < 3; ++k)
                            worst =
                                std::max(worst, std::abs(double(img.rgba(x, y)[k]) / c[k] - 1.0));
            }
        qInfo("uniform environment: %d levels x 6 faces, worst relative deviation %.4f %%",
              baker.specularLevels(), 100.0 * worst);
        QCOMPARE(baker.specularLevels(), 6);
        QVERIFY2(worst <= 0.01, qPrintable(QString::number(worst)));
    }

    // White furnace. A white Lambertian sphere (metallic 0, specular weight 0) under a uniform
    // white environment is 1.0 ± 2 %. Then the specular lobe alone (a white metal): the energy the
    // single-scattering split sum loses on rough surfaces is reported (not hidden), with and
    // without Fdez-Agüera 2019's multiple-scattering compensation; with it the furnace is white.
    void whiteFurnace() {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
        scene.material = test::whiteMaterial(0.0f, 0.5f, 0.0f);
        const Frame lambert = renderScene(scene, 96);
        int count = 0;
        double worst = 0.0;
        for (int y = 0; y < 96; ++y)
            for (int x = 0; x < 96; ++x)
                if (onSphere(lambert, x, y))
                    for (int k = 0; k < 3; ++k) {
                        worst =
                            std::max(worst, std::abs(double(lambert.linear.rgba(x, y)[k]) - 1.0));
                        ++count;
                    }
        qInfo("white furnace, white Lambert: %d values, worst |value - 1| = %.4f", count, worst);
        QVERIFY(count > 1000);
        QVERIFY2(worst <= 0.02, qPrintable(QString::number(worst)));

        for (float rough : {0.25f, 0.5f, 0.75f, 1.0f}) {
            scene.material = test::whiteMaterial(1.0f, rough, 1.0f);
            render::FrameSettings fs;
            fs.specularMultiScatter = false;
            const double single = sphereMean(renderScene(scene, 64, fs));
            fs.specularMultiScatter = true;
            const double multi = sphereMean(renderScene(scene, 64, fs));
            // The expectation from the CPU twin at normal incidence, for the record.
            const glm::vec2 ab = ibl::integrateDfg(1.0f, rough);
            qInfo("white furnace, white metal roughness %.2f: sphere mean %.4f single scattering "
                  "(loses %.1f %%; A + B at n.v = 1: %.4f), %.4f with multiple scattering "
                  "(restores %.1f %% of the light)",
                  rough, single, 100.0 * (1.0 - single), ab.x + ab.y, multi,
                  100.0 * (multi - single));
            QVERIFY(single < 1.0);
            QVERIFY2(std::abs(multi - 1.0) <= 0.02, qPrintable(QString::number(multi)));
        }
        // A white dielectric with its specular on: diffuse takes what the specular leaves.
        scene.material = test::whiteMaterial(0.0f, 0.8f, 1.0f);
        const double dielectric = sphereMean(renderScene(scene, 64));
        qInfo("white furnace, white dielectric with specular, roughness 0.8: %.4f", dielectric);
        QVERIFY(std::abs(dielectric - 1.0) <= 0.02);
    }

    // White furnace of the chosen diffuse term (issue 15): a white Burley sphere with no specular
    // (metallic 0, specular weight 0) under a uniform white environment, orthographic, so every
    // pixel's value is Burley's directional albedo at its n.v and the roughness: the integral
    // (brdf::integrateDiffuseAlbedo, checked against a closed form in test_core_diffuse_albedo)
    // within 2 %, the Lambert furnace's tolerance above, for n.v from 0.05 to 1 at roughness 0,
    // 0.5 and 1. The image-based light used to give Burley Lambert's albedo, 1: the pixels checked
    // include ones where that is more than 10 % off.
    void burleyWhiteFurnace() {
        Scene scene = test::blackOrthographicScene();
        scene.environment.color = glm::vec3(1.0f);
        scene.environment.intensity = 1.0f;
        const glm::vec3 v = glm::normalize(render::cameraEye(scene.camera) - scene.camera.target);
        constexpr int size = 64;
        render::FrameSettings fs;
        fs.width = fs.height = size;
        double worstLambertOverall = 0.0;
        for (float rough : {0.0f, 0.5f, 1.0f}) {
            scene.material = test::whiteMaterial(0.0f, rough, 0.0f);
            scene.material.setChoice(ParamId::Diffuse, int(Diffuse::Burley));
            Image image, normals;
            std::string error;
            fs.view = render::DebugView::Final;
            QVERIFY2(render::renderSceneOffscreen(scene, fs, &image, nullptr, &error),
                     error.c_str());
            fs.view = render::DebugView::Normal;
            QVERIFY2(render::renderSceneOffscreen(scene, fs, &normals, nullptr, &error),
                     error.c_str());
            int count = 0;
            double worst = 0.0, worstLambert = 0.0, worstMu = 0.0;
            double lowest = 10.0, highest = 0.0;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const glm::vec3 n(normals.rgba(x, y));
                    if (glm::length(n) < 0.5f)
                        continue; // background
                    const float mu = glm::dot(glm::normalize(n), v);
                    if (mu < 0.05f)
                        continue; // the silhouette's pixels
                    const double expected =
                        brdf::integrateDiffuseAlbedo(Diffuse::Burley, mu, rough, 48, 24);
                    lowest = std::min(lowest, expected);
                    highest = std::max(highest, expected);
                    worstLambert = std::max(worstLambert, std::abs(1.0 / expected - 1.0));
                    for (int k = 0; k < 3; ++k) {
                        const double rel = std::abs(double(image.rgba(x, y)[k]) / expected - 1.0);
                        if (rel > worst) {
                            worst = rel;
                            worstMu = mu;
                        }
                    }
                    ++count;
                }
            qInfo(
                "white furnace, white Burley, roughness %.1f: %d pixels, albedo %.3f..%.3f; "
                "worst relative error %.2f %% (at n.v %.2f); Lambert's albedo would be %.1f %% off",
                rough, count, lowest, highest, 100.0 * worst, worstMu, 100.0 * worstLambert);
            QVERIFY(count > 1000);
            QVERIFY2(worst <= 0.02, qPrintable(QString::number(worst)));
            worstLambertOverall = std::max(worstLambertOverall, worstLambert);
        }
        QVERIFY(worstLambertOverall > 0.10); // the check can tell Burley from Lambert
    }

    // Rotating the environment by 180 degrees mirrors the lit image of a shiny metal sphere seen
    // along -Z horizontally, for an environment that does not depend on z (see
    // writeTestEnvironment): rotation (x, z) -> (-x, -z) equals the mirror x -> -x there.
    void rotationMirrorsImage() {
        Scene scene;
        scene.lights.clear();
        scene.environment.hdri = m_envPath;
        scene.camera.orthographic = true;
        scene.camera.yawDeg = 0.0f;
        scene.camera.pitchDeg = 0.0f;
        scene.material = test::whiteMaterial(1.0f, 0.15f, 1.0f);
        const int size = 96;
        const Frame a = renderScene(scene, size);
        scene.environment.rotationDeg = 180.0f;
        const Frame b = renderScene(scene, size);
        double diffMirror = 0.0, diffPlain = 0.0;
        int n = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const int xm = size - 1 - x;
                if (!onSphere(a, x, y) || !onSphere(a, xm, y) || !onSphere(b, x, y))
                    continue;
                const glm::vec3 ca(a.linear.rgba(xm, y)), cb(b.linear.rgba(x, y)),
                    c0(a.linear.rgba(x, y));
                diffMirror += glm::length(cb - ca);
                diffPlain += glm::length(cb - c0);
                ++n;
            }
        diffMirror /= n;
        diffPlain /= n;
        qInfo("rotation 180: mean |rotated - mirrored| %.4f, mean |rotated - unrotated| %.4f over "
              "%d pixels",
              diffMirror, diffPlain, n);
        QVERIFY(n > 2000);
        QVERIFY(diffPlain > 0.1);
        QVERIFY2(diffMirror < 0.05 * diffPlain, qPrintable(QString::number(diffMirror)));
    }

    // Each background mode shows its defining property: solid = the colour exactly; blurred has a
    // lower variance than sharp; FBM is the same for a fixed time and changes with time.
    void backgroundModes() {
        Scene scene;
        scene.lights.clear();
        scene.environment.hdri = m_envPath;
        scene.camera.fovYDeg = 90.0f;
        const int size = 64;
        auto background = [&](BackgroundMode mode, float time) {
            scene.environment.background = mode;
            render::FrameSettings fs;
            fs.time = time;
            const Frame f = renderScene(scene, size, fs);
            std::vector<glm::vec3> px;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x)
                    if (!onSphere(f, x, y))
                        px.push_back(glm::vec3(f.linear.rgba(x, y)));
            return px;
        };
        auto variance = [](const std::vector<glm::vec3>& px) {
            glm::dvec3 mean(0.0), sq(0.0);
            for (const glm::vec3& c : px) {
                mean += glm::dvec3(c);
                sq += glm::dvec3(c) * glm::dvec3(c);
            }
            mean /= double(px.size());
            const glm::dvec3 v = sq / double(px.size()) - mean * mean;
            return (v.x + v.y + v.z) / 3.0;
        };
        auto meanDiff = [](const std::vector<glm::vec3>& p, const std::vector<glm::vec3>& q) {
            double d = 0.0;
            for (size_t i = 0; i < p.size(); ++i)
                d += glm::length(p[i] - q[i]);
            return d / double(p.size());
        };

        scene.environment.backgroundColor = {0.25f, 0.5f, 0.75f};
        const auto solid = background(BackgroundMode::SolidColor, 0.0f);
        QVERIFY(solid.size() > 1000);
        for (const glm::vec3& c : solid)
            QVERIFY(c == glm::vec3(0.25f, 0.5f, 0.75f));

        const double sharp = variance(background(BackgroundMode::Sharp, 0.0f));
        const double blurred = variance(background(BackgroundMode::Blurred, 0.0f));
        qInfo("background variance: sharp %.4f, blurred %.4f", sharp, blurred);
        QVERIFY(blurred < 0.5 * sharp);

        const auto fbm1 = background(BackgroundMode::ProceduralFbm, 1.0f);
        const auto fbm1again = background(BackgroundMode::ProceduralFbm, 1.0f);
        const auto fbm5 = background(BackgroundMode::ProceduralFbm, 5.0f);
        const double change = meanDiff(fbm1, fbm5);
        qInfo("FBM background: variance %.5f, mean change from t = 1 s to 5 s %.4f", variance(fbm1),
              change);
        QVERIFY(fbm1 == fbm1again);
        QVERIFY(change > 0.01);
        QVERIFY(variance(fbm1) > 1e-4);
    }

    // The bake runs in slices: a renderer asked for frames reports progress that only grows and
    // reaches 1, needs more than one slice, and frames drawn before completion succeed (the
    // approximate path). No time is asserted (DESIGN.md, "Measuring": llvmpipe on a shared
    // machine): what bounds a slice is its work, which sliceWorkIsBounded() asserts against
    // IblBakeOptions::maxSliceUnits. The worst slice and the worst frame's bake time are logged
    // against the 50 ms a window may freeze.
    void slicedBakeWithProgress() {
        render::Renderer renderer;
        std::string error;
        QVERIFY2(renderer.initialize(&error), error.c_str());
        render::OffscreenTarget target;
        QVERIFY2(target.resize(32, 32, &error), error.c_str());
        render::FrameSettings fs;
        fs.width = fs.height = 32;
        Scene scene;
        scene.environment.hdri = resources::path("hdri/studio.exr").string();
        renderer.setScene(scene);
        const render::Renderer::EnvironmentBakeStats before = renderer.environmentBakeStats();
        float last = renderer.environmentProgress();
        QVERIFY(last < 1.0f);
        int frames = 0;
        double worstFrameIbl = 0.0;
        while (renderer.environmentProgress() < 1.0f && frames < 2000) {
            QVERIFY2(renderer.render(fs, target.framebuffer(), &error), error.c_str());
            const float p = renderer.environmentProgress();
            QVERIFY(p >= last);
            last = p;
            worstFrameIbl = std::max(worstFrameIbl, renderer.lastTimings().iblMs);
            ++frames;
        }
        QCOMPARE(renderer.environmentProgress(), 1.0f);
        const render::Renderer::EnvironmentBakeStats s = renderer.environmentBakeStats();
        qInfo("llvmpipe shader warm-up: %.1f ms over %d frames, worst warm-up frame %.1f ms",
              s.warmUpMs, s.warmUpFrames, s.worstWarmUpFrameMs);
        // The warm-up is itself sliced (about one program's machine-code compile per frame): more
        // than one frame. Its times are logged, not asserted (DESIGN.md, "Measuring").
        QVERIFY(s.warmUpFrames > 1);
        const int slices = s.slices - before.slices;
        const double target8 = render::IblBakeOptions{}.sliceTargetMs;
        auto within50 = [](double ms) { return ms <= 50.0 ? "within" : "OVER"; };
        qInfo("studio.exr bake: %d frames, %d slices, %.1f ms in all; worst slice %.1f ms (target "
              "%.1f ms; 50 ms window-freeze limit: %s); worst frame's bake time %.1f ms, "
              "including the llvmpipe shader warm-up (worst warm-up frame %.1f ms; limit: %s)",
              frames, slices, s.totalMs - before.totalMs, s.worstSliceMs, target8,
              within50(s.worstSliceMs), worstFrameIbl, s.worstWarmUpFrameMs,
              within50(worstFrameIbl));
        QVERIFY(frames > 1);
        QVERIFY(slices > 1);
        // What bounds a slice's time is its work, asserted by sliceWorkIsBounded() below.
    }

    // Every slice of a full-size bake (studio.exr: 256-texel faces, 64 samples per texel) does at
    // most IblBakeOptions::maxSliceUnits texel-samples, however the cost model estimates; the
    // largest jobs are therefore split over several slices, and stepping with the renderer's
    // per-frame budget makes many frames. Times (worst slice, worst frame) are logged only.
    void sliceWorkIsBounded() {
        render::EnvironmentCache cache;
        Environment env;
        env.hdri = resources::path("hdri/studio.exr").string();
        const render::GpuEnvironment& gpu = cache.get(env, nullptr);
        render::IblBaker baker;
        std::string error;
        QVERIFY2(baker.initialize(&error), error.c_str());
        const render::IblBakeOptions options = baker.options();
        baker.request(gpu);
        int frames = 0, warmUpFrames = 0;
        double worstFrameMs = 0.0;
        while (frames < 20000) {
            const auto t0 = std::chrono::steady_clock::now();
            const bool done = baker.step(12.0); // the renderer's per-frame budget
            const double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            ++frames;
            if (baker.warmUpFrames() > warmUpFrames)
                warmUpFrames = baker.warmUpFrames(); // a shader warm-up frame, logged apart
            else
                worstFrameMs = std::max(worstFrameMs, ms);
            if (done)
                break;
        }
        QVERIFY(baker.specularReady());
        const render::IblBakeStats& s = baker.stats();
        const long texelSamplesPerFace = long(baker.faceSize() / 2) * (baker.faceSize() / 2) *
                                         options.samples; // prefiltered level 1, one face
        qInfo("studio.exr, face %d: %d frames (%d warm-up, worst %.1f ms), %d slices, worst slice "
              "%.0f units (cap %.0f; level 1 face %ld) in %.1f ms, worst bake frame %.1f ms",
              baker.faceSize(), frames, warmUpFrames, baker.worstWarmUpFrameMs(), s.slices,
              s.worstSliceUnits, options.maxSliceUnits, texelSamplesPerFace, s.worstSliceMs,
              worstFrameMs);
        QCOMPARE(baker.faceSize(), 256);
        QVERIFY(s.worstSliceUnits > 0.0);
        QVERIFY2(s.worstSliceUnits <= options.maxSliceUnits,
                 qPrintable(QString("a slice did %1 units").arg(s.worstSliceUnits)));
        // The largest job alone needs several slices at the cap.
        QVERIFY(double(texelSamplesPerFace) > 2.0 * options.maxSliceUnits);
        QVERIFY(s.slices > 6 * baker.specularLevels());
    }
};

QTEST_GUILESS_MAIN(TestRenderIbl)
#include "test_render_ibl.moc"
