// Issue 18, "A hardened importer": a corpus of hostile mesh files built here (zero-length,
// truncated, huge counts, wrong magic, deep nesting, formats Velvet does not list) and importers
// that hang, spin or hog memory, imported through the crash-isolated importMesh() with the real
// `velvet import-mesh` child. Each is refused with false and its own message naming the file,
// within the wall-clock limit; the figures are printed (BENCHMARKS.md).
#include "core/mesh_import.h"

#include <QElapsedTimer>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>

namespace {

void writeBytes(const QString& file, const std::string& bytes) {
    std::ofstream(file.toStdString(), std::ios::binary) << bytes;
}

std::string repeat(const std::string& s, int n) {
    std::string out;
    out.reserve(s.size() * size_t(n));
    for (int i = 0; i < n; ++i)
        out += s;
    return out;
}

} // namespace

class TestAppHostileMeshes : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;

private slots:
    void corpus_data() {
        QTest::addColumn<QString>("name");
        QTest::addColumn<QByteArray>("bytes");
        QTest::addColumn<QString>("expected");
        const auto row = [](const char* tag, const char* name, const std::string& bytes,
                            const char* expected) {
            QTest::newRow(tag) << name << QByteArray::fromStdString(bytes) << expected;
        };
        row("zero-length obj", "empty.obj", "", "empty file");
        row("zero-length glb", "empty.glb", "", "empty file");
        row("truncated glb", "cut.glb", std::string("glTF\x02\0\0\0\xff\xff\0\0", 12),
            "cannot import");
        row("truncated binary stl", "cut.stl",
            std::string(80, ' ') + std::string("\xff\xff\xff\x0f", 4), "");
        row("stl huge count", "huge.stl",
            std::string(80, ' ') + std::string("\xff\xff\xff\xff", 4) + std::string(50, '\0'), "");
        row("ply huge count", "huge.ply",
            "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
            "property float y\nproperty float z\nelement face 4000000000\n"
            "property list uchar int vertex_indices\nend_header\n",
            "faces");
        row("glb with zip magic", "zip.glb", std::string("PK\x03\x04", 4) + std::string(64, '\x01'),
            "first bytes");
        row("ply with jpeg magic", "photo.ply",
            std::string("\xff\xd8\xff\xe0", 4) + std::string(64, 'x'), "first bytes");
        row("gltf that is binary", "bin.gltf", std::string("\0\x01\x02{", 4), "first bytes");
        row("dae that is not xml", "text.dae", "solid cube\n", "first bytes");
        row("obj with out-of-range indices", "bad-index.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967295\n", "");
        row("deeply nested dae", "deep.dae",
            "<?xml version=\"1.0\"?><COLLADA><library_visual_scenes><visual_scene>" +
                repeat("<node>", 200000) + repeat("</node>", 200000) +
                "</visual_scene></library_visual_scenes></COLLADA>",
            "nested more than 256 levels deep");
        row("deeply nested gltf", "deep.gltf",
            "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + repeat("[", 200000) +
                repeat("]", 200000) + "}",
            "nested more than 256 levels deep");
        {
            const std::string json =
                "{\"asset\":{\"version\":\"2.0\"},\"extras\":" + repeat("{\"a\":", 100000) + "0" +
                repeat("}", 100000) + "}";
            std::string glb("glTF\x02\0\0\0\0\0\0\0", 12);
            const auto le32 = [](std::uint32_t v) {
                return std::string{char(v & 255), char((v >> 8) & 255), char((v >> 16) & 255),
                                   char(v >> 24)};
            };
            glb += le32(std::uint32_t(json.size())) + "JSON" + json;
            row("deeply nested glb", "deep.glb", glb, "nested more than 256 levels deep");
        }
        for (const char* ext : {"md5mesh", "csm", "mdc", "iqm"}) {
            const std::string name = std::string("model.") + ext;
            QTest::newRow(ext)
                << QString::fromStdString(name) << QByteArray("MD5Version 10\n")
                << "not a mesh format Velvet reads (OBJ, FBX, glTF/GLB, PLY, STL, DAE)";
        }
    }
    void corpus() {
        QFETCH(QString, name);
        QFETCH(QByteArray, bytes);
        QFETCH(QString, expected);
        const QString file = m_dir.filePath(name);
        writeBytes(file, bytes.toStdString());
        velvet::MeshImportOptions options;
        options.helper = VELVET_BINARY;
        velvet::MeshData mesh;
        std::string error;
        QElapsedTimer clock;
        clock.start();
        const bool ok = velvet::importMeshUncached(file.toStdString(), mesh, &error, options);
        const qint64 ms = clock.elapsed();
        QVERIFY2(!ok, "a hostile file was imported");
        QVERIFY2(QString::fromStdString(error).contains(name), error.c_str());
        QVERIFY2(expected.isEmpty() || QString::fromStdString(error).contains(expected),
                 error.c_str());
        QVERIFY2(error.find('\n') == std::string::npos, error.c_str());
        QVERIFY2(ms < options.timeoutMs, qPrintable(QString::number(ms)));
        std::printf("refused in %lld ms: %s\n", ms, error.c_str());
    }

    // Each limit has its own message: the wall clock (a hang), CPU time (a spin), the address
    // space (a memory hog).
    void limits_data() {
        QTest::addColumn<QByteArray>("hook");
        QTest::addColumn<QString>("expected");
        QTest::newRow("hang") << QByteArray("VELVET_IMPORT_MESH_SIMULATE_HANG")
                              << "timed out after 1.5 s";
        QTest::newRow("spin") << QByteArray("VELVET_IMPORT_MESH_SIMULATE_SPIN")
                              << "more than 1 s of CPU time";
        QTest::newRow("hog") << QByteArray("VELVET_IMPORT_MESH_SIMULATE_HOG")
                             << "needed more than 2 GiB of memory";
    }
    void limits() {
        QFETCH(QByteArray, hook);
        QFETCH(QString, expected);
        const QString file = m_dir.filePath("cube.obj");
        writeBytes(file, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        velvet::MeshImportOptions options;
        options.helper = VELVET_BINARY;
        // The hang meets the wall clock; the spin and the hog get a wide one, so that on a loaded
        // machine (1 s of CPU can take seconds of wall clock) their own limit is the one hit.
        options.timeoutMs = hook.endsWith("HANG") ? 1500 : 30000;
        // The hog fills 2 GiB before its limit: that costs CPU, so its CPU limit is wide too.
        options.cpuSeconds = hook.endsWith("HOG") ? 30 : 1;
        // The whole binary is mapped in the child (Qt, OpenImageIO, Embree, oneTBB reserve address
        // space at load): 2 GiB leaves an honest import room and still stops the hog.
        options.addressSpaceMiB = 2048;
        qputenv(hook.constData(), "1");
        velvet::MeshData mesh;
        std::string error;
        QElapsedTimer clock;
        clock.start();
        const bool ok = velvet::importMeshUncached(file.toStdString(), mesh, &error, options);
        const qint64 ms = clock.elapsed();
        qunsetenv(hook.constData());
        QVERIFY(!ok);
        QVERIFY2(QString::fromStdString(error).contains(expected), error.c_str());
        QVERIFY2(ms < options.timeoutMs + 1000, qPrintable(QString::number(ms)));
        std::printf("%s refused in %lld ms: %s\n", hook.constData(), ms, error.c_str());
        // The same file without a hook imports: the limits do not stop honest work. The hang's
        // tight wall clock is widened for it (a loaded machine can take 1.5 s to start the child).
        options.timeoutMs = std::max(options.timeoutMs, 30000);
        QVERIFY2(velvet::importMeshUncached(file.toStdString(), mesh, &error, options),
                 error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestAppHostileMeshes)
#include "test_app_hostile_meshes.moc"
