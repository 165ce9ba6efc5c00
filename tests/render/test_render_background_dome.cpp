// The inline frame's HDRI background drawn as a dome from its display-encoded cache
// (render/background_dome.h, issue 16): the same picture as the full-size background pass, at
// the seam and the poles too; an orbit draws the cache once; a change of what the picture shows
// draws it again; the frames at rest, display steps that read the pixel's position and an
// orthographic camera keep the smaller background.
#include "core/post_effects.h"
#include "render_test_util.h"

#include <QtTest>
#include <cmath>
#include <glm/trigonometric.hpp>

using namespace velvet;

namespace {

constexpr int kWidth = 256, kHeight = 144;

/// The bench's scene (core/document_io.h) through a narrow lens, the sphere as large: the
/// shipped 1024-wide HDRI at about 9 pixels a texel, where the background may be drawn smaller
/// (render/background_downsample.h) and so as the dome.
Scene narrowLensScene(float yawDeg, float pitchDeg) {
    Scene scene = forwardPeerScene();
    scene.camera.fovYDeg = 6.0f;
    scene.camera.distance = 4.5f * std::tan(glm::radians(17.5f)) / std::tan(glm::radians(3.0f));
    scene.camera.yawDeg = yawDeg;
    scene.camera.pitchDeg = pitchDeg;
    return scene;
}

/// An environment whose colour is a smooth function of the direction, 0.5 + 0.4 d, continuous
/// across the equirect's seam and at its poles: a triangle of the dome whose coordinates wrapped
/// the wrong way, or a pole's coordinates off, would show colours from elsewhere.
Image directionColouredEnvironment(int width, int height) {
    Image image(width, height, 3);
    const float pi = 3.14159265f;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const float u = (float(x) + 0.5f) / float(width), v = (float(y) + 0.5f) / float(height);
            const float theta = pi * v, phi = 2.0f * pi * (u - 0.5f);
            const float d[3] = {std::sin(phi) * std::sin(theta), std::cos(theta),
                                -std::cos(phi) * std::sin(theta)};
            for (int k = 0; k < 3; ++k)
                image.at(x, y)[k] = 0.5f + 0.4f * d[k];
        }
    return image;
}

} // namespace

class TestRenderBackgroundDome : public QObject {
    Q_OBJECT
    std::unique_ptr<render::Renderer> m_renderer;
    std::unique_ptr<render::OffscreenTarget> m_target;
    render::FrameSettings m_fs;

    Image draw(bool displayOnly) {
        m_fs.displayOnly = displayOnly;
        std::string error;
        if (!m_renderer->render(m_fs, m_target->framebuffer(), &error))
            qFatal("render failed: %s", error.c_str());
        return m_renderer->readDisplay();
    }
    void show(const Scene& scene) {
        m_renderer->setScene(scene);
        m_renderer->finishEnvironment();
        m_renderer->finishGraph();
    }
    /// An orbit step: a frame from @p camera, the scene unchanged.
    Image drawFrom(const Camera& camera) {
        m_fs.camera = camera;
        const Image image = draw(true);
        m_fs.camera.reset();
        return image;
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_renderer = std::make_unique<render::Renderer>();
        m_target = std::make_unique<render::OffscreenTarget>();
        QVERIFY2(m_renderer->initialize(&error), error.c_str());
        QVERIFY2(m_target->resize(kWidth, kHeight, &error), error.c_str());
        m_fs.width = kWidth;
        m_fs.height = kHeight;
    }
    void cleanupTestCase() {
        m_target.reset();
        m_renderer.reset();
    }

