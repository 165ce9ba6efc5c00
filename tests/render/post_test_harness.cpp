// Test-only harness around PostChainRenderer::run (post_test_harness.h).
#include "post_test_harness.h"

#include "render/gbuffer_layout.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <glm/geometric.hpp>
#include <vector>

namespace velvet::test {
namespace {

GLuint makeTexture(GLenum format, const Image& img, int channels) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, format, img.width, img.height);
    std::vector<float> rows(size_t(img.width) * img.height * channels, 0.0f);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float* src = img.at(x, y);
            float* dst = rows.data() + (size_t(img.height - 1 - y) * img.width + x) * channels;
            for (int c = 0; c < channels; ++c)
                dst[c] = c < img.channels ? src[c] : (c == 3 ? 1.0f : src[0]);
        }
    const GLenum layout = channels == 4 ? GL_RGBA : channels == 2 ? GL_RG : GL_RED;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glTextureSubImage2D(tex, 0, 0, 0, img.width, img.height, layout, GL_FLOAT, rows.data());
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return tex;
}

} // namespace

bool applyPostChain(render::PostChainRenderer& post, const PostChain& chain,
                    const PostTestInput& input, Image& output, std::string* error) {
    using namespace render;
    const int w = input.color.width, h = input.color.height;
    if (w <= 0 || h <= 0) {
        if (error)
            *error = "applyPostChain: empty input";
        return false;
    }
    GLint previousFbo = 0, viewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousFbo);
    glGetIntegerv(GL_VIEWPORT, viewport);

    const GLuint color = makeTexture(GL_RGBA32F, input.color, 4);
    Image depth = input.depth;
    if (depth.width != w || depth.height != h) {
        depth = Image(w, h, 1);
        std::fill(depth.pixels.begin(), depth.pixels.end(), 1.0f);
    }
    Image normals(w, h, 2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::vec3 n(0, 0, 1);
            if (input.normals.width == w && input.normals.height == h)
                n = glm::vec3(input.normals.at(x, y)[0], input.normals.at(x, y)[1],
                              input.normals.at(x, y)[2]);
            const glm::uvec2 q = octEncodeUnorm16(glm::normalize(n));
            normals.at(x, y)[0] = float(q.x) / 65535.0f;
            normals.at(x, y)[1] = float(q.y) / 65535.0f;
        }
    const GLuint depthTex = makeTexture(GL_R32F, depth, 1);
    const GLuint normalTex = makeTexture(GL_RG32F, normals, 2);
    const int depthUnit = gbufferUnit("GBUFFER_DEPTH");
    const int normalUnit = gbufferUnit("GBUFFER_NORMAL");
    glBindTextureUnit(GLuint(depthUnit), depthTex);
    glBindTextureUnit(GLuint(normalUnit), normalTex);

    GLuint outTex = 0, outFbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &outTex);
    glTextureStorage2D(outTex, 1, GL_RGBA32F, w, h);
    glCreateFramebuffers(1, &outFbo);
    glNamedFramebufferTexture(outFbo, GL_COLOR_ATTACHMENT0, outTex, 0);

    PostRunInputs in;
    in.hdrTexture = color;
    in.width = w;
    in.height = h;
    in.viewProj = input.viewProj;
    in.prevViewProj = input.prevViewProj;
    in.proj = input.proj;
    in.time = input.time;
    in.encoding = input.encoding;
    in.finalFbo = outFbo;
    PostRunResult result;
    const bool ok = post.run(chain, in, result, error);
    if (ok) {
        const GLuint tex = result.displayEncoded ? outTex : result.hdrTexture;
        std::vector<float> rows(size_t(w) * h * 4);
        glGetTextureImage(tex, 0, GL_RGBA, GL_FLOAT, GLsizei(rows.size() * sizeof(float)),
                          rows.data());
        output = Image(w, h, 4);
        for (int y = 0; y < h; ++y)
            std::copy_n(rows.data() + size_t(h - 1 - y) * w * 4, size_t(w) * 4,
                        output.pixels.data() + size_t(y) * w * 4);
    }
    post.endFrame();
    glBindTextureUnit(GLuint(depthUnit), 0);
    glBindTextureUnit(GLuint(normalUnit), 0);
    glDeleteTextures(1, &color);
    glDeleteTextures(1, &depthTex);
    glDeleteTextures(1, &normalTex);
    glDeleteTextures(1, &outTex);
    glDeleteFramebuffers(1, &outFbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(previousFbo));
    glViewport(viewport[0], viewport[1], viewport[2], viewport[3]);
    return ok;
}

} // namespace velvet::test
