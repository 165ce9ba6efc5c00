// `velvet import` (issue 12, "Import") and the UV transform on export (issue 17 item 6): every
// library preset goes Velvet -> glTF -> Velvet and Velvet -> MaterialX (each shader) -> Velvet
// with equal parameters (1e-4; the few a format cannot carry are skipped exactly as
// docs/interchange.md lists them), in-process through core's export and import functions and
// once through the binary; a texture slot's UV transform is written as
// KHR_texture_transform (checked by the Khronos glTF-Validator, 0 errors) and read back; the
// exit codes: warnings 0, malformed files 2 with the place, an existing output 2.
#include "core/document_io.h"
#include "core/image.h"
#include "core/material_export.h"
#include "core/material_import.h"
#include "run_velvet.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

using namespace velvet;

namespace {

test::Result run(const QStringList& args) {
    test::RunOptions options;
    options.timeoutMs = 120000;
    return test::runVelvet(args, options);
}

QStringList libraryPresets() {
    return QDir(QStringLiteral(VELVET_SOURCE_DIR "/resources/presets"))
        .entryList({QStringLiteral("*.json")}, QDir::Files, QDir::Name);
}

Material load(const QString& file) {
    Problems problems;
    std::optional<Material> m = loadMaterialFile(file.toStdString(), problems);
    if (!m || problems.hasErrors())
        qFatal("cannot load %s", qPrintable(file));
    return *m;
}

/// What a format cannot carry, as docs/interchange.md ("Round trips") lists it: parameters
/// that shape nothing where they stand (a lobe's values with the lobe off, a map's strength
/// without the map), glTF's sheen that keeps only weight x colour, and the BRDF term choices.
std::vector<std::string> differences(const Material& a, const Material& b, bool gltfSheen) {
    std::vector<std::string> out;
    const auto skip = [&](ParamId id) {
        switch (id) {
        case ParamId::NormalScale:
            return a.texture(TextureSlot::Normal).empty();
        case ParamId::OcclusionStrength:
            return a.texture(TextureSlot::Occlusion).empty();
        case ParamId::ClearcoatNormalScale:
            return a.texture(TextureSlot::ClearcoatNormal).empty();
        case ParamId::ClearcoatRoughness:
            return gltfSheen && a.scalar(ParamId::ClearcoatWeight) == 0.0f;
        case ParamId::EmissiveStrength:
            return gltfSheen && a.color(ParamId::EmissiveColor) == glm::vec3(0.0f);
        case ParamId::SheenWeight:
        case ParamId::SheenColor:
            return gltfSheen; // compared as their product below
        case ParamId::SheenRoughness:
            return gltfSheen && a.scalar(ParamId::SheenWeight) == 0.0f;
        default:
            return paramMeta(id).type == ParamType::Choice;
        }
    };
    for (int i = 0; i < kParamCount; ++i) {
        const ParamId id = ParamId(i);
        if (skip(id))
            continue;
        const glm::vec3 d = glm::abs(a.value(id) - b.value(id));
        if (std::max({d.x, d.y, d.z}) > 1e-4f)
            out.push_back(std::string(paramMeta(id).id));
    }
    if (gltfSheen) {
        const glm::vec3 pa = a.scalar(ParamId::SheenWeight) * a.color(ParamId::SheenColor);
        const glm::vec3 pb = b.scalar(ParamId::SheenWeight) * b.color(ParamId::SheenColor);
        const glm::vec3 d = glm::abs(pa - pb);
        if (std::max({d.x, d.y, d.z}) > 1e-4f)
            out.emplace_back("sheen weight x colour");
    }
    return out;
}

QJsonObject gltfJson(const QString& file) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

/// The Khronos glTF-Validator's report (scripts/gltf-validate.js, installed by `make deps`).
QJsonObject validate(const QString& file) {
    const QString node = QStringLiteral(VELVET_NODE);
    if (node.isEmpty())
        qFatal("node (Node.js) was not found when configuring; run 'make deps'");
    QProcess p;
    p.start(node, {QStringLiteral(VELVET_SOURCE_DIR "/scripts/gltf-validate.js"), file});
    if (!p.waitForFinished(120000) || p.exitCode() == 2)
        qFatal("the glTF validator could not run on %s (run 'make deps')", qPrintable(file));
    return QJsonDocument::fromJson(p.readAllStandardOutput()).object();
}

/// @p m exported as @p format (with MaterialX @p shader, or none) into @p dir as "look".
ExportOutcome exportAs(const Material& m, const QString& format, const QString& shader,
                       const QString& dir) {
    ExportOptions options;
    options.format = *exportFormatFromId(format.toStdString());
    if (!shader.isEmpty())
        options.shader = *mtlxShaderFromId(shader.toStdString());
    return exportMaterial(sceneWithMaterial(m), dir.toStdString(), "look", options);
}

} // namespace

