// core/texture_set_export (issue 12, engine texture sets): for every target the files, their
// names and the manifest's roles; channel by channel against the material's own maps (an ORM
// texel is occlusion, roughness, metallic; HDRP's mask map is metallic, occlusion, detail mask,
// smoothness = 1 - roughness); the normal map's green channel flipped for DirectX (Unreal) and
// not for OpenGL (Unity, Godot, glTF), and as --normal asks; colour maps sRGB-encoded in PNG,
// linear in EXR; emission above 1 scaled with its factor in the manifest; refused options; the
// lobe maps (clearcoat, sheen, specular, anisotropy) each engine reads.
#include "core/color_management.h"
#include "core/texture_set_export.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

using namespace velvet;

namespace {

constexpr int kW = 4, kH = 3;

/// Maps whose texels all differ: roughness, metallic, occlusion on a ramp, a tilted normal,
/// one texel of alpha 0.25, emission up to 4.
MaterialMaps knownMaps(bool alpha = true, bool emission = true) {
    MaterialMaps m;
    m.baseColor = Image(kW, kH, 4);
    m.normal = Image(kW, kH, 3);
    m.orm = Image(kW, kH, 3);
    m.emission = Image(kW, kH, 3);
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const float t = float(y * kW + x) / float(kW * kH - 1);
            float* b = m.baseColor.at(x, y);
            b[0] = t, b[1] = 1.0f - t, b[2] = 0.5f * t,
            b[3] = alpha && x == 1 && y == 2 ? 0.25f : 1;
            const glm::vec3 n = glm::normalize(glm::vec3(0.3f * t, 0.6f - t, 1.0f));
            std::copy(&n.x, &n.x + 3, m.normal.at(x, y));
            float* orm = m.orm.at(x, y);
            orm[0] = 1.0f - 0.5f * t, orm[1] = 0.1f + 0.8f * t, orm[2] = t * t;
            float* e = m.emission.at(x, y);
            e[0] = emission ? 4.0f * t : 0.0f, e[1] = emission ? t : 0.0f, e[2] = 0.0f;
        }
    return m;
}

struct Written {
    QMap<QString, Image> images; ///< by file name
    QJsonObject manifest;
    QStringList names; ///< in the order written
};

Written build(const MaterialMaps& maps, const TextureSetOptions& o, const QString& dir) {
    BuiltExport built;
    std::string error;
    if (!buildTextureSet(maps, "Silk", "Silk test", o, built, &error))
        qFatal("buildTextureSet: %s", error.c_str());
    Written w;
    for (const ExportFile& f : built.files) {
        const QString name = QString::fromStdString(f.name);
        w.names << name;
        QFile file(dir + "/" + name);
        if (!file.open(QIODevice::WriteOnly))
            qFatal("cannot write %s", qPrintable(name));
        file.write(f.bytes.data(), qint64(f.bytes.size()));
        file.close();
        if (name.endsWith(".json")) {
            w.manifest = QJsonDocument::fromJson(QByteArray::fromStdString(f.bytes)).object();
            continue;
        }
        Image img;
        if (!readImage((dir + "/" + name).toStdString(), img, &error))
            qFatal("%s", error.c_str());
        w.images[name] = img;
    }
    return w;
}

/// The manifest's entry for @p role.
QJsonObject entry(const QJsonObject& manifest, const QString& role) {
    for (const QJsonValue v : manifest["files"].toArray())
        if (v.toObject()["role"].toString() == role)
            return v.toObject();
    return {};
}

bool near(float got, float expected, float tolerance, const char* what) {
    if (std::abs(got - expected) <= tolerance)
        return true;
    qWarning("%s: got %.5f, expected %.5f", what, got, expected);
    return false;
}

constexpr float k8 = 0.5f / 255.0f + 1e-6f; ///< 8-bit rounding

} // namespace

