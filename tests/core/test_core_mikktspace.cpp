// core/mikktspace: Velvet's MikkTSpace against the reference algorithm (Mikkelsen's mikktspace.c
// through its Rust port built to WebAssembly: the npm package mikktspace, run by
// scripts/mikktspace-reference.js), per triangle corner, on meshes Velvet makes and imports.
// The reference must be installed (`make deps`): without node or the package the test fails
// with the reason, it does not skip. Measurements (largest angle, sign mismatches, times) are
// printed per mesh; docs/architecture.md ("Tangents") records them.
#include "core/mesh.h"
#include "core/mesh_import.h"
#include "core/mesh_tangents.h"
#include "core/mikktspace.h"

#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <glm/geometric.hpp>
#include <sstream>

using namespace velvet;

namespace {

Vertex vert(glm::vec3 p, glm::vec3 n, glm::vec2 uv) {
    Vertex v{};
    v.position = p;
    v.normal = glm::normalize(n);
    v.uv = uv;
    return v;
}

/// Two flat sheets meeting at a hard edge (the ridge's vertices duplicated, one normal per
/// sheet), each UV-mirrored about x = 0 on shared vertices (u = |x|), as the halves of a
/// symmetric model share one half of a texture. The x = 0 vertices' fans hold both
/// orientations, so MikkTSpace gives them two frames each.
MeshData seamMesh() {
    MeshData m;
    const int nx = 8, ny = 4;
    for (int sheet = 0; sheet < 2; ++sheet) {
        const glm::vec3 dir =
            sheet == 0 ? glm::vec3(0, -1, 0) : glm::normalize(glm::vec3(0, 0.6f, 0.8f));
        const glm::vec3 n =
            glm::normalize(glm::cross(dir, glm::vec3(1, 0, 0))) * (sheet == 0 ? -1.0f : 1.0f);
        const auto base = std::uint32_t(m.vertices.size());
        for (int j = 0; j <= ny; ++j)
            for (int i = 0; i <= nx; ++i) {
                const float x = -1.0f + 2.0f * float(i) / nx, s = float(j) / ny;
                const float v = 0.5f + (sheet == 0 ? 0.5f : -0.5f) * s;
                m.vertices.push_back(vert(glm::vec3(x, 0, 0) + s * dir, n, {std::abs(x), v}));
            }
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                const std::uint32_t a = base + std::uint32_t(j * (nx + 1) + i), b = a + 1,
                                    c = a + nx + 1, d = c + 1;
                m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
            }
    }
    return m;
}

/// A bent 4x4 grid with the reference's special cases: a triangle with collinear UVs (no UV
/// area: it joins its neighbours' groups, its own corner gets none), a triangle with two corners
/// at one position but different UVs and one with a repeated index (degenerate: their corners
/// copy a valid corner's frame, or keep the placeholder where none touches), a degenerate
/// triangle touching nothing and an isolated triangle without UV area (placeholders).
/// 8 corners are left undefined.
MeshData degenerateMesh() {
    MeshData m;
    const glm::vec3 n(0, 0, 1);
    for (int j = 0; j <= 4; ++j)
        for (int i = 0; i <= 4; ++i)
            m.vertices.push_back(vert(glm::vec3(i, j, 0.1f * float(i * j)) * 0.5f,
                                      glm::vec3(-0.05f * float(j), -0.05f * float(i), 1),
                                      glm::vec2(i, j) * 0.25f));
    for (std::uint32_t j = 0; j < 4; ++j)
        for (std::uint32_t i = 0; i < 4; ++i) {
            const std::uint32_t a = j * 5 + i, b = a + 1, c = a + 5, d = c + 1;
            if (i == 2 && j == 2) {
                const auto e = std::uint32_t(m.vertices.size());
                Vertex v = m.vertices[d];
                v.uv = 0.5f * (m.vertices[a].uv + m.vertices[b].uv);
                m.vertices.push_back(v);
                m.indices.insert(m.indices.end(), {a, b, e, a, d, c});
                continue;
            }
            m.indices.insert(m.indices.end(), {a, b, d, a, d, c});
        }
    Vertex twin = m.vertices[6];
    twin.uv += glm::vec2(0.1f, 0.0f);
    m.vertices.push_back(twin);
    m.indices.insert(m.indices.end(), {6, std::uint32_t(m.vertices.size() - 1), 12});
    m.indices.insert(m.indices.end(), {7, 7, 13});
    const auto e = std::uint32_t(m.vertices.size());
    m.vertices.push_back(vert({3, 3, 1}, n, {0.9f, 0.9f}));
    m.vertices.push_back(vert({3, 3, 1}, n, {0.8f, 0.9f}));
    m.vertices.push_back(vert({3, 4, 1}, n, {0.9f, 0.8f}));
    m.vertices.push_back(vert({4, 3, 1}, n, {0.5f, 0.5f}));
    m.vertices.push_back(vert({4, 4, 1}, n, {0.5f, 0.5f}));
    m.vertices.push_back(vert({4, 3, 2}, n, {0.5f, 0.5f}));
    m.indices.insert(m.indices.end(), {e, e + 1, e + 2, e + 3, e + 4, e + 5});
    return m;
}

