// core/mesh, mesh_procedural, mesh_tangents, mesh_import: what each case proves is stated on it.
// Geometry invariants of every preview mesh, Lengyel tangents against analytic ones, Assimp round
// trips of files written here, refusals before allocation, and the child-process importer.
#include "core/mesh.h"
#include "core/mesh_import.h"
#include "core/mesh_nesting.h"
#include "core/mesh_tangents.h"
#include "core/scene.h"

#include <QTemporaryDir>
#include <QtTest>
#include <algorithm>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/scene.h>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <unordered_map>

using namespace velvet;
namespace fs = std::filesystem;

namespace {

/// Vertex ids merged by position (within 1e-5), so seams, hard edges and poles count as shared.
std::vector<std::uint32_t> weldPositions(const MeshData& mesh) {
    const float cell = 1e-4f;
    struct Key {
        long long x, y, z;
        bool operator==(const Key&) const = default;
    };
    struct Hash {
        size_t operator()(const Key& k) const {
            return size_t(k.x * 73856093LL ^ k.y * 19349663LL ^ k.z * 83492791LL);
        }
    };
    std::unordered_map<Key, std::vector<std::uint32_t>, Hash> grid;
    std::vector<std::uint32_t> id(mesh.vertices.size());
    for (std::uint32_t v = 0; v < mesh.vertices.size(); ++v) {
        const glm::vec3 p = mesh.vertices[v].position;
        const Key k{std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell)};
        id[v] = v;
        bool found = false;
        for (int dx = -1; dx <= 1 && !found; ++dx)
            for (int dy = -1; dy <= 1 && !found; ++dy)
                for (int dz = -1; dz <= 1 && !found; ++dz) {
                    const auto it = grid.find(Key{k.x + dx, k.y + dy, k.z + dz});
                    if (it == grid.end())
                        continue;
                    for (std::uint32_t other : it->second)
                        if (glm::length(mesh.vertices[other].position - p) < 1e-5f) {
                            id[v] = id[other];
                            found = true;
                            break;
                        }
                }
        grid[k].push_back(v);
    }
    return id;
}

struct EdgeStats {
    int boundary = 0;    ///< undirected edges used once
    int nonManifold = 0; ///< used more than twice
    int misoriented = 0; ///< a directed edge used twice (neighbours wound inconsistently)
};

EdgeStats edgeStats(const MeshData& mesh) {
    const auto id = weldPositions(mesh);
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (size_t i = 0; i < mesh.indices.size(); i += 3) {
        const std::uint32_t t[3] = {id[mesh.indices[i]], id[mesh.indices[i + 1]],
                                    id[mesh.indices[i + 2]]};
        if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            continue; // collapsed by welding: contributes no edge
        for (int k = 0; k < 3; ++k)
            ++directed[{t[k], t[(k + 1) % 3]}];
    }
    EdgeStats s;
    for (const auto& [e, n] : directed) {
        if (n > 1)
            ++s.misoriented;
        const auto back = directed.find({e.second, e.first});
        const int total = n + (back == directed.end() ? 0 : back->second);
        if (total == 1)
            ++s.boundary;
        if (total > 2)
            ++s.nonManifold;
    }
    return s;
}

void writeText(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
}

/// A binary STL of @p triangles (each three corners), with an 80-byte header that does not
/// start with "solid".
void writeBinaryStl(const fs::path& file, const std::vector<glm::vec3>& corners,
                    std::uint32_t claimedCount) {
    std::string data(80, 'V');
    data.append(reinterpret_cast<const char*>(&claimedCount), 4);
    for (size_t i = 0; i + 2 < corners.size(); i += 3) {
        const glm::vec3 n =
            glm::normalize(glm::cross(corners[i + 1] - corners[i], corners[i + 2] - corners[i]));
        data.append(reinterpret_cast<const char*>(&n), 12);
        for (int k = 0; k < 3; ++k)
            data.append(reinterpret_cast<const char*>(&corners[i + k]), 12);
        data.append(2, '\0');
    }
    writeText(file, data);
}

