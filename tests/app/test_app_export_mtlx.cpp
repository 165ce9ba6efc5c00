// `velvet export -f mtlx` (issue 12): the MaterialX 1.39 document's structure — one material
// whose shader is the one asked for, every connection resolving to a node of the document,
// every image a relative path to a file beside the .mtlx with the right colour space — and its
// values equal to the material's (as docs/interchange.md maps them). No MaterialX package is
// available from Debian 12 (`apt-cache search materialx` finds none), so the document is checked
// here with Qt's XML reader against the MaterialX 1.39 specification, not with MaterialX itself.
#include "core/document_io.h"
#include "core/image.h"
#include "export_fixtures.h"
#include "run_velvet.h"

#include <QDir>
#include <QFileInfo>
#include <QMap>
#include <QTemporaryDir>
#include <QXmlStreamReader>
#include <QtTest>
#include <cmath>

namespace {

struct MxInput {
    QString type, value, nodename, colorspace;
};
struct MxNode {
    QString category, type, doc;
    QMap<QString, MxInput> inputs;
};
struct MxDocument {
    QString version, colorspace;
    QMap<QString, MxNode> nodes; ///< by name
    QString error;
};

MxDocument parse(const QString& file) {
    MxDocument doc;
    QFile f(file);
    if (!f.open(QIODevice::ReadOnly)) {
        doc.error = "cannot open " + file;
        return doc;
    }
    QXmlStreamReader xml(&f);
    QString current;
    while (!xml.atEnd()) {
        if (xml.readNext() != QXmlStreamReader::StartElement)
            continue;
        const auto a = xml.attributes();
        if (xml.name() == u"materialx") {
            doc.version = a.value("version").toString();
            doc.colorspace = a.value("colorspace").toString();
        } else if (xml.name() == u"input") {
            if (current.isEmpty())
                doc.error = "an input outside a node";
            doc.nodes[current].inputs[a.value("name").toString()] = {
                a.value("type").toString(), a.value("value").toString(),
                a.value("nodename").toString(), a.value("colorspace").toString()};
        } else {
            current = a.value("name").toString();
            if (doc.nodes.contains(current))
                doc.error = "two nodes named " + current;
            doc.nodes[current] = {
                xml.name().toString(), a.value("type").toString(), a.value("doc").toString(), {}};
        }
    }
    if (xml.hasError())
        doc.error = xml.errorString();
    return doc;
}

QList<float> numbers(const QString& text) {
    QList<float> out;
    for (const QString& part : text.split(','))
        out << part.trimmed().toFloat();
    return out;
}

QString preset(const QString& name) {
    return QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/") + name;
}

/// Which shader input holds which parameter (docs/interchange.md, MaterialX table).
struct Mapped {
    const char* input;
    velvet::ParamId param;
    bool timesSheenWeight = false;
};
const QMap<QString, QList<Mapped>>& mappings() {
    using P = velvet::ParamId;
    static const QMap<QString, QList<Mapped>> m{
        {"standard_surface",
         {{"base_color", P::BaseColor},
          {"metalness", P::Metallic},
          {"specular_roughness", P::Roughness},
          {"specular", P::SpecularWeight},
          {"specular_color", P::SpecularColor},
          {"specular_IOR", P::Ior},
          {"coat", P::ClearcoatWeight},
          {"coat_roughness", P::ClearcoatRoughness},
          {"sheen", P::SheenWeight},
          {"sheen_color", P::SheenColor},
          {"sheen_roughness", P::SheenRoughness},
          {"emission", P::EmissiveStrength},
          {"emission_color", P::EmissiveColor}}},
        {"open_pbr_surface",
         {{"base_color", P::BaseColor},
          {"base_metalness", P::Metallic},
          {"specular_roughness", P::Roughness},
          {"specular_weight", P::SpecularWeight},
          {"specular_color", P::SpecularColor},
          {"specular_ior", P::Ior},
          {"coat_weight", P::ClearcoatWeight},
          {"coat_roughness", P::ClearcoatRoughness},
          {"fuzz_weight", P::SheenWeight},
          {"fuzz_color", P::SheenColor},
          {"fuzz_roughness", P::SheenRoughness},
          {"emission_luminance", P::EmissiveStrength},
          {"emission_color", P::EmissiveColor}}},
        {"gltf_pbr",
         {{"base_color", P::BaseColor},
          {"metallic", P::Metallic},
          {"roughness", P::Roughness},
          {"specular", P::SpecularWeight},
          {"specular_color", P::SpecularColor},
          {"ior", P::Ior},
          {"clearcoat", P::ClearcoatWeight},
          {"clearcoat_roughness", P::ClearcoatRoughness},
          {"sheen_color", P::SheenColor, true},
          {"sheen_roughness", P::SheenRoughness},
          {"emissive", P::EmissiveColor},
          {"emissive_strength", P::EmissiveStrength}}},
    };
    return m;
}

/// Follows @p input's connection through multiply/extract/convert/mix/normalmap nodes to the
/// image node it reads, or returns "" when it ends elsewhere.
QString imageBehind(const MxDocument& doc, const MxInput& input) {
    QString name = input.nodename;
    for (int hops = 0; hops < 8 && doc.nodes.contains(name); ++hops) {
        const MxNode& n = doc.nodes[name];
        if (n.category == "image")
            return name;
        QString next;
        for (const QString key : {"in1", "in", "fg"})
            if (n.inputs.contains(key) && !n.inputs[key].nodename.isEmpty())
                next = n.inputs[key].nodename;
        name = next;
    }
    return {};
}

} // namespace

