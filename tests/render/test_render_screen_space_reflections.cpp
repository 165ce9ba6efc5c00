// The mesh reflected in itself: a frame at rest draws the surfaces twice on a mesh that can see
// itself, the second pass reading the first's image where its rays meet the mesh
// (FrameSettings::screenSpaceReflections, screen_space_reflection.glsl), and what the mesh's
// occlusion hides of a lobe brings the light the surface there sends back (common_occlusion.glsl's
// meshReflection). Known answers: a white furnace stays white (a white metal; a white diffuse
// ball under the stage's occlusion comes back towards white); in the dark the ball reflects only
// its own light. And the frames that must not pay for the second pass do not: the convex sphere,
// a rough lobe, a frame without reflection samples, the setting off.
#include "render/progressive_accumulation.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <vector>

using namespace velvet;

namespace {

constexpr int kSize = 96;

struct Frame {
    Image color;
    render::FramePasses passes;
};

Frame draw(const Scene& scene, render::FrameSettings fs) {
    test::OffscreenRenderer* r = test::processRenderer(kSize);
    r->renderer->setScene(scene, nullptr);
    r->renderer->finishEnvironment();
    fs.width = fs.height = kSize;
    std::string error;
    // Twice: the first frame after a scene change may not build a specialised program yet.
    for (int i = 0; i < 2; ++i)
        if (!r->renderer->render(fs, r->target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
    return {r->renderer->readLinear(), r->renderer->lastFramePasses()};
}

/// The frame's normal view (the mesh's pixels are those with a normal).
Image normalView(const Scene& scene) {
    render::FrameSettings fs;
    fs.view = render::DebugView::Normal;
    return draw(scene, fs).color;
}

/// A frame at rest: reflections sampled as the viewport's refinement samples them.
render::FrameSettings atRest(bool reflections = true) {
    render::FrameSettings fs;
    fs.reflectionSamples = render::kRefinementReflectionSamples;
    fs.reflectionSampleTotal = render::kRefinementReflectionSamples;
    fs.screenSpaceReflections = reflections;
    return fs;
}

/// The shader ball's pixels' mean RGB, sorted (the background, black in the normal view, left out).
std::vector<float> meshValues(const Image& color, const Image& normals) {
    std::vector<float> values;
    for (int y = 0; y < color.height; ++y)
        for (int x = 0; x < color.width; ++x) {
            const glm::vec4 n = normals.rgba(x, y);
            if (n.x * n.x + n.y * n.y + n.z * n.z < 0.25f)
                continue;
            const glm::vec4 c = color.rgba(x, y);
            values.push_back((c.r + c.g + c.b) / 3.0f);
        }
    std::sort(values.begin(), values.end());
    return values;
}

float percentile(const std::vector<float>& sorted, float p) {
    return sorted[size_t(p * float(sorted.size() - 1))];
}

} // namespace

class TestRenderScreenSpaceReflections : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

    /// @p material (white, F0 = 1) on the shader ball in a uniform white environment, its
    /// reflections occluded only and traced: every pixel within 2 % of 1 on average, the
    /// @p low percentile above 0.9 and none above 1.05.
    void staysWhiteInAWhiteFurnace(const Material& material, const char* what, float low) {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
        scene.mesh.kind = PreviewMeshKind::ShaderBall;
        scene.material = material;
        const Image normals = normalView(scene);
        for (bool traced : {false, true}) {
            render::FrameSettings fs = atRest(traced);
            fs.reflectionSamples = fs.reflectionSampleTotal = 64; // the lobe's own noise down
            const Frame f = draw(scene, fs);
            QCOMPARE(f.passes.screenSpaceReflections, traced);
            const std::vector<float> v = meshValues(f.color, normals);
            QVERIFY(v.size() > size_t(kSize * kSize / 5));
            double error = 0.0;
            for (float x : v)
                error += std::abs(double(x) - 1.0);
            error /= double(v.size());
            qInfo("white furnace, %s shader ball, reflections %s: mean |value - 1| %.4f, "
                  "%.2f quantile %.3f, brightest %.3f",
                  what, traced ? "traced" : "occluded only", error, double(low), percentile(v, low),
                  v.back());
            QVERIFY2(error < 0.02, qPrintable(QString::number(error)));
            QVERIFY2(percentile(v, low) > 0.9f, qPrintable(QString::number(percentile(v, low))));
            QVERIFY2(v.back() < 1.05f, qPrintable(QString::number(v.back())));
        }
    }

private slots:
    void initTestCase() {
        const std::string error = test::startWithCacheIn(m_dir);
        QVERIFY2(error.empty(), error.c_str());
    }
    void cleanupTestCase() { test::stopProcessRenderer(); }

    // A white metal (F0 = 1) in a uniform white environment reflects exactly the environment's
    // radiance however often the light bounces between its parts: every pixel of the shader ball
    // is 1, in its cavities too. With the mesh's occlusion alone the hidden part of a lobe brings
    // the light the surface there sends back (meshReflection, common_occlusion.glsl: all of it
    // for albedo 1), and the traced reflections read the first pass's white.
    void aWhiteMetalBallStaysWhiteInAWhiteFurnace() {
        staysWhiteInAWhiteFurnace(test::whiteMaterial(1.0f, 0.25f), "white metal", 0.05f);
    }

    // The same white metal under a mirror-like clearcoat (a glaze, car paint's coat): the coat
    // reflects its Fresnel share of the surroundings and the base the rest, so the furnace stays
    // white where the mesh hides the coat's lobe too. Before the coat's hidden part brought the
    // light the surface sends back (as the base's does), it was black there: the ring's underside
    // and the neck read 0.44 at the 1st percentile.
    void aCoatedWhiteBallStaysWhiteInAWhiteFurnace() {
        Material coated = test::whiteMaterial(1.0f, 0.25f);
        coated.setScalar(ParamId::ClearcoatWeight, 1.0f);
        coated.setScalar(ParamId::ClearcoatRoughness, 0.05f);
        staysWhiteInAWhiteFurnace(coated, "coated white metal", 0.01f);
    }

    // A white Lambertian ball (no specular lobe) in a white furnace under the stage's
    // screen-space occlusion, which darkens its cavities: the truth is 1 everywhere. The traced
    // diffuse light replaces that occlusion by what the rays meet (the first pass's light) and
    // the environment where they escape, so the cavities come back towards 1, and nothing
    // exceeds it.
    void aWhiteDiffuseBallComesBackTowardsWhiteUnderTheStagesOcclusion() {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(1.0f));
        scene.mesh.kind = PreviewMeshKind::ShaderBall;
        applyStageDefaults(scene.environment, PreviewMeshKind::ShaderBall);
        scene.environment.ground = GroundMode::Off;
        QVERIFY(scene.environment.ambientOcclusion);
        scene.material = test::whiteMaterial(0.0f, 0.5f, /*specularWeight=*/0.0f);
        const Image normals = normalView(scene);
        double error[2] = {0.0, 0.0};
        float brightest[2] = {0.0f, 0.0f}, low[2] = {0.0f, 0.0f};
        for (bool traced : {false, true}) {
            const Frame f = draw(scene, atRest(traced));
            QCOMPARE(f.passes.screenSpaceReflections, traced);
            const std::vector<float> v = meshValues(f.color, normals);
            for (float x : v)
                error[traced] += std::abs(double(x) - 1.0);
            error[traced] /= double(v.size());
            brightest[traced] = v.back();
            low[traced] = percentile(v, 0.05f);
        }
        qInfo("white furnace, white Lambertian shader ball under the stage's occlusion: mean "
              "|value - 1| %.4f occluded, %.4f traced; 5th percentile %.3f / %.3f; brightest "
              "%.3f / %.3f",
              error[0], error[1], low[0], low[1], brightest[0], brightest[1]);
        QVERIFY2(error[0] > 0.01, "the occlusion darkens nothing: no test");
        QVERIFY(error[1] < 0.6 * error[0]);
        QVERIFY(low[1] > low[0]);
        QVERIFY2(brightest[1] < 1.03f, qPrintable(QString::number(brightest[1])));
    }

