#include "core/mesh_import.h"

#include "core/atomic_file.h"
#include "core/mesh_nesting.h"
#include "core/mesh_tangents.h"
#include "core/mikktspace.h"

#include <algorithm>
#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/mesh.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <glm/geometric.hpp>
#include <mutex>
#include <poll.h>
#include <set>
#include <spawn.h>
#include <sstream>
#include <string_view>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

extern char** environ;

namespace velvet {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool fail(std::string* error, const std::string& message) {
    if (error)
        *error = message;
    return false;
}

std::string tooMany(const std::filesystem::path& file, std::uint64_t count,
                    const MeshImportLimits& limits) {
    return file.string() + ": " + std::to_string(count) + " triangles, more than the limit of " +
           std::to_string(limits.maxTriangles) + "; refused";
}

/// Binary STL (no standard; the de-facto layout): 80-byte header, uint32 triangle count, then
/// 50 bytes per triangle. An ASCII STL starts with "solid" — and so do some binary ones, which
/// the exact size 84 + 50 n tells apart.
bool checkStl(const std::filesystem::path& file, std::uintmax_t size, std::string* error,
              const MeshImportLimits& limits) {
    if (size < 84)
        return true; // too short to be binary; the ASCII parser decides
    std::ifstream in(file, std::ios::binary);
    char header[84] = {};
    if (!in.read(header, 84))
        return fail(error, file.string() + ": cannot read the STL header");
    const std::uint32_t count = std::uint32_t(std::uint8_t(header[80])) |
                                std::uint32_t(std::uint8_t(header[81])) << 8 |
                                std::uint32_t(std::uint8_t(header[82])) << 16 |
                                std::uint32_t(std::uint8_t(header[83])) << 24;
    const bool sizeMatches = std::uintmax_t(84) + std::uintmax_t(50) * count == size;
    std::string start(header, 80);
    start.erase(0, start.find_first_not_of(" \t\r\n"));
    const bool ascii = lower(start.substr(0, 5)) == "solid" && !sizeMatches;
    if (ascii)
        return true;
    if (count > limits.maxTriangles)
        return fail(error, file.string() + ": binary STL header claims " + std::to_string(count) +
                               " triangles, more than the limit of " +
                               std::to_string(limits.maxTriangles) + "; refused");
    if (!sizeMatches)
        return fail(error, file.string() + ": binary STL header claims " + std::to_string(count) +
                               " triangles (" + std::to_string(84 + 50 * std::uint64_t(count)) +
                               " bytes) but the file has " + std::to_string(size) +
                               " bytes; truncated or not an STL file");
    return true;
}

/// PLY (Turk 1994): a text header up to "end_header" that declares "element face N".
bool checkPly(const std::filesystem::path& file, std::string* error,
              const MeshImportLimits& limits) {
    std::ifstream in(file, std::ios::binary);
    std::string line;
    size_t read = 0;
    while (read < 65536 && std::getline(in, line)) {
        read += line.size() + 1;
        std::istringstream words(line);
        std::string a, b, c;
        words >> a >> b >> c;
        if (a == "end_header")
            break;
        if (a == "element" && b == "face") {
            errno = 0;
            const unsigned long long n = std::strtoull(c.c_str(), nullptr, 10);
            if (errno == ERANGE || n > limits.maxTriangles)
                return fail(error, file.string() + ": PLY header claims " + c +
                                       " faces, more than the limit of " +
                                       std::to_string(limits.maxTriangles) + " triangles; refused");
        }
    }
    return true;
}

bool finite(const aiVector3D& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::mutex g_helperMutex;
std::filesystem::path g_helper;

/// Last non-empty line of a child's stderr, without the "velvet import-mesh: " prefix.
std::string lastLine(const std::string& text) {
    std::istringstream in(text);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos)
            last = line;
    const std::string prefix = "velvet import-mesh: ";
    if (last.rfind(prefix, 0) == 0)
        last.erase(0, prefix.size());
    return last;
}

/// The formats Velvet lists (issue 18: only these reach Assimp), by lower-case extension.
const char* const kSupportedList = "OBJ, FBX, glTF/GLB, PLY, STL, DAE";
bool supportedExtension(const std::string& ext) {
    for (const char* e : {".obj", ".fbx", ".gltf", ".glb", ".ply", ".stl", ".dae"})
        if (ext == e)
            return true;
    return false;
}

/// Whether the file's first bytes are what its extension promises (each format's signature:
/// glTF 2.0 §4.4.3 "glTF" for GLB, "ply" for PLY, Kaydara's binary FBX header or text, an XML
/// '<' for COLLADA, a JSON '{' for glTF; OBJ and ASCII formats are text: no NUL in the first
/// block). Binary STL has no signature (80 free bytes), so any STL passes to checkStl.
bool magicMatches(const std::filesystem::path& file, const std::string& ext) {
    std::ifstream in(file, std::ios::binary);
    char head[512] = {};
    in.read(head, sizeof head);
    const std::string_view h(head, size_t(in.gcount()));
    const bool text = h.find('\0') == std::string_view::npos;
    const size_t first = h.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
    const char lead = first == std::string_view::npos ? '\0' : h[first];
    if (ext == ".glb")
        return h.substr(0, 4) == "glTF";
    if (ext == ".ply")
        return h.substr(0, 3) == "ply";
    if (ext == ".fbx")
        return h.substr(0, 18) == "Kaydara FBX Binary" || text;
    if (ext == ".dae")
        return text && lead == '<';
    if (ext == ".gltf")
        return text && lead == '{';
    if (ext == ".obj")
        return text;
    return true; // .stl
}

// Assimp picks an importer by extension and, when none claims the file, tries every importer's
// signature check: a file named .obj holding an MD5 mesh could reach the MD5 reader. Keeping only
// the importers registered for the file's (listed) extension tells Assimp which to use.
// Unregistered importers are no longer the Importer's to delete, so they are deleted here.
void keepOnlyImportersFor(Assimp::Importer& importer, const std::string& ext) {
    std::vector<Assimp::BaseImporter*> others;
    for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
        Assimp::BaseImporter* candidate = importer.GetImporter(i);
        std::set<std::string> extensions;
        candidate->GetExtensionList(extensions);
        if (!extensions.contains(ext.substr(1)))
            others.push_back(candidate);
    }
    for (Assimp::BaseImporter* other : others)
        if (importer.UnregisterLoader(other) == aiReturn_SUCCESS)
            delete other;
}

} // namespace

