// Every lobe per pixel (render/lobe_channels.h): the channel assignment on its own, then, through
// the real renderer, a two-valued map in each lobe slot draws each half of the sphere exactly as
// the material with that value as a constant does, and a graph's IOR likewise; the clear coat's
// own normal map moves the coat's highlight and not the base's; the compact 16-byte layout is
// still there to compare.
#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "core/image.h"
#include "render/gbuffer_layout.h"
#include "render/lobe_channels.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"
#include "tests/core/graph_test_util.h"

#include <QtTest>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>

using namespace velvet;
using render::LobeValue;
namespace fs = std::filesystem;

namespace {

constexpr int kSize = 64;

/// A 16 x 8 map whose left half (u < 0.5) is @p left and right half @p right.
Image halves(glm::vec4 left, glm::vec4 right) {
    Image img(16, 8, 4);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 16; ++x)
            for (int k = 0; k < 4; ++k)
                img.at(x, y)[k] = x < 8 ? left[k] : right[k];
    return img;
}

Image flat(glm::vec4 value) {
    return halves(value, value);
}

/// Grey base under a warm key light and a dim uniform environment: direct and image-based light
/// both reach every lobe.
Scene litSphere() {
    Scene scene = test::blackOrthographicScene();
    scene.lights = {test::analyticKeyLight()};
    scene.environment.color = glm::vec3(0.3f);
    Material& m = scene.material;
    m.setColor(ParamId::BaseColor, glm::vec3(0.4f));
    m.setScalar(ParamId::Roughness, 0.35f);
    return scene;
}

} // namespace

class TestRenderLobeChannels : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    test::OffscreenRenderer m_fixture;

    fs::path write(const char* name, const Image& image) {
        const fs::path file = fs::path(m_dir.path().toStdString()) / name;
        std::string error;
        if (!writeImage(file, image, PixelFormat::UInt8, &error))
            qFatal("%s", error.c_str());
        return file;
    }

    Image render(const Scene& scene, render::DebugView view = render::DebugView::Final,
                 Problems* problems = nullptr) {
        return m_fixture.draw(&scene, view, problems);
    }

    static void setRaw(Material& m, TextureSlot slot, const fs::path& file) {
        TextureRef ref;
        ref.file = file.string();
        ref.colorSpace = "Raw";
        m.setTexture(slot, ref);
    }

