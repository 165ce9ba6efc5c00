// velvet export -f texture-set (issue 12) through the real binary: for Unreal and glTF the maps
// are baked from a textured preset and checked channel by channel against the material's own
// maps (an ORM texel = occlusion with its strength, roughness x G, metallic x B), the normal
// map's green channel is flipped for Unreal (DirectX) and not for glTF (OpenGL), the manifest
// names each file's role; an existing set is refused (exit 2) unless --force, names cannot leave
// the folder; bad options are usage errors; presets' clearcoat and sheen reach the lobe maps.
#include "core/color_management.h"
#include "core/document_io.h"
#include "core/image.h"
#include "run_velvet.h"

#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest>

namespace {

using velvet::test::Result;
constexpr int kSide = 8;

Result runVelvet(const QStringList& args) {
    velvet::test::RunOptions options;
    options.timeoutMs = 120000;
    return velvet::test::runVelvet(args, options);
}

float texel(int x, int y, int c) {
    return float((x * 29 + y * 11 + c * 83) % 256) / 255.0f;
}

velvet::Image pattern(int channels) {
    velvet::Image img(kSide, kSide, channels);
    for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
            for (int c = 0; c < channels; ++c)
                img.at(x, y)[c] = texel(x, y, c);
    return img;
}

void write(const QString& file, const velvet::Image& img) {
    std::string error;
    if (!velvet::writeImage(file.toStdString(), img, velvet::PixelFormat::UInt8, &error))
        qFatal("%s", error.c_str());
}

velvet::Image read(const QString& file) {
    velvet::Image img;
    std::string error;
    if (!velvet::readImage(file.toStdString(), img, &error))
        qFatal("%s", error.c_str());
    return img;
}

/// 8-bit output of an 8-bit input through half-float textures.
constexpr float kTol = 1.5f / 255.0f;

} // namespace