bool checkMeshFile(const std::filesystem::path& file, std::string* error,
                   const MeshImportLimits& limits) {
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (ec || !std::filesystem::exists(status))
        return fail(error, file.string() + ": no such mesh file");
    if (!std::filesystem::is_regular_file(status))
        return fail(error, file.string() + ": not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec)
        return fail(error, file.string() + ": cannot read its size: " + ec.message());
    if (size == 0)
        return fail(error, file.string() + ": empty file");
    if (size > limits.maxFileBytes)
        return fail(error, file.string() + ": " + std::to_string(size) +
                               " bytes, more than the mesh file limit of " +
                               std::to_string(limits.maxFileBytes) + " bytes; refused");
    const std::string ext = lower(file.extension().string());
    if (!supportedExtension(ext))
        return fail(error, file.string() + ": \"" + ext + "\" is not a mesh format Velvet reads (" +
                               kSupportedList + "); refused");
    if (!magicMatches(file, ext))
        return fail(error, file.string() + ": its contents are not " + ext.substr(1) +
                               " (the file's first bytes do not match the format); refused");
    if (!checkMeshNesting(file, ext, error))
        return false;
    if (ext == ".stl")
        return checkStl(file, size, error, limits);
    if (ext == ".ply")
        return checkPly(file, error, limits);
    return true;
}

namespace {

/// One of the file's meshes in the merged mesh (a glTF primitive).
struct MeshPart {
    size_t firstVertex, vertexCount, firstIndex, indexCount;
    bool fileTangents; ///< the vertices' tangents are the file's
};

/// Makes a part's file tangents unit and orthogonal to their normals (Gram-Schmidt; glTF asks
/// for unit tangents but does not require exact orthogonality). False when one is not finite
/// or along its normal: the part then gets MikkTSpace instead.
bool orthonormalizeTangents(MeshData& mesh, const MeshPart& part) {
    for (size_t v = part.firstVertex; v < part.firstVertex + part.vertexCount; ++v) {
        Vertex& vert = mesh.vertices[v];
        const glm::vec3 t = glm::vec3(vert.tangent);
        const glm::vec3 ortho = t - vert.normal * glm::dot(vert.normal, t);
        const float len = glm::length(ortho);
        if (!(len > 1e-6f * glm::length(t)) || !std::isfinite(len))
            return false;
        vert.tangent = glm::vec4(ortho / len, vert.tangent.w);
    }
    return true;
}

} // namespace

/// Faces meeting at a larger angle get separate normals where a file has none.
constexpr float kCreaseAngleDeg = 60.0f;

bool importMeshInProcess(const std::filesystem::path& file, MeshData& out, std::string* error,
                         const MeshImportLimits& limits) {
    if (!checkMeshFile(file, error, limits))
        return false;
    Assimp::Importer importer;
    keepOnlyImportersFor(importer, lower(file.extension().string()));
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // Normals made for a file without them keep hard edges hard: faces meeting at more than
    // kCreaseAngleDeg are not averaged (a cube keeps its edges instead of shading like a
    // pillow), gentler ones are (the 30-degree steps of a 12-sided cylinder still shade round).
    // Assimp's own default, 175 degrees, smooths nearly everything.
    importer.SetPropertyFloat(AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, kCreaseAngleDeg);
    // Pre-transforming bakes the node hierarchy into the vertices, so merging is a concatenation.
    // FlipUVs turns Assimp's OpenGL-style UVs (v = 0 at the bottom) into glTF's (v = 0 at the top).
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                           aiProcess_GenSmoothNormals | aiProcess_SortByPType |
                           aiProcess_PreTransformVertices | aiProcess_FlipUVs |
                           aiProcess_ValidateDataStructure;
    const aiScene* scene = importer.ReadFile(file.string(), flags);
    if (!scene || !scene->mRootNode)
        return fail(error, file.string() + ": cannot import: " + importer.GetErrorString());
    std::uint64_t triangles = 0, vertices = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        triangles += mesh->mNumFaces;
        vertices += mesh->mNumVertices;
    }
    if (triangles > limits.maxTriangles)
        return fail(error, tooMany(file, triangles, limits));
    if (triangles == 0)
        return fail(error, file.string() + ": contains no triangles");

    MeshData result;
    result.vertices.reserve(size_t(vertices));
    result.indices.reserve(size_t(triangles) * 3);
    bool missingNormals = false;
    // glTF gives each primitive (one Assimp mesh) its own TANGENT, or none: then MikkTSpace
    // (glTF 2.0 §3.7.2.1). Other formats' tangents are not read: their importers disagree on
    // the bitangent's convention, so those meshes always get MikkTSpace, as bakers expect.
    const std::string ext = lower(file.extension().string());
    const bool gltf = ext == ".gltf" || ext == ".glb";
    std::vector<MeshPart> parts;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE))
            continue;
        const auto base = std::uint32_t(result.vertices.size());
        missingNormals |= mesh->mNormals == nullptr;
        const bool fileTangents = gltf && mesh->mNormals && mesh->mTangents && mesh->mBitangents;
        parts.push_back({base, mesh->mNumVertices, result.indices.size(), 0, fileTangents});
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            if (!finite(p))
                return fail(error, file.string() + ": vertex " + std::to_string(v) + " of mesh " +
                                       std::to_string(m) + " is not finite");
            Vertex vert{};
            vert.position = glm::vec3(p.x, p.y, p.z);
            if (mesh->mNormals && finite(mesh->mNormals[v]))
                vert.normal =
                    glm::vec3(mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z);
            if (mesh->mTextureCoords[0])
                vert.uv = glm::vec2(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y);
            if (fileTangents) {
                // Assimp's glTF importer gives bitangent = cross(n, t) * w; w comes back as its
                // sign along cross(n, t), after the node transforms.
                const aiVector3D& t = mesh->mTangents[v];
                const aiVector3D& b = mesh->mBitangents[v];
                const aiVector3D c = mesh->mNormals[v] ^ t;
                vert.tangent = glm::vec4(t.x, t.y, t.z, c * b < 0.0f ? -1.0f : 1.0f);
            }
            result.vertices.push_back(vert);
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3)
                continue;
            for (int k = 0; k < 3; ++k)
                result.indices.push_back(base + face.mIndices[k]);
        }
        parts.back().indexCount = result.indices.size() - parts.back().firstIndex;
    }
    if (missingNormals)
        generateNormals(result); // GenSmoothNormals covers this; kept for degenerate inputs
    for (Vertex& v : result.vertices) {
        const float len = glm::length(v.normal);
        v.normal = len > 0.0f ? v.normal / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    // Fitted first, so the tangents are MikkTSpace's of the positions Velvet draws (the same
    // frames: a uniform scale and a shift change no direction, but could round differently).
    fitToUnitBox(result, 1.0f);
    for (const MeshPart& part : parts)
        if (!part.fileTangents || !orthonormalizeTangents(result, part))
            generateMikkTSpaceTangents(result, part.firstVertex, part.vertexCount, part.firstIndex,
                                       part.indexCount);
    out = std::move(result);
    return true;
}