    /// Against the linear path, which draws the background at full size per pixel: the view
    /// ahead (u = 0.5), the equirect's seam behind the default view (u = 0 and 1 at +Z), the top
    /// pole from below, a rotated environment, and the blurred background.
    void theDomeShowsWhatTheFullSizePassShows_data() {
        QTest::addColumn<float>("yaw");
        QTest::addColumn<float>("pitch");
        QTest::addColumn<float>("rotation");
        QTest::addColumn<int>("background");
        QTest::newRow("ahead") << 0.0f << 10.0f << 0.0f << int(BackgroundMode::Sharp);
        QTest::newRow("the seam") << 180.0f << 0.0f << 0.0f << int(BackgroundMode::Sharp);
        QTest::newRow("the top pole") << 30.0f << -88.0f << 0.0f << int(BackgroundMode::Sharp);
        QTest::newRow("rotated") << 0.0f << 10.0f << 75.0f << int(BackgroundMode::Sharp);
        QTest::newRow("blurred") << 0.0f << 10.0f << 0.0f << int(BackgroundMode::Blurred);
    }
    void theDomeShowsWhatTheFullSizePassShows() {
        QFETCH(float, yaw);
        QFETCH(float, pitch);
        QFETCH(float, rotation);
        QFETCH(int, background);
        Scene scene = narrowLensScene(yaw, pitch);
        scene.environment.rotationDeg = rotation;
        scene.environment.background = BackgroundMode(background);
        show(scene);
        const Image linearPath = draw(false);
        m_fs.reflectionSamples = render::kRefinementReflectionSamples; // at rest: no dome
        const Image smaller = draw(true);
        m_fs.reflectionSamples = 0;
        QVERIFY(!m_renderer->lastFramePasses().backgroundDome);
        QVERIFY(m_renderer->lastFramePasses().backgroundDownsample > 1);
        m_renderer->update(scene, ScenePart::Camera); // not a value edit: the background is drawn
        const Image dome = draw(true);
        QVERIFY(m_renderer->lastFramePasses().backgroundDome);
        QCOMPARE(m_renderer->lastFramePasses().backgroundDownsample, 1);
        const int domeWorst = test::maxDifference(linearPath, dome);
        const int domeMoved = test::differingPixels(linearPath, dome, 2);
        const int smallerMoved = test::differingPixels(linearPath, smaller, 2);
        qInfo("dome: max %d/255, %d pixels by 2/255 or more; smaller picture: max %d/255, %d "
              "pixels",
              domeWorst, domeMoved, test::maxDifference(linearPath, smaller), smallerMoved);
        // The dome interpolates the texels' display values where the full-size pass
        // interpolates their radiance and then encodes: the same at the texels' centres, apart
        // by up to 7 255ths across a texel's edge where the encoding bends most (the studio's
        // dark backdrop beside its lamps, 9 pixels a texel here; 2.3 % of the frame by 2 or
        // more). The smaller picture, sampled every other pixel, is apart by 3 at most there.
        QVERIFY2(domeWorst <= 8, qPrintable(QString::number(domeWorst)));
        QVERIFY2(domeMoved <= kWidth * kHeight * 4 / 100, qPrintable(QString::number(domeMoved)));
    }

    /// The seam (behind the default view) and both poles of a smooth environment, at 11 pixels
    /// a texel: the dome's picture is the full-size pass's within the encoding's rounding.
    void aSmoothEnvironmentMeetsItselfAtTheSeamAndThePoles() {
        QTemporaryDir dir;
        std::string error;
        const std::string path = (dir.path() + "/directions.exr").toStdString();
        QVERIFY2(
            writeImage(path, directionColouredEnvironment(128, 64), PixelFormat::Float, &error),
            error.c_str());
        for (const float pitch : {0.0f, -80.0f, 80.0f}) {
            Scene scene = forwardPeerScene();
            scene.environment.hdri = path;
            scene.camera.yawDeg = 180.0f;
            scene.camera.pitchDeg = pitch;
            show(scene);
            const Image linearPath = draw(false);
            draw(true);
            m_renderer->update(scene, ScenePart::Camera);
            const Image dome = draw(true);
            QVERIFY(m_renderer->lastFramePasses().backgroundDome);
            const int worst = test::maxDifference(linearPath, dome);
            qInfo("pitch %.0f: max %d/255", double(pitch), worst);
            QVERIFY2(worst <= 2, qPrintable(QString::number(worst)));
        }
    }

