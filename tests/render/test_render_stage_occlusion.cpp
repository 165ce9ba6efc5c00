// The look-dev stage's screen-space occlusion term (docs/shadows.md): 1 on an open plane (also
// under a weave that bends its normals), below 1 in a crease, exactly 1 beyond its radius from
// the mesh, and the light a bright crease bounces given back; in frames drawn at rest and while
// the camera moves (FrameSettings::navigating: the stage at a quarter).
#include "core/document_io.h"
#include "core/light_rigs.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render/stage_interface.h"
#include "render_test_util.h"
#include "stage_test_rig.h"

#include <QtTest>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <memory>
#include <vector>

using namespace velvet;
using namespace velvet::test;

namespace {

/// The crease the occlusion tests look into: the cube (half size 0.8) on a plain ground, seen from
/// 5 m, with screen-space occlusion of radius 0.3.
Scene creaseScene() {
    Scene scene = stageScene(PreviewMeshKind::Cube);
    scene.camera.orthographic = false;
    scene.camera.target = {0.0f, -0.8f, 0.0f};
    scene.camera.distance = 5.0f;
    scene.environment.ground = GroundMode::Plain;
    scene.environment.ambientOcclusion = true;
    scene.environment.occlusionRadius = 0.3f;
    return scene;
}

/// How far the world position @p p (the Position view) lies from the cube's footprint (|x|,
/// |z| <= 0.8) on the ground; negative when @p p is not on the ground.
float distanceFromCube(glm::vec3 p) {
    if (p.y > -0.8f || p.y < -0.81f)
        return -1.0f;
    const float dx = std::max(std::abs(p.x) - 0.8f, 0.0f);
    const float dz = std::max(std::abs(p.z) - 0.8f, 0.0f);
    return std::sqrt(dx * dx + dz * dz);
}

} // namespace