// ---- mesh cache -------------------------------------------------------------------------------

namespace {
constexpr char kMagic[8] = {'V', 'L', 'V', 'M', 'E', 'S', 'H', '\0'};
constexpr size_t kHeaderBytes = 40;
static_assert(sizeof(Vertex) == 48, "the mesh cache stores Vertex as 12 packed floats");

template <typename T>
void put(std::string& s, T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T)); // little-endian hosts only (x86-64, AArch64)
    s.append(b, sizeof(T));
}
template <typename T>
T get(const std::string& s, size_t offset) {
    T v;
    std::memcpy(&v, s.data() + offset, sizeof(T));
    return v;
}
} // namespace

bool writeMeshCache(const std::filesystem::path& file, const MeshData& mesh, std::string* error) {
    std::string data;
    data.reserve(kHeaderBytes + mesh.vertices.size() * sizeof(Vertex) + mesh.indices.size() * 4);
    data.append(kMagic, 8);
    put<std::uint32_t>(data, kMeshCacheVersion);
    put<std::uint32_t>(data, sizeof(Vertex));
    put<std::uint64_t>(data, mesh.vertices.size());
    put<std::uint64_t>(data, mesh.indices.size());
    put<std::uint32_t>(data, mesh.doubleSided ? 1u : 0u);
    put<std::uint32_t>(data, 0u);
    data.append(reinterpret_cast<const char*>(mesh.vertices.data()),
                mesh.vertices.size() * sizeof(Vertex));
    data.append(reinterpret_cast<const char*>(mesh.indices.data()), mesh.indices.size() * 4);
    return writeFileAtomically(file, data, error);
}