class TestAppImport : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;

private slots:
    void initTestCase() { QVERIFY(m_tmp.isValid()); }

    void roundTrips_data() {
        QTest::addColumn<QString>("preset");
        QTest::addColumn<QString>("format");
        QTest::addColumn<QString>("shader");
        for (const QString& p : libraryPresets()) {
            QTest::newRow(qPrintable(p + " gltf")) << p << "gltf"
                                                   << "";
            for (const char* s : {"standard_surface", "open_pbr_surface", "gltf_pbr"})
                QTest::newRow(qPrintable(p + " " + s)) << p << "mtlx" << QString(s);
        }
    }
    // In-process, through the same core functions the CLI calls (exportMaterial,
    // importMaterialFile): 72 round trips as 144 processes took minutes on a loaded machine.
    void roundTrips() {
        QFETCH(QString, preset);
        QFETCH(QString, format);
        QFETCH(QString, shader);
        const QString dir = m_tmp.filePath(QFileInfo(preset).baseName() + "_" + format + shader);
        const QString source = QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/") + preset;
        const Material a = load(source);
        const ExportOutcome out = exportAs(a, format, shader, dir);
        QVERIFY2(out.ok(), out.error.c_str());
        ImportOptions in;
        in.imageFolder = dir.toStdString();
        const ImportOutcome back = importMaterialFile(out.written.back(), in);
        QVERIFY2(back.ok(), back.error.c_str());
        const Material& b = back.material;
        const bool gltfSheen = format == "gltf" || shader == "gltf_pbr";
        const std::vector<std::string> d = differences(a, b, gltfSheen);
        std::string list;
        for (const std::string& s : d)
            list += s + " ";
        QVERIFY2(d.empty(), list.c_str());
        QCOMPARE(b.name, a.name);
    }

    // KHR_materials_anisotropy and its MaterialX counterparts (issue 13): strength 0.6 and 30
    // degrees come back within 1e-4; open_pbr_surface has no rotation input and says so.
    void anisotropyRoundTrips_data() {
        QTest::addColumn<QString>("format");
        QTest::addColumn<QString>("shader");
        QTest::newRow("gltf") << "gltf"
                              << "";
        for (const char* s : {"standard_surface", "open_pbr_surface", "gltf_pbr"})
            QTest::newRow(s) << "mtlx" << QString(s);
    }
    void anisotropyRoundTrips() {
        QFETCH(QString, format);
        QFETCH(QString, shader);
        Material a;
        a.name = "Brushed";
        a.setScalar(ParamId::Metallic, 1.0f);
        a.setScalar(ParamId::Roughness, 0.4f);
        a.setScalar(ParamId::AnisotropyStrength, 0.6f);
        a.setScalar(ParamId::AnisotropyRotation, 30.0f);
        const QString dir = m_tmp.filePath("aniso_" + format + shader);
        const ExportOutcome out = exportAs(a, format, shader, dir);
        QVERIFY2(out.ok(), out.error.c_str());
        bool rotationWarned = false;
        for (const std::string& w : out.warnings)
            rotationWarned |= w.find("lobes.anisotropy.rotation") != std::string::npos;
        QCOMPARE(rotationWarned, shader == "open_pbr_surface");
        if (format == "gltf") {
            const QJsonObject doc = gltfJson(QString::fromStdString(out.written.back().string()));
            const QJsonObject e =
                doc["materials"][0]["extensions"]["KHR_materials_anisotropy"].toObject();
            QVERIFY(std::abs(e["anisotropyStrength"].toDouble() - 0.6) < 1e-6);
            QVERIFY(std::abs(e["anisotropyRotation"].toDouble() - M_PI / 6.0) < 1e-6);
            QVERIFY(doc["extensionsUsed"].toArray().contains("KHR_materials_anisotropy"));
        }
        ImportOptions in;
        in.imageFolder = dir.toStdString();
        const ImportOutcome back = importMaterialFile(out.written.back(), in);
        QVERIFY2(back.ok(), back.error.c_str());
        const Material& b = back.material;
        QVERIFY2(std::abs(b.scalar(ParamId::AnisotropyStrength) - 0.6f) < 1e-4f,
                 qPrintable(QString::number(b.scalar(ParamId::AnisotropyStrength))));
        const float rotation = shader == "open_pbr_surface" ? 0.0f : 30.0f;
        QVERIFY2(std::abs(b.scalar(ParamId::AnisotropyRotation) - rotation) < 1e-4f,
                 qPrintable(QString::number(b.scalar(ParamId::AnisotropyRotation))));
        QVERIFY(std::abs(b.scalar(ParamId::Roughness) - 0.4f) < 1e-4f);
    }

    // The same through the binary once: export, import, the preset file compared.
    void roundTripThroughTheBinary() {
        const QString dir = m_tmp.filePath("binary");
        const QString source =
            QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/car_paint.json");
        const test::Result out = run({"export", source, "-f", "glb", "-o", dir});
        QVERIFY2(out.exitCode == 0, qPrintable(out.err));
        const test::Result in = run({"import", dir + "/car_paint.glb", "-o", dir + "/back.json"});
        QVERIFY2(in.exitCode == 0, qPrintable(in.err));
        const std::vector<std::string> d =
            differences(load(source), load(dir + "/back.json"), true);
        QVERIFY(d.empty());
    }

    void uvTransformOnExportAndBack() {
        const QString dir = m_tmp.filePath("uv");
        QDir().mkpath(dir);
        Image img(8, 8, 3);
        for (float& v : img.pixels)
            v = 0.5f;
        std::string error;
        QVERIFY(writeImage((dir + "/c.png").toStdString(), img, PixelFormat::UInt8, &error));
        Material m;
        m.name = "Tiled";
        TextureRef ref;
        ref.file = (dir + "/c.png").toStdString();
        ref.uv.scale = {4.0f, 2.0f};
        ref.uv.offset = {0.25f, -0.5f};
        ref.uv.rotation = 30.0f;
        m.setTexture(TextureSlot::BaseColor, ref);
        ref.uv = {};
        ref.uv.scale = {3.0f, 3.0f};
        m.setTexture(TextureSlot::Emissive, ref);
        m.setColor(ParamId::EmissiveColor, glm::vec3(1.0f));
        QVERIFY(saveMaterialFile(m, (dir + "/tiled.json").toStdString(), &error));

        const test::Result out =
            run({"export", dir + "/tiled.json", "-f", "gltf", "-o", dir + "/gltf"});
        QVERIFY2(out.exitCode == 0, qPrintable(out.err));
        const QString gltf = dir + "/gltf/tiled.gltf";
        const QJsonObject doc = gltfJson(gltf);
        const QJsonObject t = doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]
                                 ["extensions"]["KHR_texture_transform"]
                                     .toObject();
        QCOMPARE(t["scale"].toArray()[0].toDouble(), 4.0);
        QCOMPARE(t["scale"].toArray()[1].toDouble(), 2.0);
        QCOMPARE(t["offset"].toArray()[0].toDouble(), 0.25);
        QCOMPARE(t["offset"].toArray()[1].toDouble(), -0.5);
        // glTF's rotation is the transpose of Velvet's: -30 degrees in radians.
        QVERIFY(std::abs(t["rotation"].toDouble() + 30.0 * M_PI / 180.0) < 1e-6);
        QVERIFY(doc["extensionsUsed"].toArray().contains("KHR_texture_transform"));
        const QJsonObject report = validate(gltf);
        QCOMPARE(report["numErrors"].toInt(-1), 0); // -1: no report
        qInfo("validator: %d errors, %d warnings, %d infos", report["numErrors"].toInt(),
              report["numWarnings"].toInt(), report["numInfos"].toInt());

        const test::Result in = run({"import", gltf, "-o", dir + "/back.json"});
        QVERIFY2(in.exitCode == 0, qPrintable(in.err));
        const Material b = load(dir + "/back.json");
        const UvTransform uv = b.texture(TextureSlot::BaseColor).uv;
        QVERIFY(uv.scale == glm::vec2(4.0f, 2.0f));
        QVERIFY(uv.offset == glm::vec2(0.25f, -0.5f));
        QVERIFY(std::abs(uv.rotation - 30.0f) < 1e-4f);
        QVERIFY(b.texture(TextureSlot::Emissive).uv.scale == glm::vec2(3.0f));

        // MaterialX: tiling and offset in its own UV space; the rotated slot through a place2d
        // on the image's texcoord (rotate in degrees), back the same (trigonometry: 1e-4).
        const test::Result mx =
            run({"export", dir + "/tiled.json", "-f", "mtlx", "-o", dir + "/mx"});
        QVERIFY2(mx.exitCode == 0, qPrintable(mx.err));
        QVERIFY2(!mx.err.contains("rotation"), qPrintable(mx.err));
        QFile mtlx(dir + "/mx/tiled.mtlx");
        QVERIFY(mtlx.open(QIODevice::ReadOnly));
        const QByteArray xml = mtlx.readAll();
        QVERIFY2(xml.contains("<place2d ") && xml.contains("<input name=\"rotate\""),
                 xml.constData());
        const test::Result mxIn =
            run({"import", dir + "/mx/tiled.mtlx", "-o", dir + "/mxback.json"});
        QVERIFY2(mxIn.exitCode == 0, qPrintable(mxIn.err));
        QVERIFY2(!mxIn.err.contains("not mapped"), qPrintable(mxIn.err));
        const Material c = load(dir + "/mxback.json");
        const UvTransform cu = c.texture(TextureSlot::BaseColor).uv;
        QVERIFY2(glm::length(cu.scale - glm::vec2(4.0f, 2.0f)) < 1e-4f &&
                     glm::length(cu.offset - glm::vec2(0.25f, -0.5f)) < 1e-4f &&
                     std::abs(cu.rotation - 30.0f) < 1e-4f,
                 qPrintable(QStringLiteral("scale %1 %2 offset %3 %4 rotation %5")
                                .arg(cu.scale.x)
                                .arg(cu.scale.y)
                                .arg(cu.offset.x)
                                .arg(cu.offset.y)
                                .arg(cu.rotation)));
        QVERIFY(c.texture(TextureSlot::Emissive).uv.scale == glm::vec2(3.0f));
        QVERIFY(c.texture(TextureSlot::Emissive).uv.rotation == 0.0f);
    }

    void exitCodes() {
        const QString dir = m_tmp.filePath("codes");
        QDir().mkpath(dir);
        auto write = [&](const QString& name, const QByteArray& text) {
            QFile f(dir + "/" + name);
            QVERIFY(f.open(QIODevice::WriteOnly));
            f.write(text);
        };
        write("warn.gltf", R"({"asset": {"version": "2.0"}, "materials": [{"name": "w",
            "extensions": {"KHR_materials_iridescence": {"iridescenceFactor": 0.5}}}]})");
        test::Result r = run({"import", dir + "/warn.gltf", "-o", dir + "/w.json"});
        QCOMPARE(r.exitCode, 0);
        QVERIFY2(r.err.contains("warning:") && r.err.contains("KHR_materials_iridescence"),
                 qPrintable(r.err));
        // KHR_materials_anisotropy is mapped (issue 13): no warning, the values in degrees.
        write("aniso.gltf", R"({"asset": {"version": "2.0"}, "materials": [{"name": "a",
            "extensions": {"KHR_materials_anisotropy": {"anisotropyStrength": 0.5,
            "anisotropyRotation": 1.5707963}}}]})");
        r = run({"import", dir + "/aniso.gltf", "-o", dir + "/a.json"});
        QCOMPARE(r.exitCode, 0);
        QVERIFY2(!r.err.contains("KHR_materials_anisotropy"), qPrintable(r.err));
        const Material aniso = load(dir + "/a.json");
        QVERIFY(std::abs(aniso.scalar(ParamId::AnisotropyStrength) - 0.5f) < 1e-6f);
        QVERIFY(std::abs(aniso.scalar(ParamId::AnisotropyRotation) - 90.0f) < 1e-4f);
        r = run({"import", dir + "/warn.gltf", "-o", dir + "/w.json"});
        QCOMPARE(r.exitCode, 2); // exists
        QVERIFY(run({"import", dir + "/warn.gltf", "-o", dir + "/w.json", "--force"}).exitCode ==
                0);
        write("bad.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"materials\": "
                          "[{\"pbrMetallicRoughness\": {\"roughnessFactor\": -1}}]}");
        r = run({"import", dir + "/bad.gltf", "-o", dir + "/b.json"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("bad.gltf: materials[0].pbrMetallicRoughness.roughnessFactor"),
                 qPrintable(r.err));
        QVERIFY(!QFile::exists(dir + "/b.json"));
        write("two.gltf",
              R"({"asset": {"version": "2.0"}, "materials": [{"name": "a"}, {"name": "b"}]})");
        r = run({"import", dir + "/two.gltf", "--list"});
        QCOMPARE(r.exitCode, 0);
        QCOMPARE(r.out, QStringLiteral("0\ta\n1\tb\n"));
        QCOMPARE(run({"import", dir + "/two.gltf", "-o", dir + "/t.json"}).exitCode, 2);
        QCOMPARE(run({"import", dir + "/two.gltf", "-o", dir + "/t.json", "-m", "b"}).exitCode, 0);
        QCOMPARE(QString::fromStdString(load(dir + "/t.json").name), QStringLiteral("b"));
        write("bad.mtlx", "<materialx version=\"1.39\">\n<oops");
        r = run({"import", dir + "/bad.mtlx", "-o", dir + "/x.json"});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("bad.mtlx: line 2"), qPrintable(r.err));
    }
};

QTEST_GUILESS_MAIN(TestAppImport)
#include "test_app_import.moc"