/// A cube from (0, 0, 0) to (10, 4, 2) offset by (5, 5, 5), as OBJ quads (triangulated on
/// import): 6 faces -> 12 triangles; it should come back spanning [-1, 1] in x, centred.
const char* kCubeObj = "o box\n"
                       "v 5 5 5\n"
                       "v 15 5 5\n"
                       "v 15 9 5\n"
                       "v 5 9 5\n"
                       "v 5 5 7\n"
                       "v 15 5 7\n"
                       "v 15 9 7\n"
                       "v 5 9 7\n"
                       "vt 0 0\n"
                       "vt 1 0\n"
                       "vt 1 1\n"
                       "vt 0 1\n"
                       "f 5/1 6/2 7/3 8/4\n"
                       "f 2/1 1/2 4/3 3/4\n"
                       "f 6/1 2/2 3/3 7/4\n"
                       "f 1/1 5/2 8/3 4/4\n"
                       "f 8/1 7/2 3/3 4/4\n"
                       "f 1/1 2/2 6/3 5/4\n";

void checkUnitBox(const MeshData& mesh, glm::vec3 expectedHalf) {
    const MeshBounds b = meshBounds(mesh);
    for (int k = 0; k < 3; ++k) {
        QVERIFY2(std::abs(b.center()[k]) < 1e-4f,
                 qPrintable(QString("centre %1").arg(b.center()[k])));
        QVERIFY2(std::abs(0.5f * b.size()[k] - expectedHalf[k]) < 1e-4f,
                 qPrintable(QString("half size %1 on axis %2").arg(0.5f * b.size()[k]).arg(k)));
    }
}

} // namespace

class TestCoreMesh : public QObject {
    Q_OBJECT
    QTemporaryDir m_dir;
    fs::path path(const char* name) const { return fs::path(m_dir.path().toStdString()) / name; }

private slots:
    // Every preview mesh: indices in range; inside [-1, 1]^3 and centred; unit normals; unit
    // tangents orthogonal to them with w = +1 (no mirrored UVs anywhere, so one handedness);
    // counter-clockwise front faces (each face's winding normal agrees with its vertex normals);
    // closed meshes watertight and consistently wound once seams, poles and hard edges are welded;
    // open ones (plane, cloth) manifold and double-sided.
    void proceduralMeshInvariants_data() {
        QTest::addColumn<int>("kind");
        QTest::addColumn<bool>("closed");
        QTest::newRow("sphere") << int(PreviewMeshKind::Sphere) << true;
        QTest::newRow("cube") << int(PreviewMeshKind::Cube) << true;
        QTest::newRow("rounded cube") << int(PreviewMeshKind::RoundedCube) << true;
        QTest::newRow("plane") << int(PreviewMeshKind::Plane) << false;
        QTest::newRow("cloth drape") << int(PreviewMeshKind::ClothDrape) << false;
        QTest::newRow("shader ball") << int(PreviewMeshKind::ShaderBall) << true;
    }
    void proceduralMeshInvariants() {
        QFETCH(int, kind);
        QFETCH(bool, closed);
        const MeshData mesh = makePreviewMesh(PreviewMeshKind(kind));
        QVERIFY(mesh.triangleCount() > 0);
        QCOMPARE(mesh.indices.size() % 3, size_t(0));
        for (std::uint32_t i : mesh.indices)
            QVERIFY(i < mesh.vertices.size());
        const MeshBounds b = meshBounds(mesh);
        for (int k = 0; k < 3; ++k) {
            QVERIFY(b.min[k] >= -1.0f - 1e-5f && b.max[k] <= 1.0f + 1e-5f);
            QVERIFY2(std::abs(b.center()[k]) < 1e-3f,
                     qPrintable(QString("centre %1").arg(b.center()[k])));
        }
        for (const Vertex& v : mesh.vertices) {
            QVERIFY(std::abs(glm::length(v.normal) - 1.0f) < 1e-3f);
            const glm::vec3 t(v.tangent);
            QVERIFY(std::abs(glm::length(t) - 1.0f) < 1e-3f);
            QVERIFY2(std::abs(glm::dot(t, v.normal)) < 1e-3f,
                     qPrintable(QString("n.t = %1").arg(glm::dot(t, v.normal))));
            QCOMPARE(v.tangent.w, 1.0f);
            QVERIFY(v.uv.x >= 0.0f && v.uv.x <= 1.0f && v.uv.y >= 0.0f && v.uv.y <= 1.0f);
        }
        int disagree = 0;
        for (size_t i = 0; i < mesh.indices.size(); i += 3) {
            const Vertex& a = mesh.vertices[mesh.indices[i]];
            const Vertex& b2 = mesh.vertices[mesh.indices[i + 1]];
            const Vertex& c = mesh.vertices[mesh.indices[i + 2]];
            const glm::vec3 face = glm::cross(b2.position - a.position, c.position - a.position);
            if (glm::length(face) < 1e-9f)
                continue;
            if (glm::dot(face, a.normal + b2.normal + c.normal) <= 0.0f)
                ++disagree;
        }
        QCOMPARE(disagree, 0);
        const EdgeStats edges = edgeStats(mesh);
        QCOMPARE(edges.nonManifold, 0);
        QCOMPARE(edges.misoriented, 0);
        if (closed)
            QCOMPARE(edges.boundary, 0);
        else
            QVERIFY(edges.boundary > 0 && mesh.doubleSided);
        QVERIFY(makePreviewMesh(PreviewMeshKind::Custom).vertices.empty());
    }