bool readMeshCache(const std::filesystem::path& file, MeshData& out, std::string* error,
                   const MeshImportLimits& limits) {
    const std::uint64_t maxIndices = limits.maxTriangles * 3;
    // A mesh never needs more vertices than corners.
    const std::uintmax_t maxBytes = kHeaderBytes + maxIndices * (sizeof(Vertex) + 4);
    std::string reason;
    const auto data = readFileWithLimit(file, maxBytes, &reason);
    if (!data)
        return fail(error, file.string() + ": mesh cache " + reason);
    const std::string& s = *data;
    if (s.size() < kHeaderBytes || std::memcmp(s.data(), kMagic, 8) != 0)
        return fail(error, file.string() + ": not a Velvet mesh cache");
    if (const auto v = get<std::uint32_t>(s, 8); v != kMeshCacheVersion)
        return fail(error, file.string() + ": mesh cache version " + std::to_string(v) +
                               ", this build reads version " + std::to_string(kMeshCacheVersion));
    if (get<std::uint32_t>(s, 12) != sizeof(Vertex))
        return fail(error, file.string() + ": mesh cache has an unexpected vertex stride");
    const auto vertexCount = get<std::uint64_t>(s, 16);
    const auto indexCount = get<std::uint64_t>(s, 24);
    if (indexCount % 3 != 0 || indexCount > maxIndices || vertexCount > maxIndices)
        return fail(error, tooMany(file, indexCount / 3, limits));
    if (s.size() != kHeaderBytes + vertexCount * sizeof(Vertex) + indexCount * 4)
        return fail(error, file.string() + ": mesh cache size does not match its header");
    // Found by tests/fuzz (fuzz_mesh_cache): a header of zero counts reached memcpy with the
    // null data() of empty vectors. A mesh without a triangle has nothing to preview anyway.
    if (indexCount == 0 || vertexCount == 0)
        return fail(error, file.string() + ": mesh cache holds no triangles");
    MeshData mesh;
    mesh.doubleSided = (get<std::uint32_t>(s, 32) & 1u) != 0;
    mesh.vertices.resize(size_t(vertexCount));
    mesh.indices.resize(size_t(indexCount));
    std::memcpy(mesh.vertices.data(), s.data() + kHeaderBytes, vertexCount * sizeof(Vertex));
    std::memcpy(mesh.indices.data(), s.data() + kHeaderBytes + vertexCount * sizeof(Vertex),
                indexCount * 4);
    for (std::uint32_t i : mesh.indices)
        if (i >= vertexCount)
            return fail(error, file.string() + ": mesh cache index out of range");
    // Non-finite positions would poison the mesh's bounds, its framing and every pixel it covers.
    for (const Vertex& v : mesh.vertices)
        if (!std::isfinite(v.position.x) || !std::isfinite(v.position.y) ||
            !std::isfinite(v.position.z))
            return fail(error, file.string() + ": mesh cache has a non-finite vertex position");
    out = std::move(mesh);
    return true;
}

