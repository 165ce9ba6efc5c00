#pragma once
/// @file mesh_cache.h
/// Render-private: the preview meshes on the GPU, uploaded once per kind or custom file. A custom
/// mesh that fails to import is remembered with its message, so it is reported again at each
/// selection but never re-imported.

#include "core/diagnostics.h"
#include "core/scene.h"
#include "render/gpu_mesh.h"

#include <future>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace velvet::render {

class MeshCache {
public:
    struct Entry {
        GpuMesh gpu;
        bool doubleSided = false;
        MeshBounds bounds; ///< of the vertices (the stage fits shadows and the ground to it)
        /// The largest distance of a vertex from the origin (frames the view: View > Frame Mesh).
        float radius = 1.0f;
        std::string failure; ///< why the import failed ("" when the mesh is uploaded)
        /// The visibility bake still running on a worker (setAsyncBake), adopted by adoptBakes().
        std::future<std::vector<glm::vec4>> bake;
    };

    MeshCache() = default;
    MeshCache(const MeshCache&) = delete;
    MeshCache& operator=(const MeshCache&) = delete;

    /// Selects (uploading once) the mesh @p ref names; a custom mesh that fails to import is
    /// reported to @p problems and the sphere selected instead. Needs a current context.
    const Entry& select(const MeshRef& ref, Problems* problems);
    /// The selected mesh (null before the first select()).
    const Entry* selected() const { return m_selected; }

    /// Whether a new mesh's visibility from itself (render/mesh_visibility.h) is ray traced on a
    /// worker thread (the editor: a frame never waits for it; the mesh draws without it until
    /// adoptBakes() uploads it) or before select() returns (the default: headless renders are
    /// the same image every time).
    void setAsyncBake(bool async) { m_asyncBake = async; }
    /// Uploads every finished bake (needs the context current); true when one was adopted.
    bool adoptBakes();
    /// Whether a bake is still running: a host keeps drawing until it is adopted.
    bool bakePending() const;

private:
    std::map<std::string, std::unique_ptr<Entry>> m_entries;
    const Entry* m_selected = nullptr;
    bool m_asyncBake = false;
};

} // namespace velvet::render
