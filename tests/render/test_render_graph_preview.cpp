// Node thumbnails rendered through the graph compiler (render/graph_preview.h): known answers for
// a checker, a constant colour, a gradient (data, not encoded) and an image texture through its
// UV transform, and a value edit that compiles nothing. 64x64 thumbnails, one context.
#include "core/color_management.h"
#include "core/graph/graph.h"
#include "core/image.h"
#include "core/texture_cache.h"
#include "render/graph_preview.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <filesystem>

using namespace velvet;
using namespace velvet::graph;
namespace fs = std::filesystem;

namespace {

constexpr int kSide = 64;

/// sRGB encoding (IEC 61966-2-1) of a linear value, in 0..255 units (not rounded).
float srgbByte(float v) {
    const float e = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
    return e * 255.0f;
}

/// Pixel (x, y) in 0..255 units.
glm::vec3 bytes(const Image& img, int x, int y) {
    return glm::vec3(img.rgba(x, y)) * 255.0f;
}

/// Whether pixel (x, y) is within @p tolerance (0..255 units) of @p expected in every channel;
/// says which one is not.
bool near(const Image& img, int x, int y, glm::vec3 expected, float tolerance = 1.0f) {
    const glm::vec3 got = bytes(img, x, y);
    for (int k = 0; k < 3; ++k)
        if (std::abs(got[k] - expected[k]) > tolerance) {
            qWarning("pixel (%d, %d): got %.1f %.1f %.1f, expected %.1f %.1f %.1f", x, y, got.x,
                     got.y, got.z, expected.x, expected.y, expected.z);
            return false;
        }
    return true;
}

glm::vec3 encoded(glm::vec3 linear) {
    return {srgbByte(linear.x), srgbByte(linear.y), srgbByte(linear.z)};
}

} // namespace

class TestRenderGraphPreview : public QObject {
    Q_OBJECT
    std::unique_ptr<render::GraphPreview> m_preview;

