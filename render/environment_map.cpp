#include "render/environment_map.h"

#include "core/cache_dir.h"
#include "core/content_hash.h"
#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <epoxy/gl.h>
#include <filesystem>
#include <string>

namespace velvet::render {
namespace {

constexpr size_t kMaxEntries = 4;

/// The file's modification time and size: part of an HDRI's cache key, so a file edited in another
/// program is read again, and, its key being new, prefiltered again by the IBL baker.
std::string fileStamp(const std::string& path) {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(path, ec);
    if (ec)
        return "missing";
    const auto size = std::filesystem::file_size(path, ec);
    return std::to_string(time.time_since_epoch().count()) + ":" + std::to_string(ec ? 0 : size);
}
constexpr int kShWidth = 128; ///< SH9 is projected from a copy this wide (box-filtered)

/// Box-filtered copy at most @p maxWidth wide (integer factor), RGB.
Image downsample(const Image& src, int maxWidth) {
    const int f = std::max(1, src.width / maxWidth);
    Image out(std::max(1, src.width / f), std::max(1, src.height / f), 3);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            glm::vec3 sum(0.0f);
            for (int j = 0; j < f; ++j)
                for (int i = 0; i < f; ++i)
                    sum += glm::vec3(src.rgba(std::min(x * f + i, src.width - 1),
                                              std::min(y * f + j, src.height - 1)));
            sum /= float(f * f);
            float* p = out.at(x, y);
            p[0] = sum.x, p[1] = sum.y, p[2] = sum.z;
        }
    return out;
}

/// An RGBA16F texture of @p width x @p height with a full mip chain; level 0 from @p pixels
/// (RGB, @p type GL_FLOAT or GL_HALF_FLOAT), the other levels generated.
GLuint makeEquirectTexture(int width, int height, int levels, GLenum type, const void* pixels) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, levels, GL_RGBA16F, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(texture, 0, 0, 0, width, height, GL_RGB, type, pixels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // GPU-generated levels here, unlike material textures (uploadMipChain, core::mipChain): an
    // HDRI is large (2k-8k wide), so CPU filtering would stall loading for seconds; its levels
    // only feed the approximate lighting until the IBL bake (GPU prefiltering) is done; and the
    // Blackman-Harris filter's negative lobes would ring around the sun's HDR peaks (values in the
    // thousands) into negative radiance, which a box filter cannot produce.
    glGenerateTextureMipmap(texture);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

int levelsOf(int width, int height) {
    return 1 + int(std::floor(std::log2(float(std::max(width, height)))));
}

GpuEnvironment upload(const Image& radiance, std::string key) {
    GpuEnvironment e;
    e.key = std::move(key);
    e.width = radiance.width;
    e.height = radiance.height;
    e.levels = levelsOf(radiance.width, radiance.height);
    // Rows go in top first, so texture t = 0 is the image top = +Y, as equirectUv() expects.
    Image rgb = radiance.channels == 3 ? radiance : downsample(radiance, radiance.width);
    e.texture = makeEquirectTexture(rgb.width, rgb.height, e.levels, GL_FLOAT, rgb.pixels.data());
    e.sh = projectEquirect(radiance.width > kShWidth ? downsample(radiance, kShWidth) : radiance);
    return e;
}

/// An environment from the on-disk cache: the equirect as the GPU held it (half floats: the
/// same texels, so the same generated levels), the SH9 as projected then, and the prefiltered
/// cube for IblBaker::request to adopt.
GpuEnvironment uploadCached(IblCacheEntry entry, std::string key) {
    GpuEnvironment e;
    e.key = std::move(key);
    e.width = entry.width;
    e.height = entry.height;
    e.levels = levelsOf(entry.width, entry.height);
    e.texture = makeEquirectTexture(entry.width, entry.height, e.levels, GL_HALF_FLOAT,
                                    entry.equirect.data());
    e.sh = entry.sh;
    entry.equirect = {}; // on the GPU now
    e.cached = std::make_shared<const IblCacheEntry>(std::move(entry));
    return e;
}

/// A uniform environment: a 1x1 texture, and the exact SH9 of a constant (projecting the single
/// texel would give it a direction).
GpuEnvironment uploadUniform(glm::vec3 c, std::string key) {
    Image img(1, 1, 3);
    img.pixels = {c.x, c.y, c.z};
    GpuEnvironment e = upload(img, std::move(key));
    e.sh = uniformSH9(c);
    return e;
}

std::string uniformKey(glm::vec3 c) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "uniform:%.9g,%.9g,%.9g", c.x, c.y, c.z);
    return buf;
}

} // namespace

