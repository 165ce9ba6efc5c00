// render/material_bake (issue 12, engine texture sets): a material's maps baked on the GPU in UV
// space hold, texel by texel, what the G-buffer pass computes: parameters times their textures
// (varying texels, one of them an atlas region), occlusion with its strength, the normal map with
// its scale, emission colour x texture x strength; a node graph's output (a UV gradient into
// roughness) is evaluated per texel; a material without textures gives flat maps; the lobes
// (clearcoat, sheen, specular, anisotropy) as the G-buffer pass reads them.
#include "core/color_management.h"
#include "core/graph/graph.h"
#include "core/graph/node_catalogue.h"
#include "core/image.h"
#include "render/material_bake.h"
#include "render_test_util.h"

#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

using namespace velvet;

namespace {

constexpr int kSide = 16;
/// Textures go up as RGBA16F: half precision (11 bits) on values in [0, 1].
constexpr float kHalf = 2e-3f;

/// A texel value on the 8-bit grid that differs per texel and per channel.
float texel(int x, int y, int c) {
    return float((x * 13 + y * 7 + c * 71) % 256) / 255.0f;
}

Image pattern(int w, int h, int channels) {
    Image img(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                img.at(x, y)[c] = texel(x, y, c);
    return img;
}

void write(const QString& file, const Image& img) {
    std::string error;
    if (!writeImage(file.toStdString(), img, PixelFormat::UInt8, &error))
        qFatal("%s", error.c_str());
}

TextureRef ref(const QString& file, const std::string& colorSpace = {}) {
    TextureRef r;
    r.file = file.toStdString();
    r.colorSpace = colorSpace;
    return r;
}

bool near(float got, float expected, float tolerance, const char* what, int x, int y) {
    if (std::abs(got - expected) <= tolerance)
        return true;
    qWarning("%s at (%d, %d): got %.5f, expected %.5f", what, x, y, got, expected);
    return false;
}

} // namespace

class TestRenderMaterialBake : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void initTestCase() {
        std::string error;
        QVERIFY2(test::headlessContext(&error), error.c_str());
        QVERIFY(m_dir.isValid());
    }

