#pragma once
/// @file texture_cache.h
/// Textures loaded once per (file, colour space) into scene-linear float, shared, and reloaded
/// when the file changes on disk, so an image edited in another program updates the viewport.
/// No GL here: render/ uploads what it is handed and re-uploads when the generation changes.

#include "core/diagnostics.h"
#include "core/image.h"
#include "core/texture_ref.h"

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace velvet {

class ColorManagement;

/// What a texture's pixels are: colour (converted from its input colour space to scene-linear;
/// a grey file becomes RRR, grey + alpha RRRA) or data (normals, roughness, masks: left as
/// stored, channel count kept; Image::rgba() reads grey as RRR).
enum class TextureUsage { Color, Data };

/// What poll() compares to see that a file changed: one stat(2).
struct TextureFileStamp {
    bool exists = false;
    std::int64_t mtimeNs = 0;
    std::uint64_t size = 0;
    std::uint64_t inode = 0;
    std::uint64_t device = 0;
    bool operator==(const TextureFileStamp&) const = default;
};
/// Stats @p file (missing: exists false).
TextureFileStamp textureFileStamp(const std::filesystem::path& file);

/// The canonical input colour space of a texture: @p colorSpace, or when empty the usage's
/// default (TextureCache::get explains it), aliases and roles resolved to the config's name.
std::string resolveTextureColorSpace(const ColorManagement& colorManagement,
                                     const std::filesystem::path& file, TextureUsage usage,
                                     const std::string& colorSpace);

/// One cached texture as handed out.
struct Texture {
    /// Scene-linear float pixels, shared and immutable; null when the file is missing or broken
    /// (problems says why) and the caller falls back to the slot's parameter value.
    std::shared_ptr<const Image> image;
    /// Changes whenever the entry is (re)loaded, whether or not the load succeeded; unique
    /// across the cache, never 0 for a loaded entry. Re-upload when it differs from the last.
    std::uint64_t generation = 0;
    std::string colorSpace;        ///< the input colour space the pixels were converted from
    std::vector<Problem> problems; ///< errors (image null) and warnings (e.g. downscaled)
};

/// Options of a TextureCache.
struct TextureCacheOptions {
    ImageReadLimits limits; ///< refused before decoding when the header exceeds them
    /// Largest side the GPU takes (GL_MAX_TEXTURE_SIZE); larger textures are downscaled with a
    /// warning (fitToLimit). 0: no limit.
    int maxTextureSide = 0;
};

/// A cache of textures keyed by (file, input colour space, usage). Thread-safe: every member
/// may be called from any thread (loads run under the cache's lock). The ColorManagement must
/// outlive the cache. Never throws for a bad file: see Texture::problems.
class TextureCache {
public:
    explicit TextureCache(const ColorManagement& colorManagement, TextureCacheOptions options = {});
    ~TextureCache();
    TextureCache(const TextureCache&) = delete;
    TextureCache& operator=(const TextureCache&) = delete;

    /// The texture of @p file in @p colorSpace, loaded on first use. An empty @p colorSpace
    /// means the usage's default: for colour the config's file rules (sRGB texture for 8- and
    /// 16-bit formats, Linear Rec.709 for OpenEXR and Radiance HDR in the shipped config; "sRGB
    /// texture" when the config has no rule), for data the config's `data` role ("Raw").
    Texture get(const std::filesystem::path& file, TextureUsage usage,
                const std::string& colorSpace = {});
    /// The texture of a slot: colour for colour slots (textureSlotMeta(slot).isColor), else
    /// data, in ref.colorSpace (empty: the default above). ref.file is used as it is: resolve a
    /// document-relative path first. An empty ref gives an empty Texture with no problem.
    Texture get(const TextureRef& ref, TextureSlot slot);

    /// Stats each cached file once (one stat per file, cheap enough to call every frame) and
    /// reloads the entries whose file changed: modification time, size or identity (a new
    /// inode, as an atomic save gives), or that appeared or vanished. Returns how many entries
    /// were reloaded; their generation changes.
    int poll();

    /// Number of files read (decode attempts, successful or not) since construction.
    std::uint64_t decodeCount() const;
    /// Number of cached entries.
    size_t size() const;
    /// Drops the entries whose image no one else holds (and the failed ones).
    void trim();
    /// Drops every entry.
    void clear();

private:
    using FileStamp = TextureFileStamp;
    struct Entry {
        std::filesystem::path file;
        std::string colorSpace;
        TextureUsage usage = TextureUsage::Color;
        FileStamp stamp;
        Texture texture;
    };
    static FileStamp stampOf(const std::filesystem::path& file);
    std::string resolveColorSpace(const std::filesystem::path& file, TextureUsage usage,
                                  const std::string& colorSpace) const;
    void load(Entry& entry, const FileStamp& stamp); ///< under m_mutex

    const ColorManagement& m_colorManagement;
    TextureCacheOptions m_options;
    mutable std::mutex m_mutex;
    std::map<std::string, Entry> m_entries; ///< key: file, colour space, usage
    std::uint64_t m_generation = 0;
    std::uint64_t m_decodes = 0;
};

} // namespace velvet
