// The screen-space shadow mask's scissor (render/shadow_mask.h): the part of the frame where a
// shadow slot's visibility can differ from 1, for known geometry seen straight down, on the CPU,
// and the half-resolution mask's texels those pixels read; the occlusion's scissor
// (render/ao_pass.h) the same way.
// (The mask's image against the lookup it replaced: test_render_shadow_golden.)
#include "render/ao_pass.h"
#include "render/shadow_mask.h"

#include <QtTest>
#include <algorithm>
#include <cstdlib>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

constexpr int kSize = 100;

/// The unit sphere's bounds at the origin (its bounding sphere, from the box, has radius sqrt(3));
/// the ground just under it at y = -1.
MeshBounds unitSphere() {
    MeshBounds b;
    b.min = glm::vec3(-1.0f);
    b.max = glm::vec3(1.0f);
    return b;
}

/// An orthographic camera straight down over the origin, 2 @p half m across: with the default
/// x and z in [-2, 2] fill the 100-pixel frame, so a world x maps to pixel 25 (x + 2).
glm::mat4 topDown(float half = 2.0f) {
    return glm::ortho(-half, half, -half, half, 0.1f, 100.0f) *
           glm::lookAt(glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
}

/// Each edge of @p r within a pixel of @p expected's (the corners are unprojected in floats).
bool close(const render::PixelRect& r, const render::PixelRect& expected) {
    const bool ok = std::abs(r.x - expected.x) <= 1 && std::abs(r.y - expected.y) <= 1 &&
                    std::abs(r.x + r.width - expected.x - expected.width) <= 1 &&
                    std::abs(r.y + r.height - expected.y - expected.height) <= 1;
    if (!ok)
        qWarning("rectangle %d %d %d %d, expected %d %d %d %d", r.x, r.y, r.width, r.height,
                 expected.x, expected.y, expected.width, expected.height);
    return ok;
}

render::ShadowSlot slotFor(const Light& light) {
    Problems problems;
    const std::vector<render::ShadowSlot> planned =
        render::planShadows({light}, render::boundingSphere(unitSphere()), &problems);
    if (planned.size() != 1)
        qFatal("the light got no shadow slot");
    return planned[0];
}

Light directional(glm::vec3 direction) {
    Light l;
    l.type = LightType::Directional;
    l.direction = direction;
    l.castShadows = true;
    return l;
}

} // namespace

class TestRenderShadowMask : public QObject {
    Q_OBJECT
private slots:
    // A light straight down: its map's box holds the bounding sphere, x and z in
    // [-sqrt(3), sqrt(3)], and so does the ground inside it: pixels 6.7..93.3 and one of margin.
    void straightDownCoversTheSphereAndItsShadow() {
        const render::PixelRect r =
            render::shadowReceiverRect(slotFor(directional({0.0f, -1.0f, 0.0f})), unitSphere(),
                                       true, -1.0f, topDown(), kSize, kSize);
        QVERIFY(close(r, {5, 5, 90, 90}));
    }

    // At 45 degrees towards +x the box's edges (sqrt(3) either side of the light's axis in the
    // x-y plane) meet the ground at x = 1 - sqrt(6) (pixel 13.8) and x = 1 + sqrt(6) (off the
    // frame); z stays in [-sqrt(3), sqrt(3)].
    void slantedLightReachesItsShadow() {
        const render::PixelRect r =
            render::shadowReceiverRect(slotFor(directional({1.0f, -1.0f, 0.0f})), unitSphere(),
                                       true, -1.0f, topDown(), kSize, kSize);
        QVERIFY(close(r, {12, 5, 88, 90}));
        // Without a ground only the mesh's bounds receive: x and z in [-1, 1].
        const render::PixelRect meshOnly =
            render::shadowReceiverRect(slotFor(directional({1.0f, -1.0f, 0.0f})), unitSphere(),
                                       false, -1.0f, topDown(), kSize, kSize);
        QVERIFY(close(meshOnly, {24, 24, 52, 52}));
    }

