#pragma once
/// @file texture_set.h
/// Render-private: the GL textures of a material's slots, loaded through core's TextureLoader
/// (core/mip_texture.h: every level built once, 8-bit files kept 8-bit, cached on disk by
/// content) off the drawing thread in the editor, uploaded a budget of bytes a frame, and
/// reloaded when a file changes on disk. No shader ever changes: the G-buffer program samples unit
/// binding::kMaterialTexFirst + slot when the material record's presence bit says so
/// (GpuMaterial::terms2.y; atlas-region bits in terms2.z; regions in a per-draw uniform).
///
/// What reaches the pixels: every slot, per pixel. Base colour (and alpha, a 0.5 cut-out),
/// metallic-roughness, the seeds' atlas, normal map and occlusion go through the G-buffer's
/// common 16 bytes, emission straight into the HDR target, and the lobe slots (sheen, clearcoat
/// and its normal, specular, anisotropy) through the lobe channels each material maps them into
/// (render/lobe_channels.h). Only a value that finds no channel (the compact 16-byte layout, or a
/// material varying more than eight channels' worth) enters the material table as its texture's
/// mean, multiplied with the parameter.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/material.h"
#include "core/texture_ref.h"
#include "render/texture_progress.h"

#include <array>
#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <map>
#include <memory>
#include <string>

namespace velvet {
class ColorManagement;
struct MipLevel;
class TextureCache;
class TextureLoader;
} // namespace velvet

namespace velvet::render {

class TextureStorageThread;
class WorkerGlContext;

struct GpuMaterial;
struct LobeChannelMap;

/// A slot's UV transform (core/texture_ref.h) as the shader applies it: uv' = mat2(linear.xy,
/// linear.zw) * uv + offset (columns), uniforms uTexUvLinear and uTexUvOffset of
/// common_material_textures.glsl.
struct UvTransformMatrix {
    glm::vec4 linear{1.0f, 0.0f, 0.0f, 1.0f};
    glm::vec2 offset{0.0f};
};
UvTransformMatrix uvTransformMatrix(const UvTransform& uv);

class TextureSet {
public:
    TextureSet();
    /// Needs the renderer's context current (frees GL textures).
    ~TextureSet();
    TextureSet(const TextureSet&) = delete;
    TextureSet& operator=(const TextureSet&) = delete;

    /// The OCIO config input colour spaces come from (null: ColorManagement's default config,
    /// loaded when a first texture needs it). Drops the textures: names may mean other spaces.
    void setColorManagement(std::shared_ptr<const ColorManagement> colorManagement);

    /// Asynchronous loading (the editor): files are read on core::TextureLoader's thread, each
    /// poll() uploads at most uploadBudget() bytes (smallest level first, so a coarse proxy
    /// shows within a frame or two), and until a slot's first level is on the GPU it draws the
    /// parameter value. Synchronous (the default: headless rendering, tests): setMaterial() and
    /// poll() load and upload everything before returning. Drops the textures.
    void setAsync(bool async);
    bool async() const { return m_async; }
    /// Bytes one poll() may upload in asynchronous mode (default 8 MiB: a 4096² RGBA8 level 0
    /// in 8 frames; a 16 MiB copy measured 3-20 ms on llvmpipe, idle).
    void setUploadBudget(std::uint64_t bytes) { m_budget = bytes; }
    std::uint64_t uploadBudget() const { return m_budget; }
    /// A context sharing objects with the drawing one, for a thread that makes large textures'
    /// storage in asynchronous mode (render/texture_storage_thread.h), so that no frame waits
    /// for llvmpipe to zero-fill it. Without one (the default) the drawing thread allocates.
    /// Drops the textures.
    void setStorageContext(std::unique_ptr<WorkerGlContext> context);
    /// The on-disk mip cache's folder (empty: core::defaultMipCacheDir()). Drops the textures.
    void setCacheDir(std::filesystem::path dir);