private slots:
    void initTestCase() {
        QVERIFY(m_dir.isValid());
        const std::string error = m_fixture.start(kSize);
        QVERIFY2(error.empty(), error.c_str());
    }
    void cleanupTestCase() { m_fixture.stop(); }

    // The layout's budget: 16 common bytes + 8 lobe channels = 24, the compact one 16.
    void budget() {
        QCOMPARE(render::gbufferBytesPerPixel(), 24);
        QCOMPARE(render::gbufferBytesPerPixel(/*compact=*/true), 16);
        QCOMPARE(render::gbufferUnit("GBUFFER_DEPTH"), 3);
    }

    // Values get contiguous channels in priority order; what does not fit overflows and is named;
    // the packed map holds 4 bits a value, 15 for "per material".
    void assignment() {
        using render::lobeBit;
        const auto none = render::assignLobeChannels(0);
        QCOMPARE(none.packed(), std::int32_t(-1));
        QCOMPARE(none.channelsUsed, 0);

        const auto velvet = render::assignLobeChannels(lobeBit(LobeValue::SheenColor) |
                                                       lobeBit(LobeValue::SheenRoughness));
        QCOMPARE(velvet.firstChannel[size_t(LobeValue::SheenColor)], 0);
        QCOMPARE(velvet.firstChannel[size_t(LobeValue::SheenRoughness)], 3);
        QCOMPARE(velvet.channelsUsed, 4);
        QCOMPARE((velvet.packed() >> (4 * int(LobeValue::SheenRoughness))) & 15, 3);
        QCOMPARE((velvet.packed() >> (4 * int(LobeValue::Clearcoat))) & 15, 15);

        // All of them: 15 channels' worth, 8 fit (anisotropy 2, sheen 3 + 1, coat 1 + 1); the
        // coat normal, the specular weight and colour and the IOR stay per material.
        const render::LobeValueSet all = (1u << render::kLobeValueCount) - 1;
        const auto full = render::assignLobeChannels(all);
        QCOMPARE(full.channelsUsed, 8);
        QCOMPARE(full.overflow, lobeBit(LobeValue::ClearcoatNormal) |
                                    lobeBit(LobeValue::SpecularWeight) |
                                    lobeBit(LobeValue::SpecularColor) | lobeBit(LobeValue::Ior));
        QCOMPARE(full.firstChannel[size_t(LobeValue::ClearcoatRoughness)], 7);
        QCOMPARE(render::lobeValueNames(full.overflow),
                 std::string("clearcoat normal, specular, specular colour, IOR"));
        // The IOR's entry lives outside the packed word (GpuMaterial::clearcoat.w).
        QCOMPARE(full.iorEntry(), render::kLobePerMaterial);
        const auto ior = render::assignLobeChannels(lobeBit(LobeValue::Ior));
        QCOMPARE(ior.iorEntry(), 0);
        QCOMPARE(ior.packed(), std::int32_t(-1));
        // A smaller value still takes a channel a larger one before it could not.
        const auto gap = render::assignLobeChannels(
            lobeBit(LobeValue::Anisotropy) | lobeBit(LobeValue::SheenColor) |
            lobeBit(LobeValue::ClearcoatNormal) | lobeBit(LobeValue::SpecularColor));
        QCOMPARE(gap.overflow, lobeBit(LobeValue::SpecularColor));
        QCOMPARE(gap.firstChannel[size_t(LobeValue::ClearcoatNormal)], 5);
        for (int v = 0; v < render::kLobeValueCount; ++v)
            if (full.perPixel(LobeValue(v)))
                QVERIFY(full.firstChannel[size_t(v)] + render::lobeValueChannels(LobeValue(v)) <=
                        render::kLobeChannelCount);
        // The compact layout has no channel: everything per material, nothing "overflows" there
        // as a surprise to the caller (it asked for none).
        QCOMPARE(render::assignLobeChannels(all, 0).channelsUsed, 0);
    }

    // What makes a value vary: its slot, a graph input, and for anisotropy any strength (the
    // direction follows the surface); the coat's normal when either normal is bumped.
    void varyingValues() {
        Material m;
        m.setScalar(ParamId::ClearcoatWeight, 0.0f);
        m.setScalar(ParamId::AnisotropyStrength, 0.0f);
        QCOMPARE(render::varyingLobeValues(m, 0, {}), render::LobeValueSet(0));
        const auto slot = [](TextureSlot s) { return 1u << int(s); };
        QCOMPARE(render::varyingLobeValues(m, slot(TextureSlot::SheenColor), {}),
                 render::lobeBit(LobeValue::SheenColor));
        QCOMPARE(render::varyingLobeValues(m, 0, {"sheenWeight"}),
                 render::lobeBit(LobeValue::SheenColor));
        QCOMPARE(render::varyingLobeValues(m, slot(TextureSlot::SpecRoughMetal), {}),
                 render::lobeBit(LobeValue::SpecularWeight));
        QCOMPARE(render::varyingLobeValues(m, 0, {"ior"}), render::lobeBit(LobeValue::Ior));
        // A normal map alone bends no coat when there is none.
        QCOMPARE(render::varyingLobeValues(m, slot(TextureSlot::Normal), {}),
                 render::LobeValueSet(0));
        m.setScalar(ParamId::ClearcoatWeight, 1.0f);
        QCOMPARE(render::varyingLobeValues(m, slot(TextureSlot::Normal), {}),
                 render::lobeBit(LobeValue::ClearcoatNormal));
        m.setScalar(ParamId::AnisotropyStrength, 0.5f);
        QVERIFY(render::varyingLobeValues(m, 0, {}) & render::lobeBit(LobeValue::Anisotropy));
        // The shading normal is bent by a normal map or a graph's normal, by nothing else.
        QVERIFY(render::perturbsNormal(slot(TextureSlot::Normal), {}));
        QVERIFY(render::perturbsNormal(0, {"baseColor", "normal"}));
        QVERIFY(!render::perturbsNormal(slot(TextureSlot::BaseColor) | slot(TextureSlot::Occlusion),
                                        {"baseColor", "sheenColor"}));
    }

    // Each lobe slot per pixel: with a map whose halves hold two values, every sphere pixel away
    // from the seams equals the render of the material with one of the two values as its
    // parameter (the known answer), and both halves show. The view is the G-buffer view that
    // shows the decoded value (sheen colour, clearcoat weight and roughness, specular colour x
    // weight, anisotropy direction x strength), or the final image for the sheen roughness, which
    // has none. Values are 8-bit exact (or sRGB-encoded colours); the tolerance covers that.
    void everyLobeSlotIsPerPixel_data() {
        QTest::addColumn<int>("slot");
        QTest::addColumn<int>("param");
        QTest::addColumn<int>("channel"); // the texture channel the slot reads (3: RGB)
        QTest::addColumn<float>("high");
        QTest::addColumn<float>("low");
        QTest::addColumn<int>("view");
        using V = render::DebugView;
        QTest::newRow("sheen colour") << int(TextureSlot::SheenColor) << int(ParamId::SheenColor)
                                      << 3 << 1.0f << 0.2f << int(V::Sheen);
        QTest::newRow("sheen roughness")
            << int(TextureSlot::SheenRoughness) << int(ParamId::SheenRoughness) << 3 << 0.8f << 0.2f
            << int(V::Final);
        QTest::newRow("clearcoat") << int(TextureSlot::Clearcoat) << int(ParamId::ClearcoatWeight)
                                   << 0 << 1.0f << 0.2f << int(V::Clearcoat);
        QTest::newRow("clearcoat roughness")
            << int(TextureSlot::ClearcoatRoughness) << int(ParamId::ClearcoatRoughness) << 1 << 0.6f
            << 0.2f << int(V::Clearcoat);
        QTest::newRow("specular") << int(TextureSlot::Specular) << int(ParamId::SpecularWeight) << 3
                                  << 1.0f << 0.2f << int(V::Specular);
        QTest::newRow("specular colour")
            << int(TextureSlot::SpecularColor) << int(ParamId::SpecularColor) << 3 << 1.0f << 0.2f
            << int(V::Specular);
        QTest::newRow("anisotropy")
            << int(TextureSlot::Anisotropy) << int(ParamId::AnisotropyStrength) << 2 << 1.0f << 0.2f
            << int(V::Anisotropy);
        QTest::newRow("anisotropy, lit")
            << int(TextureSlot::Anisotropy) << int(ParamId::AnisotropyStrength) << 2 << 1.0f << 0.2f
            << int(V::Final);
    }
    void everyLobeSlotIsPerPixel() {
        QFETCH(int, slot);
        QFETCH(int, param);
        QFETCH(int, channel);
        QFETCH(float, high);
        QFETCH(float, low);
        QFETCH(int, view);
        const auto debugView = render::DebugView(view);
        Scene base = litSphere();
        Material& m = base.material;
        const TextureSlot s = TextureSlot(slot);
        const ParamId p = ParamId(param);
        if (s == TextureSlot::SheenColor || s == TextureSlot::SheenRoughness) {
            m.setScalar(ParamId::SheenWeight, 1.0f);
            m.setColor(ParamId::SheenColor, glm::vec3(1.0f, 0.8f, 0.9f));
            m.setScalar(ParamId::SheenRoughness, 0.5f);
        }
        if (s == TextureSlot::Clearcoat || s == TextureSlot::ClearcoatRoughness) {
            m.setScalar(ParamId::ClearcoatWeight, 1.0f);
            m.setScalar(ParamId::ClearcoatRoughness, 0.3f);
        }
        if (s == TextureSlot::Anisotropy) {
            m.setScalar(ParamId::Roughness, 0.3f);
            m.setScalar(ParamId::Metallic, 1.0f);
            m.setColor(ParamId::BaseColor, glm::vec3(0.9f));
        }
        // The factor 1 (white for colours) times the map; the constants are the map's values.
        const auto texel = [&](float value) {
            glm::vec4 t(0.0f, 0.0f, 0.0f, 1.0f);
            if (s == TextureSlot::Anisotropy)
                t = glm::vec4(1.0f, 0.5f, value, 1.0f); // direction (1, 0): the tangent
            else if (channel == 3 && s != TextureSlot::SheenRoughness && s != TextureSlot::Specular)
                t = glm::vec4(glm::vec3(value), 1.0f);
            else
                t[channel] = value;
            return t;
        };
        const auto constant = [&](float value) {
            Scene scene = base;
            if (paramMeta(p).type == ParamType::Color)
                scene.material.setColor(p, glm::vec3(value));
            else
                scene.material.setScalar(p, value);
            return scene;
        };
        Scene mapped = base;
        if (paramMeta(p).type == ParamType::Color)
            mapped.material.setColor(p, glm::vec3(1.0f));
        else
            mapped.material.setScalar(p, 1.0f);
        setRaw(mapped.material, s, write("lobe_halves.png", halves(texel(high), texel(low))));
        Problems problems;
        const Image got = render(mapped, debugView, &problems);
        QVERIFY(!problems.hasErrors());
        const Image hi = render(constant(high), debugView);
        const Image lo = render(constant(low), debugView);
        const Image normals = render(base, render::DebugView::Normal);
        expectHalves(got, hi, lo, normals);
    }

    // KHR_materials_ior through the material graph (it has no texture slot): an image whose
    // halves hold 1.0 and 0.4, plus 1, drives the IOR (2.0 and 1.4, stored as (ior - 1) / 2 in a
    // lobe channel: 128/255 and 51/255); each half of the sphere draws as the material with that
    // IOR as its parameter.
    void graphIorIsPerPixel() {
        // A black dielectric in a white uniform environment: all it shows is its reflection,
        // whose strength is the IOR's Fresnel (F0 0.111 at 2.0, 0.028 at 1.4).
        Scene base = litSphere();
        base.lights.clear();
        base.environment.color = glm::vec3(1.0f);
        base.material.setColor(ParamId::BaseColor, glm::vec3(0.0f));
        base.material.setScalar(ParamId::Roughness, 0.25f);
        graph::Graph g;
        const graph::NodeId tex = g.addNode("texture.image").node;
        const graph::NodeId plus = g.addNode("math.add").node;
        const graph::NodeId out = g.addNode(graph::kOutputTypeId).node;
        const fs::path file = write("ior_halves.png", halves(glm::vec4(glm::vec3(1.0f), 1.0f),
                                                             glm::vec4(glm::vec3(0.4f), 1.0f)));
        QVERIFY(g.setSetting(tex, "file", file.string()).ok);
        QVERIFY(g.setSetting(tex, "colorSpace", "Raw").ok);
        QVERIFY(g.setInputValue(plus, 1, glm::vec4(1.0f)).ok);
        QVERIFY(g.connect(test::link(g, tex, "color", plus, "a")).ok);
        QVERIFY(g.connect(test::link(g, plus, "result", out, "ior")).ok);
        Scene mapped = base;
        mapped.material.graph = SharedGraph(g);
        const auto constant = [&](float ior) {
            Scene scene = base;
            scene.material.setScalar(ParamId::Ior, ior);
            return scene;
        };
        Problems problems;
        render(mapped, render::DebugView::Final, &problems);
        render(mapped); // the frame after a new structure draws with its specialised program
        const Image got = render(mapped, render::DebugView::Final, &problems);
        QVERIFY(!problems.hasErrors());
        const Image hi = render(constant(2.0f));
        const Image lo = render(constant(1.4f));
        expectHalves(got, hi, lo, render(base, render::DebugView::Normal));
    }

    /// Every sphere pixel of @p got where @p hi and @p lo (the two constants' images) differ
    /// matches one of them, and both show: a two-valued map drawn per pixel.
    void expectHalves(const Image& got, const Image& hi, const Image& lo, const Image& normals) {
        const auto tolerance = [](float e) { return 0.03f * e + 2.0f / 255.0f; };
        int sphere = 0, matchHigh = 0, matchLow = 0, differ = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                if (glm::length(glm::vec3(normals.rgba(x, y))) < 0.5f)
                    continue; // background
                ++sphere;
                const glm::vec3 a(glm::abs(glm::vec3(hi.rgba(x, y)))),
                    b(glm::abs(glm::vec3(lo.rgba(x, y)))), c(glm::abs(glm::vec3(got.rgba(x, y))));
                const auto near = [&](glm::vec3 e) {
                    const glm::vec3 d = glm::abs(c - e);
                    return d.x <= tolerance(e.x) && d.y <= tolerance(e.y) && d.z <= tolerance(e.z);
                };
                // Only pixels where the two constants differ by more than twice the tolerance
                // tell the halves apart (and can match only one of them).
                bool telling = false;
                for (int k = 0; k < 3; ++k)
                    telling |= std::abs(a[k] - b[k]) > 2.0f * tolerance(std::max(a[k], b[k]));
                if (!telling)
                    continue;
                ++differ;
                matchHigh += near(a);
                matchLow += near(b);
            }
        qInfo("sphere %d, telling %d: like the high value %d, like the low value %d", sphere,
              differ, matchHigh, matchLow);
        QVERIFY2(differ > sphere / 20, "the two values look different on enough of the sphere");
        QVERIFY2(matchHigh > differ / 6 && matchLow > differ / 6, "both halves show");
        QVERIFY2(matchHigh + matchLow > differ * 6 / 10, "only seams and poles are filtered");
    }

    // KHR_materials_clearcoat: the coat has its own normal. A tilted coat normal map moves the
    // coat's highlight (clearcoat-only view) and leaves the base's specular exactly as it was.
    void clearcoatNormalMovesOnlyTheCoat() {
        Scene scene = litSphere();
        scene.environment.color = glm::vec3(0.0f); // the lobe views show direct light
        scene.material.setScalar(ParamId::ClearcoatWeight, 1.0f);
        scene.material.setScalar(ParamId::ClearcoatRoughness, 0.15f);
        const Image coatBefore = render(scene, render::DebugView::ClearcoatOnly);
        const Image baseBefore = render(scene, render::DebugView::BaseSpecular);
        // (0.35, 0.2, 1) tangent-space, encoded: a normal tilted by ~22 degrees.
        const glm::vec3 tilted = glm::normalize(glm::vec3(0.35f, 0.2f, 1.0f));
        setRaw(scene.material, TextureSlot::ClearcoatNormal,
               write("coat_normal.png", flat(glm::vec4(tilted * 0.5f + 0.5f, 1.0f))));
        const Image coatAfter = render(scene, render::DebugView::ClearcoatOnly);
        const Image baseAfter = render(scene, render::DebugView::BaseSpecular);
        // The brightest pixel of each lobe: the highlight's position.
        const auto peak = [](const Image& img) {
            int best = 0;
            float value = -1.0f;
            for (int i = 0; i < kSize * kSize; ++i) {
                const float y = img.rgba(i % kSize, i / kSize).y;
                if (y > value)
                    value = y, best = i;
            }
            return std::pair{glm::ivec2(best % kSize, best / kSize), value};
        };
        const auto [coatPeakBefore, coatMax] = peak(coatBefore);
        const auto [coatPeakAfter, coatMaxAfter] = peak(coatAfter);
        const auto [basePeakBefore, baseMax] = peak(baseBefore);
        const auto [basePeakAfter, baseMaxAfter] = peak(baseAfter);
        double baseChange = 0.0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                baseChange = std::max(
                    baseChange,
                    double(glm::length(glm::vec3(baseAfter.rgba(x, y) - baseBefore.rgba(x, y)))));
        qInfo("coat highlight (%d,%d) -> (%d,%d); base highlight (%d,%d) -> (%d,%d), largest "
              "base change %.5f of its peak %.4f (the coat's Fresnel over it)",
              coatPeakBefore.x, coatPeakBefore.y, coatPeakAfter.x, coatPeakAfter.y,
              basePeakBefore.x, basePeakBefore.y, basePeakAfter.x, basePeakAfter.y, baseChange,
              double(baseMax));
        QVERIFY(coatMax > 0.05f && baseMax > 0.05f);
        QVERIFY2(glm::length(glm::vec2(coatPeakAfter - coatPeakBefore)) >= 3.0f,
                 "the coat's highlight moved");
        QVERIFY2(basePeakAfter == basePeakBefore, "the base's did not");
        // The base changes only through the coat's Fresnel attenuation over it (a few per mille).
        QVERIFY2(baseChange < 0.01 * baseMax, "the base's lobe is the same");
    }

    // The compact layout draws what the 16-byte G-buffer drew: lobe maps as their mean. The
    // sheen-colour halves (mean 0.6) then give one value over the whole sphere.
    void compactLayoutKeepsMeans() {
        Scene scene = litSphere();
        scene.material.setScalar(ParamId::SheenWeight, 1.0f);
        scene.material.setColor(ParamId::SheenColor, glm::vec3(1.0f));
        setRaw(scene.material, TextureSlot::SheenColor,
               write("sheen_halves.png",
                     halves(glm::vec4(1.0f, 1.0f, 1.0f, 1.0f), glm::vec4(0.2f, 0.2f, 0.2f, 1.0f))));
        m_fixture.renderer->setCompactGBuffer(true);
        const Image compact = render(scene, render::DebugView::Sheen);
        m_fixture.renderer->setCompactGBuffer(false);
        const Image full = render(scene, render::DebugView::Sheen);
        float compactMin = 1e9f, compactMax = 0.0f, fullMin = 1e9f, fullMax = 0.0f;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x) {
                const float c = compact.rgba(x, y).x, f = full.rgba(x, y).x;
                if (c <= 0.0f)
                    continue;
                compactMin = std::min(compactMin, c);
                compactMax = std::max(compactMax, c);
                fullMin = std::min(fullMin, f);
                fullMax = std::max(fullMax, f);
            }
        qInfo("compact sheen %.4f .. %.4f, per pixel %.4f .. %.4f", compactMin, compactMax, fullMin,
              fullMax);
        QVERIFY(std::abs(compactMin - 0.6f) < 0.01f && std::abs(compactMax - 0.6f) < 0.01f);
        QVERIFY(fullMax > 0.97f && fullMin < 0.22f);
    }
};

QTEST_GUILESS_MAIN(TestRenderLobeChannels)
#include "test_render_lobe_channels.moc"
