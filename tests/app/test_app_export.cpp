// `velvet export` (issue 12): glTF 2.0 files that pass the Khronos glTF-Validator with 0 errors,
// whose factors and extensions are the material's values, whose packed and colour textures hold
// the material's texels, whose node graph is baked to textures holding what the graph's CPU twin
// computes; standalone presets; the output-folder safety rules (--force, atomic replacement,
// names that cannot escape). Runs the real binary.
#include "core/baked_maps.h"
#include "core/color_management.h"
#include "core/document_io.h"
#include "core/graph/graph.h"
#include "core/graph/graph_eval.h"
#include "core/graph/node_catalogue.h"
#include "core/image.h"
#include "export_fixtures.h"
#include "run_velvet.h"

#include <QDir>
#include <QDirIterator>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSize>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <unistd.h>

namespace {

using velvet::test::Result;

Result runVelvet(const QStringList& args) {
    velvet::test::RunOptions options;
    options.timeoutMs = 120000;
    return velvet::test::runVelvet(args, options);
}

QString preset(const QString& name) {
    return QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/") + name;
}

/// The glTF JSON of a .gltf, or of a .glb's JSON chunk (glTF 2.0 section 4.4).
QJsonObject gltfJson(const QString& file) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    QByteArray bytes = f.readAll();
    if (file.endsWith(".glb")) {
        if (bytes.size() < 20 || bytes.left(4) != "glTF")
            return {};
        quint32 length = 0;
        std::memcpy(&length, bytes.constData() + 12, 4);
        bytes = bytes.mid(20, int(length));
    }
    return QJsonDocument::fromJson(bytes).object();
}

/// The validator's report (scripts/gltf-validate.js). Fails the test loudly when the validator
/// is not installed: the export's correctness is not optional.
QJsonObject validate(const QString& file) {
    const QString node = QStringLiteral(VELVET_NODE);
    if (node.isEmpty())
        qFatal("node (Node.js) was not found when configuring; run 'make deps'");
    QProcess p;
    p.start(node, {QStringLiteral(VELVET_SOURCE_DIR "/scripts/gltf-validate.js"), file});
    if (!p.waitForFinished(120000))
        qFatal("gltf-validate.js did not finish on %s", qPrintable(file));
    const QString err = QString::fromUtf8(p.readAllStandardError());
    if (p.exitCode() == 2)
        qFatal("the glTF validator could not run (run 'make deps'): %s", qPrintable(err));
    const QJsonObject report = QJsonDocument::fromJson(p.readAllStandardOutput()).object();
    if (report.isEmpty())
        qFatal("gltf-validate.js printed no report: %s", qPrintable(err));
    for (const QJsonValue m : report["messages"].toArray()) {
        const QJsonObject o = m.toObject();
        qInfo("validator %s (severity %d) %s at %s", qPrintable(o["code"].toString()),
              o["severity"].toInt(), qPrintable(o["message"].toString()),
              qPrintable(o["pointer"].toString()));
    }
    return report;
}

bool near(double a, double b, double tolerance = 1e-6) {
    return std::abs(a - b) <= tolerance;
}

bool nearColor(const QJsonValue& v, glm::vec3 c) {
    const QJsonArray a = v.toArray();
    return a.size() >= 3 && near(a[0].toDouble(), c.x) && near(a[1].toDouble(), c.y) &&
           near(a[2].toDouble(), c.z);
}

/// Every file under @p dir (relative paths), hidden ones included.
QStringList filesUnder(const QString& dir) {
    QStringList out;
    QDirIterator it(dir, QDir::Files | QDir::Hidden | QDir::System, QDirIterator::Subdirectories);
    while (it.hasNext())
        out << QDir(dir).relativeFilePath(it.next());
    out.sort();
    return out;
}

