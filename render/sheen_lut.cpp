#include "render/sheen_lut.h"

#include "core/brdf.h"
#include "core/brdf_energy.h"
#include "core/diffuse_albedo.h"

#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {

unsigned createSheenAlbedoLut() {
    // Red and green: the two distinct sheen tables (core/brdf.cpp integrates them on the CPU, and
    // its lookup, the C++ twin, and the GPU read the same values). Ashikhmin's and Neubelt's
    // visibility are one function, so both read green.
    constexpr int N = brdf::kSheenLutSize;
    std::vector<float> rgba(size_t(N) * N * 4, 0.0f);
    for (int m = 0; m < 2; ++m) {
        const auto& t = brdf::sheenAlbedoLut(SheenModel(m));
        for (size_t i = 0; i < t.size(); ++i)
            rgba[i * 4 + size_t(m)] = t[i];
    }
    // Blue: Burley's diffuse albedo relative to Lambert's, for the image-based light's diffuse
    // term (core/diffuse_albedo.h), read at the same (n.v, roughness) as alpha.
    const auto& d = brdf::burleyAlbedoLut();
    for (size_t i = 0; i < d.size(); ++i)
        rgba[i * 4 + 2] = d[i];
    // Alpha: the base specular lobe's E for the direct light's multiple-scattering compensation
    // (core/brdf_energy.h), on the same grid; every pass that shades light binds this texture.
    const auto& e = brdf::specularAlbedoLut();
    for (size_t i = 0; i < e.size(); ++i)
        rgba[i * 4 + 3] = e[i];
    GLuint lut = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &lut);
    glTextureStorage2D(lut, 1, GL_RGBA32F, N, N);
    glTextureSubImage2D(lut, 0, 0, 0, N, N, GL_RGBA, GL_FLOAT, rgba.data());
    glTextureParameteri(lut, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(lut, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(lut, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(lut, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return lut;
}

} // namespace velvet::render
