#include "render/mesh_cache.h"

#include "core/mesh.h"
#include "core/mesh_import.h"
#include "render/mesh_visibility.h"

#include <algorithm>
#include <chrono>
#include <glm/geometric.hpp>

namespace velvet::render {

const MeshCache::Entry& MeshCache::select(const MeshRef& ref, Problems* problems) {
    const bool custom = ref.kind == PreviewMeshKind::Custom;
    const std::string key = std::to_string(int(ref.kind)) + (custom ? ":" + ref.file : "");
    auto& entry = m_entries[key];
    if (!entry) {
        entry = std::make_unique<Entry>();
        MeshData data;
        std::string error;
        // importMesh runs `velvet import-mesh` in a child process when the application set
        // the helper, in process otherwise (core/mesh_import.h).
        if (custom && ref.file.empty())
            entry->failure = "a custom mesh needs a file";
        else if (custom && !importMesh(ref.file, data, &error))
            entry->failure = error;
        else if (!custom)
            data = makePreviewMesh(ref.kind);
        if (entry->failure.empty()) {
            // The mesh's visibility from itself, for image-based light's occlusion; the convex
            // preview meshes hide nothing from themselves, so they skip the rays.
            const bool bake = !previewMeshIsConvex(ref.kind);
            if (bake && !m_asyncBake)
                data.visibility = bakeMeshVisibility(data);
            entry->gpu.upload(data);
            if (bake && m_asyncBake) {
                MeshData geometry;
                geometry.vertices = data.vertices;
                geometry.indices = data.indices;
                entry->bake = std::async(std::launch::async, [geometry = std::move(geometry)] {
                    return bakeMeshVisibility(geometry);
                });
            }
            entry->doubleSided = data.doubleSided;
            entry->bounds = meshBounds(data);
            float radius = 0.0f;
            for (const Vertex& v : data.vertices)
                radius = std::max(radius, glm::length(v.position));
            entry->radius = radius > 0.0f ? radius : 1.0f;
        }
    }
    if (!entry->failure.empty()) {
        if (problems)
            problems->error(ref.file, "mesh", entry->failure + "; showing the sphere");
        return select(MeshRef{}, nullptr);
    }
    m_selected = entry.get();
    return *entry;
}

bool MeshCache::adoptBakes() {
    bool adopted = false;
    for (auto& [key, entry] : m_entries)
        if (entry->bake.valid() &&
            entry->bake.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
            entry->gpu.uploadVisibility(entry->bake.get());
            adopted = true;
        }
    return adopted;
}

bool MeshCache::bakePending() const {
    for (const auto& [key, entry] : m_entries)
        if (entry->bake.valid())
            return true;
    return false;
}

} // namespace velvet::render
