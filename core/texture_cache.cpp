#include "core/texture_cache.h"

#include "core/color_management.h"
#include "core/image_ops.h"

#include <chrono>
#include <glm/vec4.hpp>
#include <system_error>
#include <unordered_map>
#include <utility>

#if __has_include(<sys/stat.h>)
#include <sys/stat.h>
#define VELVET_HAVE_POSIX_STAT 1
#endif

namespace velvet {
namespace {

/// readImage()'s message starts with the file name, which Problem::file already holds.
std::string withoutFilePrefix(std::string message, const std::filesystem::path& file) {
    const std::string prefix = file.string() + ": ";
    if (message.compare(0, prefix.size(), prefix) == 0)
        message.erase(0, prefix.size());
    return message;
}

/// Grey -> RRR, grey + alpha -> RRRA (the way Image::rgba() reads them), so a colour slot's
/// pixels are RGB whatever the file stored.
void expandGrey(Image& image) {
    if (image.channels > 2)
        return;
    Image rgb(image.width, image.height, image.channels + 2);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec4 p = image.rgba(x, y);
            float* o = rgb.at(x, y);
            for (int c = 0; c < rgb.channels; ++c)
                o[c] = p[c];
        }
    image = std::move(rgb);
}

std::string keyOf(const std::filesystem::path& file, const std::string& colorSpace,
                  TextureUsage usage) {
    std::string key = file.string();
    key += '\n';
    key += colorSpace;
    key += usage == TextureUsage::Color ? "\ncolor" : "\ndata";
    return key;
}

} // namespace

TextureCache::TextureCache(const ColorManagement& colorManagement, TextureCacheOptions options)
    : m_colorManagement(colorManagement), m_options(std::move(options)) {}

TextureCache::~TextureCache() = default;

TextureCache::FileStamp TextureCache::stampOf(const std::filesystem::path& file) {
    return textureFileStamp(file);
}

TextureFileStamp textureFileStamp(const std::filesystem::path& file) {
    TextureFileStamp s;
#ifdef VELVET_HAVE_POSIX_STAT
    // One stat(2) gives all of it (std::filesystem would need one call per field).
    struct stat st {};
    if (::stat(file.c_str(), &st) != 0)
        return s;
    s.exists = true;
    s.mtimeNs = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
    s.size = std::uint64_t(st.st_size);
    s.inode = std::uint64_t(st.st_ino);
    s.device = std::uint64_t(st.st_dev);
#else
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(file, ec);
    if (ec)
        return s;
    s.exists = true;
    s.mtimeNs =
        std::chrono::duration_cast<std::chrono::nanoseconds>(time.time_since_epoch()).count();
    s.size = std::filesystem::file_size(file, ec);
#endif
    return s;
}

std::string TextureCache::resolveColorSpace(const std::filesystem::path& file, TextureUsage usage,
                                            const std::string& colorSpace) const {
    return resolveTextureColorSpace(m_colorManagement, file, usage, colorSpace);
}

std::string resolveTextureColorSpace(const ColorManagement& colorManagement,
                                     const std::filesystem::path& file, TextureUsage usage,
                                     const std::string& colorSpace) {
    std::string name = colorSpace;
    if (name.empty()) {
        if (usage == TextureUsage::Color) {
            // The config's file rules (OCIO 2 FileRules): EXR/HDR are scene-linear, the rest
            // sRGB texture in the shipped config.
            name = colorManagement.colorSpaceForFile(file);
            if (name.empty())
                name = "sRGB texture";
        } else {
            name = colorManagement.roleColorSpace("data");
            if (name.empty())
                name = "Raw";
        }
    }
    // Aliases and roles share one entry under the canonical name.
    const std::string canonical = colorManagement.canonicalColorSpace(name);
    return canonical.empty() ? name : canonical;
}

void TextureCache::load(Entry& entry, const FileStamp& stamp) {
    entry.stamp = stamp; // taken before reading: a change during the read shows at the next poll
    Texture& t = entry.texture;
    t.image.reset();
    t.problems.clear();
    t.colorSpace = entry.colorSpace;
    t.generation = ++m_generation;
    const std::string fileName = entry.file.string();
    auto problem = [&](Problem::Severity severity, std::string message) {
        t.problems.push_back({severity, fileName, std::string(), std::move(message)});
    };

    if (!stamp.exists) {
        problem(Problem::Severity::Error, "no such file");
        return;
    }
    ++m_decodes;
    Image image;
    std::string error;
    if (!readImage(entry.file, image, &error, m_options.limits)) {
        problem(Problem::Severity::Error, withoutFilePrefix(error, entry.file));
        return;
    }
    if (entry.usage == TextureUsage::Color)
        expandGrey(image);
    std::string warning;
    if (fitToLimit(image, m_options.maxTextureSide, &warning, fileName))
        problem(Problem::Severity::Warning, withoutFilePrefix(warning, entry.file));
    if (!m_colorManagement.toSceneLinear(image, entry.colorSpace, &error)) {
        problem(Problem::Severity::Error,
                "cannot convert from colour space \"" + entry.colorSpace + "\": " + error);
        return;
    }
    t.image = std::make_shared<const Image>(std::move(image));
}

Texture TextureCache::get(const std::filesystem::path& file, TextureUsage usage,
                          const std::string& colorSpace) {
    if (file.empty())
        return {};
    const std::filesystem::path path = file.lexically_normal();
    const std::string space = resolveColorSpace(path, usage, colorSpace);
    const std::string key = keyOf(path, space, usage);
    std::lock_guard lock(m_mutex);
    auto it = m_entries.find(key);
    if (it == m_entries.end()) {
        Entry entry;
        entry.file = path;
        entry.colorSpace = space;
        entry.usage = usage;
        it = m_entries.emplace(key, std::move(entry)).first;
        load(it->second, stampOf(path));
    }
    return it->second.texture;
}

Texture TextureCache::get(const TextureRef& ref, TextureSlot slot) {
    if (ref.empty())
        return {};
    const TextureUsage usage =
        textureSlotMeta(slot).isColor ? TextureUsage::Color : TextureUsage::Data;
    return get(std::filesystem::path(ref.file), usage, ref.colorSpace);
}

int TextureCache::poll() {
    std::lock_guard lock(m_mutex);
    std::unordered_map<std::string, FileStamp> stamps; // one stat per file, shared by entries
    int reloaded = 0;
    for (auto& [key, entry] : m_entries) {
        auto [it, fresh] = stamps.try_emplace(entry.file.string());
        if (fresh)
            it->second = stampOf(entry.file);
        if (it->second == entry.stamp)
            continue;
        load(entry, it->second);
        ++reloaded;
    }
    return reloaded;
}

std::uint64_t TextureCache::decodeCount() const {
    std::lock_guard lock(m_mutex);
    return m_decodes;
}

size_t TextureCache::size() const {
    std::lock_guard lock(m_mutex);
    return m_entries.size();
}

void TextureCache::trim() {
    std::lock_guard lock(m_mutex);
    std::erase_if(m_entries, [](const auto& item) {
        const auto& image = item.second.texture.image;
        return !image || image.use_count() == 1;
    });
}

void TextureCache::clear() {
    std::lock_guard lock(m_mutex);
    m_entries.clear();
}

} // namespace velvet
