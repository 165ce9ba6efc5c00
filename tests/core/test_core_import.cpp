// core/material_import (issue 12, "Import"): hand-written glTF 2.0 and MaterialX 1.39 files that
// exercise every mapped parameter with known values, the spec-gloss conversion's known answers,
// embedded images written beside the preset under safe names, node graphs as Velvet nodes, and
// every refusal (broken JSON / XML with the place, dangling references, missing buffers,
// out-of-range values, ambiguous selection), each with the file and the place.
#include "core/document_io.h"
#include "core/gltf_spec_gloss.h"
#include "core/graph/graph.h"
#include "core/image.h"
#include "core/material_import.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QTest>

using namespace velvet;

namespace {

QString write(const QString& dir, const QString& name, const QByteArray& text) {
    const QString path = dir + "/" + name;
    QFile f(path);
    if (!f.open(QIODevice::WriteOnly))
        qFatal("cannot write %s", qPrintable(path));
    f.write(text);
    return path;
}

bool near(float a, float b, float tolerance = 1e-5f) {
    return std::abs(a - b) <= tolerance;
}

bool hasWarning(const ImportOutcome& o, const char* part) {
    for (const std::string& w : o.warnings)
        if (w.find(part) != std::string::npos)
            return true;
    return false;
}

QByteArray pngBase64() {
    Image img(2, 2, 3);
    for (float& v : img.pixels)
        v = 0.5f;
    std::string png, error;
    if (!encodeImage(img, ".png", PixelFormat::UInt8, png, &error))
        qFatal("%s", error.c_str());
    return QByteArray::fromStdString(png).toBase64();
}

/// A full material using every mapped glTF property (values chosen distinct).
QByteArray fullGltf(const QByteArray& imageName) {
    return R"({
  "asset": {"version": "2.0"},
  "extensionsUsed": ["KHR_materials_clearcoat", "KHR_materials_sheen", "KHR_materials_specular",
                     "KHR_materials_ior", "KHR_materials_emissive_strength", "KHR_texture_transform",
                     "KHR_materials_transmission"],
  "images": [{"name": ")" +
           imageName + R"(", "uri": "data:image/png;base64,)" + pngBase64() + R"("}],
  "samplers": [{"wrapS": 33071}],
  "textures": [{"source": 0}, {"source": 0, "sampler": 0}],
  "materials": [{
    "name": "Full",
    "pbrMetallicRoughness": {"baseColorFactor": [0.1, 0.2, 0.3, 1], "metallicFactor": 0.4,
      "roughnessFactor": 0.55,
      "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform":
        {"offset": [0.25, 0.5], "scale": [2, 3], "rotation": 1.5707963267948966}}}},
    "normalTexture": {"index": 0, "scale": 0.7},
    "occlusionTexture": {"index": 0, "strength": 0.35},
    "emissiveTexture": {"index": 1, "texCoord": 1},
    "emissiveFactor": [0.9, 0.8, 0.7],
    "extensions": {
      "KHR_materials_emissive_strength": {"emissiveStrength": 6},
      "KHR_materials_ior": {"ior": 1.7},
      "KHR_materials_specular": {"specularFactor": 0.6, "specularColorFactor": [0.9, 0.95, 1.0]},
      "KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.12,
        "clearcoatNormalTexture": {"index": 0, "scale": 0.4}},
      "KHR_materials_sheen": {"sheenColorFactor": [0.5, 0.25, 0.125], "sheenRoughnessFactor": 0.45},
      "KHR_materials_transmission": {"transmissionFactor": 0.5}
    }
  }]
})";
}

const char* kMinimal = R"({"asset": {"version": "2.0"}, "materials": [%1]})";

} // namespace

class TestCoreImport : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

    ImportOutcome import(const QString& file, const std::string& material = {}) {
        ImportOptions o;
        o.material = material;
        o.imageFolder = (m_dir.path() + "/out").toStdString();
        o.imageStem = "look";
        o.force = true;
        return importMaterialFile(file.toStdString(), o);
    }
    ImportOutcome importGltfText(const QByteArray& text, const char* name = "m.gltf") {
        return import(write(m_dir.path(), name, text));
    }