// ---- crash-isolated import ----------------------------------------------------------------------

void setMeshImportHelper(const std::filesystem::path& executable) {
    const std::lock_guard lock(g_helperMutex);
    g_helper = executable;
}

std::filesystem::path meshImportHelper() {
    const std::lock_guard lock(g_helperMutex);
    return g_helper;
}

bool importMeshUncached(const std::filesystem::path& file, MeshData& out, std::string* error,
                        const MeshImportOptions& options, bool* isolated) {
    if (isolated)
        *isolated = false;
    const std::filesystem::path helper =
        options.helper.empty() ? meshImportHelper() : options.helper;
    // Without the executable (unit tests of core/render, library users) there is no child to
    // run: import in this process, which loses only the crash isolation.
    if (helper.empty())
        return importMeshInProcess(file, out, error, options.limits);
    // Refuse what the header already refuses without starting a process.
    if (!checkMeshFile(file, error, options.limits))
        return false;

    static std::atomic<int> counter{0};
    std::error_code ec;
    const std::filesystem::path cache =
        std::filesystem::temp_directory_path(ec) /
        ("velvet-mesh-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".vmesh");
    int pipeFds[2];
    if (::pipe2(pipeFds, O_CLOEXEC) != 0)
        return fail(error,
                    file.string() + ": cannot start the mesh importer: " + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, pipeFds[1], 2);
    const std::string helperPath = helper.string(), in = file.string(), outPath = cache.string();
    // The child sets these on itself (setrlimit) before Assimp runs: CPU seconds, address space,
    // and the size of what it writes.
    const std::string cpu = std::to_string(options.cpuSeconds),
                      memory = std::to_string(options.addressSpaceMiB),
                      output = std::to_string(options.maxOutputMiB);
    char* argv[] = {const_cast<char*>(helperPath.c_str()),
                    const_cast<char*>("import-mesh"),
                    const_cast<char*>(in.c_str()),
                    const_cast<char*>(outPath.c_str()),
                    const_cast<char*>("--cpu-seconds"),
                    const_cast<char*>(cpu.c_str()),
                    const_cast<char*>("--memory-mib"),
                    const_cast<char*>(memory.c_str()),
                    const_cast<char*>("--output-mib"),
                    const_cast<char*>(output.c_str()),
                    nullptr};
    pid_t pid = 0;
    const int spawned = ::posix_spawn(&pid, helperPath.c_str(), &actions, nullptr, argv, environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipeFds[1]);
    if (spawned != 0) {
        ::close(pipeFds[0]);
        return fail(error, file.string() + ": cannot start the mesh importer " + helperPath + ": " +
                               std::strerror(spawned));
    }
    if (isolated)
        *isolated = true;

    // Collect the child's stderr until it closes and the child exits, or the deadline passes.
    // VELVET_MESH_IMPORT_TIMEOUT_S overrides the wall-clock limit (an artist's slow network disk).
    int timeoutMs = options.timeoutMs;
    if (const char* env = std::getenv("VELVET_MESH_IMPORT_TIMEOUT_S"); env && std::atof(env) > 0)
        timeoutMs = int(std::atof(env) * 1000.0);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeoutMs);
    std::string messages;
    bool eof = false, exited = false, timedOut = false;
    int status = 0;
    while (!(eof && exited)) {
        if (!eof) {
            pollfd p{pipeFds[0], POLLIN, 0};
            if (::poll(&p, 1, 20) > 0) {
                char buffer[4096];
                const ssize_t n = ::read(pipeFds[0], buffer, sizeof buffer);
                if (n > 0 && messages.size() < 65536)
                    messages.append(buffer, size_t(n));
                else if (n == 0 || (n < 0 && errno != EINTR && errno != EAGAIN))
                    eof = true;
            }
        } else {
            ::usleep(2000);
        }
        if (!exited && ::waitpid(pid, &status, WNOHANG) == pid)
            exited = true;
        if (!(eof && exited) && std::chrono::steady_clock::now() > deadline) {
            if (!exited) {
                ::kill(pid, SIGKILL);
                ::waitpid(pid, &status, 0);
            }
            timedOut = true;
            break;
        }
    }
    ::close(pipeFds[0]);
    const auto cleanup = [&] { std::filesystem::remove(cache, ec); };
    if (timedOut) {
        cleanup();
        char seconds[32];
        std::snprintf(seconds, sizeof seconds, "%g", double(timeoutMs) / 1000.0);
        return fail(error, file.string() + ": the mesh importer timed out after " + seconds +
                               " s and was stopped; the document is unaffected");
    }
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXCPU) {
        cleanup();
        return fail(error, file.string() + ": the mesh importer used more than " +
                               std::to_string(options.cpuSeconds) +
                               " s of CPU time and was stopped; the document is unaffected");
    }
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) {
        cleanup();
        return fail(error, file.string() + ": the imported mesh is larger than " +
                               std::to_string(options.maxOutputMiB) +
                               " MiB; refused, the document is unaffected");
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == kImportExitOutOfMemory) {
        cleanup();
        const long mib = options.addressSpaceMiB;
        const std::string amount = mib >= 1024 && mib % 1024 == 0
                                       ? std::to_string(mib / 1024) + " GiB"
                                       : std::to_string(mib) + " MiB";
        return fail(error, file.string() + ": the mesh importer needed more than " + amount +
                               " of memory; refused, the document is unaffected");
    }
    if (WIFSIGNALED(status)) {
        cleanup();
        const int sig = WTERMSIG(status);
        return fail(error, file.string() + ": the mesh importer crashed (signal " +
                               std::to_string(sig) + ", " + strsignal(sig) +
                               "); the document is unaffected");
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        cleanup();
        std::string message = lastLine(messages);
        if (message.empty())
            message = file.string() + ": the mesh importer failed (exit code " +
                      std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
        return fail(error, message);
    }
    const bool ok = readMeshCache(cache, out, error, options.limits);
    cleanup();
    return ok;
}

} // namespace velvet