/// A roof as an OBJ without normals: two slopes at 90 degrees (Assimp's normals, creased at 60
/// degrees, make the ridge a hard edge), UVs mirrored about x = 0 (u = |x|).
std::string roofObj() {
    std::ostringstream obj;
    const float xs[5] = {-1.0f, -0.5f, 0.0f, 0.5f, 1.0f};
    for (int slope = 0; slope < 2; ++slope)
        for (int row = 0; row < 3; ++row)
            for (const float x : xs) {
                const float d = 0.5f * float(row);
                obj << "v " << x << ' ' << 1.0f - d << ' ' << (slope ? -d : d) << '\n';
                obj << "vt " << std::abs(x) << ' ' << 1.0f - 0.5f * d << '\n';
            }
    for (int slope = 0; slope < 2; ++slope)
        for (int row = 0; row < 2; ++row)
            for (int i = 0; i < 4; ++i) {
                const int a = 1 + slope * 15 + row * 5 + i, b = a + 1, c = a + 5, d = c + 1;
                // Counter-clockwise seen from outside: the slopes face +z and -z.
                if (slope == 0)
                    obj << "f " << a << '/' << a << ' ' << c << '/' << c << ' ' << d << '/' << d
                        << "\nf " << a << '/' << a << ' ' << d << '/' << d << ' ' << b << '/' << b
                        << '\n';
                else
                    obj << "f " << a << '/' << a << ' ' << d << '/' << d << ' ' << c << '/' << c
                        << "\nf " << a << '/' << a << ' ' << b << '/' << b << ' ' << d << '/' << d
                        << '\n';
            }
    return obj.str();
}

