#include "render/texture_set.h"

#include "core/color_management.h"
#include "core/image_ops.h"
#include "core/texture_cache.h"
#include "render/material_table.h"
#include "render/shader_program.h"

#include <cmath>
#include <epoxy/gl.h>
#include <glm/common.hpp>
#include <glm/trigonometric.hpp>

namespace velvet::render {

struct TextureSet::Slot {
    TextureRef ref;
    std::uint64_t generation = 0;
    GLuint texture = 0;
    int width = 0, height = 0;
    bool valid = false;                       ///< a texture is uploaded and in use
    bool useRegion = false;                   ///< an atlas region is in use
    glm::vec4 region{1.0f, 1.0f, 0.0f, 0.0f}; ///< xy: size / atlas size, zw: offset / atlas size
    glm::vec4 mean{1.0f};                     ///< mean RGBA over the image or region
};

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

namespace {

// Uniform locations of common_material_textures.glsl: uTexRegion takes 1 .. kTextureSlotCount.
constexpr int kUvLinearLocation = 1 + kTextureSlotCount;
constexpr int kUvOffsetLocation = kUvLinearLocation + kTextureSlotCount;
static_assert(kUvLinearLocation == 14 && kUvOffsetLocation == 27, "the GLSL's literal locations");

bool bit(std::uint32_t mask, TextureSlot s) {
    return (mask >> int(s)) & 1u;
}

} // namespace

TextureSet::TextureSet() : m_slots(std::make_unique<std::array<Slot, kTextureSlotCount>>()) {}

TextureSet::~TextureSet() {
    for (Slot& s : *m_slots)
        if (s.texture)
            glDeleteTextures(1, &s.texture);
}

void TextureSet::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    m_colorManagement = std::move(colorManagement);
    m_cache.reset();
    for (Slot& s : *m_slots)
        s.generation = 0; // reload from the new cache at the next setMaterial
}

TextureCache& TextureSet::cache() {
    if (!m_cache) {
        if (!m_colorManagement) {
            auto loaded = std::make_shared<ColorManagement>();
            std::string error;
            loaded->loadDefault(&error); // a failure shows up as each texture's problem
            m_colorManagement = std::move(loaded);
        }
        // Larger images are downscaled by the cache with a warning (fitToLimit).
        GLint maxSide = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
        TextureCacheOptions options;
        options.maxTextureSide = maxSide;
        m_cache = std::make_unique<TextureCache>(*m_colorManagement, options);
    }
    return *m_cache;
}

void TextureSet::setMaterial(const Material& material, Problems* problems) {
    for (int i = 0; i < kTextureSlotCount; ++i) {
        Slot& s = (*m_slots)[size_t(i)];
        const TextureRef& ref = material.texture(TextureSlot(i));
        if (!(ref == s.ref)) {
            // A new UV transform is a uniform (bind()), not a new image: no re-upload.
            TextureRef a = ref, b = s.ref;
            a.uv = b.uv = UvTransform{};
            if (!(a == b))
                s.generation = 0;
            s.ref = ref;
        }
        refresh(i, problems);
    }
}

bool TextureSet::poll() {
    if (!m_cache || m_cache->poll() == 0)
        return false;
    for (int i = 0; i < kTextureSlotCount; ++i)
        if (!(*m_slots)[size_t(i)].ref.empty())
            refresh(i, nullptr);
    return true;
}