class TestAppTextureSet : public QObject {
    Q_OBJECT
    QTemporaryDir m_tmp;
    QString m_preset;

private slots:
    void initTestCase() {
        QVERIFY(m_tmp.isValid());
        const QString t = m_tmp.filePath("textures/");
        QDir().mkpath(t);
        write(t + "occlusion.png", pattern(1));
        write(t + "mr.png", pattern(3));
        velvet::Image normal(kSide, kSide, 3);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                normal.at(x, y)[0] = float(96 + 8 * x) / 255.0f;
                normal.at(x, y)[1] = float(200 - 12 * y) / 255.0f;
                normal.at(x, y)[2] = 1.0f;
            }
        write(t + "normal.png", normal);
        using velvet::ParamId;
        using velvet::TextureSlot;
        velvet::Material m;
        m.name = "Set test";
        m.setScalar(ParamId::Roughness, 0.8f);
        m.setScalar(ParamId::Metallic, 0.6f);
        m.setScalar(ParamId::OcclusionStrength, 0.75f);
        auto ref = [&](const char* f) {
            velvet::TextureRef r;
            r.file = (t + f).toStdString();
            return r;
        };
        m.setTexture(TextureSlot::Occlusion, ref("occlusion.png"));
        m.setTexture(TextureSlot::MetallicRoughness, ref("mr.png"));
        m.setTexture(TextureSlot::Normal, ref("normal.png"));
        m_preset = m_tmp.filePath("set_test.json");
        std::string error;
        QVERIFY2(velvet::saveMaterialFile(m, m_preset.toStdString(), &error), error.c_str());
    }

    void unrealAndGltfChannelByChannel() {
        const QString ue = m_tmp.filePath("ue"), gl = m_tmp.filePath("gl");
        Result r = runVelvet({"export", m_preset, "-f", "texture-set", "--target", "unreal",
                              "--size", QString::number(kSide), "-o", ue});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY(r.out.contains("set_test_texture_set.json"));
        r = runVelvet({"export", m_preset, "-f", "texture-set", "--target", "gltf", "--size",
                       QString::number(kSide), "-o", gl});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QCOMPARE(QDir(ue).entryList(QDir::Files, QDir::Name | QDir::IgnoreCase),
                 (QStringList{"set_test_texture_set.json", "T_set_test_D.png", "T_set_test_N.png",
                              "T_set_test_ORM.png"}));

        const velvet::Image orm = read(ue + "/T_set_test_ORM.png");
        const velvet::Image gltfOrm = read(gl + "/set_test_orm.png");
        QCOMPARE(orm.width, kSide);
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                const float ao = 1.0f + 0.75f * (texel(x, y, 0) - 1.0f);
                QVERIFY(std::abs(orm.at(x, y)[0] - ao) <= kTol);
                QVERIFY(std::abs(orm.at(x, y)[1] - 0.8f * texel(x, y, 1)) <= kTol);
                QVERIFY(std::abs(orm.at(x, y)[2] - 0.6f * texel(x, y, 2)) <= kTol);
                for (int c = 0; c < 3; ++c)
                    QCOMPARE(gltfOrm.at(x, y)[c], orm.at(x, y)[c]);
            }
        // Green flipped for Unreal, not for glTF; red and blue the same.
        const velvet::Image nu = read(ue + "/T_set_test_N.png");
        const velvet::Image ng = read(gl + "/set_test_normal.png");
        bool tilted = false;
        for (int y = 0; y < kSide; ++y)
            for (int x = 0; x < kSide; ++x) {
                QVERIFY(std::abs(nu.at(x, y)[1] - (1.0f - ng.at(x, y)[1])) <= 1.0f / 255.0f);
                QCOMPARE(nu.at(x, y)[0], ng.at(x, y)[0]);
                QCOMPARE(nu.at(x, y)[2], ng.at(x, y)[2]);
                tilted = tilted || std::abs(ng.at(x, y)[1] - 0.5f) > 0.1f;
            }
        QVERIFY(tilted); // the test's normals do lean in Y: the flip is visible
        // The glTF normal is the texture's own (OpenGL), normalised: texel (0, 0) leans +Y.
        QVERIFY(ng.at(0, 0)[1] > 0.7f);

        QFile f(ue + "/set_test_texture_set.json");
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject manifest = QJsonDocument::fromJson(f.readAll()).object();
        QCOMPARE(manifest["target"].toString(), QStringLiteral("unreal"));
        QCOMPARE(manifest["material"].toString(), QStringLiteral("Set test"));
        QStringList roles;
        for (const QJsonValue v : manifest["files"].toArray())
            roles << v.toObject()["role"].toString();
        QCOMPARE(roles, (QStringList{"baseColor", "normal", "occlusionRoughnessMetallic"}));
    }

    // The lobes end to end: the car paint preset's clearcoat reaches glTF's clearcoat map (R
    // weight, G roughness, the preset's values), crimson velvet's sheen glTF's sheen map (sRGB
    // weight x colour, A roughness); HDRP Lit and Godot have no sheen input and say so by name.
    void lobeMapsFromPresets() {
        velvet::Problems problems;
        const QString presets = QStringLiteral(VELVET_SOURCE_DIR "/resources/presets/");
        const auto car =
            velvet::loadMaterialFile((presets + "car_paint.json").toStdString(), problems);
        const auto velvetM =
            velvet::loadMaterialFile((presets + "crimson_velvet.json").toStdString(), problems);
        QVERIFY(car && velvetM);
        using velvet::ParamId;
        const QString out = m_tmp.filePath("lobes");
        Result r = runVelvet({"export", presets + "car_paint.json", "-f", "texture-set", "--target",
                              "gltf", "--size", "4", "-o", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        QVERIFY2(!r.err.contains("clearcoat"), qPrintable(r.err)); // carried, not warned
        const velvet::Image coat = read(out + "/car_paint_clearcoat.png");
        QVERIFY(std::abs(coat.at(1, 1)[0] - car->scalar(ParamId::ClearcoatWeight)) <= kTol);
        QVERIFY(std::abs(coat.at(1, 1)[1] - car->scalar(ParamId::ClearcoatRoughness)) <= kTol);

        r = runVelvet({"export", presets + "crimson_velvet.json", "-f", "texture-set", "--target",
                       "gltf", "--size", "4", "-o", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        const velvet::Image sheen = read(out + "/crimson_velvet_sheen.png");
        const glm::vec3 expected =
            velvetM->scalar(ParamId::SheenWeight) * velvetM->color(ParamId::SheenColor);
        for (int c = 0; c < 3; ++c)
            QVERIFY2(std::abs(sheen.at(2, 2)[c] - velvet::linearToSrgb(expected[c])) <= kTol,
                     qPrintable(QString::number(c)));
        QVERIFY(std::abs(sheen.at(2, 2)[3] - velvetM->scalar(ParamId::SheenRoughness)) <= kTol);
        for (const char* target : {"unity-hdrp", "godot"}) {
            r = runVelvet({"export", presets + "crimson_velvet.json", "-f", "texture-set",
                           "--target", target, "--size", "4", "-o", m_tmp.filePath(target)});
            QVERIFY2(r.exitCode == 0, qPrintable(r.err));
            QVERIFY2(r.err.contains("sheen.weight") && r.err.contains("no sheen input"),
                     qPrintable(r.err));
        }
    }

    void existingSetIsRefusedUnlessForce() {
        const QString out = m_tmp.filePath("again");
        const QStringList args{"export", m_preset, "-f", "texture-set", "--target",
                               "godot",  "--size", "4",  "-o",          out};
        QCOMPARE(runVelvet(args).exitCode, 0);
        const QByteArray before = [&] {
            QFile f(out + "/set_test_orm.png");
            f.open(QIODevice::ReadOnly);
            return f.readAll();
        }();
        const Result again = runVelvet(args);
        QCOMPARE(again.exitCode, 2);
        QVERIFY2(again.err.contains("--force"), qPrintable(again.err));
        QCOMPARE(runVelvet(args + QStringList{"--force"}).exitCode, 0);
        QFile f(out + "/set_test_orm.png");
        QVERIFY(f.open(QIODevice::ReadOnly));
        QCOMPARE(f.readAll(), before);
        QVERIFY(QDir(out).entryList(QDir::Files | QDir::Hidden).size() == 4); // no litter
    }

    void namesCannotLeaveTheFolder() {
        // Beside the preset, so its relative texture paths still resolve.
        const QString evil = m_tmp.filePath("..%2F..%2Fevil.json");
        QVERIFY(QFile::copy(m_preset, evil));
        const QString out = m_tmp.filePath("safe");
        const Result r = runVelvet(
            {"export", evil, "-f", "texture-set", "--target", "gltf", "--size", "2", "-o", out});
        QVERIFY2(r.exitCode == 0, qPrintable(r.err));
        for (const QString& f : QDir(out).entryList(QDir::Files))
            QVERIFY2(!f.contains('/') && !f.startsWith('.'), qPrintable(f));
        QVERIFY(QFile::exists(out + "/2F_2Fevil_texture_set.json"));
    }

    void usageErrors() {
        const QString out = m_tmp.filePath("u");
        for (const QStringList& extra : {QStringList{},
                                         {"--target", "cryengine"},
                                         {"--target", "unreal", "--bits", "12"},
                                         {"--target", "unreal", "--image", "tga", "--bits", "16"},
                                         {"--target", "unreal", "--size", "0"},
                                         {"--target", "unreal", "--normal", "up"},
                                         {"--target", "unreal", "--mesh", "cube"}}) {
            const Result r =
                runVelvet(QStringList{"export", m_preset, "-f", "texture-set", "-o", out} + extra);
            QVERIFY2(r.exitCode == 1, qPrintable(extra.join(' ') + ": " + r.err));
        }
        QCOMPARE(
            runVelvet({"export", m_preset, "-f", "glb", "--target", "unreal", "-o", out}).exitCode,
            1);
    }
};

QTEST_GUILESS_MAIN(TestAppTextureSet)
#include "test_app_texture_set.moc"