    /// An orbit draws the cache once; every frame of it matches a full-size background.
    void anOrbitDrawsTheCacheOnce() {
        const Scene scene = narrowLensScene(0.0f, 10.0f);
        show(scene);
        int cacheDraws = 0, domeFrames = 0;
        Camera camera = scene.camera;
        for (int i = 0; i < 6; ++i) {
            camera.yawDeg += 7.0f;
            camera.pitchDeg += 3.0f;
            drawFrom(camera);
            cacheDraws += m_renderer->lastFramePasses().backgroundCacheDrawn;
            domeFrames += m_renderer->lastFramePasses().backgroundDome;
        }
        QCOMPARE(domeFrames, 6);
        QCOMPARE(cacheDraws, 1);
        // The last step, the same view through the linear path.
        const Image dome = drawFrom(camera);
        QVERIFY(m_renderer->lastFramePasses().backgroundKept); // the same view: kept
        m_fs.camera = camera;
        const Image linearPath = draw(false);
        m_fs.camera.reset();
        QVERIFY2(test::maxDifference(linearPath, dome) <= 8,
                 qPrintable(QString::number(test::maxDifference(linearPath, dome))));
    }

    /// The exposure, the environment's rotation and the tone map's parameters change the
    /// picture: the frame after the change draws the cache again, the next reuses it, and the
    /// picture follows.
    void aChangedPictureDrawsTheCacheAgain() {
        Scene scene = narrowLensScene(0.0f, 10.0f);
        show(scene);
        Camera camera = scene.camera;
        const auto orbitTwice = [&]() -> Image {
            camera.yawDeg += 5.0f;
            drawFrom(camera);
            const render::FramePasses first = m_renderer->lastFramePasses();
            camera.yawDeg += 5.0f;
            const Image image = drawFrom(camera);
            const render::FramePasses second = m_renderer->lastFramePasses();
            if (!first.backgroundDome || !first.backgroundCacheDrawn)
                QTest::qFail("the frame after the change: the cache drawn again", __FILE__,
                             __LINE__);
            if (!second.backgroundDome || second.backgroundCacheDrawn)
                QTest::qFail("the next frame: the cache kept", __FILE__, __LINE__);
            m_fs.camera = camera;
            const Image linearPath = draw(false);
            m_fs.camera.reset();
            const int worst = test::maxDifference(linearPath, image);
            if (worst > 8)
                QTest::qFail(
                    qPrintable("the dome against the linear path: " + QString::number(worst)),
                    __FILE__, __LINE__);
            return image;
        };
        orbitTwice();
        m_fs.exposureEv = 1.0f;
        const Image brighter = orbitTwice();
        m_fs.exposureEv = 0.0f;
        scene.environment.rotationDeg = 120.0f;
        m_renderer->update(scene, ScenePart::Environment);
        orbitTwice();
        // A parameter of the tone map (a uniform the key does not hold): the update redraws.
        scene.post.effects[0].params["operator"] = {float(toneMapOperatorIndex("aces"))};
        m_renderer->update(scene, ScenePart::PostChain);
        const Image aces = orbitTwice();
        QVERIFY(test::maxDifference(brighter, aces) > 10);
    }

    /// A vignette reads the pixel's position, an orthographic camera sees one direction: the
    /// smaller background, every frame.
    void positionDependentPicturesKeepTheSmallerBackground() {
        Scene vignette = narrowLensScene(0.0f, 10.0f);
        vignette.post.effects.push_back(makeEffect("vignette"));
        Scene orthographic = narrowLensScene(0.0f, 10.0f);
        orthographic.camera.orthographic = true;
        for (const Scene& scene : {vignette, orthographic}) {
            show(scene);
            Camera camera = scene.camera;
            for (int i = 0; i < 3; ++i) {
                camera.yawDeg += 5.0f;
                drawFrom(camera);
                QVERIFY(!m_renderer->lastFramePasses().backgroundDome);
                QVERIFY(m_renderer->lastFramePasses().inlineDisplay);
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestRenderBackgroundDome)
#include "test_render_background_dome.moc"
