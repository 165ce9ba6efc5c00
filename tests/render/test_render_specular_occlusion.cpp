// The mesh's visibility from itself through the real pipeline (render/mesh_visibility.h baked by
// the mesh cache, the vertex attribute, gbuffer.frag's cone intersection into the G-buffer's
// specular occlusion channel, the Specular occlusion debug view): a convex mesh has none and
// reads exactly 1 everywhere; the shader ball reads 1 where a smooth reflection sees only the
// sky (the top of its ball, seen from above) and well below 1 where it looks into the mesh (under
// the ring, at the pedestal's neck); a wide lobe on the open top is not occluded even where it
// reaches below the horizon at the silhouette. Under a uniform environment a black
// dielectric's pixel is its unoccluded specular albedo (the sphere's at the same normal) times
// the view's factor, and the hidden rest the light its own surface sends back: the factor
// reaches the lighting.
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QElapsedTimer>
#include <QtTest>
#include <algorithm>
#include <glm/geometric.hpp>
#include <memory>
#include <vector>

using namespace velvet;

namespace {

Image draw(const Scene& scene, render::DebugView view) {
    Problems problems;
    Image image = test::processRenderer(96)->draw(&scene, view, &problems);
    for (const Problem& p : problems.items)
        qWarning("%s", p.toString().c_str());
    return image;
}

/// A uniform white environment (no screen-space occlusion, no lights), the orthographic camera
/// looking down at 30 degrees on @p mesh, a black glossy dielectric: its image-based light is
/// its specular term alone.
Scene uniformScene(PreviewMeshKind mesh, float roughness) {
    Scene scene = test::blackOrthographicScene();
    scene.mesh.kind = mesh;
    scene.camera.pitchDeg = 30.0f;
    scene.environment.color = glm::vec3(1.0f);
    scene.environment.intensity = 1.0f;
    scene.environment.ambientOcclusion = false;
    scene.material.setColor(ParamId::BaseColor, glm::vec3(0.0f));
    scene.material.setScalar(ParamId::Metallic, 0.0f);
    scene.material.setScalar(ParamId::Roughness, roughness);
    scene.material.setScalar(ParamId::SheenWeight, 0.0f);
    scene.material.setScalar(ParamId::ClearcoatWeight, 0.0f);
    return scene;
}

struct Coverage {
    int pixels = 0, occluded = 0, open = 0;
    float least = 1.0f;
    double sum = 0.0;
};

/// The specular occlusion view over the mesh's pixels (those with a normal).
Coverage measure(const Image& occlusion, const Image& normal) {
    Coverage c;
    for (int y = 0; y < occlusion.height; ++y)
        for (int x = 0; x < occlusion.width; ++x) {
            if (glm::length(glm::vec3(normal.rgba(x, y))) < 0.5f)
                continue;
            const float o = occlusion.rgba(x, y).r;
            ++c.pixels;
            c.sum += o;
            c.least = std::min(c.least, o);
            c.occluded += o < 0.5f;
            c.open += o > 0.99f;
        }
    return c;
}

} // namespace

