// The shadow maps' depth bounds and what they settle (render/shadow_depth_bounds.h,
// render/shadow_mask.h, docs/shadows.md): the min-max chain equals the minimum and maximum of
// the depth maps computed on the CPU, level by level; and a stage drawn with the bounds settling
// mask texels is the same image, to the bit, as the one whose every texel went through the PCSS
// lookup, while the lookup filters only part of the texels.
#include "core/light_rigs.h"
#include "render/shadow_depth_bounds.h"
#include "render_test_util.h"

#include <QtTest>
#include <algorithm>
#include <epoxy/gl.h>
#include <random>
#include <vector>

using namespace velvet;

namespace {

struct Frame {
    Image image;
    long long texels = 0, filtered = 0;
};

Frame drawStage(test::OffscreenRenderer& r, bool settle) {
    render::FrameSettings fs;
    fs.width = fs.height = r.size;
    fs.settleShadows = settle;
    std::string error;
    if (!r.renderer->render(fs, r.target->framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    const render::FrameTimings t = r.renderer->lastTimings();
    return {r.renderer->readLinear(), t.shadowMaskTexels, t.shadowMaskFiltered};
}

} // namespace

class TestRenderShadowSettle : public QObject {
    Q_OBJECT
    test::OffscreenRenderer fx;

private slots:
    void initTestCase() {
        const std::string error = fx.start(160);
        QVERIFY2(error.empty(), error.c_str());
    }
    void cleanupTestCase() { fx.stop(); }

    void boundsAreTheMinimumAndMaximumOfTheMaps() {
        // Two 64² layers of random depths, a few texels at 0 and 1 (the extremes the maps hold).
        constexpr int size = 64, layers = 2;
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> depth(0.05f, 0.95f);
        std::vector<float> texels(size_t(size) * size * layers);
        for (float& d : texels)
            d = depth(rng);
        texels[17] = 0.0f;
        texels[size_t(size) * size + 4000] = 1.0f;
        GLuint maps = 0;
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &maps);
        glTextureStorage3D(maps, 1, GL_DEPTH_COMPONENT32F, size, size, layers);
        glTextureSubImage3D(maps, 0, 0, 0, 0, size, size, layers, GL_DEPTH_COMPONENT, GL_FLOAT,
                            texels.data());
        render::ShadowDepthBounds bounds;
        std::string error;
        QVERIFY2(bounds.build(&error), error.c_str());
        bounds.update(maps, layers, size);
        glFinish();
        const int base = size / render::kShadowBoundsBlock;
        QCOMPARE(bounds.levels(), render::shadowBoundsLevels(base));
        for (int level = 0; level < bounds.levels(); ++level) {
            const int n = base >> level, block = size / n; // map texels per bounds texel
            std::vector<float> got(size_t(n) * n * layers * 2);
            glGetTextureImage(bounds.texture(), level, GL_RG, GL_FLOAT,
                              GLsizei(got.size() * sizeof(float)), got.data());
            for (int l = 0; l < layers; ++l)
                for (int y = 0; y < n; ++y)
                    for (int x = 0; x < n; ++x) {
                        float lo = 1.0f, hi = 0.0f;
                        for (int v = y * block; v < (y + 1) * block; ++v)
                            for (int u = x * block; u < (x + 1) * block; ++u) {
                                const float d = texels[(size_t(l) * size + v) * size + u];
                                lo = std::min(lo, d);
                                hi = std::max(hi, d);
                            }
                        const size_t i = ((size_t(l) * n + y) * n + x) * 2;
                        QCOMPARE(got[i], lo);
                        QCOMPARE(got[i + 1], hi);
                    }
        }
        glDeleteTextures(1, &maps);
    }

    void settledMasksDrawTheLookupsImage_data() {
        QTest::addColumn<int>("mesh");
        QTest::addColumn<QString>("rig");
        QTest::addColumn<int>("ground");
        QTest::newRow("shader ball, key, catcher")
            << int(PreviewMeshKind::ShaderBall) << "key" << int(GroundMode::ShadowCatcher);
        QTest::newRow("drape, three-point, plain ground")
            << int(PreviewMeshKind::ClothDrape) << "three-point" << int(GroundMode::Plain);
        QTest::newRow("sphere, stage spot, catcher")
            << int(PreviewMeshKind::Sphere) << "stage-spot" << int(GroundMode::ShadowCatcher);
        QTest::newRow("shader ball, key, no ground")
            << int(PreviewMeshKind::ShaderBall) << "key" << int(GroundMode::Off);
    }
    void settledMasksDrawTheLookupsImage() {
        QFETCH(int, mesh);
        QFETCH(QString, rig);
        QFETCH(int, ground);
        Scene scene = defaultScene();
        scene.mesh.kind = PreviewMeshKind(mesh);
        scene.lights = *lightRigLights(rig.toStdString());
        scene.environment.ground = GroundMode(ground);
        fx.renderer->setScene(scene);
        fx.renderer->finishEnvironment();
        drawStage(fx, true); // the shadow maps and their bounds
        const Frame settled = drawStage(fx, true), filtered = drawStage(fx, false);
        QVERIFY(settled.texels > 0);
        QCOMPARE(filtered.texels, settled.texels);
        // Without settling every receiver is filtered; with it, a share of them is not.
        QVERIFY2(settled.filtered < filtered.filtered,
                 qPrintable(QString("%1 of %2 filtered, %3 without settling")
                                .arg(settled.filtered)
                                .arg(settled.texels)
                                .arg(filtered.filtered)));
        QCOMPARE(settled.image.pixels.size(), filtered.image.pixels.size());
        size_t differing = 0;
        for (size_t i = 0; i < settled.image.pixels.size(); ++i)
            differing += settled.image.pixels[i] != filtered.image.pixels[i];
        QCOMPARE(differing, size_t(0));
    }
};

QTEST_APPLESS_MAIN(TestRenderShadowSettle)
#include "test_render_shadow_settle.moc"