    /// Takes @p material's texture slots: requests what changed, releases emptied slots. A file
    /// used by several slots (same file, colour space and usage) is one texture, read once. In
    /// synchronous mode a missing or broken file is reported to @p problems now and its slot
    /// falls back to the parameter value; in asynchronous mode such problems come from
    /// takeProblems() once the load finishes. Needs a current context.
    void setMaterial(const Material& material, Problems* problems);

    /// Every frame: stats the files in use (one stat per file) and reloads those changed on
    /// disk, takes the loads that finished and uploads (within the budget in asynchronous
    /// mode). True when what the material record holds changed (re-pack it then): a slot's
    /// presence or mean.
    bool poll();
    /// Loads and uploads everything now (headless rendering before its one frame).
    void finish();
    /// Problems of loads finished since the last call (asynchronous mode), each naming the file
    /// and the slot.
    Problems takeProblems();
    TextureLoadProgress progress() const;
    const TextureUploadStats& uploadStats() const { return m_stats; }
    /// Files decoded and on-disk cache hits since the loader was made (tests, bench).
    std::uint64_t decodeCount() const;
    std::uint64_t cacheHits() const;

    /// Bit i set: slot i has a texture on the GPU (drawn per pixel).
    std::uint32_t presentSlots() const;
    /// Writes presence and region bits into @p g (packMaterial's output), and the texture means
    /// of the lobe values @p lobes keeps per material.
    void applyTo(GpuMaterial& g, const LobeChannelMap& lobes) const;
    /// Binds the slot textures and sets @p program's region and UV-transform uniforms (location 1
    /// onwards: uTexRegion, uTexUvLinear, uTexUvOffset, kTextureSlotCount each).
    void bind(unsigned program) const;
    /// Unbinds the slot units.
    void unbind() const;

    /// GL texture (re)allocations since construction (tests: a changed file of the same size
    /// re-uploads without reallocating).
    int allocationCount() const { return m_allocations; }
    /// The GL texture name of @p slot (0 when the slot is empty, its file failed or nothing of
    /// it is uploaded yet; tests read its levels back).
    unsigned texture(TextureSlot slot) const;
    /// The finest level of @p slot's texture on the GPU (0 when complete; -1 when none).
    int finestLevel(TextureSlot slot) const;
    /// The float texture cache the material graph's texture nodes and thumbnails use (created
    /// on first use; needs a current context).
    TextureCache& sharedCache() { return cache(); }

private:
    struct Slot;
    struct Entry;
    TextureCache& cache();
    TextureLoader& loader();
    const ColorManagement& colorManagement();
    void startLoad(Entry& entry, bool leaveFinestInCache = true);
    bool takeFinished(Entry& entry, Problems* problems);
    /// The storage thread's texture for @p entry once it is made (true), or false while it is not
    /// (@p wait: until it is).
    bool takeStorage(Entry& entry, bool wait);
    void releaseTexture(Entry& entry);
    std::uint64_t upload(Entry& entry, std::uint64_t budget, bool& becameVisible);
    bool readBand(Entry& entry, const MipLevel& level, std::uint64_t rowBytes, std::uint64_t fit);
    bool updateSlots(Problems* problems);
    void reportProblems(const Entry& entry, Problems& into) const;
    void dropEntries();

    std::shared_ptr<const ColorManagement> m_colorManagement;
    std::unique_ptr<TextureCache> m_cache;
    std::unique_ptr<TextureLoader> m_loader;
    /// Storage of at least this many bytes (with mips) is made off the drawing thread: a 1024²
    /// RGBA8 chain and larger.
    static constexpr std::uint64_t kOffThreadStorageBytes = std::uint64_t(4) << 20;
    std::unique_ptr<TextureStorageThread> m_storageThread;
    std::unique_ptr<std::array<Slot, kTextureSlotCount>> m_slots;
    std::unique_ptr<std::map<std::string, Entry>> m_entries;
    Problems m_problems;
    TextureUploadStats m_stats;
    std::filesystem::path m_cacheDir;
    std::uint64_t m_budget = std::uint64_t(8) << 20;
    std::uint64_t m_generation = 0;
    int m_maxSide = 0;
    int m_allocations = 0;
    bool m_async = false;
};

} // namespace velvet::render