class TestRenderSpecularOcclusion : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        if (!test::headlessContext(&error))
            QSKIP(qPrintable("no headless GL context: " + QString::fromStdString(error)));
    }

    void convexMeshIsNeverOccluded() {
        const Scene scene = uniformScene(PreviewMeshKind::Sphere, 0.1f);
        const Coverage c = measure(draw(scene, render::DebugView::SpecularOcclusion),
                                   draw(scene, render::DebugView::Normal));
        QVERIFY(c.pixels > 2000);
        QCOMPARE(c.least, 1.0f);
    }

    void shaderBallOccludesWhereItSeesItself() {
        const Scene scene = uniformScene(PreviewMeshKind::ShaderBall, 0.1f);
        const Image occlusion = draw(scene, render::DebugView::SpecularOcclusion);
        const Image normal = draw(scene, render::DebugView::Normal);
        const Coverage c = measure(occlusion, normal);
        qInfo("%d pixels: %d below 0.5, %d above 0.99, least %.3f", c.pixels, c.occluded, c.open,
              double(c.least));
        QVERIFY(c.pixels > 1000);
        QVERIFY2(c.occluded > c.pixels / 50, "the cavities are not occluded");
        QVERIFY2(c.open > c.pixels / 4, "the open parts are occluded");
        QVERIFY(c.least < 0.2f);
        // The top of the ball (the mesh's highest points, above the ring) reflects the sky:
        // open. (The ring's flat top faces up too, but the ball overhangs it; at the top's
        // silhouette a grazing lobe reaches past the open cone's rim, partly occluded.)
        const Image position = draw(scene, render::DebugView::Position);
        // Every pixel of the ball's top (front-facing ones only with @p frontOnly) open in
        // @p view; how many there are.
        const auto checkTopOpen = [&](const Image& view, bool frontOnly) {
            int count = 0;
            for (int y = 0; y < normal.height; ++y)
                for (int x = 0; x < normal.width; ++x) {
                    const glm::vec4 n = normal.rgba(x, y);
                    if (glm::length(glm::vec3(n)) < 0.5f || position.rgba(x, y).y <= 0.85f ||
                        (frontOnly && n.z <= 0.3f))
                        continue;
                    ++count;
                    if (view.rgba(x, y).r <= 0.97f) {
                        qWarning("top pixel %d,%d: %f", x, y, double(view.rgba(x, y).r));
                        return -1;
                    }
                }
            return count;
        };
        const int top = checkTopOpen(occlusion, true);
        QVERIFY(top > 20);
        // A wide lobe on the open top, silhouette included: its part below the horizon is not
        // occlusion, so an open vertex occludes none of it.
        const Image rough = draw(uniformScene(PreviewMeshKind::ShaderBall, 0.8f),
                                 render::DebugView::SpecularOcclusion);
        QVERIFY(checkTopOpen(rough, false) > top);
    }

    void finalImageDarkensByTheFactor() {
        // Under the uniform environment a black dielectric's pixel is its specular albedo, a
        // function of n.v alone, times the factor, plus what the hidden part reflects back. The
        // sphere, which has no factor, gives the albedo per n.v (its centre pixel's normal is the
        // orthographic view direction); each shader ball pixel must be that albedo at its n.v times
        // its factor from the view.
        const Scene sphere = uniformScene(PreviewMeshKind::Sphere, 0.1f);
        const Image sphereNormal = draw(sphere, render::DebugView::Normal);
        const Image sphereFinal = draw(sphere, render::DebugView::Final);
        const glm::vec3 v = glm::normalize(
            glm::vec3(sphereNormal.rgba(sphereNormal.width / 2, sphereNormal.height / 2)));
        constexpr int kBins = 64;
        const auto bin = [&](glm::vec3 n) {
            return std::clamp(int(glm::dot(glm::normalize(n), v) * kBins), 0, kBins - 1);
        };
        std::vector<double> albedo(kBins, 0.0);
        std::vector<int> count(kBins, 0);
        for (int y = 0; y < sphereFinal.height; ++y)
            for (int x = 0; x < sphereFinal.width; ++x) {
                const glm::vec3 n = glm::vec3(sphereNormal.rgba(x, y));
                if (glm::length(n) < 0.5f)
                    continue;
                albedo[size_t(bin(n))] += sphereFinal.rgba(x, y).g;
                ++count[size_t(bin(n))];
            }

        const Scene ball = uniformScene(PreviewMeshKind::ShaderBall, 0.1f);
        const Image occlusion = draw(ball, render::DebugView::SpecularOcclusion);
        const Image normal = draw(ball, render::DebugView::Normal);
        const Image final = draw(ball, render::DebugView::Final);
        int compared = 0, agree = 0, occludedAgree = 0, occluded = 0;
        for (int y = 0; y < final.height; ++y)
            for (int x = 0; x < final.width; ++x) {
                const glm::vec3 n = glm::vec3(normal.rgba(x, y));
                // Silhouette pixels mix the mesh with the background; grazing bins are sparse.
                if (glm::length(n) < 0.5f || glm::dot(glm::normalize(n), v) < 0.2f ||
                    count[size_t(bin(n))] < 3)
                    continue;
                // What the factor hides brings the light the black surface there sends back:
                // its albedo a of the white surroundings, through the series of
                // common_occlusion.glsl's meshReflection (open share 0.5).
                const double a = albedo[size_t(bin(n))] / count[size_t(bin(n))];
                const double f = occlusion.rgba(x, y).r;
                const double expected = a * (f + (1.0 - f) * a * 0.5 / (1.0 - 0.5 * a));
                const bool close = std::abs(final.rgba(x, y).g - expected) < 0.1 * expected + 0.003;
                ++compared;
                agree += close;
                if (occlusion.rgba(x, y).r < 0.7f) {
                    ++occluded;
                    occludedAgree += close;
                }
            }
        qInfo("%d of %d pixels agree (%d of %d occluded ones)", agree, compared, occludedAgree,
              occluded);
        QVERIFY(compared > 500 && occluded > 20);
        QVERIFY(agree > compared * 0.9);
        QVERIFY(occludedAgree > occluded * 0.9);
    }

    // The editor's asynchronous bake: frames draw while it runs (the ball without occlusion),
    // and once a frame adopts it the image is the synchronous bake's, to the bit.
    void asyncBakeEndsInTheSameImage() {
        const Scene scene = uniformScene(PreviewMeshKind::ShaderBall, 0.1f);
        const Image synchronous = draw(scene, render::DebugView::Final);
        test::OffscreenRenderer async;
        QVERIFY2(async.start(96).empty(), "second renderer");
        async.renderer->setAsyncMeshBake(true);
        Problems problems;
        async.renderer->setScene(scene, &problems);
        QElapsedTimer clock;
        clock.start();
        int frames = 0;
        do {
            async.draw(nullptr, render::DebugView::Final);
            ++frames;
        } while (async.renderer->meshBakePending() && clock.elapsed() < 20000);
        QVERIFY(!async.renderer->meshBakePending());
        qInfo("bake adopted after %d frames", frames);
        const Image adopted = async.draw(nullptr, render::DebugView::Final);
        QVERIFY(adopted.pixels == synchronous.pixels);
        async.stop();
    }

    void cleanupTestCase() { test::stopProcessRenderer(); }
};

QTEST_MAIN(TestRenderSpecularOcclusion)
#include "test_render_specular_occlusion.moc"
