/// @file mesh_import_memo.cpp
/// importMesh's memo (core/mesh_import.h): the editor imports a custom mesh to check it before
/// the edit enters History (issue 17 item 13), then the renderer imports it to draw it. Both go
/// through importMesh; the second is answered from here instead of a second child process (an
/// import of a large file takes seconds). Only successes are remembered, a small number of them
/// (a preview mesh can be hundreds of MB), and only while the file is unchanged on disk.

#include "core/mesh_import.h"

#include <atomic>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <system_error>

namespace velvet {
namespace {

/// Two: the mesh in use and the one before it (an undo swaps between them).
constexpr std::size_t kRememberedMeshes = 2;

struct MemoKey {
    std::string path; ///< absolute, normalised
    std::uintmax_t size = 0;
    std::filesystem::file_time_type modified{};
    std::uintmax_t maxFileBytes = 0;
    std::uint64_t maxTriangles = 0;
    bool operator==(const MemoKey&) const = default;
};

struct MemoEntry {
    MemoKey key;
    std::shared_ptr<const MeshData> mesh;
};

std::mutex g_memoMutex;
std::deque<MemoEntry> g_memo; // most recent first
std::atomic<std::uint64_t> g_imports{0};

/// The key of @p file as it is on disk now; nullopt when it cannot be stat'ed (the import then
/// runs and reports why).
std::optional<MemoKey> keyOf(const std::filesystem::path& file, const MeshImportLimits& limits) {
    std::error_code ec;
    MemoKey key;
    key.path = std::filesystem::absolute(file, ec).lexically_normal().string();
    if (ec)
        return std::nullopt;
    key.size = std::filesystem::file_size(file, ec);
    if (ec)
        return std::nullopt;
    key.modified = std::filesystem::last_write_time(file, ec);
    if (ec)
        return std::nullopt;
    key.maxFileBytes = limits.maxFileBytes;
    key.maxTriangles = limits.maxTriangles;
    return key;
}

} // namespace

bool importMesh(const std::filesystem::path& file, MeshData& out, std::string* error,
                const MeshImportOptions& options, bool* isolated) {
    if (isolated)
        *isolated = false;
    const std::optional<MemoKey> key = keyOf(file, options.limits);
    if (key) {
        const std::lock_guard lock(g_memoMutex);
        for (const MemoEntry& e : g_memo)
            if (e.key == *key) {
                out = *e.mesh;
                return true;
            }
    }
    ++g_imports;
    MeshData imported;
    if (!importMeshUncached(file, imported, error, options, isolated))
        return false;
    // Keyed by the stat taken before the import: a file rewritten meanwhile is imported again.
    if (key) {
        auto mesh = std::make_shared<const MeshData>(imported);
        const std::lock_guard lock(g_memoMutex);
        std::erase_if(g_memo, [&](const MemoEntry& e) { return e.key.path == key->path; });
        g_memo.push_front({*key, std::move(mesh)});
        if (g_memo.size() > kRememberedMeshes)
            g_memo.pop_back();
    }
    out = std::move(imported);
    return true;
}

std::uint64_t meshImportCount() {
    return g_imports.load();
}

} // namespace velvet