    // A light from under the ground (the lookup is 0 on a ground facing away from it, not the
    // mask's clear value) and a point light whose map's pyramid is unbounded on the ground: the
    // whole frame.
    void unboundedOrUnderTheGroundIsTheWholeFrame() {
        const render::PixelRect full{0, 0, kSize, kSize};
        QCOMPARE(render::shadowReceiverRect(slotFor(directional({0.3f, 1.0f, 0.0f})), unitSphere(),
                                            true, -1.0f, topDown(), kSize, kSize),
                 full);
        Light low;
        low.type = LightType::Point;
        low.position = {4.0f, 0.5f, 0.0f}; // above the ground, below the sphere's top
        low.range = 50.0f;
        low.castShadows = true;
        QCOMPARE(render::shadowReceiverRect(slotFor(low), unitSphere(), true, -1.0f, topDown(),
                                            kSize, kSize),
                 full);
        // High above, its pyramid meets the ground in a bounded patch around the sphere (about
        // 1.85 m either side; seen 8 m across, the sphere's bounds are pixels 37.5..62.5).
        Light high = low;
        high.position = {0.5f, 20.0f, 0.0f};
        const render::PixelRect r = render::shadowReceiverRect(slotFor(high), unitSphere(), true,
                                                               -1.0f, topDown(4.0f), kSize, kSize);
        QVERIFY(r.x > 0 && r.y > 0 && r.x + r.width < kSize && r.y + r.height < kSize);
        QVERIFY(r.x <= 37 && r.x + r.width >= 63 && r.y <= 37 && r.y + r.height >= 63);
    }

    // The half-resolution mask's texels for a frame rectangle: texel t stands for pixel 2t and
    // pixel p reads texels floor(p / 2) and the next (clamped to the mask), so every pixel of the
    // rectangle finds both inside, and a rectangle's texels stay inside the mask.
    void maskTexelsCoverEveryPixelsNeighbours() {
        const int frameW = 101, frameH = 64, maskW = (frameW + 1) / 2, maskH = (frameH + 1) / 2;
        const render::PixelRect rects[] = {{0, 0, frameW, frameH},
                                           {10, 7, 31, 20},
                                           {11, 8, 1, 1},
                                           {100, 63, 1, 1},
                                           {40, 40, 0, 0}};
        for (const render::PixelRect& r : rects) {
            const render::PixelRect m = render::maskRect(r, maskW, maskH);
            QVERIFY(m.x >= 0 && m.y >= 0 && m.x + m.width <= maskW && m.y + m.height <= maskH);
            for (int y = r.y; y < r.y + r.height; ++y)
                for (int x = r.x; x < r.x + r.width; ++x)
                    for (int k = 0; k < 4; ++k) {
                        const int tx = std::min(x / 2 + (k & 1), maskW - 1);
                        const int ty = std::min(y / 2 + (k >> 1), maskH - 1);
                        QVERIFY2(tx >= m.x && tx < m.x + m.width && ty >= m.y &&
                                     ty < m.y + m.height,
                                 qPrintable(QString("pixel %1,%2 reads texel %3,%4 outside")
                                                .arg(x)
                                                .arg(y)
                                                .arg(tx)
                                                .arg(ty)));
                    }
        }
        // The whole frame is the whole mask; an empty rectangle stays empty.
        QCOMPARE(render::maskRect({0, 0, frameW, frameH}, maskW, maskH),
                 (render::PixelRect{0, 0, maskW, maskH}));
        QCOMPARE(render::maskRect({40, 40, 0, 0}, maskW, maskH).width, 0);
    }

    // The occlusion can differ from 1 only within its radius of the mesh: seen straight down, the
    // unit box grown by 0.5 m is x, z in [-1.5, 1.5], pixels 12.5..87.5 and one of margin; no
    // mesh, no pixel; a camera inside the reach, the whole frame.
    void occlusionReachesItsRadiusAroundTheMesh() {
        QVERIFY(close(render::occlusionRect(unitSphere(), 0.5f, topDown(), kSize, kSize),
                      {11, 11, 78, 78}));
        QVERIFY(close(render::occlusionRect(unitSphere(), 0.0f, topDown(), kSize, kSize),
                      {24, 24, 52, 52}));
        QCOMPARE(render::occlusionRect(MeshBounds{}, 0.5f, topDown(), kSize, kSize).width, 0);
        const glm::mat4 inside =
            glm::perspective(1.0f, 1.0f, 0.01f, 100.0f) *
            glm::lookAt(glm::vec3(0.0f, 1.2f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
        QCOMPARE(render::occlusionRect(unitSphere(), 0.5f, inside, kSize, kSize),
                 (render::PixelRect{0, 0, kSize, kSize}));
    }
};

QTEST_APPLESS_MAIN(TestRenderShadowMask)
#include "test_render_shadow_mask.moc"
