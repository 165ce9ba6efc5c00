#pragma once
/// @file mesh_import.h
/// Custom preview meshes from files (OBJ, FBX, glTF/GLB, PLY, STL, DAE) through Assimp (its
/// headers stay in mesh_import.cpp), the binary mesh cache the import helper process writes, and
/// the crash-isolated import: DESIGN.md, "Data safety" — an importer that crashes or hangs on an
/// untrusted file takes down a child process, not the document.

#include "core/mesh.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace velvet {

/// Limits checked before and after decoding a mesh file.
struct MeshImportLimits {
    /// Files larger than this are refused before Assimp sees them.
    std::uintmax_t maxFileBytes = std::uintmax_t(512) << 20;
    /// Meshes with more triangles (after triangulation, all meshes merged) are refused. Formats
    /// whose header states a count (binary STL, PLY) are refused from the header, before any
    /// allocation.
    std::uint64_t maxTriangles = 2'000'000;
};

/// Checks a file's size and, for binary STL and PLY, the triangle / face count its header
/// claims, without decoding it. False + one line naming the file and the number on refusal.
bool checkMeshFile(const std::filesystem::path& file, std::string* error,
                   const MeshImportLimits& limits = {});

/// Imports @p file in this process with Assimp: checkMeshFile(), then triangulate, pre-transform
/// and merge every mesh into one, drop points and lines, generate normals where missing
/// (smooth, except across edges sharper than a 60-degree crease angle: a cube stays hard-edged),
/// UVs in glTF's space (v = 0 at the image's top; files without UVs get zeros), centre and
/// scale into [-1, 1]^3 (fitToUnitBox), then tangents: a glTF primitive's TANGENT where it has
/// one, otherwise MikkTSpace per file mesh (core/mikktspace.h; other formats' tangents are not
/// read, their importers disagree on bitangent conventions), splitting vertices whose corners
/// get different frames. False + one line naming the file.
bool importMeshInProcess(const std::filesystem::path& file, MeshData& out, std::string* error,
                         const MeshImportLimits& limits = {});

/// @name Mesh cache: the file `velvet import-mesh` writes and the parent reads back.
/// Little-endian, version 1:
///
///     offset  size  field
///     0       8     magic "VLVMESH\0"
///     8       4     uint32 version (1)
///     12      4     uint32 vertex stride in bytes (48: position 3f, normal 3f, tangent 4f, uv 2f)
///     16      8     uint64 vertex count
///     24      8     uint64 index count (a multiple of 3)
///     32      4     uint32 flags (bit 0: double-sided)
///     36      4     reserved (0)
///     40            vertices (count x stride), then indices (count x uint32)
///
/// The reader checks magic, version, stride, that the counts match the file's size exactly,
/// the triangle limit and that every index is in range, before trusting anything.
/// @{
inline constexpr std::uint32_t kMeshCacheVersion = 1;
bool writeMeshCache(const std::filesystem::path& file, const MeshData& mesh, std::string* error);
bool readMeshCache(const std::filesystem::path& file, MeshData& out, std::string* error,
                   const MeshImportLimits& limits = {});
/// @}

/// Options of importMesh().
struct MeshImportOptions {
    MeshImportLimits limits;
    /// The `velvet` executable that runs `velvet import-mesh IN OUT` in a child process. Empty:
    /// meshImportHelper() (set by the application at start-up).
    std::filesystem::path helper;
    /// The child is killed after this long (wall clock) and the import fails with "timed out
    /// after 10 s"; VELVET_MESH_IMPORT_TIMEOUT_S overrides it.
    int timeoutMs = 10'000;
    /// Limits the child sets on itself with setrlimit (issue 18): CPU time (SIGXCPU past it),
    /// address space (an allocation fails: exit kImportExitOutOfMemory), and the size of the mesh
    /// cache it writes (SIGXFSZ past it). Each has its own message.
    int cpuSeconds = 20;
    long addressSpaceMiB = 4096;
    long maxOutputMiB = 512;
};

/// `velvet import-mesh`'s exit code when an allocation failed under its address-space limit.
inline constexpr int kImportExitOutOfMemory = 4;

/// Sets / returns the default import helper (the running `velvet` executable). Unset in unit
/// tests and in library users without the executable; importMesh() then imports in process.
void setMeshImportHelper(const std::filesystem::path& executable);
std::filesystem::path meshImportHelper();

/// Imports @p file, crash-isolated: runs `HELPER import-mesh FILE CACHE` in a child process
/// with a timeout and reads the cache back (readMeshCache). Without a helper (see above) it
/// imports in this process. A crash, a timeout or a non-zero exit gives false and one line
/// naming the file and what happened (the child's own message when it printed one).
/// @p isolated, when given, says whether a child process did the work.
///
/// The last few successful imports are remembered (core/mesh_import_memo.cpp), keyed by the
/// file's path, size and modification time and the limits: the editor checks a mesh before the
/// edit and the renderer draws it right after, and a file imported once is not imported again
/// until it changes on disk (@p isolated is then false: no child ran).
bool importMesh(const std::filesystem::path& file, MeshData& out, std::string* error,
                const MeshImportOptions& options = {}, bool* isolated = nullptr);
/// importMesh without the memo: always a child process (or in process without a helper).
bool importMeshUncached(const std::filesystem::path& file, MeshData& out, std::string* error,
                        const MeshImportOptions& options = {}, bool* isolated = nullptr);
/// Imports importMesh really ran (not answered from the memo) since start, in this process.
std::uint64_t meshImportCount();

} // namespace velvet