    // In a black environment under one light the only light the traced rays can bring is the
    // mesh's own: parts of the ball that face its lit parts gain light, no pixel loses any (a miss
    // sees the black environment as before), and none gains more than the brightest lit pixel
    // (a white surface reflects at most what it meets). A white metal gains it in its
    // reflections of the highlights; a white diffuse ball, whose lit parts light every part that
    // faces them, in many more pixels.
    void inTheDarkTheBallReflectsOnlyItsOwnLight_data() {
        QTest::addColumn<float>("metallic");
        QTest::addColumn<int>("atLeastPerMille");
        QTest::newRow("white metal") << 1.0f << 10;    // 65 of 3498 pixels here
        QTest::newRow("white diffuse") << 0.0f << 100; // the pedestal under the lit ring
    }
    void inTheDarkTheBallReflectsOnlyItsOwnLight() {
        QFETCH(float, metallic);
        QFETCH(int, atLeastPerMille);
        Scene scene = test::uniformEnvironmentScene(glm::vec3(0.0f));
        scene.lights = {test::analyticKeyLight()};
        scene.mesh.kind = PreviewMeshKind::ShaderBall;
        scene.material = test::whiteMaterial(metallic, 0.25f, metallic > 0.5f ? 1.0f : 0.0f);
        const Image normals = normalView(scene);
        const Frame occluded = draw(scene, atRest(false));
        const Frame traced = draw(scene, atRest(true));
        QVERIFY(traced.passes.screenSpaceReflections);
        int mesh = 0, brighter = 0;
        float brightest = 0.0f, gain = 0.0f, loss = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const glm::vec4 n = normals.rgba(x, y);
                if (n.x * n.x + n.y * n.y + n.z * n.z < 0.25f)
                    continue;
                ++mesh;
                const glm::vec4 a = occluded.color.rgba(x, y), b = traced.color.rgba(x, y);
                const float before = (a.r + a.g + a.b) / 3.0f, after = (b.r + b.g + b.b) / 3.0f;
                brightest = std::max(brightest, before);
                gain = std::max(gain, after - before);
                loss = std::max(loss, before - after);
                brighter += after > before + 0.01f;
            }
        qInfo("black environment, key light: %d of %d mesh pixels brighter with the light traced; "
              "largest gain %.3f (brightest lit pixel %.3f), largest loss %.5f",
              brighter, mesh, gain, brightest, loss);
        QVERIFY(brighter * 1000 > mesh * atLeastPerMille);
        QVERIFY2(loss < 1e-3f, qPrintable(QString::number(loss)));
        QVERIFY(gain <= brightest);
    }

    // The editor's refinement: its first frame draws the first pass, each later one reads the
    // light of the frame before (one more bounce, no first pass); a frame outside the mean in
    // between (a grab, an edit's frame) makes the next draw its own again.
    void aRefinementsLaterFramesReadTheFrameBefore() {
        Scene scene = test::uniformEnvironmentScene(glm::vec3(0.2f));
        scene.lights = {test::analyticKeyLight()};
        scene.mesh.kind = PreviewMeshKind::ShaderBall;
        scene.material = test::whiteMaterial(1.0f, 0.25f);
        test::OffscreenRenderer* r = test::processRenderer(kSize);
        draw(scene, atRest()); // the scene set and its programs built
        auto refine = [&](int index) {
            render::FrameSettings fs = atRest();
            fs.width = fs.height = kSize;
            fs.accumulation = index;
            fs.jitter = render::progressiveJitter(index);
            fs.reflectionSampleTotal = render::kRefinementReflectionSamples * 16;
            fs.reflectionSampleSet = index;
            std::string error;
            if (!r->renderer->render(fs, r->target->framebuffer(), &error))
                qFatal("render failed: %s", error.c_str());
            return r->renderer->lastFramePasses();
        };
        for (int k = 0; k < 4; ++k) {
            const render::FramePasses p = refine(k);
            QVERIFY(p.screenSpaceReflections);
            QCOMPARE(p.reflectionSourceReused, k > 0);
        }
        draw(scene, atRest()); // a plain frame between
        QVERIFY(!refine(4).reflectionSourceReused);
        QVERIFY(refine(5).reflectionSourceReused);
    }

    // Only frames at rest on a mesh that can see itself draw the surfaces twice.
    void framesThatCannotUseThemDrawTheSurfacesOnce() {
        Scene ball = test::uniformEnvironmentScene(glm::vec3(1.0f));
        ball.mesh.kind = PreviewMeshKind::ShaderBall;
        ball.material = test::whiteMaterial(1.0f, 0.25f);
        Scene sphere = ball;
        sphere.mesh.kind = PreviewMeshKind::Sphere;
        Scene rough = ball;
        rough.material = test::whiteMaterial(1.0f, 0.9f);

        const Frame convex = draw(sphere, atRest());
        QVERIFY(!convex.passes.screenSpaceReflections);
        // A rough lobe traces no reflection but its diffuse light: drawn twice.
        QVERIFY(draw(rough, atRest()).passes.screenSpaceReflections);
        QVERIFY(!draw(ball, render::FrameSettings{}).passes.screenSpaceReflections);
        // A frame of the editor that reads only the display image keeps its display step inside
        // the lighting pass, unless it reflects the mesh (which needs the linear image).
        render::FrameSettings display = atRest();
        display.displayOnly = true;
        QVERIFY(draw(ball, display).passes.screenSpaceReflections);
        display.screenSpaceReflections = false;
        const Frame plain = draw(ball, display);
        QVERIFY(!plain.passes.screenSpaceReflections);
    }
};

QTEST_GUILESS_MAIN(TestRenderScreenSpaceReflections)
#include "test_render_screen_space_reflections.moc"
