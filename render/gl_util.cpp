#include "render/gl_util.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {

std::string glErrorName(unsigned e) {
    switch (e) {
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    default:
        return "GL error " + std::to_string(e);
    }
}

std::string takeGlErrors() {
    std::string first;
    for (int i = 0; i < 32; ++i) {
        const GLenum e = glGetError();
        if (e == GL_NO_ERROR)
            break;
        if (first.empty())
            first = glErrorName(e);
    }
    return first;
}

bool fail(std::string* error, const std::string& message) {
    if (error)
        *error = message;
    return false;
}

Image readFramebuffer(unsigned fbo, int width, int height) {
    Image img(width, height, 4);
    if (width <= 0 || height <= 0)
        return {};
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    std::vector<float> rows(size_t(width) * height * 4);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    const size_t rowFloats = size_t(width) * 4;
    for (int y = 0; y < height; ++y)
        std::copy_n(rows.data() + size_t(height - 1 - y) * rowFloats, rowFloats,
                    img.pixels.data() + size_t(y) * rowFloats);
    return img;
}

} // namespace velvet::render
