#include "render/environment_map.h"

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

GpuEnvironment upload(const Image& radiance, std::string key) {
    GpuEnvironment e;
    e.key = std::move(key);
    e.width = radiance.width;
    e.levels = 1 + int(std::floor(std::log2(float(std::max(radiance.width, radiance.height)))));
    // Rows go in top first, so texture t = 0 is the image top = +Y, as equirectUv() expects.
    Image rgb = radiance.channels == 3 ? radiance : downsample(radiance, radiance.width);
    glCreateTextures(GL_TEXTURE_2D, 1, &e.texture);
    glTextureStorage2D(e.texture, e.levels, GL_RGBA16F, radiance.width, radiance.height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(e.texture, 0, 0, 0, rgb.width, rgb.height, GL_RGB, GL_FLOAT,
                        rgb.pixels.data());
    // GPU-generated levels here, unlike material textures (uploadMipChain, core::mipChain): an
    // HDRI is large (2k-8k wide), so CPU filtering would stall loading for seconds; its levels
    // only feed the approximate lighting until the IBL bake (GPU prefiltering) is done; and the
    // Blackman-Harris filter's negative lobes would ring around the sun's HDR peaks (values in the
    // thousands) into negative radiance, which a box filter cannot produce.
    glGenerateTextureMipmap(e.texture);
    glTextureParameteri(e.texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(e.texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(e.texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(e.texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    e.sh = projectEquirect(radiance.width > kShWidth ? downsample(radiance, kShWidth) : radiance);
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

const GpuEnvironment& EnvironmentCache::get(const Environment& env, Problems* problems) {
    const std::string key =
        env.hdri.empty() ? uniformKey(env.color) : env.hdri + "\n" + fileStamp(env.hdri);
    auto it = std::find_if(m_entries.begin(), m_entries.end(),
                           [&](const GpuEnvironment& e) { return e.key == key; });
    if (it == m_entries.end()) {
        GpuEnvironment entry;
        if (env.hdri.empty()) {
            entry = uploadUniform(env.color, key);
        } else {
            Image img;
            std::string error;
            if (readImage(env.hdri, img, &error)) {
                entry = upload(img, key);
            } else {
                entry = uploadUniform(glm::vec3(kFallbackGrey), key);
                // readImage's message starts with the file name, which the Problem already holds.
                if (const std::string prefix = env.hdri + ": "; error.rfind(prefix, 0) == 0)
                    error.erase(0, prefix.size());
                entry.warning = "environment HDRI not used (" + error +
                                "); lighting with a uniform grey environment instead";
            }
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
    return *it;
}

} // namespace velvet::render