    // Every per-pixel slot with varying texels, baked at the textures' own size so each baked
    // texel is one source texel: ORM = (1 + s (ao - 1), roughness x G, metallic x B), base colour
    // = parameter x texel (colour read "Raw" so the file's values are the linear ones) with the
    // texel's alpha, emission = colour x texel x strength, normal = normalize((2t - 1)(s, s, 1)).
    void texturedSlotsTexelByTexel() {
        const QString d = m_dir.path() + "/";
        // The base colour is the right half of a 2:1 atlas (a region), the left half is noise.
        Image atlas(2 * kSide, kSide, 4);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < 2 * kSide; ++x)
                for (int c = 0; c < 4; ++c)
                    atlas.at(x, y)[c] = x < kSide ? 0.0f : texel(x - kSide, y, c) * 0.5f + 0.5f;
        write(d + "atlas.png", atlas);
        write(d + "occlusion.png", pattern(kSide, kSide, 1));
        write(d + "mr.png", pattern(kSide, kSide, 3));
        write(d + "emissive.png", pattern(kSide, kSide, 3));
        Image normal(kSide, kSide, 3);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                normal.at(x, y)[0] = float(64 + x * 8) / 255.0f;
                normal.at(x, y)[1] = float(200 - y * 8) / 255.0f;
                normal.at(x, y)[2] = 1.0f;
            }
        write(d + "normal.png", normal);

        Material m;
        const glm::vec3 baseParam(0.8f, 0.6f, 0.4f), emissionParam(1.0f, 0.5f, 0.25f);
        m.setColor(ParamId::BaseColor, baseParam);
        m.setScalar(ParamId::Roughness, 0.9f);
        m.setScalar(ParamId::Metallic, 0.7f);
        m.setScalar(ParamId::OcclusionStrength, 0.5f);
        m.setScalar(ParamId::NormalScale, 0.75f);
        m.setColor(ParamId::EmissiveColor, emissionParam);
        m.setScalar(ParamId::EmissiveStrength, 3.0f);
        TextureRef base = ref(d + "atlas.png", "Raw");
        base.useRegion = true;
        base.region = {kSide, 0, kSide, kSide};
        m.setTexture(TextureSlot::BaseColor, base);
        m.setTexture(TextureSlot::Occlusion, ref(d + "occlusion.png"));
        m.setTexture(TextureSlot::MetallicRoughness, ref(d + "mr.png"));
        m.setTexture(TextureSlot::Normal, ref(d + "normal.png"));
        m.setTexture(TextureSlot::Emissive, ref(d + "emissive.png", "Raw"));

        MaterialMaps maps;
        Problems problems;
        std::string error;
        QVERIFY2(render::bakeMaterialMaps(m, kSide, kSide, maps, &problems, &error), error.c_str());
        for (const Problem& p : problems.items)
            qWarning("%s", p.toString().c_str());
        QVERIFY(problems.items.empty());
        QCOMPARE(maps.orm.width, kSide);
        QCOMPARE(maps.baseColor.channels, 4);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float* orm = maps.orm.at(x, y);
                QVERIFY(
                    near(orm[0], 1.0f + 0.5f * (texel(x, y, 0) - 1.0f), kHalf, "occlusion", x, y));
                QVERIFY(near(orm[1], 0.9f * texel(x, y, 1), kHalf, "roughness", x, y));
                QVERIFY(near(orm[2], 0.7f * texel(x, y, 2), kHalf, "metallic", x, y));
                const float* bc = maps.baseColor.at(x, y);
                for (int c = 0; c < 3; ++c)
                    QVERIFY(near(bc[c], baseParam[c] * (texel(x, y, c) * 0.5f + 0.5f), kHalf,
                                 "base colour", x, y));
                QVERIFY(near(bc[3], texel(x, y, 3) * 0.5f + 0.5f, kHalf, "alpha", x, y));
                const float* e = maps.emission.at(x, y);
                for (int c = 0; c < 3; ++c)
                    QVERIFY(near(e[c], 3.0f * emissionParam[c] * texel(x, y, c), 3 * kHalf,
                                 "emission", x, y));
                glm::vec3 n(normal.at(x, y)[0], normal.at(x, y)[1], normal.at(x, y)[2]);
                n = n * 2.0f - 1.0f;
                n = glm::normalize(glm::vec3(n.x * 0.75f, n.y * 0.75f, n.z));
                const float* b = maps.normal.at(x, y);
                for (int c = 0; c < 3; ++c)
                    QVERIFY(near(b[c], n[c], 4 * kHalf, "normal", x, y));
            }
    }

    // The lobes, texel by texel against the material: clearcoat weight x texture R and
    // roughness x texture G, sheen weight x colour x texture RGB and roughness x texture A,
    // specular colour x texture RGB and weight x texture A (KHR_materials_* channels), and the
    // anisotropy direction from the texture's RG turned by the rotation, strength x its B.
    void lobesTexelByTexel() {
        const QString d = m_dir.path() + "/";
        write(d + "lobe_a.png", pattern(kSide, kSide, 4));
        Image dir(kSide, kSide, 3);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float a = 0.3f * float(x) + 0.1f * float(y); // radians, varies per texel
                dir.at(x, y)[0] = std::cos(a) * 0.5f + 0.5f;
                dir.at(x, y)[1] = std::sin(a) * 0.5f + 0.5f;
                dir.at(x, y)[2] = texel(x, y, 2);
            }
        write(d + "direction.png", dir);
        Material m;
        m.setScalar(ParamId::ClearcoatWeight, 0.7f);
        m.setScalar(ParamId::ClearcoatRoughness, 0.6f);
        m.setScalar(ParamId::SheenWeight, 0.5f);
        const glm::vec3 sheenColour(1.0f, 0.5f, 0.25f), specColour(1.0f, 0.9f, 0.8f);
        m.setColor(ParamId::SheenColor, sheenColour);
        m.setScalar(ParamId::SheenRoughness, 0.8f);
        m.setScalar(ParamId::SpecularWeight, 0.9f);
        m.setColor(ParamId::SpecularColor, specColour);
        m.setScalar(ParamId::AnisotropyStrength, 0.75f);
        m.setScalar(ParamId::AnisotropyRotation, 30.0f);
        for (TextureSlot slot : {TextureSlot::Clearcoat, TextureSlot::ClearcoatRoughness,
                                 TextureSlot::SheenRoughness, TextureSlot::Specular})
            m.setTexture(slot, ref(d + "lobe_a.png"));
        for (TextureSlot slot : {TextureSlot::SheenColor, TextureSlot::SpecularColor})
            m.setTexture(slot, ref(d + "lobe_a.png", "Raw"));
        m.setTexture(TextureSlot::Anisotropy, ref(d + "direction.png"));

        MaterialMaps maps;
        Problems problems;
        std::string error;
        QVERIFY2(render::bakeMaterialMaps(m, kSide, kSide, maps, &problems, &error), error.c_str());
        QVERIFY(problems.items.empty());
        QCOMPARE(maps.coat.width, kSide);
        QCOMPARE(maps.sheen.channels, 4);
        const float r = glm::radians(30.0f);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float* coat = maps.coat.at(x, y);
                QVERIFY(near(coat[0], 0.7f * texel(x, y, 0), kHalf, "clearcoat", x, y));
                QVERIFY(near(coat[1], 0.6f * texel(x, y, 1), kHalf, "clearcoat roughness", x, y));
                const float* sheen = maps.sheen.at(x, y);
                for (int c = 0; c < 3; ++c)
                    QVERIFY(near(sheen[c], 0.5f * sheenColour[c] * texel(x, y, c), kHalf,
                                 "sheen colour", x, y));
                QVERIFY(near(sheen[3], 0.8f * texel(x, y, 3), kHalf, "sheen roughness", x, y));
                const float* spec = maps.specular.at(x, y);
                for (int c = 0; c < 3; ++c)
                    QVERIFY(near(spec[c], specColour[c] * texel(x, y, c), kHalf, "specular colour",
                                 x, y));
                QVERIFY(near(spec[3], 0.9f * texel(x, y, 3), kHalf, "specular", x, y));
                const float a = 0.3f * float(x) + 0.1f * float(y) + r;
                const float* an = maps.anisotropy.at(x, y);
                // The direction from 8-bit texels: a few thousandths of a radian.
                QVERIFY(near(an[0], std::cos(a), 0.01f, "anisotropy direction x", x, y));
                QVERIFY(near(an[1], std::sin(a), 0.01f, "anisotropy direction y", x, y));
                QVERIFY(near(an[2], 0.75f * texel(x, y, 2), kHalf, "anisotropy strength", x, y));
            }
    }

    // A graph drives roughness with a gradient along U: the baked roughness is u at each texel
    // centre, (x + 0.5) / size, on every row; the other maps keep the parameters (flat).
    void graphOutputIsBakedPerTexel() {
        graph::Graph g;
        const graph::NodeId out = g.addNode(graph::kOutputTypeId).node;
        const graph::NodeId ramp = g.addNode("noise.gradient").node;
        const graph::NodeType* outType = graph::findNodeType(graph::kOutputTypeId);
        QVERIFY(g.connect({ramp, 0, out, graph::PortIndex(outType->inputIndex("roughness"))}));
        Material m;
        m.setColor(ParamId::BaseColor, {0.25f, 0.5f, 0.75f});
        m.setScalar(ParamId::Metallic, 1.0f);
        m.graph = SharedGraph(g);
        MaterialMaps maps;
        std::string error;
        constexpr int kSize = 32;
        QVERIFY2(render::bakeMaterialMaps(m, kSize, 8, maps, nullptr, &error), error.c_str());
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < kSize; ++x) {
                QVERIFY(near(maps.orm.at(x, y)[1], (float(x) + 0.5f) / kSize, 1e-5f, "roughness", x,
                             y));
                QVERIFY(near(maps.orm.at(x, y)[2], 1.0f, 0.0f, "metallic", x, y));
                QVERIFY(near(maps.orm.at(x, y)[0], 1.0f, 0.0f, "occlusion", x, y));
                QVERIFY(near(maps.baseColor.at(x, y)[1], 0.5f, 1e-6f, "base colour", x, y));
                QVERIFY(near(maps.normal.at(x, y)[2], 1.0f, 1e-6f, "flat normal", x, y));
                QVERIFY(near(maps.emission.at(x, y)[0], 0.0f, 0.0f, "no emission", x, y));
            }
    }

    // A missing texture is reported (the slot falls back to its parameter, as in the viewport).
    void missingTextureIsReported() {
        Material m;
        m.setTexture(TextureSlot::Occlusion, ref(m_dir.path() + "/missing.png"));
        MaterialMaps maps;
        Problems problems;
        std::string error;
        QVERIFY(render::bakeMaterialMaps(m, 4, 4, maps, &problems, &error));
        QVERIFY(problems.hasErrors() || !problems.items.empty());
        QCOMPARE(maps.orm.at(0, 0)[0], 1.0f);
    }
};

QTEST_GUILESS_MAIN(TestRenderMaterialBake)
#include "test_render_material_bake.moc"