class TestTextureSetExport : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void namesAndRolesPerTarget() {
        struct Case {
            TextureSetTarget target;
            QStringList files;
            QString packedRole;
        };
        const Case cases[] = {
            {TextureSetTarget::Unreal,
             {"T_Silk_D.png", "T_Silk_N.png", "T_Silk_ORM.png", "T_Silk_E.png"},
             "occlusionRoughnessMetallic"},
            {TextureSetTarget::UnityHdrp,
             {"Silk_BaseMap.png", "Silk_Normal.png", "Silk_MaskMap.png", "Silk_Emission.png"},
             "maskMap"},
            {TextureSetTarget::Godot,
             {"Silk_albedo.png", "Silk_normal.png", "Silk_orm.png", "Silk_emission.png"},
             "occlusionRoughnessMetallic"},
            {TextureSetTarget::Gltf,
             {"Silk_baseColor.png", "Silk_normal.png", "Silk_orm.png", "Silk_emissive.png"},
             "occlusionRoughnessMetallic"},
        };
        for (const Case& c : cases) {
            QTemporaryDir dir;
            TextureSetOptions o;
            o.target = c.target;
            const Written w = build(knownMaps(), o, dir.path());
            QCOMPARE(w.names, c.files + QStringList{"Silk_texture_set.json"});
            QCOMPARE(w.manifest["target"].toString(),
                     QString::fromUtf8(textureSetTargetId(c.target).data()));
            QCOMPARE(w.manifest["material"].toString(), QStringLiteral("Silk test"));
            QCOMPARE(w.manifest["width"].toInt(), kW);
            QCOMPARE(w.manifest["alphaMode"].toString(), QStringLiteral("mask"));
            QCOMPARE(w.manifest["files"].toArray().size(), 4);
            QCOMPARE(entry(w.manifest, c.packedRole)["file"].toString(), c.files[2]);
            QCOMPARE(entry(w.manifest, "baseColor")["colorSpace"].toString(),
                     QStringLiteral("srgb"));
            QCOMPARE(entry(w.manifest, "normal")["colorSpace"].toString(),
                     QStringLiteral("linear"));
        }
        // No emission and no alpha: no emissive file, an RGB base colour, alphaMode opaque.
        QTemporaryDir dir;
        const Written w = build(knownMaps(false, false), {}, dir.path());
        QCOMPARE(w.names, (QStringList{"Silk_baseColor.png", "Silk_normal.png", "Silk_orm.png",
                                       "Silk_texture_set.json"}));
        QCOMPARE(w.images["Silk_baseColor.png"].channels, 3);
        QCOMPARE(w.manifest["alphaMode"].toString(), QStringLiteral("opaque"));
    }

    // The lobe maps each engine reads, channel by channel against the baked lobe values
    // (16-bit PNG): glTF's KHR_materials_clearcoat (R weight, G roughness), _sheen (RGB colour
    // sRGB, A roughness), _specular (RGB colour sRGB, A weight), _anisotropy (RG direction, B
    // strength); Unreal's clear coat (R, G), fuzz colour (the colour over its largest channel,
    // sRGB) with Cloth (that channel) in A, Specular = F0 / 0.08 = 0.5 weight mean(colour), and
    // anisotropy strength; HDRP Lit's coat mask and anisotropy map; Godot's clearcoat texture
    // (R, G) and flowmap (RG direction, A strength). Without lobes no lobe file is written.
    void lobeMapsPerTarget() {
        MaterialMaps maps = knownMaps();
        maps.coat = Image(kW, kH, 2);
        maps.sheen = Image(kW, kH, 4);
        maps.specular = Image(kW, kH, 4);
        maps.anisotropy = Image(kW, kH, 3);
        const auto coat = [](int x, int y) { return glm::vec2(0.1f * x, 0.2f + 0.2f * y); };
        const auto sheen = [](int x, int y) {
            return glm::vec4(0.5f, 0.25f + 0.05f * x, 0.1f * y, 0.4f);
        };
        const auto spec = [](int x, int y) {
            return glm::vec4(1.0f, 0.9f - 0.1f * y, 0.8f, 0.2f * x);
        };
        const auto dir = [](int x, int y) {
            const float a = 0.5f * x + 0.25f * y;
            return glm::vec3(std::cos(a), std::sin(a), 0.15f * (x + y));
        };
        for (int y = 0; y < kH; ++y)
            for (int x = 0; x < kW; ++x) {
                const glm::vec2 cc = coat(x, y);
                std::copy(&cc.x, &cc.x + 2, maps.coat.at(x, y));
                const glm::vec4 sh = sheen(x, y), sp = spec(x, y);
                const glm::vec3 d = dir(x, y);
                std::copy(&sh.x, &sh.x + 4, maps.sheen.at(x, y));
                std::copy(&sp.x, &sp.x + 4, maps.specular.at(x, y));
                std::copy(&d.x, &d.x + 3, maps.anisotropy.at(x, y));
            }
        constexpr float k16 = 0.5f / 65535.0f + 1e-5f;
        const auto srgb = [](float v) { return linearToSrgb(v); };
        struct Case {
            TextureSetTarget target;
            QStringList lobeFiles; ///< after the four base files, before the manifest
        };
        const Case cases[] = {
            {TextureSetTarget::Gltf,
             {"Silk_clearcoat.png", "Silk_sheen.png", "Silk_specular.png", "Silk_anisotropy.png"}},
            {TextureSetTarget::Unreal,
             {"T_Silk_CC.png", "T_Silk_Fuzz.png", "T_Silk_S.png", "T_Silk_Aniso.png"}},
            {TextureSetTarget::UnityHdrp, {"Silk_CoatMask.png", "Silk_Anisotropy.png"}},
            {TextureSetTarget::Godot, {"Silk_clearcoat.png", "Silk_flowmap.png"}},
        };
        for (const Case& c : cases) {
            QTemporaryDir tmp;
            TextureSetOptions o;
            o.target = c.target;
            o.bits = 16;
            const Written w = build(maps, o, tmp.path());
            QCOMPARE(w.names.mid(4, w.names.size() - 5), c.lobeFiles);
            QCOMPARE(entry(w.manifest, "clearcoat")["file"].toString(), c.lobeFiles[0]);
            QCOMPARE(entry(w.manifest, "anisotropy")["file"].toString(), c.lobeFiles.back());
            const Image& coatImage = *w.images.find(c.lobeFiles[0]);
            const Image& anisoImage = *w.images.find(c.lobeFiles.back());
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const glm::vec2 cc = coat(x, y);
                    const glm::vec4 sh = sheen(x, y), sp = spec(x, y);
                    const glm::vec3 d = dir(x, y);
                    const float* cf = coatImage.at(x, y);
                    QVERIFY(near(cf[0], cc.x, k16, "coat weight"));
                    if (c.target != TextureSetTarget::UnityHdrp)
                        QVERIFY(near(cf[1], cc.y, k16, "coat roughness"));
                    const float* an = anisoImage.at(x, y);
                    switch (c.target) {
                    case TextureSetTarget::Gltf: {
                        const float* s = w.images.find("Silk_sheen.png")->at(x, y);
                        for (int k = 0; k < 3; ++k)
                            QVERIFY(near(s[k], srgb(sh[k]), k16, "sheen colour (sRGB)"));
                        QVERIFY(near(s[3], sh[3], k16, "sheen roughness"));
                        const float* p = w.images.find("Silk_specular.png")->at(x, y);
                        for (int k = 0; k < 3; ++k)
                            QVERIFY(near(p[k], srgb(sp[k]), k16, "specular colour (sRGB)"));
                        QVERIFY(near(p[3], sp[3], k16, "specular weight"));
                        QVERIFY(near(an[0], d.x * 0.5f + 0.5f, k16, "direction x"));
                        QVERIFY(near(an[1], d.y * 0.5f + 0.5f, k16, "direction y"));
                        QVERIFY(near(an[2], d.z, k16, "anisotropy strength"));
                        break;
                    }
                    case TextureSetTarget::Unreal: {
                        const float top = std::max({sh.r, sh.g, sh.b});
                        const float* f = w.images.find("T_Silk_Fuzz.png")->at(x, y);
                        for (int k = 0; k < 3; ++k)
                            QVERIFY(near(f[k], srgb(sh[k] / top), k16, "fuzz colour"));
                        QVERIFY(near(f[3], top, k16, "cloth"));
                        const float specular = 0.5f * sp.a * (sp.r + sp.g + sp.b) / 3.0f;
                        QVERIFY(near(w.images.find("T_Silk_S.png")->at(x, y)[0], specular, k16,
                                     "Unreal Specular = F0 / 0.08"));
                        QVERIFY(near(an[0], d.z, k16, "anisotropy strength"));
                        break;
                    }
                    case TextureSetTarget::UnityHdrp:
                        QVERIFY(near(an[0], d.z, k16, "anisotropy map"));
                        break;
                    case TextureSetTarget::Godot:
                        QCOMPARE(anisoImage.channels, 4);
                        QVERIFY(near(an[0], d.x * 0.5f + 0.5f, k16, "flow x"));
                        QVERIFY(near(an[1], d.y * 0.5f + 0.5f, k16, "flow y"));
                        QVERIFY(near(an[3], d.z, k16, "flowmap strength (A)"));
                        break;
                    default:
                        break;
                    }
                }
        }
        // The glTF set's roles and channels as the manifest names them.
        QTemporaryDir tmp;
        const Written w = build(maps, {}, tmp.path());
        const QJsonObject sheenEntry = entry(w.manifest, "sheen");
        QCOMPARE(sheenEntry["colorSpace"].toString(), QStringLiteral("srgb"));
        QCOMPARE(sheenEntry["channels"].toObject()["A"].toString(),
                 QStringLiteral("sheenRoughness"));
        QCOMPARE(entry(w.manifest, "anisotropy")["rotation"].toInt(-1), 0);
        QCOMPARE(entry(w.manifest, "specular")["channels"].toObject()["A"].toString(),
                 QStringLiteral("specular"));
        // Lobes off (weight 0, default specular, strength 0): no lobe file.
        MaterialMaps off = knownMaps();
        off.coat = Image(kW, kH, 2);
        off.sheen = Image(kW, kH, 4);
        off.specular = Image(kW, kH, 4);
        std::fill(off.specular.pixels.begin(), off.specular.pixels.end(), 1.0f);
        off.anisotropy = Image(kW, kH, 3);
        QTemporaryDir none;
        QCOMPARE(build(off, {}, none.path()).names.size(), 5);
    }

    // Unreal's ORM and glTF's and Godot's: R occlusion, G roughness, B metallic; HDRP's mask
    // map: R metallic, G occlusion, B detail mask (1), A smoothness = 1 - roughness. 16-bit PNG.
    void packedTexelsAreTheMaterialsMaps() {
        const MaterialMaps maps = knownMaps();
        constexpr float k16 = 0.5f / 65535.0f + 1e-6f;
        for (TextureSetTarget t : {TextureSetTarget::Unreal, TextureSetTarget::Godot,
                                   TextureSetTarget::Gltf, TextureSetTarget::UnityHdrp}) {
            QTemporaryDir dir;
            TextureSetOptions o;
            o.target = t;
            o.bits = 16;
            const Written w = build(maps, o, dir.path());
            const bool hdrp = t == TextureSetTarget::UnityHdrp;
            const Image& packed = w.images[w.names[2]];
            QCOMPARE(packed.channels, hdrp ? 4 : 3);
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const float* src = maps.orm.at(x, y);
                    const float* p = packed.at(x, y);
                    if (hdrp) {
                        QVERIFY(near(p[0], src[2], k16, "mask R = metallic"));
                        QVERIFY(near(p[1], src[0], k16, "mask G = occlusion"));
                        QVERIFY(near(p[2], 1.0f, k16, "mask B = detail mask"));
                        QVERIFY(near(p[3], 1.0f - src[1], k16, "mask A = smoothness"));
                    } else {
                        QVERIFY(near(p[0], src[0], k16, "ORM R = occlusion"));
                        QVERIFY(near(p[1], src[1], k16, "ORM G = roughness"));
                        QVERIFY(near(p[2], src[2], k16, "ORM B = metallic"));
                    }
                }
        }
    }

    // The green channel: n.y * 0.5 + 0.5 for OpenGL, -n.y * 0.5 + 0.5 for DirectX; R and B the
    // same either way. Defaults per target, and --normal replacing them.
    void normalGreenChannelFollowsTheConvention() {
        const MaterialMaps maps = knownMaps();
        struct Case {
            TextureSetTarget target;
            std::optional<NormalConvention> asked;
            bool flipped;
        };
        const Case cases[] = {
            {TextureSetTarget::Unreal, std::nullopt, true},
            {TextureSetTarget::UnityHdrp, std::nullopt, false},
            {TextureSetTarget::Godot, std::nullopt, false},
            {TextureSetTarget::Gltf, std::nullopt, false},
            {TextureSetTarget::Unreal, NormalConvention::OpenGl, false},
            {TextureSetTarget::UnityHdrp, NormalConvention::DirectX, true},
        };
        for (const Case& c : cases) {
            QTemporaryDir dir;
            TextureSetOptions o;
            o.target = c.target;
            o.normal = c.asked;
            const Written w = build(maps, o, dir.path());
            const Image& n = w.images[w.names[1]];
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    const float* src = maps.normal.at(x, y);
                    QVERIFY(near(n.at(x, y)[0], src[0] * 0.5f + 0.5f, k8, "normal R"));
                    QVERIFY(near(n.at(x, y)[1], (c.flipped ? -src[1] : src[1]) * 0.5f + 0.5f, k8,
                                 "normal G"));
                    QVERIFY(near(n.at(x, y)[2], src[2] * 0.5f + 0.5f, k8, "normal B"));
                }
            QCOMPARE(entry(w.manifest, "normal")["convention"].toString(),
                     QString(c.flipped ? "directx" : "opengl"));
            QCOMPARE(entry(w.manifest, "normal")["channels"].toObject()["G"].toString(),
                     QString(c.flipped ? "-normal.y" : "normal.y"));
        }
    }

    // Base colour: sRGB-encoded in PNG, its alpha kept linear; emission divided by its maximum
    // (4) with scale 4 in the manifest. EXR: both linear and unscaled.
    void colourEncodingAndEmissionScale() {
        const MaterialMaps maps = knownMaps();
        {
            QTemporaryDir dir;
            const Written w = build(maps, {}, dir.path());
            const Image& bc = w.images["Silk_baseColor.png"];
            const Image& e = w.images["Silk_emissive.png"];
            QCOMPARE(entry(w.manifest, "emissive")["scale"].toDouble(), 4.0);
            for (int y = 0; y < kH; ++y)
                for (int x = 0; x < kW; ++x) {
                    for (int c = 0; c < 3; ++c) {
                        QVERIFY(near(bc.at(x, y)[c], linearToSrgb(maps.baseColor.at(x, y)[c]), k8,
                                     "base colour sRGB"));
                        QVERIFY(near(e.at(x, y)[c], linearToSrgb(maps.emission.at(x, y)[c] / 4.0f),
                                     k8, "emission sRGB / scale"));
                    }
                    QVERIFY(near(bc.at(x, y)[3], maps.baseColor.at(x, y)[3], k8, "alpha"));
                }
        }
        QTemporaryDir dir;
        TextureSetOptions o;
        o.fileType = TextureFileType::Exr;
        o.bits = 32;
        const Written w = build(maps, o, dir.path());
        QCOMPARE(w.names.front(), QStringLiteral("Silk_baseColor.exr"));
        QCOMPARE(entry(w.manifest, "baseColor")["colorSpace"].toString(), QStringLiteral("linear"));
        QCOMPARE(entry(w.manifest, "emissive")["scale"].toDouble(), 1.0);
        QCOMPARE(w.manifest["bitsPerChannel"].toInt(), 32);
        const Image& e = w.images["Silk_emissive.exr"];
        QCOMPARE(e.at(kW - 1, kH - 1)[0], 4.0f);
        QCOMPARE(w.images["Silk_baseColor.exr"].at(2, 1)[0], maps.baseColor.at(2, 1)[0]);
    }

    void refusedOptions() {
        TextureSetOptions o;
        o.fileType = TextureFileType::Tga;
        o.bits = 16;
        QVERIFY(checkTextureSetOptions(o).find("TGA holds 8") != std::string::npos);
        o.fileType = TextureFileType::Png;
        o.bits = 32;
        QVERIFY(!checkTextureSetOptions(o).empty());
        o.bits = 8;
        o.size = 0;
        QVERIFY(!checkTextureSetOptions(o).empty());
        o.size = 8192;
        QVERIFY(checkTextureSetOptions(o).empty());
        o.fileType = TextureFileType::Exr;
        o.bits = 8;
        QVERIFY(!checkTextureSetOptions(o).empty());
        // TGA 8-bit works end to end.
        QTemporaryDir dir;
        TextureSetOptions tga;
        tga.fileType = TextureFileType::Tga;
        tga.target = TextureSetTarget::Unreal;
        const Written w = build(knownMaps(), tga, dir.path());
        QCOMPARE(w.names.front(), QStringLiteral("T_Silk_D.tga"));
        QVERIFY(near(w.images["T_Silk_ORM.tga"].at(3, 2)[1], knownMaps().orm.at(3, 2)[1], k8,
                     "TGA roughness"));
        // Maps of different sizes are refused.
        MaterialMaps bad = knownMaps();
        bad.orm = Image(2, 2, 3);
        BuiltExport built;
        std::string error;
        QVERIFY(!buildTextureSet(bad, "x", "x", {}, built, &error));
        QVERIFY(error.find("size") != std::string::npos);
    }
};

QTEST_APPLESS_MAIN(TestTextureSetExport)
#include "test_core_texture_set_export.moc"