/// A unit quad in the XY plane facing +z, UVs in glTF's space (v down the image = -y), as a
/// .gltf with its buffer in a data URI; with a TANGENT attribute when @p tangent has a w.
std::string quadGltf(const glm::vec4* tangent) {
    const float pos[12] = {0, 0, 0, 1, 0, 0, 1, -1, 0, 0, -1, 0};
    const float nrm[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float uv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
    const std::uint16_t idx[6] = {0, 3, 2, 0, 2, 1};
    QByteArray buffer;
    const auto add = [&](const void* data, int bytes) {
        const int offset = int(buffer.size());
        buffer.append(static_cast<const char*>(data), bytes);
        return std::to_string(offset);
    };
    std::string views = "{\"buffer\":0,\"byteOffset\":" + add(pos, 48) + ",\"byteLength\":48},";
    views += "{\"buffer\":0,\"byteOffset\":" + add(nrm, 48) + ",\"byteLength\":48},";
    views += "{\"buffer\":0,\"byteOffset\":" + add(uv, 32) + ",\"byteLength\":32},";
    views += "{\"buffer\":0,\"byteOffset\":" + add(idx, 12) + ",\"byteLength\":12}";
    std::string accessors =
        "{\"bufferView\":0,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\","
        "\"min\":[0,-1,0],\"max\":[1,0,0]},"
        "{\"bufferView\":1,\"componentType\":5126,\"count\":4,\"type\":\"VEC3\"},"
        "{\"bufferView\":2,\"componentType\":5126,\"count\":4,\"type\":\"VEC2\"},"
        "{\"bufferView\":3,\"componentType\":5123,\"count\":6,\"type\":\"SCALAR\"}";
    std::string attributes = "\"POSITION\":0,\"NORMAL\":1,\"TEXCOORD_0\":2";
    if (tangent) {
        float tan[16];
        for (int v = 0; v < 4; ++v)
            for (int k = 0; k < 4; ++k)
                tan[v * 4 + k] = (*tangent)[k];
        views += ",{\"buffer\":0,\"byteOffset\":" + add(tan, 64) + ",\"byteLength\":64}";
        accessors += ",{\"bufferView\":4,\"componentType\":5126,\"count\":4,\"type\":\"VEC4\"}";
        attributes += ",\"TANGENT\":4";
    }
    return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
           "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{" +
           attributes + "},\"indices\":3}]}],\"accessors\":[" + accessors + "],\"bufferViews\":[" +
           views + "],\"buffers\":[{\"byteLength\":" + std::to_string(buffer.size()) +
           ",\"uri\":\"data:application/octet-stream;base64," + buffer.toBase64().toStdString() +
           "\"}]}";
}

struct Reference {
    std::vector<float> tangents;          ///< 4 per corner, the reference's own sign convention
    double firstCpuMs = 0.0, cpuMs = 0.0; ///< its first call, its second
};

/// The reference's tangents for @p mesh's corners (unindexed, as the reference takes them).
Reference runReference(const MeshData& mesh, const QString& dir) {
    const QString node = QStringLiteral(VELVET_NODE);
    if (node.isEmpty())
        qFatal("node (Node.js) was not found when configuring; run 'make deps'");
    const QString in = dir + "/corners.bin", out = dir + "/tangents.bin";
    {
        std::ofstream file(in.toStdString(), std::ios::binary);
        const auto n = std::uint32_t(mesh.indices.size());
        file.write(reinterpret_cast<const char*>(&n), 4);
        for (const std::uint32_t i : mesh.indices)
            file.write(reinterpret_cast<const char*>(&mesh.vertices[i].position), 12);
        for (const std::uint32_t i : mesh.indices)
            file.write(reinterpret_cast<const char*>(&mesh.vertices[i].normal), 12);
        for (const std::uint32_t i : mesh.indices)
            file.write(reinterpret_cast<const char*>(&mesh.vertices[i].uv), 8);
    }
    QProcess p;
    p.start(node, {QStringLiteral(VELVET_SOURCE_DIR "/scripts/mikktspace-reference.js"), in, out});
    if (!p.waitForFinished(120000))
        qFatal("mikktspace-reference.js did not finish");
    const QString err = QString::fromUtf8(p.readAllStandardError());
    if (p.exitStatus() != QProcess::NormalExit || p.exitCode() != 0)
        qFatal("the MikkTSpace reference could not run (run 'make deps'): %s", qPrintable(err));
    const QJsonObject report = QJsonDocument::fromJson(p.readAllStandardOutput()).object();
    Reference r;
    r.firstCpuMs = report["first_cpu_ms"].toDouble();
    r.cpuMs = report["cpu_ms"].toDouble();
    r.tangents.resize(mesh.indices.size() * 4);
    std::ifstream file(out.toStdString(), std::ios::binary);
    file.read(reinterpret_cast<char*>(r.tangents.data()), std::streamsize(r.tangents.size() * 4));
    if (!file)
        qFatal("mikktspace-reference.js wrote a short file: %s", qPrintable(err));
    return r;
}

struct Comparison {
    double maxAngle = 0.0;  ///< radians, over the corners both define
    int signMismatches = 0; ///< over the same corners
    int undefined = 0;      ///< corners Velvet leaves undefined
    int undefinedButReferenceDefines = 0;
};

/// Corner by corner: the angle between the tangents (atan2 of |cross| and dot, in double:
/// acos of a float dot cannot resolve below 5e-4 rad), w against the reference's sign negated
/// (glTF's UV space), and where Velvet finds no frame, that the reference has its placeholder.
Comparison compare(const std::vector<glm::vec4>& ours, const std::vector<std::uint8_t>& defined,
                   const Reference& ref) {
    Comparison c;
    for (size_t i = 0; i < ours.size(); ++i) {
        const glm::dvec3 r(ref.tangents[i * 4], ref.tangents[i * 4 + 1], ref.tangents[i * 4 + 2]);
        if (!defined[i]) {
            ++c.undefined;
            if (r != glm::dvec3(1, 0, 0) && r != glm::dvec3(0))
                ++c.undefinedButReferenceDefines;
            continue;
        }
        const glm::dvec3 t(ours[i]);
        c.maxAngle =
            std::max(c.maxAngle, std::atan2(glm::length(glm::cross(r, t)), glm::dot(r, t)));
        c.signMismatches += ours[i].w != -ref.tangents[i * 4 + 3];
    }
    return c;
}

/// Median CPU milliseconds of @p runs calls of @p f.
template <typename F>
double medianCpuMs(int runs, F f) {
    std::vector<double> ms;
    for (int i = 0; i < runs; ++i) {
        const std::clock_t start = std::clock();
        f();
        ms.push_back(1000.0 * double(std::clock() - start) / CLOCKS_PER_SEC);
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

} // namespace

class TestMikkTSpace : public QObject {
    Q_OBJECT
    QTemporaryDir dir_;

private slots:
    // A flat quad: the tangent is the analytic dP/du, w = 1; with u mirrored, -dP/du and w = -1
    // (the glTF bitangent cross(n, t) * w points up the image either way).
    void quadMatchesAnalytic() {
        const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        const glm::vec3 dPdu = glm::normalize(glm::cross(glm::vec3(0, 1, 0), n)) * 2.0f;
        const glm::vec3 up = glm::cross(n, glm::normalize(dPdu));
        for (const bool mirrored : {false, true}) {
            MeshData quad;
            for (const glm::vec2 uv :
                 {glm::vec2(0, 0), glm::vec2(0, 1), glm::vec2(1, 1), glm::vec2(1, 0)}) {
                const glm::vec3 p = (uv.x - 0.5f) * dPdu - (uv.y - 0.5f) * 1.5f * up;
                quad.vertices.push_back(vert(p, n, mirrored ? glm::vec2(1 - uv.x, uv.y) : uv));
            }
            quad.indices = {0, 1, 2, 0, 2, 3};
            generateMikkTSpaceTangents(quad);
            QCOMPARE(quad.vertices.size(), size_t(4));
            for (const Vertex& v : quad.vertices) {
                const glm::vec3 expected = glm::normalize(mirrored ? -dPdu : dPdu);
                QVERIFY(glm::length(glm::vec3(v.tangent) - expected) < 1e-5f);
                QCOMPARE(v.tangent.w, mirrored ? -1.0f : 1.0f);
                QVERIFY(glm::dot(glm::cross(v.normal, glm::vec3(v.tangent)) * v.tangent.w, up) >
                        0.99f);
            }
        }
    }

    void matchesReference_data() {
        QTest::addColumn<int>("mesh");
        QTest::addColumn<int>("expectedUndefined");
        QTest::newRow("sphere") << 0 << 0;
        QTest::newRow("shader ball") << 1 << 0;
        QTest::newRow("cloth drape") << 2 << 0;
        QTest::newRow("cube (hard edges)") << 3 << 0;
        QTest::newRow("rounded cube") << 4 << 0;
        QTest::newRow("mirrored seam + hard edge") << 5 << 0;
        QTest::newRow("degenerate triangles") << 6 << 8;
    }

    // Per corner against the reference: every tangent within 1e-3 rad (measured: 0, the same
    // floats), every w the reference's negated, undefined corners exactly where the reference
    // leaves its placeholder. Prints the measurements and both CPU times.
    void matchesReference() {
        QFETCH(int, mesh);
        QFETCH(int, expectedUndefined);
        const MeshData m = mesh == 0   ? makeSphere()
                           : mesh == 1 ? makeShaderBall()
                           : mesh == 2 ? makeClothDrape()
                           : mesh == 3 ? makeCube()
                           : mesh == 4 ? makeRoundedCube()
                           : mesh == 5 ? seamMesh()
                                       : degenerateMesh();
        const Reference ref = runReference(m, dir_.path());
        const CornerTangents ours = mikkTSpaceCornerTangents(m);
        const Comparison c = compare(ours.tangents, ours.defined, ref);
        const double oursMs = medianCpuMs(5, [&] {
            MeshData copy = m;
            generateMikkTSpaceTangents(copy);
        });
        const double lengyelMs = medianCpuMs(5, [&] {
            MeshData copy = m;
            generateTangents(copy);
        });
        qInfo("%s: %zu corners, max angle %.3g rad, %d sign mismatches, %d undefined; CPU ms: "
              "Velvet MikkTSpace %.2f (with the vertex split), Lengyel %.2f, reference (wasm) "
              "%.2f (its first call %.2f)",
              QTest::currentDataTag(), m.indices.size(), c.maxAngle, c.signMismatches, c.undefined,
              oursMs, lengyelMs, ref.cpuMs, ref.firstCpuMs);
        QVERIFY2(c.maxAngle < 1e-3, qPrintable(QString::number(c.maxAngle)));
        QCOMPARE(c.signMismatches, 0);
        QCOMPARE(c.undefined, expectedUndefined);
        QCOMPARE(c.undefinedButReferenceDefines, 0);
    }

    // The vertex split: each corner's vertex carries that corner's tangent, and keeps its
    // position, normal and UV. On the mirrored seam the 10 vertices at x = 0 (5 per sheet) get
    // two frames, +x on the u = x half and -x with the other w on the u = -x half.
    void splitGivesEachCornerItsTangent() {
        MeshData m = seamMesh();
        const MeshData before = m;
        const CornerTangents corners = mikkTSpaceCornerTangents(m);
        generateMikkTSpaceTangents(m);
        QCOMPARE(m.vertices.size(), before.vertices.size() + 10);
        for (size_t c = 0; c < m.indices.size(); ++c) {
            const Vertex& v = m.vertices[m.indices[c]];
            const Vertex& old = before.vertices[before.indices[c]];
            QCOMPARE(v.tangent, corners.tangents[c]);
            QVERIFY(v.position == old.position && v.normal == old.normal && v.uv == old.uv);
        }
        float w[2][2] = {}; // per sheet, the u = -x half's and the u = x half's
        for (size_t t = 0; t < m.indices.size(); t += 3) {
            const glm::vec3 centre =
                (m.vertices[m.indices[t]].position + m.vertices[m.indices[t + 1]].position +
                 m.vertices[m.indices[t + 2]].position) /
                3.0f;
            const float side = centre.x > 0.0f ? 1.0f : -1.0f;
            for (size_t k = 0; k < 3; ++k) {
                const glm::vec4 tangent = m.vertices[m.indices[t + k]].tangent;
                QVERIFY(glm::length(glm::vec3(tangent) - glm::vec3(side, 0, 0)) < 1e-5f);
                const int sheet = m.vertices[m.indices[t + k]].normal.y > 0.4f ? 1 : 0;
                float& halfW = w[sheet][side > 0.0f ? 1 : 0];
                if (halfW == 0.0f)
                    halfW = tangent.w;
                QCOMPARE(tangent.w, halfW);
            }
        }
        QCOMPARE(w[0][0], -w[0][1]);
        QCOMPARE(w[1][0], -w[1][1]);
    }

    // End to end through the importer: an OBJ roof (hard ridge from Assimp's creased normals,
    // mirrored UVs) comes out with the reference's tangents at every corner.
    void importedMeshMatchesReference() {
        const QString file = dir_.path() + "/roof.obj";
        std::ofstream(file.toStdString()) << roofObj();
        MeshData m;
        std::string error;
        QVERIFY2(importMeshInProcess(file.toStdString(), m, &error), error.c_str());
        QCOMPARE(m.triangleCount(), size_t(32));
        std::vector<glm::vec4> tangents;
        for (const std::uint32_t i : m.indices)
            tangents.push_back(m.vertices[i].tangent);
        const Comparison c = compare(tangents, std::vector<std::uint8_t>(tangents.size(), 1),
                                     runReference(m, dir_.path()));
        qInfo("imported roof: %zu vertices, max angle %.3g rad, %d sign mismatches",
              m.vertices.size(), c.maxAngle, c.signMismatches);
        QVERIFY2(c.maxAngle < 1e-3, qPrintable(QString::number(c.maxAngle)));
        QCOMPARE(c.signMismatches, 0);
        // Both slopes face away from each other: the ridge stayed hard.
        int up = 0, down = 0;
        for (const Vertex& v : m.vertices) {
            up += v.normal.z > 0.6f;
            down += v.normal.z < -0.6f;
        }
        QCOMPARE(up + down, int(m.vertices.size()));
    }
    // A glTF primitive's TANGENT is the file's frame and stays (made orthogonal to the normal:
    // (0.2, 1, 0.5) on a +z quad becomes (0.2, 1, 0) normalised), w included; without the
    // attribute the same quad gets MikkTSpace's dP/du = +x, w = 1 (v runs down the image = -y).
    void gltfTangentIsKept() {
        const glm::vec4 fileTangent(0.2f, 1.0f, 0.5f, -1.0f);
        for (const bool withTangent : {true, false}) {
            const QString file = dir_.path() + (withTangent ? "/tangent.gltf" : "/plain.gltf");
            std::ofstream(file.toStdString()) << quadGltf(withTangent ? &fileTangent : nullptr);
            MeshData m;
            std::string error;
            QVERIFY2(importMeshInProcess(file.toStdString(), m, &error), error.c_str());
            QCOMPARE(m.triangleCount(), size_t(2));
            const glm::vec4 expected = withTangent
                                           ? glm::vec4(glm::normalize(glm::vec3(0.2f, 1, 0)), -1)
                                           : glm::vec4(1, 0, 0, 1);
            for (const Vertex& v : m.vertices) {
                QVERIFY2(
                    glm::length(glm::vec3(v.tangent) - glm::vec3(expected)) < 1e-5f,
                    qPrintable(
                        QString("%1 %2 %3").arg(v.tangent.x).arg(v.tangent.y).arg(v.tangent.z)));
                QCOMPARE(v.tangent.w, expected.w);
            }
        }
    }
};

QTEST_GUILESS_MAIN(TestMikkTSpace)
#include "test_core_mikktspace.moc"
