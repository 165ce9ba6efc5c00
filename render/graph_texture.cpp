#include "render/graph_texture.h"

#include "core/texture_ref.h"
#include "render/shader_program.h"
#include "render/texture_set.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {

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
