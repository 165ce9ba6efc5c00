#include "render/graph_texture.h"

#include "core/image_ops.h"
#include "core/texture_ref.h"
#include "render/shader_program.h"
#include "render/texture_set.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {
namespace {

/// Uploads @p image (1 to 4 channels, RRR for grey, alpha 1 when absent) into every level of
/// @p texture, an RGBA16F 2D texture with the full mip chain allocated
/// (mipLevelCount(width, height) levels): the levels of core::mipChain, filtered on the CPU
/// through OpenImageIO (Blackman-Harris, the same filter for every platform and driver) rather
/// than glGenerateTextureMipmap's unspecified box filter. Row 0 goes to t = 0. Needs a current
/// context. (Material slots take core/mip_texture.h's cached levels: render/texture_set.cpp.)
void uploadMipChain(unsigned texture, const Image& image) {
    std::string error;
    std::vector<Image> levels = mipChain(image, &error);
    const int count = mipLevelCount(image.width, image.height);
    if (int(levels.size()) != count) {
        // mipChain refuses only empty or inconsistent images, which the cache never hands out;
        // keep the texture complete regardless: level 0 and GPU-built levels.
        levels.assign(1, image);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    std::vector<float> rgba;
    for (size_t level = 0; level < levels.size(); ++level) {
        const Image& l = levels[level];
        rgba.resize(size_t(l.width) * l.height * 4);
        for (int y = 0; y < l.height; ++y)
            for (int x = 0; x < l.width; ++x) {
                const glm::vec4 c = l.rgba(x, y);
                float* o = rgba.data() + (size_t(y) * l.width + x) * 4;
                o[0] = c.r, o[1] = c.g, o[2] = c.b, o[3] = c.a;
            }
        glTextureSubImage2D(texture, GLint(level), 0, 0, l.width, l.height, GL_RGBA, GL_FLOAT,
                            rgba.data());
    }
    if (int(levels.size()) != count)
        glGenerateTextureMipmap(texture);
}

} // namespace

graph::CompileOptions graphCompileOptions() {
    graph::CompileOptions options;
    options.valuesBinding = 2;
    options.firstSamplerUnit = binding::kMaterialTexFirst + kTextureSlotCount;
    return options;
}

void uploadGraphTexture(const Image& image, unsigned& texture, int& width, int& height) {
    if (!texture || width != image.width || height != image.height) {
        if (texture)
            glDeleteTextures(1, &texture);
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        int levels = 1;
        for (int side = std::max(image.width, image.height); side > 1; side /= 2)
            ++levels;
        glTextureStorage2D(texture, levels, GL_RGBA16F, image.width, image.height);
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
        width = image.width;
        height = image.height;
    }
    // The levels of core::mipChain (OpenImageIO's filtered resize), as for material slots.
    uploadMipChain(texture, image);
}

unsigned createGraphFallbackTexture() {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA16F, 1, 1);
    const float white[4] = {1, 1, 1, 1};
    glTextureSubImage2D(texture, 0, 0, 0, 1, 1, GL_RGBA, GL_FLOAT, white);
    return texture;
}

} // namespace velvet::render