GpuEnvironment uploadEquirect(const Image& radiance, std::string key) {
    return upload(radiance, std::move(key));
}

EnvironmentCache::~EnvironmentCache() {
    for (auto& e : m_entries)
        if (e.texture)
            glDeleteTextures(1, &e.texture);
}

const GpuEnvironment& EnvironmentCache::get(const Environment& env, Problems* problems,
                                            const std::string& bakeSignature) {
    const std::string key =
        env.hdri.empty() ? uniformKey(env.color) : env.hdri + "\n" + fileStamp(env.hdri);
    auto it = std::find_if(m_entries.begin(), m_entries.end(),
                           [&](const GpuEnvironment& e) { return e.key == key; });
    if (it == m_entries.end()) {
        GpuEnvironment entry;
        if (env.hdri.empty()) {
            entry = uploadUniform(env.color, key);
        } else {
            // The disk cache, keyed by the file's content (a copy hits, an edit misses) and the
            // bake's signature (core/ibl_cache.h).
            std::filesystem::path cacheFile;
            std::string cacheKey;
            if (const auto dir = velvetCacheDir(); !dir.empty() && !bakeSignature.empty()) {
                if (const std::string hash = fileContentHash(env.hdri, nullptr); !hash.empty()) {
                    cacheKey = hash + "\n" + bakeSignature;
                    cacheFile = iblCacheFile(dir, cacheKey);
                }
            }
            IblCacheEntry cached;
            std::string why;
            if (!cacheFile.empty() && readIblCache(cacheFile, cacheKey, cached, &why)) {
                entry = uploadCached(std::move(cached), key);
                ++m_diskCacheHits;
            } else {
                if (!why.empty())
                    m_cacheWarning = "the prefiltered environment cache entry " +
                                     cacheFile.string() + " is not usable (" + why +
                                     "); baking it again";
                Image img;
                std::string error;
                ++m_decodes;
                if (readImage(env.hdri, img, &error)) {
                    entry = upload(img, key);
                } else {
                    cacheFile.clear(); // a fallback is never cached
                    entry = uploadUniform(glm::vec3(kFallbackGrey), key);
                    // readImage's message starts with the file name, which the Problem already
                    // holds.
                    if (const std::string prefix = env.hdri + ": "; error.rfind(prefix, 0) == 0)
                        error.erase(0, prefix.size());
                    entry.warning = "environment HDRI not used (" + error +
                                    "); lighting with a uniform grey environment instead";
                }
            }
            entry.cacheFile = cacheFile;
            entry.cacheKey = cacheFile.empty() ? std::string() : cacheKey;
        }
        m_entries.push_front(std::move(entry));
        while (m_entries.size() > kMaxEntries) {
            if (m_entries.back().texture)
                glDeleteTextures(1, &m_entries.back().texture);
            m_entries.pop_back();
        }
        it = m_entries.begin();
    } else if (it != m_entries.begin()) {
        m_entries.splice(m_entries.begin(), m_entries, it);
        it = m_entries.begin();
    }
    if (problems && !it->warning.empty())
        problems->warning(env.hdri, "environment.hdri", it->warning);
    if (problems && !m_cacheWarning.empty()) {
        problems->warning(env.hdri, "environment.hdri", m_cacheWarning);
        m_cacheWarning.clear();
    }
    return *it;
}

} // namespace velvet::render
