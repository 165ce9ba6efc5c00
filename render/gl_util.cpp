#include "render/gl_util.h"

#include "core/half_float.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
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

namespace {

/// How a framebuffer's first colour attachment stores its values: 8-bit unsigned normalised
/// (linear encoding), 16-bit float, or anything else (read as float by the driver).
enum class ReadFormat { Unorm8, Half, Float };

ReadFormat readFormatOf(unsigned fbo) {
    if (fbo == 0) // the default framebuffer: whatever the window system made, read as float
        return ReadFormat::Float;
    GLint type = 0, bits = 0, encoding = 0;
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &type);
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, &bits);
    glGetNamedFramebufferAttachmentParameteriv(fbo, GL_COLOR_ATTACHMENT0,
                                               GL_FRAMEBUFFER_ATTACHMENT_COLOR_ENCODING, &encoding);
    if (type == GL_UNSIGNED_NORMALIZED && bits == 8 && encoding == GL_LINEAR)
        return ReadFormat::Unorm8;
    if (type == GL_FLOAT && bits == 16)
        return ReadFormat::Half;
    return ReadFormat::Float;
}

} // namespace

Image readFramebuffer(unsigned fbo, int width, int height) {
    Image img(width, height, 4);
    if (width <= 0 || height <= 0)
        return {};
    GLint previous = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    glReadBuffer(fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    // Read in the attachment's own format and widen here: the driver then copies instead of
    // converting every value (llvmpipe's float conversion of a 1280x720 frame took most of the
    // read-back). The results are the same floats: c / 255 for 8-bit values (the GL rule for
    // unsigned normalised values), halves widened exactly.
    const size_t values = size_t(width) * height * 4, rowValues = size_t(width) * 4;
    const auto flip = [&](auto&& widen) {
        for (int y = 0; y < height; ++y) {
            float* out = img.pixels.data() + size_t(y) * rowValues;
            const size_t in = size_t(height - 1 - y) * rowValues;
            for (size_t i = 0; i < rowValues; ++i)
                out[i] = widen(in + i);
        }
    };
    switch (readFormatOf(fbo)) {
    case ReadFormat::Unorm8: {
        std::vector<std::uint8_t> rows(values);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
        float table[256];
        for (int i = 0; i < 256; ++i)
            table[i] = float(i) * (1.0f / 255.0f); // as Mesa widens (u_math.h)
        flip([&](size_t i) { return table[rows[i]]; });
        break;
    }
    case ReadFormat::Half: {
        std::vector<std::uint16_t> rows(values);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_HALF_FLOAT, rows.data());
        for (int y = 0; y < height; ++y) // widened a row at a time, flipped
            halvesToFloats(rows.data() + size_t(height - 1 - y) * rowValues, rowValues,
                           img.pixels.data() + size_t(y) * rowValues);
        break;
    }
    case ReadFormat::Float: {
        std::vector<float> rows(values);
        glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, rows.data());
        flip([&](size_t i) { return rows[i]; });
        break;
    }
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(previous));
    return img;
}

} // namespace velvet::render