/// Width and height of image @p index of a .glb, read from its PNG's IHDR chunk (PNG
/// specification 11.2.2: the width and height, big-endian, at bytes 16 and 20).
QSize glbImageSize(const QString& file, int index) {
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly))
        return {};
    const QByteArray bytes = f.readAll();
    quint32 jsonLength = 0;
    std::memcpy(&jsonLength, bytes.constData() + 12, 4);
    const QJsonObject doc = gltfJson(file);
    const int view = doc["images"].toArray()[index].toObject()["bufferView"].toInt(-1);
    if (view < 0)
        return {};
    const qsizetype bin = 20 + qsizetype(jsonLength) + 8; // the BIN chunk's data
    const qsizetype at = bin + doc["bufferViews"].toArray()[view].toObject()["byteOffset"].toInt();
    auto be32 = [&](qsizetype o) {
        const auto* u = reinterpret_cast<const unsigned char*>(bytes.constData() + o);
        return int(u[0] << 24 | u[1] << 16 | u[2] << 8 | u[3]);
    };
    if (bytes.size() < at + 24 || bytes.mid(at + 1, 3) != "PNG")
        return {};
    return {be32(at + 16), be32(at + 20)};
}

} // namespace

class TestAppExport : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;
    QString m_textured; ///< a preset using most texture slots, an atlas and packed maps