    // Lengyel's tangents on a quad equal the analytic dP/du, and w flips when the UVs are
    // mirrored (u reversed): the glTF bitangent cross(n, t) * w must point up the image.
    void quadTangentMatchesAnalytic() {
        const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        const glm::vec3 dPdu = glm::normalize(glm::cross(glm::vec3(0, 1, 0), n)) * 2.0f;
        const glm::vec3 up = glm::cross(n, glm::normalize(dPdu)); // up the image
        for (const bool mirrored : {false, true}) {
            MeshData quad;
            const glm::vec2 uvs[4] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}}; // a, b, c, d as the grids
            for (const glm::vec2 uv : uvs) {
                Vertex v{};
                v.position = (uv.x - 0.5f) * dPdu - (uv.y - 0.5f) * 1.5f * up;
                v.normal = n;
                v.uv = mirrored ? glm::vec2(1.0f - uv.x, uv.y) : uv;
                quad.vertices.push_back(v);
            }
            quad.indices = {0, 1, 2, 0, 2, 3};
            generateTangents(quad);
            for (const Vertex& v : quad.vertices) {
                const glm::vec3 expected = glm::normalize(mirrored ? -dPdu : dPdu);
                QVERIFY(glm::length(glm::vec3(v.tangent) - expected) < 1e-5f);
                QCOMPARE(v.tangent.w, mirrored ? -1.0f : 1.0f);
                QVERIFY(glm::dot(glm::cross(v.normal, glm::vec3(v.tangent)) * v.tangent.w, up) >
                        0.99f);
            }
        }
    }

    // The generator agrees with the sphere's analytic tangents (same convention as makeSphere).
    void generatedTangentsMatchSphere() {
        MeshData sphere = makeSphere(1.0f, 32, 16);
        const MeshData analytic = sphere;
        generateTangents(sphere);
        for (size_t v = 0; v < sphere.vertices.size(); ++v) {
            const float y = analytic.vertices[v].position.y;
            if (std::abs(y) > 0.95f)
                continue; // poles: the analytic frame is a convention there
            QVERIFY(glm::dot(glm::vec3(sphere.vertices[v].tangent),
                             glm::vec3(analytic.vertices[v].tangent)) > 0.99f);
            QCOMPARE(sphere.vertices[v].tangent.w, analytic.vertices[v].tangent.w);
        }
    }

    // Assimp round trips of files written here: triangle count and the unit-box fit.
    void objRoundTrip() {
        writeText(path("box.obj"), kCubeObj);
        MeshData mesh;
        std::string error;
        QVERIFY2(importMeshInProcess(path("box.obj"), mesh, &error), error.c_str());
        QCOMPARE(mesh.triangleCount(), size_t(12));
        checkUnitBox(mesh, {1.0f, 0.4f, 0.2f});
        for (const Vertex& v : mesh.vertices) {
            QVERIFY(std::abs(glm::length(v.normal) - 1.0f) < 1e-3f);
            QVERIFY(std::abs(glm::dot(glm::vec3(v.tangent), v.normal)) < 1e-3f);
        }
    }
    // Issue 17 item 14: the OBJ cube above has no normals. Generated ones keep its 90-degree
    // edges hard (a crease angle): every vertex normal is its face's axis, not the average of
    // three faces (0.577 on each axis, a pillow).
    void objWithoutNormalsKeepsHardEdges() {
        writeText(path("hard.obj"), kCubeObj);
        MeshData mesh;
        std::string error;
        QVERIFY2(importMeshInProcess(path("hard.obj"), mesh, &error), error.c_str());
        QCOMPARE(mesh.triangleCount(), size_t(12));
        for (size_t t = 0; t < mesh.indices.size(); t += 3) {
            const glm::vec3 a = mesh.vertices[mesh.indices[t]].position;
            const glm::vec3 b = mesh.vertices[mesh.indices[t + 1]].position;
            const glm::vec3 c = mesh.vertices[mesh.indices[t + 2]].position;
            const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
            for (int k = 0; k < 3; ++k) {
                const glm::vec3 n = mesh.vertices[mesh.indices[t + size_t(k)]].normal;
                QVERIFY2(glm::dot(n, face) > 0.999f,
                         qPrintable(QString("triangle %1: normal (%2, %3, %4), face (%5, %6, %7)")
                                        .arg(t / 3)
                                        .arg(n.x)
                                        .arg(n.y)
                                        .arg(n.z)
                                        .arg(face.x)
                                        .arg(face.y)
                                        .arg(face.z)));
            }
        }
    }
    void plyRoundTrip() {
        writeText(path("quad.ply"), "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n4 0 0\n4 2 0\n0 2 0\n4 0 1 2 3\n");
        MeshData mesh;
        std::string error;
        QVERIFY2(importMeshInProcess(path("quad.ply"), mesh, &error), error.c_str());
        QCOMPARE(mesh.triangleCount(), size_t(2)); // the quad, triangulated
        checkUnitBox(mesh, {1.0f, 0.5f, 0.0f});
    }
    void stlRoundTrip() {
        const std::vector<glm::vec3> tris = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0},
                                             {0, 0, 0}, {0, 2, 0}, {0, 0, 2}};
        writeBinaryStl(path("two.stl"), tris, 2);
        MeshData mesh;
        std::string error;
        QVERIFY2(importMeshInProcess(path("two.stl"), mesh, &error), error.c_str());
        QCOMPARE(mesh.triangleCount(), size_t(2));
        checkUnitBox(mesh, {1.0f, 1.0f, 1.0f});
    }
    void gltfRoundTrip() {
        // One triangle, positions in a base64 data URI (glTF 2.0, section 3.9 buffers).
        const float positions[9] = {0, 0, 0, 3, 0, 0, 0, 1, 0};
        const QByteArray b64 =
            QByteArray(reinterpret_cast<const char*>(positions), sizeof positions).toBase64();
        // (Plain strings: moc's tokenizer does not take raw string literals with quotes.)
        const std::string json =
            "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
            "\"nodes\":[{\"mesh\":0}],"
            "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0}}]}],"
            "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,"
            "\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[3,1,0]}],"
            "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36}],"
            "\"buffers\":[{\"byteLength\":36,"
            "\"uri\":\"data:application/octet-stream;base64," +
            b64.toStdString() + "\"}]}";
        writeText(path("tri.gltf"), json);
        MeshData mesh;
        std::string error;
        QVERIFY2(importMeshInProcess(path("tri.gltf"), mesh, &error), error.c_str());
        QCOMPARE(mesh.triangleCount(), size_t(1));
        checkUnitBox(mesh, {1.0f, 1.0f / 3.0f, 0.0f});
    }

    // FBX (ASCII), Collada and GLB: the OBJ box converted by Assimp's own exporters, then
    // imported through the application's path (the `velvet import-mesh` child process): 12
    // triangles, the unit-box fit of the 10 x 4 x 2 box (some exporters turn the up axis, so the
    // half sizes are compared sorted) and unit tangents orthogonal to unit normals. (Assimp
    // 5.2.5's binary FBX exporter, "fbx", writes files its own importer refuses with "block
    // offset is out of range", so binary FBX cannot be made this way; FBX import is the same
    // importer, whose tokenizer alone differs.)
    void exportedFormatsImportThroughChild_data() {
        QTest::addColumn<QString>("formatId");
        QTest::addColumn<QString>("extension");
        QTest::newRow("fbx") << QString("fbxa") << QString("fbx");
        QTest::newRow("dae") << QString("collada") << QString("dae");
        QTest::newRow("glb") << QString("glb2") << QString("glb");
    }
    void exportedFormatsImportThroughChild() {
        QFETCH(QString, formatId);
        QFETCH(QString, extension);
        const fs::path velvet = VELVET_BINARY;
        if (!fs::exists(velvet))
            QFAIL("the velvet executable is not built (build the velvet target first)");
        writeText(path("box.obj"), kCubeObj);
        Assimp::Importer importer;
        const aiScene* box = importer.ReadFile(path("box.obj").string(), 0);
        QVERIFY2(box, importer.GetErrorString());
        const fs::path file = path(("box." + extension).toStdString().c_str());
        Assimp::Exporter exporter;
        QVERIFY2(exporter.Export(box, formatId.toStdString(), file.string()) == AI_SUCCESS,
                 exporter.GetErrorString());
        QVERIFY(fs::file_size(file) > 0);
        MeshImportOptions options;
        options.helper = velvet;
        MeshData mesh;
        std::string error;
        bool isolated = false;
        QVERIFY2(importMesh(file, mesh, &error, options, &isolated), error.c_str());
        QVERIFY(isolated);
        QCOMPARE(mesh.triangleCount(), size_t(12));
        const MeshBounds b = meshBounds(mesh);
        glm::vec3 half = 0.5f * b.size();
        std::sort(&half.x, &half.x + 3);
        for (int k = 0; k < 3; ++k)
            QVERIFY2(std::abs(b.center()[k]) < 1e-4f,
                     qPrintable(QString("centre %1 on axis %2").arg(b.center()[k]).arg(k)));
        QVERIFY2(std::abs(half.x - 0.2f) < 1e-4f && std::abs(half.y - 0.4f) < 1e-4f &&
                     std::abs(half.z - 1.0f) < 1e-4f,
                 qPrintable(QString("half sizes %1 %2 %3").arg(half.x).arg(half.y).arg(half.z)));
        for (const Vertex& v : mesh.vertices) {
            QVERIFY(std::abs(glm::length(v.normal) - 1.0f) < 1e-3f);
            QVERIFY(std::abs(glm::length(glm::vec3(v.tangent)) - 1.0f) < 1e-3f);
            QVERIFY(std::abs(glm::dot(glm::vec3(v.tangent), v.normal)) < 1e-3f);
            QVERIFY(std::abs(std::abs(v.tangent.w) - 1.0f) < 1e-6f);
        }
        qInfo("%s: %zu bytes, %zu vertices, 12 triangles", file.filename().string().c_str(),
              size_t(fs::file_size(file)), mesh.vertices.size());
    }

    // A binary STL whose header claims 4,000,000 triangles in a 134-byte file (and a PLY
    // claiming 3,000,000 faces) is refused from the header, before anything is allocated, with
    // a message naming the file and the count.
    void hugeTriangleCountRefused() {
        writeBinaryStl(path("huge.stl"), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 4'000'000);
        MeshData mesh;
        std::string error;
        QVERIFY(!checkMeshFile(path("huge.stl"), &error));
        QVERIFY2(error.find("huge.stl") != std::string::npos, error.c_str());
        QVERIFY2(error.find("4000000") != std::string::npos, error.c_str());
        QVERIFY2(error.find("2000000") != std::string::npos, error.c_str());
        error.clear();
        QVERIFY(!importMesh(path("huge.stl"), mesh, &error));
        QVERIFY2(error.find("4000000 triangles") != std::string::npos, error.c_str());
        QVERIFY(mesh.vertices.empty());

        writeText(path("huge.ply"), "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                                    "property float x\nproperty float y\nproperty float z\n"
                                    "element face 3000000\nproperty list uchar int vertex_indices\n"
                                    "end_header\n");
        QVERIFY(!importMeshInProcess(path("huge.ply"), mesh, &error));
        QVERIFY2(error.find("huge.ply") != std::string::npos &&
                     error.find("3000000") != std::string::npos,
                 error.c_str());
        // A small limit applies after triangulation too (OBJ has no count in a header).
        writeText(path("box.obj"), kCubeObj);
        MeshImportLimits small;
        small.maxTriangles = 10;
        QVERIFY(!importMeshInProcess(path("box.obj"), mesh, &error, small));
        QVERIFY2(error.find("12 triangles") != std::string::npos, error.c_str());
        // And the file size limit.
        small.maxFileBytes = 16;
        QVERIFY(!checkMeshFile(path("box.obj"), &error, small));
        QVERIFY2(error.find("box.obj") != std::string::npos, error.c_str());
    }

    // The cache format round-trips and refuses a truncated or foreign file.
    void meshCacheRoundTrip() {
        MeshData mesh = makeShaderBall(16);
        mesh.doubleSided = true;
        std::string error;
        QVERIFY2(writeMeshCache(path("ball.vmesh"), mesh, &error), error.c_str());
        MeshData back;
        QVERIFY2(readMeshCache(path("ball.vmesh"), back, &error), error.c_str());
        QCOMPARE(back.indices, mesh.indices);
        QCOMPARE(back.vertices.size(), mesh.vertices.size());
        QVERIFY(std::memcmp(back.vertices.data(), mesh.vertices.data(),
                            mesh.vertices.size() * sizeof(Vertex)) == 0);
        QVERIFY(back.doubleSided);
        std::ifstream in(path("ball.vmesh"), std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), {});
        writeText(path("cut.vmesh"), bytes.substr(0, bytes.size() - 7));
        QVERIFY(!readMeshCache(path("cut.vmesh"), back, &error));
        writeText(path("foreign.vmesh"), std::string(64, 'x'));
        QVERIFY(!readMeshCache(path("foreign.vmesh"), back, &error));
        QVERIFY2(error.find("not a Velvet mesh cache") != std::string::npos, error.c_str());
    }

    // The nesting scans that refuse stack-overflowing files before Assimp sees them count
    // levels exactly and are not fooled by brackets in strings or tags that do not nest.
    void nestingDepthIsCountedWithoutRecursion() {
        // (Unbalanced brackets are built, not written: moc reads this file too.)
        const std::string open4 = std::string(4, '[') + std::string(4, '{');
        QCOMPARE(jsonNestingDepth("{\"a\": [1, {\"b\": []}], \"s\": \"" + open4 + "\"}"),
                 size_t(4));
        QCOMPARE(jsonNestingDepth("{\"esc\": \"\\\"" + open4 + "\"}"), size_t(1));
        QCOMPARE(jsonNestingDepth(std::string(1'000'000, '[')), kMaxMeshFileNesting + 1);
        QCOMPARE(xmlNestingDepth("<?xml version=\"1.0\"?><!-- <a><b> --><a x=\"1>2\"><b/>"
                                 "<c><![CDATA[<d><e>]]></c></a>"),
                 size_t(2));
        QCOMPARE(xmlNestingDepth("<!DOCTYPE x><a></a><b><c></c></b>"), size_t(2));
    }

    // Found by the fuzzer (tests/fuzz/corpus/fuzz_mesh_cache): a header with zero counts, and
    // a vertex that is not finite, are refused with a reason instead of read.
    void meshCacheRefusesEmptyAndNonFinite() {
        std::string error;
        MeshData empty;
        QVERIFY2(writeMeshCache(path("empty.vmesh"), empty, &error), error.c_str());
        MeshData back;
        QVERIFY(!readMeshCache(path("empty.vmesh"), back, &error));
        QVERIFY2(error.find("holds no triangles") != std::string::npos, error.c_str());
        MeshData poisoned = makeCube();
        poisoned.vertices[3].position.y = std::numeric_limits<float>::quiet_NaN();
        QVERIFY2(writeMeshCache(path("nan.vmesh"), poisoned, &error), error.c_str());
        QVERIFY(!readMeshCache(path("nan.vmesh"), back, &error));
        QVERIFY2(error.find("non-finite vertex position") != std::string::npos, error.c_str());
        QVERIFY(back.vertices.empty()); // nothing half-read
    }

    // importMesh remembers its last successes (the editor checks a mesh, then draws it): the
    // same unchanged file is imported once; rewritten on disk, it is imported again; a failure
    // is never remembered.
    void importMemoImportsAnUnchangedFileOnce() {
        const fs::path file = path("memo.obj");
        writeText(file, kCubeObj);
        MeshData first, second;
        std::string error;
        const std::uint64_t before = meshImportCount();
        QVERIFY2(importMesh(file, first, &error), error.c_str());
        QVERIFY2(importMesh(file, second, &error), error.c_str());
        QCOMPARE(meshImportCount(), before + 1);
        QCOMPARE(second.indices, first.indices);
        QCOMPARE(second.vertices.size(), first.vertices.size());
        // A different triangle (a new size, a new time stamp): imported again, the new content.
        writeText(file, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        fs::last_write_time(file, fs::last_write_time(file) + std::chrono::seconds(2));
        MeshData changed;
        QVERIFY2(importMesh(file, changed, &error), error.c_str());
        QCOMPARE(meshImportCount(), before + 2);
        QCOMPARE(changed.triangleCount(), size_t(1));
        // A failure is imported (and refused) each time.
        writeText(path("memo_broken.obj"), "o empty\n"); // no triangles
        MeshData broken;
        QVERIFY(!importMesh(path("memo_broken.obj"), broken, &error));
        QVERIFY(!importMesh(path("memo_broken.obj"), broken, &error));
        QCOMPARE(meshImportCount(), before + 4);
    }

    // The child-process importer (`velvet import-mesh`): gives the same mesh as in process;
    // survives a garbage file, a crash and a hang with one clear line naming the file.
    void childProcessImport() {
        const fs::path velvet = VELVET_BINARY;
        if (!fs::exists(velvet))
            QFAIL("the velvet executable is not built (build the velvet target first)");
        MeshImportOptions options;
        options.helper = velvet;
        writeText(path("box.obj"), kCubeObj);
        MeshData viaChild, inProcess;
        std::string error;
        bool isolated = false;
        QVERIFY2(importMesh(path("box.obj"), viaChild, &error, options, &isolated), error.c_str());
        QVERIFY(isolated);
        QVERIFY(importMeshInProcess(path("box.obj"), inProcess, &error));
        QCOMPARE(viaChild.indices, inProcess.indices);
        QCOMPARE(viaChild.vertices.size(), inProcess.vertices.size());

        std::string garbage(4096, '\0');
        for (size_t i = 0; i < garbage.size(); ++i)
            garbage[i] = char((i * 2654435761u) >> 13);
        writeText(path("garbage.fbx"), garbage);
        MeshData mesh;
        QVERIFY(!importMesh(path("garbage.fbx"), mesh, &error, options));
        qInfo("garbage: %s", error.c_str());
        QVERIFY2(error.find("garbage.fbx") != std::string::npos, error.c_str());
        QVERIFY(error.find('\n') == std::string::npos);

        qputenv("VELVET_IMPORT_MESH_SIMULATE_CRASH", "1");
        // importMeshUncached: box.obj imported above is in importMesh's memo.
        const bool crashed = importMeshUncached(path("box.obj"), mesh, &error, options);
        qunsetenv("VELVET_IMPORT_MESH_SIMULATE_CRASH");
        QVERIFY(!crashed);
        qInfo("crash: %s", error.c_str());
        QVERIFY2(error.find("box.obj") != std::string::npos &&
                     error.find("crashed") != std::string::npos,
                 error.c_str());

        qputenv("VELVET_IMPORT_MESH_SIMULATE_HANG", "1");
        options.timeoutMs = 400;
        const bool hung = importMeshUncached(path("box.obj"), mesh, &error, options);
        qunsetenv("VELVET_IMPORT_MESH_SIMULATE_HANG");
        QVERIFY(!hung);
        QVERIFY2(error.find("timed out after 0.4 s") != std::string::npos, error.c_str());
    }
};

QTEST_GUILESS_MAIN(TestCoreMesh)
#include "test_core_mesh.moc"