    Image preview(const Graph& g, NodeId node, PortIndex output = 0,
                  TextureCache* cache = nullptr) {
        const render::PreviewRequest request{node, output};
        Problems problems;
        std::vector<Image> images = m_preview->render(g, {&request, 1}, cache, &problems);
        for (const Problem& p : problems.items)
            qWarning("%s", p.toString().c_str());
        return images.empty() ? Image{} : images.front();
    }

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        m_preview = std::make_unique<render::GraphPreview>(kSide);
        QCOMPARE(m_preview->side(), kSide);
    }
    void cleanupTestCase() { m_preview.reset(); }

    // Checker at scale 4 over the unit square: 16-pixel cells; the centre of cell (i, j) is colour
    // A where i + j is even and colour B where it is odd (the snippet's mod(floor(u)+floor(v), 2)),
    // each sRGB-encoded within 1/255. The mask output is data: 0 and 255, not encoded.
    void checkerHasItsPattern() {
        Graph g;
        const NodeId c = g.addNode("noise.checker").node;
        const glm::vec3 a(0.8f, 0.2f, 0.05f), b(0.05f, 0.5f, 0.9f);
        QVERIFY(g.setInputValue(c, PortIndex(g.node(c)->type->inputIndex("scale")),
                                glm::vec4(4, 0, 0, 0))
                    .ok);
        QVERIFY(
            g.setInputValue(c, PortIndex(g.node(c)->type->inputIndex("colorA")), glm::vec4(a, 0))
                .ok);
        QVERIFY(
            g.setInputValue(c, PortIndex(g.node(c)->type->inputIndex("colorB")), glm::vec4(b, 0))
                .ok);
        const Image img = preview(g, c);
        QCOMPARE(img.width, kSide);
        QCOMPARE(img.height, kSide);
        const Image mask = preview(g, c, PortIndex(g.node(c)->type->outputIndex("mask")));
        for (int j = 0; j < 4; ++j)
            for (int i = 0; i < 4; ++i) {
                const int x = 8 + 16 * i, y = 8 + 16 * j;
                const bool odd = (i + j) % 2 == 1;
                QVERIFY(near(img, x, y, encoded(odd ? b : a)));
                QVERIFY(near(mask, x, y, glm::vec3(odd ? 255.0f : 0.0f)));
            }
    }

    // A constant colour is flat: every pixel is its sRGB encoding within 1/255.
    void constantColourIsFlat() {
        Graph g;
        const NodeId k = g.addNode("constant.color").node;
        const glm::vec3 c(0.214f, 0.5f, 0.9f);
        QVERIFY(g.setInputValue(k, 0, glm::vec4(c, 0)).ok);
        const Image img = preview(g, k);
        QCOMPARE(img.width, kSide);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x)
                QVERIFY(near(img, x, y, encoded(c)));
    }

    // A gradient at angle 0 is u, a float, shown as is: pixel x holds (x + 0.5) / 64, so the
    // preview evaluates the node over UV in [0, 1]^2 at pixel centres with no encoding.
    void gradientIsDataOverTheUnitSquare() {
        Graph g;
        const NodeId n = g.addNode("noise.gradient").node;
        const Image img = preview(g, n);
        for (int x = 0; x < kSide; x += 7)
            QVERIFY(near(img, x, 31, glm::vec3((float(x) + 0.5f) / kSide * 255.0f)));
    }

    // An image texture is sampled through its UV transform, as the G-buffer pass samples it: a
    // 2x2 file (Raw, so values are as stored) with scale 2 tiles twice across the thumbnail, and
    // row 0 of the file is the first rows of the thumbnail.
    void imageTextureFollowsItsUvTransform() {
        QTemporaryDir dir;
        Image file(2, 2, 4);
        const glm::vec4 texels[4] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 1, 1, 1}};
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 4; ++k)
                file.pixels[size_t(i * 4 + k)] = texels[i][k];
        const fs::path path = fs::path(dir.path().toStdString()) / "quad.png";
        std::string error;
        QVERIFY2(writeImage(path, file, PixelFormat::UInt8, &error), error.c_str());
        ColorManagement cm;
        QVERIFY2(cm.loadDefault(&error), error.c_str());
        TextureCache cache(cm);

        Graph g;
        const NodeId t = g.addNode("texture.image").node;
        QVERIFY(g.setSetting(t, "file", path.string()).ok);
        QVERIFY(g.setSetting(t, "colorSpace", "Raw").ok);
        QVERIFY(g.setInputValue(t, PortIndex(g.node(t)->type->inputIndex("scale")),
                                glm::vec4(2, 2, 0, 0))
                    .ok);
        const Image img = preview(g, t, 0, &cache);
        // Texel (tx, ty) covers thumbnail pixels [16 tx, 16 tx + 16) in each 32-pixel tile. Pixel
        // 8's centre is 1/32 texel past the texel centre on each axis, so bilinear filtering (with
        // repeat wrap every neighbour of a 2x2 texture is its other texel) weighs the texel 31/32,
        // its row and column neighbours 31/32 * 1/32 and the diagonal one 1/32^2.
        const float w = 31.0f / 32.0f;
        for (int tile = 0; tile < 2; ++tile)
            for (int ty = 0; ty < 2; ++ty)
                for (int tx = 0; tx < 2; ++tx) {
                    const auto texel = [&](int x, int y) {
                        return glm::vec3(texels[(y % 2) * 2 + (x % 2)]);
                    };
                    const glm::vec3 expected =
                        255.0f * (w * w * texel(tx, ty) + w * (1 - w) * texel(tx + 1, ty) +
                                  (1 - w) * w * texel(tx, ty + 1) +
                                  (1 - w) * (1 - w) * texel(tx + 1, ty + 1));
                    QVERIFY(near(img, 32 * tile + 16 * tx + 8, 32 * tile + 16 * ty + 8, expected,
                                 1.5f));
                }
    }

    // A value edit re-uses the cached program (the text depends only on the structure) and the
    // thumbnail shows the new value; a structural edit upstream compiles one new program.
    void valueEditCompilesNothing() {
        Graph g;
        const NodeId k = g.addNode("constant.color").node;
        const NodeId inv = g.addNode("math.invert").node;
        QVERIFY(g.setInputValue(k, 0, glm::vec4(0.2f, 0.2f, 0.2f, 0)).ok);
        QVERIFY(g.connect({k, 0, inv, 0}).ok);
        const Image before = preview(g, inv);
        QVERIFY(near(before, 10, 10, encoded(glm::vec3(0.8f))));
        const int compiles = m_preview->compileCount();
        QVERIFY(compiles >= 1);
        QVERIFY(g.setInputValue(k, 0, glm::vec4(0.6f, 0.6f, 0.6f, 0)).ok);
        const Image after = preview(g, inv);
        QVERIFY(near(after, 10, 10, encoded(glm::vec3(0.4f))));
        QCOMPARE(m_preview->compileCount(), compiles);

        const NodeId pow = g.addNode("math.power").node;
        QVERIFY(g.connect({inv, 0, pow, 0}).ok);
        const Image squared = preview(g, pow);
        QVERIFY(near(squared, 10, 10, encoded(glm::vec3(0.16f))));
        QCOMPARE(m_preview->compileCount(), compiles + 1);
    }

    // Requests that cannot be rendered give an empty image and a reason, and do not stop the
    // others in the batch.
    void badRequestsAreReported() {
        Graph g;
        const NodeId k = g.addNode("constant.color").node;
        const render::PreviewRequest requests[] = {{99, 0}, {k, 5}, {k, 0}};
        Problems problems;
        const std::vector<Image> images = m_preview->render(g, requests, nullptr, &problems);
        QCOMPARE(images.size(), size_t(3));
        QVERIFY(images[0].empty());
        QVERIFY(images[1].empty());
        QCOMPARE(images[2].width, kSide);
        QCOMPARE(problems.items.size(), size_t(2));
        QVERIFY(problems.items[0].toString().find("no node 99") != std::string::npos);
        QVERIFY(problems.items[1].toString().find("no output 5") != std::string::npos);
    }
};

QTEST_GUILESS_MAIN(TestRenderGraphPreview)
#include "test_render_graph_preview.moc"