void TextureSet::refresh(int index, Problems* problems) {
    Slot& s = (*m_slots)[size_t(index)];
    const TextureSlot slot = TextureSlot(index);
    if (s.ref.empty()) {
        s.valid = false;
        return;
    }
    const Texture t = cache().get(s.ref, slot);
    const std::string where = "textures." + std::string(textureSlotMeta(slot).id);
    if (problems)
        for (Problem p : t.problems) {
            if (p.path.empty())
                p.path = where;
            problems->items.push_back(std::move(p));
        }
    if (!t.image || t.image->empty()) {
        s.valid = false;
        s.generation = t.generation;
        return;
    }
    if (s.valid && t.generation == s.generation)
        return;
    const Image& image = *t.image;
    s.generation = t.generation;

    // Upload as RGBA16F (scene-linear colour needs more than 8 bits in the darks) with a full
    // mip chain filtered on the CPU (uploadMipChain).
    if (!s.texture || s.width != image.width || s.height != image.height) {
        if (s.texture)
            glDeleteTextures(1, &s.texture);
        glCreateTextures(GL_TEXTURE_2D, 1, &s.texture);
        glTextureStorage2D(s.texture, mipLevelCount(image.width, image.height), GL_RGBA16F,
                           image.width, image.height);
        glTextureParameteri(s.texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        glTextureParameteri(s.texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(s.texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(s.texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
        s.width = image.width;
        s.height = image.height;
        ++m_allocations;
    }
    // Row 0 (the image's top) goes to t = 0, matching glTF's UV space (v = 0 at the top).
    uploadMipChain(s.texture, image);
    s.valid = true;

    // Atlas region (pixels, top-left origin) -> UV scale and offset; the shader keeps samples
    // half a texel inside it so bilinear filtering never reads a neighbour.
    AtlasRegion r{0, 0, image.width, image.height};
    s.useRegion = false;
    if (s.ref.useRegion) {
        const AtlasRegion& q = s.ref.region;
        if (q.width > 0 && q.height > 0 && q.x >= 0 && q.y >= 0 && q.x + q.width <= image.width &&
            q.y + q.height <= image.height) {
            r = q;
            s.useRegion = true;
        } else if (problems) {
            problems->warning(s.ref.file, where + ".region",
                              "atlas region lies outside the " + std::to_string(image.width) + "x" +
                                  std::to_string(image.height) + " image; the whole image is used");
        }
    }
    s.region = glm::vec4(float(r.width) / float(image.width), float(r.height) / float(image.height),
                         float(r.x) / float(image.width), float(r.y) / float(image.height));
    glm::dvec4 sum(0.0);
    for (int y = r.y; y < r.y + r.height; ++y)
        for (int x = r.x; x < r.x + r.width; ++x)
            sum += glm::dvec4(image.rgba(x, y));
    s.mean = glm::vec4(sum / double(std::max(r.width * r.height, 1)));
}

void TextureSet::applyTo(GpuMaterial& g) const {
    std::uint32_t present = 0, regions = 0;
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const Slot& s = (*m_slots)[size_t(i)];
        if (s.valid)
            present |= 1u << i;
        if (s.valid && s.useRegion)
            regions |= 1u << i;
    }
    g.terms2.y = int(present);
    g.terms2.z = int(regions);
    const auto mean = [&](TextureSlot slot) { return (*m_slots)[size_t(slot)].mean; };
    // Slots the G-buffer cannot carry per pixel: their mean, times the parameter (glTF: factor
    // times texture), in the material table.
    if (bit(present, TextureSlot::Clearcoat))
        g.clearcoat.x *= mean(TextureSlot::Clearcoat).r;
    if (bit(present, TextureSlot::ClearcoatRoughness))
        g.clearcoat.y *= mean(TextureSlot::ClearcoatRoughness).g;
    if (bit(present, TextureSlot::SheenColor))
        g.sheenColorRoughness *= glm::vec4(glm::vec3(mean(TextureSlot::SheenColor)), 1.0f);
    if (bit(present, TextureSlot::SheenRoughness))
        g.sheenColorRoughness.a *= mean(TextureSlot::SheenRoughness).a;
    if (bit(present, TextureSlot::Specular))
        g.specularColorWeight.a *= mean(TextureSlot::Specular).a;
    if (bit(present, TextureSlot::SpecularColor))
        g.specularColorWeight *= glm::vec4(glm::vec3(mean(TextureSlot::SpecularColor)), 1.0f);
    if (bit(present, TextureSlot::SpecRoughMetal))
        g.specularColorWeight.a *= mean(TextureSlot::SpecRoughMetal).r;
}

UvTransformMatrix uvTransformMatrix(const UvTransform& uv) {
    // uv' = R (S uv) + o, R = [c -s; s c] (the Image node's velvetGraphUvTransform): columns of
    // R S are (c sx, s sx) and (-s sy, c sy).
    const float r = glm::radians(uv.rotation);
    const float c = std::cos(r), s = std::sin(r);
    return {glm::vec4(c * uv.scale.x, s * uv.scale.x, -s * uv.scale.y, c * uv.scale.y), uv.offset};
}

bool slotIsPerPixel(TextureSlot slot) {
    switch (slot) {
    case TextureSlot::BaseColor:
    case TextureSlot::MetallicRoughness:
    case TextureSlot::SpecRoughMetal: // G roughness and B metallic per pixel; R specular: mean
    case TextureSlot::Normal:
    case TextureSlot::Occlusion:
    case TextureSlot::Emissive: // drawn into the HDR target by the geometry pass, no G-buffer byte
        return true;
    default:
        return false;
    }
}

void TextureSet::bind(unsigned program) const {
    glm::vec4 regions[kTextureSlotCount];
    glm::vec4 uvLinear[kTextureSlotCount];
    glm::vec2 uvOffset[kTextureSlotCount];
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const Slot& s = (*m_slots)[size_t(i)];
        regions[i] = s.region;
        const UvTransformMatrix m = uvTransformMatrix(s.ref.uv);
        uvLinear[i] = m.linear;
        uvOffset[i] = m.offset;
        if (s.valid)
            glBindTextureUnit(GLuint(binding::kMaterialTexFirst + i), s.texture);
    }
    glProgramUniform4fv(program, 1, kTextureSlotCount, &regions[0].x);
    glProgramUniform4fv(program, kUvLinearLocation, kTextureSlotCount, &uvLinear[0].x);
    glProgramUniform2fv(program, kUvOffsetLocation, kTextureSlotCount, &uvOffset[0].x);
}

void TextureSet::unbind() const {
    for (int i = 0; i < kTextureSlotCount; ++i)
        glBindTextureUnit(GLuint(binding::kMaterialTexFirst + i), 0);
}

unsigned TextureSet::texture(TextureSlot slot) const {
    const Slot& s = (*m_slots)[size_t(slot)];
    return s.valid ? s.texture : 0u;
}

} // namespace velvet::render