class TestAppExportMtlx : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;
    QString m_textured;

private slots:
    void initTestCase() {
        QVERIFY(m_tmp.isValid());
        m_textured = velvet::test::writeTexturedPreset(m_tmp.path());
    }

    void structureAndValues_data() {
        QTest::addColumn<QString>("input");
        QTest::addColumn<QString>("shader");
        for (const QString& in : {preset("car_paint.json"), preset("crimson_velvet.json"),
                                  preset("gold.json"), m_textured})
            for (const char* s : {"standard_surface", "open_pbr_surface", "gltf_pbr"})
                QTest::newRow(qPrintable(QFileInfo(in).baseName() + "/" + s)) << in << s;
    }
    void structureAndValues() {
        QFETCH(QString, input);
        QFETCH(QString, shader);
        const QString out = m_tmp.filePath(shader);
        velvet::test::RunOptions options;
        const auto r = velvet::test::runVelvet(
            {"export", input, "-f", "mtlx", "--shader", shader, "-o", out, "--force"}, options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const QString file = out + "/" + QFileInfo(input).baseName() + ".mtlx";
        QCOMPARE(r.out.trimmed(), file);
        const MxDocument doc = parse(file);
        QVERIFY2(doc.error.isEmpty(), qPrintable(doc.error));
        QCOMPARE(doc.version, QString("1.39"));
        QCOMPARE(doc.colorspace, QString("lin_rec709"));

        velvet::Problems problems;
        const auto m = velvet::loadMaterialFile(input.toStdString(), problems);
        QVERIFY(m);
        // One material, its shader the one asked for.
        QString material;
        for (auto it = doc.nodes.begin(); it != doc.nodes.end(); ++it)
            if (it->category == "surfacematerial") {
                QVERIFY2(material.isEmpty(), "more than one surfacematerial");
                material = it.key();
            }
        QVERIFY(!material.isEmpty());
        QCOMPARE(doc.nodes[material].doc, QString::fromStdString(m->name));
        const QString shaderName = doc.nodes[material].inputs["surfaceshader"].nodename;
        QVERIFY(doc.nodes.contains(shaderName));
        const MxNode& sh = doc.nodes[shaderName];
        QCOMPARE(sh.category, shader);
        QCOMPARE(sh.type, QString("surfaceshader"));

        // Every connection resolves; every image is a relative file beside the document, in
        // sRGB when it is read as a colour and untagged (data) otherwise.
        for (auto n = doc.nodes.begin(); n != doc.nodes.end(); ++n) {
            for (auto i = n->inputs.begin(); i != n->inputs.end(); ++i)
                QVERIFY2(i->nodename.isEmpty() || doc.nodes.contains(i->nodename),
                         qPrintable(n.key() + "." + i.key() + " -> " + i->nodename));
            if (n->category != "image")
                continue;
            const MxInput f = n->inputs["file"];
            QCOMPARE(f.type, QString("filename"));
            QVERIFY2(QFileInfo(f.value).isRelative() && !f.value.contains(".."),
                     qPrintable(f.value));
            QVERIFY2(QFileInfo::exists(out + "/" + f.value), qPrintable(f.value));
            QCOMPARE(f.colorspace,
                     n->type.startsWith("color") ? QString("srgb_texture") : QString());
        }

        // Constant inputs equal the material's values.
        for (const Mapped& map : mappings()[shader]) {
            QVERIFY2(sh.inputs.contains(map.input), map.input);
            const MxInput in = sh.inputs[map.input];
            if (!in.nodename.isEmpty())
                continue; // textured: checked below
            const velvet::ParamMeta& meta = velvet::paramMeta(map.param);
            glm::vec3 expected = m->value(map.param);
            if (map.timesSheenWeight)
                expected *= m->scalar(velvet::ParamId::SheenWeight);
            const QList<float> got = numbers(in.value);
            const bool isColor = meta.type == velvet::ParamType::Color;
            QCOMPARE(in.type, isColor ? QString("color3") : QString("float"));
            QCOMPARE(got.size(), isColor ? 3 : 1);
            for (int c = 0; c < got.size(); ++c)
                QVERIFY2(std::abs(got[c] - expected[c]) < 1e-6f,
                         qPrintable(QString(map.input) + " = " + in.value));
        }
    }

    /// The textured preset: textures reach the inputs through image nodes, regions are cut out,
    /// occlusion reaches gltf_pbr and is warned about for the others, the cut-out alpha is
    /// gltf_pbr's MASK.
    void texturedConnections_data() {
        QTest::addColumn<QString>("shader");
        for (const char* s : {"standard_surface", "open_pbr_surface", "gltf_pbr"})
            QTest::newRow(s) << s;
    }
    void texturedConnections() {
        QFETCH(QString, shader);
        const QString out = m_tmp.filePath("tex-" + shader);
        velvet::test::RunOptions options;
        const auto r = velvet::test::runVelvet(
            {"export", m_textured, "-f", "mtlx", "--shader", shader, "-o", out}, options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const MxDocument doc = parse(out + "/textured.mtlx");
        QVERIFY2(doc.error.isEmpty(), qPrintable(doc.error));
        const MxNode& sh = doc.nodes["SR_textured"];
        const QString baseImage = imageBehind(doc, sh.inputs["base_color"]);
        QVERIFY2(!baseImage.isEmpty(), "base_color does not read an image");
        // Cut out of the atlas: the region's 32x32, not the atlas's 64x32.
        velvet::ImageInfo info;
        std::string error;
        QVERIFY(velvet::readImageInfo(
            (out + "/" + doc.nodes[baseImage].inputs["file"].value).toStdString(), info, &error));
        QCOMPARE(info.width, 32);
        QCOMPARE(info.height, 32);
        const QString normalInput = shader == "open_pbr_surface" ? "geometry_normal" : "normal";
        QCOMPARE(doc.nodes[sh.inputs[normalInput].nodename].category, QString("normalmap"));
        const QString metal = shader == "standard_surface"   ? "metalness"
                              : shader == "open_pbr_surface" ? "base_metalness"
                                                             : "metallic";
        // texel B x factor (the preset's metallic is 0: multiplied, as glTF and Velvet do)
        const MxNode& product = doc.nodes[sh.inputs[metal].nodename];
        QCOMPARE(product.category, QString("multiply"));
        QCOMPARE(product.inputs["in2"].value, QString("0"));
        const MxNode& channel = doc.nodes[product.inputs["in1"].nodename];
        QCOMPARE(channel.category, QString("extract"));
        QCOMPARE(channel.inputs["index"].value, QString("2"));
        if (shader == "gltf_pbr") {
            QVERIFY(!imageBehind(doc, sh.inputs["occlusion"]).isEmpty());
            QCOMPARE(sh.inputs["alpha_mode"].value, QString("1"));
            QCOMPARE(sh.inputs["alpha_cutoff"].value, QString("0.5"));
        } else {
            QVERIFY2(r.err.contains("warning: ") && r.err.contains("textures.occlusion") &&
                         r.err.contains("alpha cut-out"),
                     qPrintable(r.err));
        }
    }

    void shaderOptionIsChecked() {
        velvet::test::RunOptions options;
        auto r = velvet::test::runVelvet({"export", preset("gold.json"), "-f", "mtlx", "--shader",
                                          "phong", "-o", m_tmp.filePath("x")},
                                         options);
        QCOMPARE(r.exitCode, 1);
        r = velvet::test::runVelvet({"export", preset("gold.json"), "-f", "glb", "--shader",
                                     "gltf_pbr", "-o", m_tmp.filePath("x")},
                                    options);
        QCOMPARE(r.exitCode, 1);
        QVERIFY(!QFileInfo::exists(m_tmp.filePath("x")));
    }
    /// A graph-driven preset (denim drives base colour, roughness, normal, occlusion): its
    /// inputs read the baked maps through image nodes, by paths relative to the .mtlx, colour
    /// tagged srgb_texture and data untagged (vector types are never colour-transformed:
    /// MaterialX 1.39 Specification, "Color Spaces and Color Management"), at --bake-size.
    void graphIsBakedToImages() {
        const QString out = m_tmp.filePath("baked");
        velvet::test::RunOptions options;
        const auto r = velvet::test::runVelvet(
            {"export", preset("denim.json"), "-f", "mtlx", "--bake-size", "32", "-o", out},
            options);
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.err.contains("graph:"), qPrintable(r.err));
        const MxDocument doc = parse(out + "/denim.mtlx");
        QVERIFY2(doc.error.isEmpty(), qPrintable(doc.error));
        const MxNode& sh = doc.nodes["SR_denim"];
        auto fileOf = [&](const QString& input) {
            const QString image = imageBehind(doc, sh.inputs[input]);
            return image.isEmpty() ? MxInput{} : doc.nodes[image].inputs["file"];
        };
        const MxInput base = fileOf("base_color");
        QCOMPARE(base.value, QString("denim_baked_baseColor.png"));
        QCOMPARE(base.colorspace, QString("srgb_texture"));
        QVERIFY(sh.inputs["base_color"].value.isEmpty()); // no factor: the image is the value
        const MxInput rough = fileOf("specular_roughness");
        QCOMPARE(rough.value, QString("denim_baked_orm.png"));
        QCOMPARE(rough.colorspace, QString());
        const MxNode& normal = doc.nodes[sh.inputs["normal"].nodename];
        QCOMPARE(normal.category, QString("normalmap"));
        const MxInput normalFile = doc.nodes[normal.inputs["in"].nodename].inputs["file"];
        QCOMPARE(normalFile.value, QString("denim_baked_normal.png"));
        QCOMPARE(normalFile.colorspace, QString());
        for (const MxInput& file : {base, rough, normalFile}) {
            velvet::ImageInfo info;
            std::string error;
            QVERIFY2(velvet::readImageInfo((out + "/" + file.value).toStdString(), info, &error),
                     error.c_str());
            QCOMPARE(info.width, 32);
            QCOMPARE(info.height, 32);
        }
    }
    /// Issue 12: a graph input whose nodes all have MaterialX standard-library counterparts
    /// (a mix of two constants) is a nodegraph connected to the shader, with no baked image;
    /// beside it a roughness driven by a fabric node (Weave, no counterpart) is baked, alone.
    void mappableGraphIsANodegraphFabricIsBaked() {
        const QString preset = m_tmp.filePath("mixed.json");
        QFile f(preset);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write(R"({"format": "velvet.material", "version": 2, "name": "mixed", "graph": {
  "nodes": [{"id": 1, "type": "output.material", "position": [900, 0]},
            {"id": 2, "type": "constant.color", "position": [0, 0], "inputs": {"color": [0.8, 0.1, 0.1]}},
            {"id": 3, "type": "constant.color", "position": [0, 200], "inputs": {"color": [0.1, 0.2, 0.9]}},
            {"id": 4, "type": "math.mix", "position": [300, 0], "inputs": {"factor": 0.25}},
            {"id": 5, "type": "fabric.weave", "position": [300, 300]}],
  "links": [{"from": 2, "output": "color", "to": 4, "input": "a"},
            {"from": 3, "output": "color", "to": 4, "input": "b"},
            {"from": 4, "output": "result", "to": 1, "input": "baseColor"},
            {"from": 5, "output": "roughness", "to": 1, "input": "roughness"}]}})");
        f.close();
        const QString out = m_tmp.filePath("mixed-out");
        const auto r = velvet::test::runVelvet(
            {"export", preset, "-f", "mtlx", "--bake-size", "16", "-o", out}, {});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(QDir(out).entryList(QDir::Files, QDir::Name),
                 (QStringList{"mixed.mtlx", "mixed_baked_orm.png"}));
        const MxDocument doc = parse(out + "/mixed.mtlx");
        QVERIFY2(doc.error.isEmpty(), qPrintable(doc.error));
        QCOMPARE(doc.nodes["NG_mixed"].category, QString("nodegraph"));
        int mixes = 0;
        for (const MxNode& n : doc.nodes)
            mixes += n.category == "mix";
        QCOMPARE(mixes, 1);
        QFile text(out + "/mixed.mtlx");
        QVERIFY(text.open(QIODevice::ReadOnly));
        const QByteArray xml = text.readAll();
        QVERIFY(xml.contains(
            R"(<input name="base_color" type="color3" nodegraph="NG_mixed" output="out_baseColor" />)"));
        QVERIFY(imageBehind(doc, doc.nodes["SR_mixed"].inputs["specular_roughness"]) != "");
    }
    /// Silk's graph drives the anisotropy direction and the roughness, both baked; MaterialX's
    /// anisotropy inputs are constants, written from the baked maps' means (with a warning), so
    /// the stretch is kept: 1 - alpha/alpha_t at strength 0.5 and a roughness near silk's.
    void bakedAnisotropyKeepsItsStrength() {
        const QString out = m_tmp.filePath("baked-silk");
        const auto r = velvet::test::runVelvet(
            {"export", preset("silk.json"), "-f", "mtlx", "--bake-size", "32", "-o", out}, {});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(r.err.contains("graph: the anisotropy inputs are constants in MaterialX"),
                 qPrintable(r.err));
        const MxDocument doc = parse(out + "/silk.mtlx");
        QVERIFY2(doc.error.isEmpty(), qPrintable(doc.error));
        const float a = doc.nodes["SR_silk"].inputs["specular_anisotropy"].value.toFloat();
        QVERIFY2(a > 0.3f && a < 0.9f, qPrintable(QString::number(a)));
    }
};
QTEST_GUILESS_MAIN(TestAppExportMtlx)
#include "test_app_export_mtlx.moc"