private slots:
    void initTestCase() {
        QVERIFY(m_tmp.isValid());
        m_textured = velvet::test::writeTexturedPreset(m_tmp.path());
    }

    void validatesWithMaterialValues_data() {
        QTest::addColumn<QString>("input");
        QTest::addColumn<QString>("format");
        const QStringList inputs{preset("crimson_velvet.json"), preset("silk.json"),
                                 preset("gold.json"), preset("car_paint.json"), m_textured};
        for (const QString& in : inputs)
            for (const char* f : {"glb", "gltf"})
                QTest::newRow(qPrintable(QFileInfo(in).baseName() + "." + f)) << in << f;
    }
    void validatesWithMaterialValues() {
        QFETCH(QString, input);
        QFETCH(QString, format);
        const QString out = m_tmp.filePath("values-" + format);
        const Result r = runVelvet({"export", input, "-f", format, "-o", out, "--force"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString file = out + "/" + QFileInfo(input).baseName() + "." + format;
        QVERIFY2(QFileInfo::exists(file), qPrintable(r.out + r.err));
        QCOMPARE(r.out.trimmed(), file);

        const QJsonObject report = validate(file);
        QCOMPARE(report["numErrors"].toInt(-1), 0);
        qInfo("%s: %d errors, %d warnings, %d infos, %d hints (validator %s)", qPrintable(file),
              report["numErrors"].toInt(), report["numWarnings"].toInt(),
              report["numInfos"].toInt(), report["numHints"].toInt(),
              qPrintable(report["validatorVersion"].toString()));

        // Round trip of the values: each factor is the material's, each extension is present
        // exactly when its lobe is on.
        velvet::Problems problems;
        auto m = velvet::loadMaterialFile(input.toStdString(), problems);
        QVERIFY(m);
        using velvet::ParamId;
        // Inputs the graph drives are baked: their factors are 1 (white), the texture the value.
        const velvet::BakedInputs baked = velvet::bakedInputsOf(*m);
        if (baked.driven[size_t(velvet::BakedMap::BaseColor)])
            m->setColor(ParamId::BaseColor, glm::vec3(1.0f));
        if (baked.driven[size_t(velvet::BakedMap::Orm)]) {
            m->setScalar(ParamId::Metallic, 1.0f);
            m->setScalar(ParamId::Roughness, 1.0f);
        }
        QVERIFY(!baked.driven[size_t(velvet::BakedMap::Coat)] &&
                !baked.driven[size_t(velvet::BakedMap::Sheen)] &&
                !baked.driven[size_t(velvet::BakedMap::Specular)] &&
                !baked.driven[size_t(velvet::BakedMap::Emission)]);
        const QJsonObject doc = gltfJson(file);
        const QJsonObject mat = doc["materials"].toArray()[0].toObject();
        QCOMPARE(mat["name"].toString(), QString::fromStdString(m->name));
        const QJsonObject pbr = mat["pbrMetallicRoughness"].toObject();
        QVERIFY(nearColor(pbr["baseColorFactor"], m->color(ParamId::BaseColor)));
        QVERIFY(near(pbr["metallicFactor"].toDouble(), m->scalar(ParamId::Metallic)));
        QVERIFY(near(pbr["roughnessFactor"].toDouble(), m->scalar(ParamId::Roughness)));
        const QJsonObject ext = mat["extensions"].toObject();
        const bool coat = m->scalar(ParamId::ClearcoatWeight) > 0;
        QCOMPARE(ext.contains("KHR_materials_clearcoat"), coat);
        if (coat) {
            const QJsonObject c = ext["KHR_materials_clearcoat"].toObject();
            QVERIFY(near(c["clearcoatFactor"].toDouble(), m->scalar(ParamId::ClearcoatWeight)));
            QVERIFY(near(c["clearcoatRoughnessFactor"].toDouble(),
                         m->scalar(ParamId::ClearcoatRoughness)));
        }
        const bool sheen = m->scalar(ParamId::SheenWeight) > 0;
        QCOMPARE(ext.contains("KHR_materials_sheen"), sheen);
        if (sheen) {
            const QJsonObject s = ext["KHR_materials_sheen"].toObject();
            QVERIFY(nearColor(s["sheenColorFactor"],
                              m->scalar(ParamId::SheenWeight) * m->color(ParamId::SheenColor)));
            QVERIFY(near(s["sheenRoughnessFactor"].toDouble(), m->scalar(ParamId::SheenRoughness)));
        }
        const bool ior = m->scalar(ParamId::Ior) != 1.5f;
        QCOMPARE(ext.contains("KHR_materials_ior"), ior);
        if (ior)
            QVERIFY(near(ext["KHR_materials_ior"].toObject()["ior"].toDouble(),
                         m->scalar(ParamId::Ior)));
        const bool specular = m->scalar(ParamId::SpecularWeight) != 1.0f ||
                              m->color(ParamId::SpecularColor) != glm::vec3(1.0f) ||
                              !m->texture(velvet::TextureSlot::Specular).empty() ||
                              !m->texture(velvet::TextureSlot::SpecularColor).empty();
        QCOMPARE(ext.contains("KHR_materials_specular"), specular);
        const bool emits = m->color(ParamId::EmissiveColor) != glm::vec3(0.0f);
        QCOMPARE(mat.contains("emissiveFactor"), emits);
        QCOMPARE(ext.contains("KHR_materials_emissive_strength"),
                 emits && m->scalar(ParamId::EmissiveStrength) != 1.0f);
        // extensionsUsed lists exactly the extensions the file uses.
        QStringList used;
        for (const QJsonValue v : doc["extensionsUsed"].toArray())
            used << v.toString();
        QStringList expected = ext.keys();
        if (QJsonDocument(mat).toJson().contains("KHR_texture_transform"))
            expected << "KHR_texture_transform";
        expected.sort();
        QCOMPARE(used, expected);
        // Mesh: the default scene's sphere, with every attribute glTF's PBR needs.
        const QJsonObject attributes = doc["meshes"]
                                           .toArray()[0]
                                           .toObject()["primitives"]
                                           .toArray()[0]
                                           .toObject()["attributes"]
                                           .toObject();
        for (const char* a : {"POSITION", "NORMAL", "TANGENT", "TEXCOORD_0"})
            QVERIFY2(attributes.contains(a), a);
    }

    /// The textured preset's texels: the packed image holds occlusion, roughness, metallic in
    /// R, G, B; colour textures come back with the source's sRGB values; regions become
    /// KHR_texture_transform; the cut-out alpha becomes MASK.
    void texturedKnownAnswers() {
        const QString out = m_tmp.filePath("known");
        const Result r = runVelvet({"export", m_textured, "-f", "gltf", "-o", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QJsonObject doc = gltfJson(out + "/textured.gltf");
        const QJsonObject mat = doc["materials"].toArray()[0].toObject();
        const QJsonObject pbr = mat["pbrMetallicRoughness"].toObject();
        QCOMPARE(mat["alphaMode"].toString(), QString("MASK"));
        QCOMPARE(mat["occlusionTexture"].toObject()["index"].toInt(-1),
                 pbr["metallicRoughnessTexture"].toObject()["index"].toInt(-2));
        const QJsonObject baseTex = pbr["baseColorTexture"].toObject();
        const QJsonObject sheenTex =
            mat["extensions"]["KHR_materials_sheen"]["sheenColorTexture"].toObject();
        // One atlas image, two regions.
        QCOMPARE(baseTex["index"].toInt(-1), sheenTex["index"].toInt(-2));
        const QJsonObject bt = baseTex["extensions"]["KHR_texture_transform"].toObject();
        const QJsonObject st = sheenTex["extensions"]["KHR_texture_transform"].toObject();
        QCOMPARE(bt["scale"].toArray(), QJsonArray({0.5, 1.0}));
        QCOMPARE(bt["offset"].toArray(), QJsonArray({0.0, 0.0}));
        QCOMPARE(st["offset"].toArray(), QJsonArray({0.5, 0.0}));
        QVERIFY(doc["extensionsRequired"].toArray().contains("KHR_texture_transform"));
        QVERIFY(mat["normalTexture"].isObject());
        QVERIFY(mat["emissiveTexture"].isObject());

        velvet::Image orm, atlas;
        std::string error;
        QVERIFY2(velvet::readImage((out + "/textured_orm.png").toStdString(), orm, &error),
                 error.c_str());
        const glm::vec4 t = orm.rgba(5, 7);
        QVERIFY2(near(t.r, 64 / 255.0, 0.6 / 255) && near(t.g, 153 / 255.0, 0.6 / 255) &&
                     near(t.b, 230 / 255.0, 0.6 / 255),
                 qPrintable(QString("orm texel %1 %2 %3").arg(t.r).arg(t.g).arg(t.b)));
        const int source =
            doc["textures"].toArray()[baseTex["index"].toInt()].toObject()["source"].toInt();
        const QString atlasFile =
            out + "/" + doc["images"].toArray()[source].toObject()["uri"].toString();
        QVERIFY2(velvet::readImage(atlasFile.toStdString(), atlas, &error), error.c_str());
        const glm::vec4 b = atlas.rgba(10, 10), cut = atlas.rgba(3, 0), s = atlas.rgba(40, 4);
        QVERIFY2(near(b.r, 51 / 255.0, 1.1 / 255) && near(b.g, 102 / 255.0, 1.1 / 255) &&
                     near(b.b, 153 / 255.0, 1.1 / 255) && b.a == 1.0f,
                 qPrintable(QString("base texel %1 %2 %3").arg(b.r).arg(b.g).arg(b.b)));
        QCOMPARE(cut.a, 0.0f);
        QVERIFY(near(s.g, 204 / 255.0, 1.1 / 255));
        // .gltf writes its parts beside it and nothing else.
        QCOMPARE(filesUnder(out), (QStringList{"textured.bin", "textured.gltf",
                                               "textured_baseColor.png", "textured_clearcoat.png",
                                               "textured_emissive.png", "textured_normal.png",
                                               "textured_orm.png", "textured_specularColor.png"}));
    }

    void unmappableIsWarned() {
        using namespace velvet;
        Material m;
        m.setChoice(ParamId::Distribution, int(Distribution::Beckmann));
        m.setChoice(ParamId::Diffuse, int(Diffuse::Burley));
        graph::Graph g;
        const graph::NodeId outNode = g.addNode(graph::kOutputTypeId).node;
        const graph::NodeId value = g.addNode("constant.float").node;
        const graph::NodeType* outType = graph::findNodeType(graph::kOutputTypeId);
        // The IOR has no texture in glTF: a graph driving it is said, its parameter exported.
        QVERIFY(g.connect({value, 0, outNode, graph::PortIndex(outType->inputIndex("ior"))}));
        m.graph = SharedGraph(g);
        const QString in = m_tmp.filePath("unmappable.json");
        std::string error;
        QVERIFY2(saveMaterialFile(m, in.toStdString(), &error), error.c_str());
        const Result r = runVelvet({"export", in, "-f", "glb", "-o", m_tmp.filePath("warn")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains("warning: ") && r.err.contains("brdf.distribution = beckmann") &&
                     r.err.contains("brdf.diffuse = burley") &&
                     r.err.contains("graph: drives ior, which no exported texture carries"),
                 qPrintable(r.err));
        QCOMPARE(validate(m_tmp.filePath("warn/unmappable.glb"))["numErrors"].toInt(-1), 0);
        // A preset carries everything: no warning, and the same material comes back.
        const Result p = runVelvet({"export", in, "-f", "preset", "-o", m_tmp.filePath("warn")});
        QVERIFY2(p.exitCode == 0 && p.err.isEmpty(), qPrintable(p.err));
        Problems problems;
        const auto back =
            loadMaterialFile(m_tmp.filePath("warn/unmappable.json").toStdString(), problems);
        QVERIFY(back);
        QVERIFY(*back == m);
    }

    void presetIsTheSameMaterial() {
        const Result r =
            runVelvet({"export", m_textured, "-f", "preset", "-o", m_tmp.filePath("p/copy.json")});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        velvet::Problems a, b;
        const auto original = velvet::loadMaterialFile(m_textured.toStdString(), a);
        const auto copy = velvet::loadMaterialFile(m_tmp.filePath("p/copy.json").toStdString(), b);
        QVERIFY(original && copy);
        QVERIFY(*original == *copy);
    }

    void meshOption() {
        const QString out = m_tmp.filePath("mesh");
        Result r = runVelvet(
            {"export", preset("gold.json"), "-f", "glb", "--mesh", "cube", "-o", out + "/c.glb"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QJsonObject doc = gltfJson(out + "/c.glb");
        QCOMPARE(doc["accessors"].toArray()[0].toObject()["count"].toInt(), 24);
        QCOMPARE(validate(out + "/c.glb")["numErrors"].toInt(-1), 0);
        // A mesh file: the cube exported above, read back through the crash-isolated import.
        r = runVelvet({"export", preset("silk.json"), "-f", "glb", "--mesh", out + "/c.glb", "-o",
                       out + "/from-file.glb"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(validate(out + "/from-file.glb")["numErrors"].toInt(-1), 0);
        // Open surfaces are double-sided.
        r = runVelvet({"export", preset("silk.json"), "-f", "glb", "--mesh", "cloth-drape", "-o",
                       out + "/cloth.glb"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(gltfJson(out + "/cloth.glb")["materials"][0]["doubleSided"].toBool());
        QCOMPARE(validate(out + "/cloth.glb")["numErrors"].toInt(-1), 0);
    }

    void existingOutputRefusedUnlessForced() {
        const QString out = m_tmp.filePath("force");
        const QString file = out + "/gold.glb";
        QCOMPARE(runVelvet({"export", preset("gold.json"), "-f", "glb", "-o", out}).exitCode, 0);
        // A hard link to the first export: an atomic replacement (new file + rename) leaves it
        // holding the old bytes; writing in place would change it too.
        QVERIFY(::link(file.toLocal8Bit().constData(), (out + "/old-link").toLocal8Bit()) == 0);
        QFile f(file);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QByteArray before = f.readAll();
        f.close();
        Result r = runVelvet({"export", preset("silk.json"), "-f", "glb", "-o", file});
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("exists") && r.err.contains("--force"), qPrintable(r.err));
        QVERIFY(f.open(QIODevice::ReadOnly));
        QCOMPARE(f.readAll(), before);
        f.close();
        r = runVelvet({"export", preset("silk.json"), "-f", "glb", "-o", file, "--force"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(f.open(QIODevice::ReadOnly));
        QVERIFY(f.readAll() != before);
        f.close();
        QFile link(out + "/old-link");
        QVERIFY(link.open(QIODevice::ReadOnly));
        QCOMPARE(link.readAll(), before);
        // No temporary file is left behind.
        QCOMPARE(filesUnder(out), (QStringList{"gold.glb", "old-link"}));
        // .gltf: one existing part refuses the whole export, nothing else is written.
        const QString parts = m_tmp.filePath("parts");
        QVERIFY(QDir().mkpath(parts));
        QFile bin(parts + "/gold.bin");
        QVERIFY(bin.open(QIODevice::WriteOnly));
        bin.write("mine");
        bin.close();
        r = runVelvet({"export", preset("gold.json"), "-f", "gltf", "-o", parts});
        QCOMPARE(r.exitCode, 2);
        QCOMPARE(filesUnder(parts), QStringList{"gold.bin"});
    }

    void namesCannotEscape() {
        // A file name full of path syntax and a material name that is a path: every output
        // lands in the chosen folder under a sanitised name.
        const QString root = m_tmp.filePath("escape");
        QVERIFY(QDir().mkpath(root + "/in"));
        velvet::Material m;
        m.name = "../../escaped";
        const QString in = root + "/in/..;$(x) ..json";
        std::string error;
        QVERIFY2(velvet::saveMaterialFile(m, in.toStdString(), &error), error.c_str());
        for (const char* format : {"glb", "gltf", "preset"}) {
            const Result r = runVelvet({"export", in, "-f", format, "-o", root + "/out"});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        }
        QCOMPARE(filesUnder(root), (QStringList{"in/..;$(x) ..json", "out/x.bin", "out/x.glb",
                                                "out/x.gltf", "out/x.json"}));
    }

    void badInvocations_data() {
        QTest::addColumn<QStringList>("args");
        QTest::addColumn<int>("exitCode");
        const QString gold = preset("gold.json");
        QTest::newRow("no file") << QStringList{"export", "-f", "glb", "-o", "x"} << 1;
        QTest::newRow("no format") << QStringList{"export", gold, "-o", "x"} << 1;
        QTest::newRow("no output") << QStringList{"export", gold, "-f", "glb"} << 1;
        QTest::newRow("bad format") << QStringList{"export", gold, "-f", "fbx", "-o", "x"} << 1;
        QTest::newRow("bad mesh") << QStringList{"export", gold,     "-f", "glb",
                                                 "--mesh", "teapot", "-o", "x"}
                                  << 1;
        QTest::newRow("mesh with preset")
            << QStringList{"export", gold, "-f", "preset", "--mesh", "cube", "-o", "x"} << 1;
        QTest::newRow("same name twice")
            << QStringList{"export", gold, gold, "-f", "glb", "-o", "x"} << 1;
        QTest::newRow("missing input")
            << QStringList{"export", "/nonexistent/m.json", "-f", "glb", "-o", "x"} << 2;
    }
    void badInvocations() {
        QFETCH(QStringList, args);
        QFETCH(int, exitCode);
        for (QString& a : args)
            if (a == "x")
                a = m_tmp.filePath("bad/x");
        const Result r = runVelvet(args);
        QCOMPARE(r.status, QProcess::NormalExit);
        QCOMPARE(r.exitCode, exitCode);
        QVERIFY(!r.err.isEmpty());
        QVERIFY(!QFileInfo::exists(m_tmp.filePath("bad/x")) ||
                QDir(m_tmp.filePath("bad/x")).isEmpty());
    }

    void missingTextureIsBadInput() {
        velvet::Material m;
        velvet::TextureRef r;
        r.file = m_tmp.filePath("nope.png").toStdString();
        m.setTexture(velvet::TextureSlot::Normal, r);
        const QString in = m_tmp.filePath("missing-texture.json");
        std::string error;
        QVERIFY2(velvet::saveMaterialFile(m, in.toStdString(), &error), error.c_str());
        const Result res = runVelvet({"export", in, "-f", "glb", "-o", m_tmp.filePath("mt")});
        QCOMPARE(res.exitCode, 2);
        QVERIFY2(res.err.contains("textures.normal"), qPrintable(res.err));
        QVERIFY(!QFileInfo::exists(m_tmp.filePath("mt/missing-texture.glb")));
    }
    /// Denim's graph (a weave under fuzz) drives base colour, roughness, normal and occlusion:
    /// each is baked into a texture read with a white factor, and the baked base colour and
    /// roughness hold what the graph's CPU twin (core/graph/graph_eval.h) computes at the texel
    /// centres (8-bit quantisation and the GPU's float arithmetic allowed for). At 512 texels a
    /// thread of denim's weave (96 a unit) spans over four texels, so the Weave's footprint filter
    /// (docs/fabric-nodes.md) leaves the pattern as the unfiltered twin computes it.
    void graphIsBakedToTextures() {
        const QString out = m_tmp.filePath("baked");
        constexpr int kBake = 512;
        const Result r = runVelvet({"export", preset("denim.json"), "-f", "gltf", "--bake-size",
                                    QString::number(kBake), "-o", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.err.contains("graph:"), qPrintable(r.err)); // every input it drives is baked
        const QJsonObject doc = gltfJson(out + "/denim.gltf");
        const QJsonObject mat = doc["materials"].toArray()[0].toObject();
        const QJsonObject pbr = mat["pbrMetallicRoughness"].toObject();
        QCOMPARE(pbr["baseColorFactor"].toArray(), QJsonArray({1.0, 1.0, 1.0, 1.0}));
        QCOMPARE(pbr["roughnessFactor"].toDouble(), 1.0);
        QCOMPARE(pbr["metallicFactor"].toDouble(), 1.0);
        QCOMPARE(mat["normalTexture"].toObject()["scale"].toDouble(), 1.0);
        QCOMPARE(mat["occlusionTexture"].toObject()["strength"].toDouble(), 1.0);
        QCOMPARE(mat["occlusionTexture"].toObject()["index"].toInt(-1),
                 pbr["metallicRoughnessTexture"].toObject()["index"].toInt(-2));
        auto imageFile = [&](const QJsonObject& info) {
            const int source =
                doc["textures"].toArray()[info["index"].toInt()].toObject()["source"].toInt();
            return doc["images"].toArray()[source].toObject()["uri"].toString();
        };
        QCOMPARE(imageFile(pbr["baseColorTexture"].toObject()),
                 QString("denim_baked_baseColor.png"));
        QCOMPARE(imageFile(pbr["metallicRoughnessTexture"].toObject()),
                 QString("denim_baked_orm.png"));
        QCOMPARE(imageFile(mat["normalTexture"].toObject()), QString("denim_baked_normal.png"));

        velvet::Image base, orm;
        std::string error;
        QVERIFY2(
            velvet::readImage((out + "/denim_baked_baseColor.png").toStdString(), base, &error),
            error.c_str());
        QVERIFY2(velvet::readImage((out + "/denim_baked_orm.png").toStdString(), orm, &error),
                 error.c_str());
        QCOMPARE(base.width, kBake);
        QCOMPARE(base.height, kBake);
        velvet::Problems problems;
        const auto m = velvet::loadMaterialFile(preset("denim.json").toStdString(), problems);
        QVERIFY(m && m->graph);
        const velvet::graph::GraphEvaluator twin(*m->graph);
        const velvet::graph::NodeType* outType =
            velvet::graph::findNodeType(velvet::graph::kOutputTypeId);
        const int colour = outType->inputIndex("baseColor");
        const int roughness = outType->inputIndex("roughness");
        double worst = 0.0;
        for (const auto [x, y] :
             {std::pair{41, 77}, {163, 322}, {265, 18}, {511, 511}, {379, 243}, {0, 0}}) {
            // Row 0 is v ~ 0 (glTF's UVs: the image's top row), texel centres.
            const glm::vec2 uv((x + 0.5f) / float(kBake), (y + 0.5f) / float(kBake));
            const velvet::graph::GraphSample sample = twin.evaluate(uv);
            QVERIFY(sample.outputInputs[size_t(colour)] && sample.outputInputs[size_t(roughness)]);
            const glm::vec4 c = *sample.outputInputs[size_t(colour)];
            const glm::vec4 texel = base.rgba(x, y);
            for (int i = 0; i < 3; ++i) {
                const double expected = velvet::linearToSrgb(std::clamp(c[i], 0.0f, 1.0f));
                worst = std::max(worst, std::abs(texel[i] - expected));
                QVERIFY2(near(texel[i], expected, 2.5 / 255),
                         qPrintable(QString("base colour at (%1, %2) channel %3: %4, graph %5")
                                        .arg(x)
                                        .arg(y)
                                        .arg(i)
                                        .arg(texel[i])
                                        .arg(expected)));
            }
            const double rough = (*sample.outputInputs[size_t(roughness)]).x;
            QVERIFY2(near(orm.rgba(x, y).g, rough, 1.5 / 255),
                     qPrintable(QString("roughness at (%1, %2): %3, graph %4")
                                    .arg(x)
                                    .arg(y)
                                    .arg(orm.rgba(x, y).g)
                                    .arg(rough)));
        }
        qInfo("baked base colour vs the CPU twin: worst difference %.2f/255", worst * 255);
        QCOMPARE(validate(out + "/denim.gltf")["numErrors"].toInt(-1), 0);
    }

    /// --bake-size sets the baked images' size (default 1024); the .glb passes the validator.
    void bakeSizeIsRespected() {
        const QString out = m_tmp.filePath("bake-size");
        Result r = runVelvet({"export", preset("silk.json"), "-f", "glb", "--bake-size", "48", "-o",
                              out + "/small.glb"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QJsonObject small = validate(out + "/small.glb");
        QCOMPARE(small["numErrors"].toInt(-1), 0);
        const QJsonArray images = gltfJson(out + "/small.glb")["images"].toArray();
        QVERIFY(!images.isEmpty());
        for (int i = 0; i < images.size(); ++i)
            QCOMPARE(glbImageSize(out + "/small.glb", i), QSize(48, 48));
        r = runVelvet({"export", preset("silk.json"), "-f", "glb", "-o", out + "/default.glb"});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(glbImageSize(out + "/default.glb", 0), QSize(1024, 1024));
        QCOMPARE(validate(out + "/default.glb")["numErrors"].toInt(-1), 0);
        for (const char* bad : {"0", "8193", "big"}) {
            r = runVelvet({"export", preset("silk.json"), "-f", "glb", "--bake-size", bad, "-o",
                           out + "/bad.glb"});
            QCOMPARE(r.exitCode, 1);
            QVERIFY2(r.err.contains("--bake-size"), qPrintable(r.err));
        }
        r = runVelvet({"export", preset("silk.json"), "-f", "preset", "--bake-size", "8", "-o",
                       out + "/p.json"});
        QCOMPARE(r.exitCode, 1);
    }

    /// Materials without a graph gain no textures: constants stay factors.
    void constantsStayFactors() {
        for (const char* name : {"gold.json", "car_paint.json", "crimson_velvet.json"}) {
            const QString out = m_tmp.filePath("constants");
            const Result r = runVelvet({"export", preset(name), "-f", "glb", "--force", "-o", out});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            const QJsonObject doc = gltfJson(out + "/" + QFileInfo(name).baseName() + ".glb");
            QVERIFY2(!doc.contains("images") && !doc.contains("textures"), name);
        }
    }
    /// Without an OpenGL context the graph cannot be baked: exit 2 with a line saying so and
    /// nothing written, while a material without a graph (which needs no GPU) still exports.
    /// libglvnd (Debian's libEGL) finds no EGL vendor from a vendor file that does not exist.
    void noContextIsAClearError() {
        const QString out = m_tmp.filePath("no-context");
        velvet::test::RunOptions options;
        options.extraEnv["__EGL_VENDOR_LIBRARY_FILENAMES"] = m_tmp.filePath("no-vendor.json");
        Result r = velvet::test::runVelvet(
            {"export", preset("denim.json"), "-f", "glb", "--bake-size", "8", "-o", out}, options);
        QCOMPARE(r.exitCode, 2);
        QVERIFY2(r.err.contains("denim.json: cannot bake the node graph's maps: headless OpenGL"),
                 qPrintable(r.err));
        QVERIFY(!QFileInfo::exists(out + "/denim.glb"));
        r = velvet::test::runVelvet({"export", preset("gold.json"), "-f", "glb", "-o", out},
                                    options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
    }
};
QTEST_GUILESS_MAIN(TestAppExport)
#include "test_app_export.moc"