private slots:
    void initTestCase() { QVERIFY(m_dir.isValid()); }

    // A slot's UV transform in the preset JSON (issue 17 item 6): read, written only when set,
    // read back equal; a tiling of 0 and an out-of-range rotation refused with their paths.
    void uvTransformInPresetJson() {
        const std::string text = R"({"format": "velvet.material", "version": 2, "name": "t",
          "textures": {"baseColor": {"file": "c.png",
            "uv": {"scale": [2, 0.5], "offset": [0.25, -1], "rotation": 45}}}})";
        Problems problems;
        std::optional<Material> m = parseMaterial(text, "t.json", "/x", problems);
        QVERIFY(m && !problems.hasErrors());
        const UvTransform uv = m->texture(TextureSlot::BaseColor).uv;
        QVERIFY(uv.scale == glm::vec2(2.0f, 0.5f));
        QVERIFY(uv.offset == glm::vec2(0.25f, -1.0f));
        QCOMPARE(uv.rotation, 45.0f);
        const std::string json = materialToJson(*m, "/x");
        QVERIFY(json.find("\"rotation\": 45") != std::string::npos);
        Problems again;
        QVERIFY(parseMaterial(json, "t.json", "/x", again) == m);
        Material plain;
        plain.setTexture(TextureSlot::Normal, TextureRef{"/x/n.png"});
        QVERIFY(materialToJson(plain, "/x").find("\"uv\"") == std::string::npos);
        for (const char* bad : {R"("uv": {"scale": [0, 1]})", R"("uv": {"rotation": 400})"}) {
            Problems p;
            const std::string t = std::string(R"({"format": "velvet.material", "version": 2,
              "name": "t", "textures": {"baseColor": {"file": "c.png", )") +
                                  bad + "}}}";
            parseMaterial(t, "t.json", "/x", p);
            QVERIFY(p.hasErrors());
            const auto error = std::find_if(p.items.begin(), p.items.end(), [](const Problem& x) {
                return x.severity == Problem::Severity::Error;
            });
            QVERIFY2(error->path.rfind("textures.baseColor.uv.", 0) == 0, error->path.c_str());
        }
    }

    void gltfEveryMappedParameter() {
        const ImportOutcome o = importGltfText(fullGltf("../../evil name"));
        QVERIFY2(o.ok(), o.error.c_str());
        const Material& m = o.material;
        QCOMPARE(QString::fromStdString(m.name), QStringLiteral("Full"));
        QVERIFY(m.color(ParamId::BaseColor) == glm::vec3(0.1f, 0.2f, 0.3f));
        QVERIFY(near(m.scalar(ParamId::Metallic), 0.4f));
        QVERIFY(near(m.scalar(ParamId::Roughness), 0.55f));
        QVERIFY(near(m.scalar(ParamId::NormalScale), 0.7f));
        QVERIFY(near(m.scalar(ParamId::OcclusionStrength), 0.35f));
        QVERIFY(m.color(ParamId::EmissiveColor) == glm::vec3(0.9f, 0.8f, 0.7f));
        QVERIFY(near(m.scalar(ParamId::EmissiveStrength), 6.0f));
        QVERIFY(near(m.scalar(ParamId::Ior), 1.7f));
        QVERIFY(near(m.scalar(ParamId::SpecularWeight), 0.6f));
        QVERIFY(m.color(ParamId::SpecularColor) == glm::vec3(0.9f, 0.95f, 1.0f));
        QVERIFY(near(m.scalar(ParamId::ClearcoatWeight), 0.8f));
        QVERIFY(near(m.scalar(ParamId::ClearcoatRoughness), 0.12f));
        QVERIFY(near(m.scalar(ParamId::ClearcoatNormalScale), 0.4f));
        // Sheen: weight = the factor's largest channel, colour = factor / weight.
        QVERIFY(near(m.scalar(ParamId::SheenWeight), 0.5f));
        QVERIFY(m.color(ParamId::SheenColor) == glm::vec3(1.0f, 0.5f, 0.25f));
        QVERIFY(near(m.scalar(ParamId::SheenRoughness), 0.45f));
        // KHR_texture_transform: same scale and offset, rotation back in degrees, sign flipped.
        const TextureRef& base = m.texture(TextureSlot::BaseColor);
        QVERIFY(base.uv.scale == glm::vec2(2.0f, 3.0f));
        QVERIFY(base.uv.offset == glm::vec2(0.25f, 0.5f));
        QVERIFY(near(base.uv.rotation, -90.0f, 1e-4f));
        // One embedded image, written once, under a sanitised name inside the folder.
        QCOMPARE(o.written.size(), size_t(1));
        const QString written = QString::fromStdString(o.written[0].string());
        QVERIFY2(written.endsWith("/out/look_evil_name.png"), qPrintable(written));
        QVERIFY(QFile::exists(written));
        for (TextureSlot s : {TextureSlot::BaseColor, TextureSlot::Normal, TextureSlot::Occlusion,
                              TextureSlot::Emissive, TextureSlot::ClearcoatNormal})
            QCOMPARE(QString::fromStdString(m.texture(s).file), written);
        // Not mapped: each said by name.
        QVERIFY(hasWarning(o, "KHR_materials_transmission"));
        QVERIFY(hasWarning(o, "TEXCOORD_1"));
        QVERIFY(hasWarning(o, "CLAMP_TO_EDGE"));
        QCOMPARE(o.materialNames, std::vector<std::string>{"Full"});
    }

    void gltfDefaultsAreGltfs() {
        // No pbrMetallicRoughness: glTF's defaults, not Velvet's (white, metallic 1, rough 1).
        const ImportOutcome o =
            importGltfText(QByteArray(kMinimal).replace("%1", R"({"name": "d"})"));
        QVERIFY2(o.ok(), o.error.c_str());
        QVERIFY(o.material.color(ParamId::BaseColor) == glm::vec3(1.0f));
        QCOMPARE(o.material.scalar(ParamId::Metallic), 1.0f);
        QCOMPARE(o.material.scalar(ParamId::Roughness), 1.0f);
        QVERIFY(o.warnings.empty());
    }

    void gltfSelection() {
        const QByteArray two =
            QByteArray(kMinimal).replace("%1", R"({"name": "a"}, {"name": "b"})");
        const QString file = write(m_dir.path(), "two.gltf", two);
        ImportOutcome o = import(file);
        QCOMPARE(o.status, ImportOutcome::Status::Selection);
        QVERIFY2(o.error.find("0 \"a\", 1 \"b\"") != std::string::npos, o.error.c_str());
        QCOMPARE(QString::fromStdString(import(file, "b").material.name), QStringLiteral("b"));
        QCOMPARE(QString::fromStdString(import(file, "1").material.name), QStringLiteral("b"));
        QCOMPARE(import(file, "7").status, ImportOutcome::Status::Selection);
        QCOMPARE(import(file, "c").status, ImportOutcome::Status::Selection);
    }

    void gltfSpecGlossConverted() {
        // Known answers: a dielectric keeps its diffuse colour (F0 0.04 is the dielectric's),
        // a metal's specular colour becomes its base colour with metallic 1.
        MetalRough d = specGlossToMetalRough({glm::vec3(0.5f), glm::vec3(0.04f), 0.7f});
        QVERIFY(near(d.metallic, 0.0f));
        QVERIFY(near(d.baseColor.r, 0.5f, 1e-4f));
        QVERIFY(near(d.roughness, 0.3f));
        MetalRough g = specGlossToMetalRough({glm::vec3(0.0f), {1.0f, 0.766f, 0.336f}, 0.8f});
        QVERIFY(near(g.metallic, 1.0f, 1e-4f));
        QVERIFY(near(g.baseColor.g, 0.766f, 1e-4f));
        const ImportOutcome o = importGltfText(QByteArray(kMinimal).replace(
            "%1", R"({"name": "sg", "extensions": {"KHR_materials_pbrSpecularGlossiness":
              {"diffuseFactor": [0, 0, 0, 1], "specularFactor": [1, 0.766, 0.336],
               "glossinessFactor": 0.8}}})"));
        QVERIFY2(o.ok(), o.error.c_str());
        QVERIFY(near(o.material.scalar(ParamId::Metallic), 1.0f, 1e-4f));
        QVERIFY(near(o.material.scalar(ParamId::Roughness), 0.2f, 1e-5f));
        QVERIFY(near(o.material.color(ParamId::BaseColor).b, 0.336f, 1e-4f));
    }

    void gltfRefusals_data() {
        QTest::addColumn<QByteArray>("text");
        QTest::addColumn<QString>("place");
        QTest::newRow("broken JSON")
            << QByteArray("{\"asset\": {\"version\": \"2.0\"},\n  \"materials\": [}")
            << "line 2, column";
        QTest::newRow("no asset") << QByteArray(R"({"materials": [{}]})") << "asset";
        QTest::newRow("glTF 1") << QByteArray(R"({"asset": {"version": "1.0"}, "materials": [{}]})")
                                << "asset.version";
        QTest::newRow("metallic out of range")
            << QByteArray(kMinimal).replace("%1",
                                            R"({"pbrMetallicRoughness": {"metallicFactor": 1.5}})")
            << "materials[0].pbrMetallicRoughness.metallicFactor";
        QTest::newRow("dangling texture")
            << QByteArray(kMinimal).replace("%1", R"({"normalTexture": {"index": 3}})")
            << "materials[0].normalTexture.index";
        QTest::newRow("missing buffer")
            << QByteArray(
                   R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "gone.bin", "byteLength": 4}], "materials": [{}]})")
            << "buffers[0].uri";
        // glTF 2.0 section 3.6.1: relative paths and data: URIs. A file from outside must not
        // be read through an absolute path or another scheme (docs/reliability.md).
        QTest::newRow("absolute buffer path")
            << QByteArray(
                   R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "/etc/hostname", "byteLength": 1}], "materials": [{}]})")
            << "buffers[0].uri: \"/etc/hostname\" is an absolute path";
        QTest::newRow("file scheme image")
            << QByteArray(kMinimal).replace(
                   "%1",
                   R"({"normalTexture": {"index": 0}}], "textures": [{"source": 0}], "images": [{"uri": "file:/etc/passwd"}], "x": [{})")
            << "images[0].uri: \"file:/etc/passwd\" is not a relative path";
        QTest::newRow("view outside buffer")
            << QByteArray(
                   R"({"asset": {"version": "2.0"}, "buffers": [{"uri": "data:application/octet-stream;base64,AAAA", "byteLength": 3}], "bufferViews": [{"buffer": 0, "byteOffset": 2, "byteLength": 4}], "materials": [{}]})")
            << "bufferViews[0]";
        QTest::newRow("sheen colour above 1")
            << QByteArray(kMinimal).replace(
                   "%1",
                   R"({"extensions": {"KHR_materials_sheen": {"sheenColorFactor": [2, 0, 0]}}})")
            << "materials[0].extensions.KHR_materials_sheen.sheenColorFactor[0]";
        // Found by fuzz_gltf: nlohmann-json throws out_of_range, not parse_error, for a number
        // beyond a double, and it escaped the reader (the editor ended in std::terminate).
        QTest::newRow("number beyond a double")
            << QByteArray(R"({"asset": {"version": "2.0"}, "x": 1e999, "materials": [{}]})")
            << "broken JSON: number overflow";
        QTest::newRow("no materials") << QByteArray(R"({"asset": {"version": "2.0"}})") << "";
        QTest::newRow("nested too deep")
            << QByteArray(R"({"asset": {"version": "2.0"}, "x": )") + QByteArray(100000, '[') << "";
    }
    void gltfRefusals() {
        QFETCH(QByteArray, text);
        QFETCH(QString, place);
        const QString file = write(m_dir.path(), "bad.gltf", text);
        const ImportOutcome o = import(file);
        QCOMPARE(o.status, ImportOutcome::Status::Malformed);
        QVERIFY2(QString::fromStdString(o.error).startsWith(file + ": " + place), o.error.c_str());
    }

    /// A relative path that leaves the asset's folder is read (shared texture folders are common)
    /// and named in a warning.
    void gltfImageOutsideTheFolderIsNamed() {
        QDir(m_dir.path()).mkpath("asset");
        QDir(m_dir.path()).mkpath("shared");
        QFile png(m_dir.path() + "/shared/grain.png");
        QVERIFY(png.open(QIODevice::WriteOnly));
        png.write(QByteArray::fromBase64(pngBase64()));
        png.close();
        const QString file = write(
            m_dir.path() + "/asset", "outside.gltf",
            QByteArray(kMinimal).replace(
                "%1",
                R"({"normalTexture": {"index": 0}}], "textures": [{"source": 0}], "images": [{"uri": "../shared/grain.png"}], "x": [{})"));
        const ImportOutcome o = import(file);
        QCOMPARE(o.status, ImportOutcome::Status::Ok);
        QVERIFY2(hasWarning(o, "images[0].uri: reads ") &&
                     hasWarning(o, "shared/grain.png, outside the asset's folder"),
                 o.warnings.empty() ? "no warning" : o.warnings[0].c_str());
    }

    void mtlxStandardSurfaceConstants() {
        const QString file = write(m_dir.path(), "ss.mtlx", R"(<?xml version="1.0"?>
<materialx version="1.39" colorspace="lin_rec709">
  <standard_surface name="SR_a" type="surfaceshader">
    <input name="base" type="float" value="0.5" />
    <input name="base_color" type="color3" value="0.8, 0.6, 0.4" />
    <input name="metalness" type="float" value="0.3" />
    <input name="specular" type="float" value="0.7" />
    <input name="specular_color" type="color3" value="0.9, 0.8, 0.7" />
    <input name="specular_roughness" type="float" value="0.25" />
    <input name="specular_IOR" type="float" value="1.6" />
    <input name="coat" type="float" value="0.9" />
    <input name="coat_roughness" type="float" value="0.1" />
    <input name="coat_IOR" type="float" value="1.5" />
    <input name="sheen" type="float" value="0.6" />
    <input name="sheen_color" type="color3" value="0.2, 0.3, 0.4" />
    <input name="sheen_roughness" type="float" value="0.35" />
    <input name="emission" type="float" value="3" />
    <input name="emission_color" type="color3" value="1, 0.5, 0.25" />
    <input name="subsurface" type="float" value="0.2" />
  </standard_surface>
  <surfacematerial name="M_a" type="material" doc="Alpha">
    <input name="surfaceshader" type="surfaceshader" nodename="SR_a" />
  </surfacematerial>
</materialx>
)");
        const ImportOutcome o = import(file);
        QVERIFY2(o.ok(), o.error.c_str());
        const Material& m = o.material;
        QCOMPARE(QString::fromStdString(m.name), QStringLiteral("Alpha"));
        QVERIFY(m.color(ParamId::BaseColor) == glm::vec3(0.4f, 0.3f, 0.2f)); // x base
        QVERIFY(near(m.scalar(ParamId::Metallic), 0.3f));
        QVERIFY(near(m.scalar(ParamId::SpecularWeight), 0.7f));
        QVERIFY(m.color(ParamId::SpecularColor) == glm::vec3(0.9f, 0.8f, 0.7f));
        QVERIFY(near(m.scalar(ParamId::Roughness), 0.25f));
        QVERIFY(near(m.scalar(ParamId::Ior), 1.6f));
        QVERIFY(near(m.scalar(ParamId::ClearcoatWeight), 0.9f));
        QVERIFY(near(m.scalar(ParamId::ClearcoatRoughness), 0.1f));
        QVERIFY(near(m.scalar(ParamId::SheenWeight), 0.6f));
        QVERIFY(m.color(ParamId::SheenColor) == glm::vec3(0.2f, 0.3f, 0.4f));
        QVERIFY(near(m.scalar(ParamId::SheenRoughness), 0.35f));
        QVERIFY(near(m.scalar(ParamId::EmissiveStrength), 3.0f));
        QVERIFY(m.color(ParamId::EmissiveColor) == glm::vec3(1.0f, 0.5f, 0.25f));
        QVERIFY(hasWarning(o, "standard_surface.subsurface not mapped"));
        QCOMPARE(o.warnings.size(), size_t(1));
    }

    void mtlxImagesAndGraph() {
        Image img(4, 4, 3);
        std::string error;
        QDir().mkpath(m_dir.path() + "/tex");
        QVERIFY(writeImage((m_dir.path() + "/tex/c.png").toStdString(), img, PixelFormat::UInt8,
                           &error));
        const QString file = write(m_dir.path(), "g.mtlx", R"(<?xml version="1.0"?>
<materialx version="1.39">
  <nodegraph name="NG" fileprefix="tex/">
    <image name="rough_img" type="vector4">
      <input name="file" type="filename" value="c.png" />
    </image>
    <extract name="rough_g" type="float">
      <input name="in" type="vector4" nodename="rough_img" />
      <input name="index" type="integer" value="1" />
    </extract>
    <image name="albedo" type="color3">
      <input name="file" type="filename" value="c.png" colorspace="acescg" />
      <input name="uvtiling" type="vector2" value="2, 4" />
      <input name="uvoffset" type="vector2" value="0.5, 0.25" />
    </image>
    <multiply name="tint" type="color3">
      <input name="in1" type="color3" nodename="albedo" />
      <input name="in2" type="color3" value="0.5, 0.5, 0.5" />
    </multiply>
    <image name="other" type="color3">
      <input name="file" type="filename" value="c.png" />
    </image>
    <mix name="blend" type="color3">
      <input name="fg" type="color3" nodename="other" />
      <input name="bg" type="color3" value="0, 0, 0" />
      <input name="mix" type="float" value="0.25" />
    </mix>
    <noise2d name="n" type="float" />
    <output name="rough_out" type="float" nodename="rough_g" />
    <output name="base_out" type="color3" nodename="tint" />
    <output name="emit_out" type="color3" nodename="blend" />
    <output name="metal_out" type="float" nodename="n" />
  </nodegraph>
  <gltf_pbr name="SR" type="surfaceshader">
    <input name="roughness" type="float" nodegraph="NG" output="rough_out" />
    <input name="base_color" type="color3" nodegraph="NG" output="base_out" />
    <input name="emissive" type="color3" nodegraph="NG" output="emit_out" />
    <input name="metallic" type="float" nodegraph="NG" output="metal_out" />
  </gltf_pbr>
  <surfacematerial name="M" type="material">
    <input name="surfaceshader" type="surfaceshader" nodename="SR" />
  </surfacematerial>
</materialx>
)");
        const ImportOutcome o = import(file);
        QVERIFY2(o.ok(), o.error.c_str());
        const Material& m = o.material;
        const QString png = QDir::cleanPath(m_dir.path() + "/tex/c.png");
        // extract(image, 1) into roughness: the metallic-roughness slot (it reads G), factor 1.
        QCOMPARE(QString::fromStdString(m.texture(TextureSlot::MetallicRoughness).file), png);
        QCOMPARE(m.scalar(ParamId::Roughness), 1.0f);
        // image x constant into base colour: the slot, the factor, the colour space, and the
        // placement back in Velvet's UV space (offset v = 1 - tiling v - uvoffset v).
        const TextureRef& base = m.texture(TextureSlot::BaseColor);
        QCOMPARE(QString::fromStdString(base.file), png);
        QCOMPARE(QString::fromStdString(base.colorSpace), QStringLiteral("ACEScg"));
        QVERIFY(m.color(ParamId::BaseColor) == glm::vec3(0.5f));
        QVERIFY(base.uv.scale == glm::vec2(2.0f, 4.0f));
        QVERIFY(base.uv.offset == glm::vec2(0.5f, 1.0f - 4.0f - 0.25f));
        // The mix: a Velvet graph (Image texture -> Mix -> Material output's emission colour).
        QVERIFY(m.graph);
        const graph::Graph& g = *m.graph;
        std::vector<std::string> types;
        for (const auto& [id, node] : g.nodes())
            types.emplace_back(node.type->id);
        QVERIFY(std::find(types.begin(), types.end(), "math.mix") != types.end());
        QVERIFY(std::find(types.begin(), types.end(), "texture.image") != types.end());
        const int port = graph::outputInputForParam(ParamId::EmissiveColor);
        QVERIFY(g.connectionTo(g.outputNode(), graph::PortIndex(port)) != nullptr);
        // noise2d has no counterpart: said by name.
        QVERIFY(hasWarning(o, "<noise2d name=\"n\">"));
    }

    void mtlxSeveralMaterials() {
        const QString file = write(m_dir.path(), "two.mtlx", R"(<?xml version="1.0"?>
<materialx version="1.39">
  <open_pbr_surface name="A" type="surfaceshader"><input name="base_metalness" type="float" value="0.75" /></open_pbr_surface>
  <open_pbr_surface name="B" type="surfaceshader"><input name="fuzz_weight" type="float" value="0.4" /></open_pbr_surface>
  <surfacematerial name="MA" type="material"><input name="surfaceshader" type="surfaceshader" nodename="A" /></surfacematerial>
  <surfacematerial name="MB" type="material"><input name="surfaceshader" type="surfaceshader" nodename="B" /></surfacematerial>
</materialx>
)");
        QCOMPARE(import(file).status, ImportOutcome::Status::Selection);
        QCOMPARE(import(file, "MA").material.scalar(ParamId::Metallic), 0.75f);
        QVERIFY(near(import(file, "1").material.scalar(ParamId::SheenWeight), 0.4f));
    }

    void mtlxRefusals_data() {
        QTest::addColumn<QByteArray>("text");
        QTest::addColumn<QString>("place");
        QTest::newRow("broken XML")
            << QByteArray(
                   "<materialx version=\"1.39\">\n  <surfacematerial name=\"M\"\n</materialx>")
            << "line ";
        QTest::newRow("dangling nodename")
            << QByteArray(
                   "<materialx version=\"1.39\">\n<surfacematerial name=\"M\" type=\"material\">\n"
                   "<input name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"nope\" />\n"
                   "</surfacematerial>\n</materialx>")
            << "line 3";
        QTest::newRow("unknown shader")
            << QByteArray(
                   "<materialx version=\"1.39\">\n<UsdPreviewSurface name=\"S\" "
                   "type=\"surfaceshader\" />\n"
                   "<surfacematerial name=\"M\" type=\"material\"><input name=\"surfaceshader\" "
                   "type=\"surfaceshader\" nodename=\"S\" /></surfacematerial>\n</materialx>")
            << "line 2";
        QTest::newRow("cycle")
            << QByteArray(
                   "<materialx version=\"1.39\">\n<add name=\"a\" type=\"color3\"><input "
                   "name=\"in1\" "
                   "type=\"color3\" nodename=\"b\" /></add>\n<add name=\"b\" "
                   "type=\"color3\"><input "
                   "name=\"in1\" type=\"color3\" nodename=\"a\" /></add>\n<standard_surface "
                   "name=\"S\" "
                   "type=\"surfaceshader\"><input name=\"base_color\" type=\"color3\" "
                   "nodename=\"a\" "
                   "/></standard_surface>\n<surfacematerial name=\"M\" type=\"material\"><input "
                   "name=\"surfaceshader\" type=\"surfaceshader\" nodename=\"S\" "
                   "/></surfacematerial>\n"
                   "</materialx>")
            << "line ";
        // Found by fuzz_mtlx: a name in bytes that are not UTF-8 made a preset that did not load.
        QTest::newRow("not UTF-8")
            << QByteArray("<materialx version=\"1.39\">\n<standard_surface name=\"S\" "
                          "type=\"surfaceshader\" />\n<surfacematerial name=\"M\xE9\" "
                          "type=\"material\"><input name=\"surfaceshader\" "
                          "type=\"surfaceshader\" nodename=\"S\" /></surfacematerial>\n"
                          "</materialx>")
            << "line 3, column 25: not UTF-8 text (byte 0xE9)";
        QTest::newRow("not a number")
            << QByteArray(
                   "<materialx version=\"1.39\">\n<standard_surface name=\"S\" "
                   "type=\"surfaceshader\">\n"
                   "<input name=\"metalness\" type=\"float\" value=\"shiny\" "
                   "/></standard_surface>\n"
                   "<surfacematerial name=\"M\" type=\"material\"><input name=\"surfaceshader\" "
                   "type=\"surfaceshader\" nodename=\"S\" /></surfacematerial>\n</materialx>")
            << "line 3";
    }
    void mtlxRefusals() {
        QFETCH(QByteArray, text);
        QFETCH(QString, place);
        const QString file = write(m_dir.path(), "bad.mtlx", text);
        const ImportOutcome o = import(file);
        QCOMPARE(o.status, ImportOutcome::Status::Malformed);
        QVERIFY2(QString::fromStdString(o.error).startsWith(file + ": " + place), o.error.c_str());
    }
};

QTEST_APPLESS_MAIN(TestCoreImport)
#include "test_core_import.moc"