class TestRenderStageOcclusion : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
    }
    void cleanupTestCase() {
        test::stopProcessRenderer(); // while the context is current
    }
    void init() {
        navigatingFrames = false;
        packOcclusionFrames = true;
    }

    // The occlusion term alone (the occlusion view: material occlusion x GTAO).
    void occlusionIsOneOnAnOpenPlane_data() { addNavigatingRows(); }
    void occlusionIsOneOnAnOpenPlane() {
        QFETCH(bool, navigating);
        navigatingFrames = navigating;
        Scene scene = stageScene(PreviewMeshKind::Plane);
        scene.camera.orthographic = false;
        scene.camera.target = {0.0f, 0.0f, 0.0f};
        scene.camera.distance = 3.0f;
        scene.environment.ambientOcclusion = true;
        scene.environment.occlusionRadius = 0.4f;
        const int size = 96 * framePixelsPerStagePixel();
        const Image ao = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image normal = renderLinear(scene, size, render::DebugView::Normal);
        int checked = 0;
        float least = 1.0f;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                if (glm::length(glm::vec3(normal.rgba(x, y))) < 0.5f)
                    continue;
                ++checked;
                least = std::min(least, ao.rgba(x, y).r);
            }
        qInfo("%d plane pixels, least occlusion term %.4f", checked, double(least));
        QVERIFY(checked > 1000);
        QVERIFY2(least > 0.97f, qPrintable(QString("open plane occluded: %1").arg(least)));
    }

    // A weave bends the shading normal, not the surface: the open plane stays open. The search
    // measures the hemisphere about the geometric normal there (render/ao_pass.h); about the
    // bent normal it counted the part below the plane as occluded (down to 0.78 at the denim's
    // steepest threads), on top of the material's occlusion and the lighting's horizon. The
    // screen-space term alone: the occlusion view with the search on over the view with it off
    // (the material's occlusion alone).
    void occlusionIsOneOnAnOpenPlaneWhoseWeaveBendsItsNormal() {
        const std::optional<Material> denim = test::libraryPreset("denim");
        QVERIFY(denim);
        Scene scene = stageScene(PreviewMeshKind::Plane);
        scene.material = *denim;
        scene.camera.orthographic = false;
        scene.camera.target = {0.0f, 0.0f, 0.0f};
        scene.camera.distance = 0.25f; // a few pixels a thread
        scene.environment.occlusionRadius = 0.05f;
        const int size = 96;
        const Image materialOnly = renderLinear(scene, size, render::DebugView::Occlusion);
        scene.environment.ambientOcclusion = true;
        const Image both = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image normal = renderLinear(scene, size, render::DebugView::Normal);
        int checked = 0, bent = 0;
        float least = 1.0f;
        double sum = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec3 n(normal.rgba(x, y));
                if (glm::length(n) < 0.5f || materialOnly.rgba(x, y).r < 0.05f)
                    continue;
                ++checked;
                bent += n.y < 0.95f; // the threads tilt it by more than 18 degrees
                const float term = both.rgba(x, y).r / materialOnly.rgba(x, y).r;
                least = std::min(least, term);
                sum += term;
            }
        qInfo("%d plane pixels, %d bent by more than 18 degrees, screen-space term: least %.4f, "
              "mean %.4f",
              checked, bent, double(least), sum / std::max(checked, 1));
        QVERIFY(checked > 1000);
        QVERIFY2(bent > 100, "the weave bends too few normals for the check to mean anything");
        // About the bent normals: least 0.78, mean 0.88.
        QVERIFY2(least > 0.95f, qPrintable(QString("open plane occluded: %1").arg(least)));
        QVERIFY2(sum / checked > 0.985,
                 qPrintable(QString("open plane occluded: mean %1").arg(sum / checked)));
    }

    void occlusionIsBelowOneInACrease_data() { addNavigatingRows(); }
    void occlusionIsBelowOneInACrease() {
        QFETCH(bool, navigating);
        navigatingFrames = navigating;
        const Scene scene = creaseScene();
        const int size = 128 * framePixelsPerStagePixel();
        const Image ao = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image pos = renderLinear(scene, size, render::DebugView::Position);
        double creaseSum = 0.0, openSum = 0.0;
        int crease = 0, open = 0, openBelow = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float d = distanceFromCube(glm::vec3(pos.rgba(x, y)));
                if (d < 0.0f)
                    continue;
                const float a = ao.rgba(x, y).r;
                if (d > 0.01f && d < 0.06f) {
                    creaseSum += a;
                    ++crease;
                } else if (d > 0.8f) {
                    openSum += a;
                    ++open;
                    // A frame drawn while the camera moves: a ground pixel by the cube's
                    // silhouette whose four texels, a quarter of the frame apart, all lie on the
                    // cube takes the cube's occlusion (by the top edge: 0.938 in 4 of 6,765).
                    const float least = navigatingFrames ? 0.9f : 0.95f;
                    QVERIFY2(a > least, qPrintable(QString("open ground occluded: %1").arg(a)));
                    openBelow += a <= 0.95f;
                }
            }
        qInfo("crease: %d pixels, mean %.3f; open ground: %d pixels, mean %.3f, %d at or below "
              "0.95",
              crease, creaseSum / std::max(crease, 1), open, openSum / std::max(open, 1),
              openBelow);
        QVERIFY(openBelow * 1000 <= open);
        QVERIFY(crease >= 10 && open >= 100);
        QVERIFY(creaseSum / crease < 0.9);
        QVERIFY(openSum / open > 0.98);
    }

    // Beyond its radius from the mesh the ground sees only itself, flat: the occlusion passes skip
    // it (render/ao_pass.h) and the term is exactly 1 there, where the search over the open
    // ground gave values a little off 1.
    void occlusionIsExactlyOneBeyondItsRadiusFromTheMesh() {
        const Scene scene = creaseScene();
        const int size = 128;
        const Image ao = renderLinear(scene, size, render::DebugView::Occlusion);
        const Image pos = renderLinear(scene, size, render::DebugView::Position);
        // The cube's bounding sphere (radius 0.8 sqrt 3 about its centre) grown by the radius,
        // and pixels whose 13x13 neighbourhood is all such ground: the upsample and the blur read
        // about 5 pixels around, and by a silhouette the cube's texels weigh a little.
        const float reach = 0.8f * std::sqrt(3.0f) + scene.environment.occlusionRadius;
        std::vector<char> beyond(size_t(size * size), 0);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const glm::vec3 p = glm::vec3(pos.rgba(x, y));
                beyond[size_t(y * size + x)] =
                    distanceFromCube(p) >= 0.0f && glm::length(p) > reach;
            }
        const auto alone = [&](int x, int y) {
            for (int j = std::max(y - 6, 0); j <= std::min(y + 6, size - 1); ++j)
                for (int i = std::max(x - 6, 0); i <= std::min(x + 6, size - 1); ++i)
                    if (!beyond[size_t(j * size + i)])
                        return false;
            return true;
        };
        int far = 0;
        float least = 1.0f;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (alone(x, y)) {
                    ++far;
                    least = std::min(least, ao.rgba(x, y).r);
                }
        qInfo("%d ground pixels beyond the reach, least occlusion term %.6f", far, double(least));
        QVERIFY(far > 1000);
        QVERIFY2(least > 0.9999f, qPrintable(QString("open ground occluded: %1").arg(least)));
    }

    // The occlusion darkens the environment's light by Jimenez et al. 2016's multiple-bounce fit
    // of the visibility, not by the visibility itself: a bright crease gets back the light its
    // walls reflect (the path tracer's interreflection), a black one does not.
    void occlusionGivesBackTheLightACreaseBounces() {
        for (const float albedo : {0.9f, 0.05f}) {
            Scene scene = creaseScene();
            scene.environment.color = glm::vec3(1.0f); // a uniform white environment, no lights
            scene.environment.groundColor = glm::vec3(albedo);
            const int size = 128;
            const Image visibility = renderLinear(scene, size, render::DebugView::Occlusion);
            const Image pos = renderLinear(scene, size, render::DebugView::Position);
            const Image occluded = renderLinear(scene, size);
            scene.environment.ambientOcclusion = false;
            const Image open = renderLinear(scene, size);
            // The fit (common_occlusion.glsl's multiBounceOcclusion, held to 1).
            const auto bounced = [albedo](float v) {
                const float a = 2.0404f * albedo - 0.3324f, b = -4.7951f * albedo + 0.6417f,
                            c = 2.7552f * albedo + 0.6903f;
                return std::min(std::max(v, ((v * a + b) * v + c) * v), 1.0f);
            };
            double ratioSum = 0.0, expectedSum = 0.0, visibilitySum = 0.0;
            int crease = 0;
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    const float d = distanceFromCube(glm::vec3(pos.rgba(x, y)));
                    if (d < 0.01f || d > 0.06f) // the crease's ground only
                        continue;
                    const float v = visibility.rgba(x, y).r;
                    const float ratio = luminance(occluded.rgba(x, y)) /
                                        std::max(luminance(open.rgba(x, y)), 1e-6f);
                    QVERIFY2(std::abs(ratio - bounced(v)) < 0.02f,
                             qPrintable(QString("albedo %1, pixel (%2, %3): visibility %4, light "
                                                "kept %5, expected %6")
                                            .arg(albedo)
                                            .arg(x)
                                            .arg(y)
                                            .arg(v)
                                            .arg(ratio)
                                            .arg(bounced(v))));
                    ratioSum += ratio;
                    expectedSum += bounced(v);
                    visibilitySum += v;
                    ++crease;
                }
            qInfo("albedo %.2f: %d crease pixels, visibility %.3f, light kept %.3f (fit %.3f)",
                  double(albedo), crease, visibilitySum / std::max(crease, 1),
                  ratioSum / std::max(crease, 1), expectedSum / std::max(crease, 1));
            QVERIFY(crease >= 10);
            QVERIFY(visibilitySum / crease < 0.9); // a crease indeed
            if (albedo > 0.5f) // the bright crease keeps clearly more than its visibility
                QVERIFY(ratioSum / crease > visibilitySum / crease + 0.03);
            else // the dark one about its visibility
                QVERIFY(std::abs(ratioSum - visibilitySum) / crease < 0.02);
        }
    }

    // Under a shadowed light the occlusion rides in the shadow masks' free channel, read with
    // the shadows' upsample (render/ao_pass.h, packInto): the light it keeps is the light its own
    // upsample keeps, on the plain ground (the mask proper) and on the shadow catcher (the
    // ground's mask), at rest and while the camera moves; and the crease is still darker than
    // without the occlusion, so the channel holds the occlusion and not the clear's 1.
    void occlusionRidingInTheShadowMaskKeepsItsOwnLight_data() {
        QTest::addColumn<bool>("navigating");
        QTest::addColumn<bool>("catcher");
        QTest::newRow("plain ground at rest") << false << false;
        QTest::newRow("plain ground navigating") << true << false;
        QTest::newRow("shadow catcher at rest") << false << true;
        QTest::newRow("shadow catcher navigating") << true << true;
    }
    void occlusionRidingInTheShadowMaskKeepsItsOwnLight() {
        QFETCH(bool, navigating);
        QFETCH(bool, catcher);
        navigatingFrames = navigating;
        Scene scene = creaseScene();
        scene.environment.color = glm::vec3(1.0f);
        scene.environment.ground = catcher ? GroundMode::ShadowCatcher : GroundMode::Plain;
        Light key;
        key.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
        key.intensity = 0.5f;
        key.castShadows = true;
        scene.lights = {key};
        const int size = 128 * framePixelsPerStagePixel();
        const Image pos = renderLinear(scene, size, render::DebugView::Position);
        const Image packed = renderLinear(scene, size);
        QVERIFY(rig()->renderer->lastTimings().occlusionInMask);
        packOcclusionFrames = false;
        const Image own = renderLinear(scene, size);
        QVERIFY(!rig()->renderer->lastTimings().occlusionInMask);
        scene.environment.ambientOcclusion = false;
        const Image open = renderLinear(scene, size);
        double packedSum = 0.0, ownSum = 0.0, openSum = 0.0, differenceSum = 0.0;
        int crease = 0, ground = 0, apart = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float d = distanceFromCube(glm::vec3(pos.rgba(x, y)));
                if (d < 0.0f)
                    continue;
                const float a = luminance(packed.rgba(x, y)), b = luminance(own.rgba(x, y));
                const float difference = std::abs(a - b) / std::max(b, 1e-3f);
                differenceSum += difference;
                apart += difference > 0.05f;
                ++ground;
                if (d > 0.01f && d < 0.06f) {
                    packedSum += a;
                    ownSum += b;
                    openSum += luminance(open.rgba(x, y));
                    ++crease;
                }
            }
        qInfo("%d ground pixels, mean difference %.4f, %d more than 5 %% apart; crease (%d "
              "pixels): packed %.4f, own %.4f, without occlusion %.4f",
              ground, differenceSum / std::max(ground, 1), apart, crease,
              packedSum / std::max(crease, 1), ownSum / std::max(crease, 1),
              openSum / std::max(crease, 1));
        QVERIFY(ground > 1000 && crease >= 10);
        // The plain ground reads both through depth-aware upsamples, only their weights differ.
        // The catcher reads the ground's mask bilinearly, whose texels under the cube hold the
        // ground's own occlusion about them (ao_pack.frag), where the occlusion's upsample mixed
        // in the cube's face beside the crease at a like depth: its crease comes out 1 to 2 %
        // darker, and a line of pixels along the cube's base and sides differs by more than 5 %.
        const double meanLimit = catcher ? 0.008 : 0.003, apartShare = catcher ? 0.015 : 0.005;
        const double creaseLimit = catcher ? 0.03 : 0.02;
        QVERIFY(differenceSum / ground < meanLimit);
        QVERIFY(apart <= apartShare * ground);
        QVERIFY(std::abs(packedSum - ownSum) / ownSum < creaseLimit);
        QVERIFY(packedSum < 0.95 * openSum);
    }

    // With every channel of the masks taken (four shadowed lights) the occlusion keeps its own
    // upsample and still darkens the crease.
    void occlusionKeepsItsOwnUpsampleWhenTheMasksAreFull() {
        Scene scene = creaseScene();
        scene.environment.color = glm::vec3(1.0f);
        for (int i = 0; i < 4; ++i) {
            Light l;
            l.direction = glm::normalize(glm::vec3(std::cos(1.6f * i), -2.0f, std::sin(1.6f * i)));
            l.intensity = 0.2f;
            l.castShadows = true;
            scene.lights.push_back(l);
        }
        const int size = 128;
        const Image pos = renderLinear(scene, size, render::DebugView::Position);
        const Image occluded = renderLinear(scene, size);
        QVERIFY(!rig()->renderer->lastTimings().occlusionInMask);
        scene.environment.ambientOcclusion = false;
        const Image open = renderLinear(scene, size);
        double occludedSum = 0.0, openSum = 0.0;
        int crease = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const float d = distanceFromCube(glm::vec3(pos.rgba(x, y)));
                if (d > 0.01f && d < 0.06f) {
                    occludedSum += luminance(occluded.rgba(x, y));
                    openSum += luminance(open.rgba(x, y));
                    ++crease;
                }
            }
        QVERIFY(crease >= 10);
        QVERIFY(occludedSum < 0.95 * openSum);
    }
};

QTEST_GUILESS_MAIN(TestRenderStageOcclusion)
#include "test_render_stage_occlusion.moc"
