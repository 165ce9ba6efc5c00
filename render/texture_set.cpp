#include "render/texture_set.h"

#include "core/atlas_packing.h"
#include "core/color_management.h"
#include "core/mip_cache.h"
#include "core/mip_texture.h"
#include "core/texture_cache.h"
#include "core/texture_loader.h"
#include "render/lobe_channels.h"
#include "render/material_table.h"
#include "render/shader_program.h"
#include "render/texture_set_entry.h"
#include "render/texture_storage_thread.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <epoxy/gl.h>
#include <glm/common.hpp>
#include <glm/trigonometric.hpp>
#include <utility>

namespace velvet::render {

struct TextureSet::Slot {
    TextureRef ref;
    std::string key;                          ///< the entry it samples ("" when empty)
    std::uint64_t generation = 0;             ///< the entry's generation region and mean are of
    bool valid = false;                       ///< some level of the texture is on the GPU
    bool useRegion = false;                   ///< an atlas region is in use
    glm::vec4 region{1.0f, 1.0f, 0.0f, 0.0f}; ///< xy: size / atlas size, zw: offset / atlas size
    glm::vec4 mean{1.0f};                     ///< mean RGBA over the image or region
};

namespace {

// Uniform locations of common_material_textures.glsl (generated: render_bindings.glsl).
constexpr int kUvLinearLocation = textureUvLinearLocation();
constexpr int kUvOffsetLocation = textureUvOffsetLocation();

bool bit(std::uint32_t mask, TextureSlot s) {
    return (mask >> int(s)) & 1u;
}

std::string keyOf(const std::filesystem::path& file, const std::string& colorSpace,
                  TextureUsage usage) {
    return file.string() + "\n" + colorSpace +
           (usage == TextureUsage::Color ? "\ncolor" : "\ndata");
}

double msSince(std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

} // namespace

TextureSet::TextureSet()
    : m_slots(std::make_unique<std::array<Slot, kTextureSlotCount>>()),
      m_entries(std::make_unique<std::map<std::string, Entry>>()) {}

TextureSet::~TextureSet() {
    dropEntries();
}

void TextureSet::dropEntries() {
    for (auto& [key, e] : *m_entries)
        releaseTexture(e);
    m_entries->clear();
    for (Slot& s : *m_slots)
        s = Slot{};
    m_loader.reset();
}

void TextureSet::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    dropEntries(); // the loader refers to the old config: gone before it
    m_colorManagement = std::move(colorManagement);
    m_cache.reset();
}

void TextureSet::setAsync(bool async) {
    if (async == m_async)
        return;
    dropEntries();
    m_async = async;
}

void TextureSet::setCacheDir(std::filesystem::path dir) {
    dropEntries();
    m_cacheDir = std::move(dir);
}

const ColorManagement& TextureSet::colorManagement() {
    if (!m_colorManagement) {
        auto loaded = std::make_shared<ColorManagement>();
        std::string error;
        loaded->loadDefault(&error); // a failure shows up as each texture's problem
        m_colorManagement = std::move(loaded);
    }
    if (!m_maxSide) {
        GLint maxSide = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSide);
        m_maxSide = maxSide;
    }
    return *m_colorManagement;
}

TextureCache& TextureSet::cache() {
    if (!m_cache) {
        const ColorManagement& cm = colorManagement();
        // Larger images are downscaled by the cache with a warning (fitToLimit).
        TextureCacheOptions options;
        options.maxTextureSide = m_maxSide;
        m_cache = std::make_unique<TextureCache>(cm, options);
    }
    return *m_cache;
}

TextureLoader& TextureSet::loader() {
    if (!m_loader) {
        const ColorManagement& cm = colorManagement();
        MipLoadOptions options;
        options.maxTextureSide = m_maxSide;
        options.cacheDir = m_cacheDir;
        // The editor streams a large level 0 from the cache entry in bands (upload());
        // VELVET_TEXTURE_STREAMING=0 holds it in memory instead (`velvet bench --textures`
        // measures both).
        const char* streaming = std::getenv("VELVET_TEXTURE_STREAMING");
        options.leaveFinestInCache = m_async && !(streaming && std::string(streaming) == "0");
        m_loader = std::make_unique<TextureLoader>(cm, options, m_async);
    }
    return *m_loader;
}

void TextureSet::startLoad(Entry& e, bool leaveFinestInCache) {
    e.job = loader().request(e.file, e.colorSpace, e.usage, leaveFinestInCache);
}

void TextureSet::setMaterial(const Material& material, Problems* problems) {
    for (int i = 0; i < kTextureSlotCount; ++i) {
        Slot& s = (*m_slots)[size_t(i)];
        const TextureSlot slot = TextureSlot(i);
        const TextureRef& ref = material.texture(slot);
        if (ref.empty()) {
            s = Slot{};
            continue;
        }
        const TextureUsage usage =
            textureSlotMeta(slot).isColor ? TextureUsage::Color : TextureUsage::Data;
        const std::filesystem::path file = std::filesystem::path(ref.file).lexically_normal();
        const std::string space =
            resolveTextureColorSpace(colorManagement(), file, usage, ref.colorSpace);
        const std::string key = keyOf(file, space, usage);
        // A new UV transform is a uniform (bind()), not a new image: the slot keeps its texture.
        TextureRef withoutUv = ref, oldWithoutUv = s.ref;
        withoutUv.uv = oldWithoutUv.uv = UvTransform{};
        if (!(withoutUv == oldWithoutUv) || key != s.key) {
            s = Slot{};
            s.ref = ref;
            s.key = key;
        } else {
            s.ref = ref;
        }
        auto [it, fresh] = m_entries->try_emplace(key);
        if (fresh) {
            Entry& e = it->second;
            e.file = file;
            e.colorSpace = space;
            e.usage = usage;
            e.stamp = textureFileStamp(file);
            startLoad(e);
        }
    }
    // Entries no slot names any more: their GL texture goes now.
    for (auto it = m_entries->begin(); it != m_entries->end();) {
        bool used = false;
        for (const Slot& s : *m_slots)
            used = used || s.key == it->first;
        if (used) {
            ++it;
            continue;
        }
        releaseTexture(it->second);
        it = m_entries->erase(it);
    }
    if (!m_async) {
        finish();
        // Synchronously the problems of every slot's file come with each call, as they did.
        if (problems)
            for (const auto& [key, e] : *m_entries)
                reportProblems(e, *problems);
        updateSlots(problems);
        return;
    }
    updateSlots(nullptr); // a slot whose texture is already on the GPU draws it at once
}

void TextureSet::reportProblems(const Entry& e, Problems& into) const {
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const Slot& s = (*m_slots)[size_t(i)];
        if (s.key.empty() || s.key != keyOf(e.file, e.colorSpace, e.usage))
            continue;
        for (Problem p : e.problems) {
            if (p.path.empty())
                p.path = "textures." + std::string(textureSlotMeta(TextureSlot(i)).id);
            into.items.push_back(std::move(p));
        }
    }
}

bool TextureSet::updateSlots(Problems* problems) {
    bool changed = false;
    for (Slot& s : *m_slots) {
        if (s.key.empty())
            continue;
        const auto it = m_entries->find(s.key);
        const Entry* e = it == m_entries->end() ? nullptr : &it->second;
        const bool valid = e && e->finest >= 0;
        if (valid != s.valid)
            changed = true;
        s.valid = valid;
        if (!valid || s.generation == e->generation)
            continue;
        s.generation = e->generation;
        changed = true;
        // Atlas region (pixels, top-left origin) -> UV scale and offset; the shader keeps
        // samples half a texel inside it so bilinear filtering never reads a neighbour.
        const int w = e->width, h = e->height;
        AtlasRegion r{0, 0, w, h};
        s.useRegion = false;
        if (s.ref.useRegion) {
            const AtlasRegion& q = s.ref.region;
            if (q.width > 0 && q.height > 0 && q.x >= 0 && q.y >= 0 && q.x + q.width <= w &&
                q.y + q.height <= h) {
                r = q;
                s.useRegion = true;
            } else if (problems) {
                problems->warning(
                    s.ref.file,
                    "textures." +
                        std::string(textureSlotMeta(TextureSlot(int(&s - m_slots->data()))).id) +
                        ".region",
                    "atlas region lies outside the " + std::to_string(w) + "x" + std::to_string(h) +
                        " image; the whole image is used");
            }
        }
        s.region = glm::vec4(float(r.width) / float(w), float(r.height) / float(h),
                             float(r.x) / float(w), float(r.y) / float(h));
        if (!s.useRegion || e->meanLevel.empty()) {
            s.mean = e->mean;
            continue;
        }
        // The region's mean from a level of at most 256 px (exact for maps that small; for a
        // larger atlas, the mean of the filtered level over the region's footprint in it).
        s.mean = regionMean(e->meanLevel, r, w, h);
    }
    return changed;
}

bool TextureSet::poll() {
    if (m_entries->empty())
        return false;
    const auto start = std::chrono::steady_clock::now();
    Problems* sink = m_async ? &m_problems : nullptr;
    // Files changed on disk (edited in another program): load again; the old levels keep
    // drawing until the new ones arrive.
    for (auto& [key, e] : *m_entries) {
        const TextureFileStamp stamp = textureFileStamp(e.file);
        if (!(stamp == e.stamp)) {
            e.stamp = stamp;
            startLoad(e);
        }
    }
    bool changed = false;
    for (auto& [key, e] : *m_entries)
        changed = takeFinished(e, sink) || changed;
    std::uint64_t budget = m_async ? m_budget : ~std::uint64_t(0);
    std::uint64_t spent = 0;
    bool visible = false, coarse = false;
    for (auto& [key, e] : *m_entries) {
        if (spent < budget)
            spent += upload(e, budget - spent, visible);
        coarse = coarse || (e.finest > 0);
    }
    if (spent > 0) {
        const double ms = msSince(start);
        ++m_stats.frames;
        m_stats.bytes += spent;
        m_stats.worstFrameBytes = std::max(m_stats.worstFrameBytes, spent);
        m_stats.worstFrameMs = std::max(m_stats.worstFrameMs, ms);
        if (coarse)
            ++m_stats.proxyFrames;
    }
    if (m_loader)
        for (Problem& p : m_loader->takeLateProblems())
            m_problems.items.push_back(std::move(p));
    changed = updateSlots(sink) || changed || visible;
    return changed;
}

void TextureSet::finish() {
    for (auto& [key, e] : *m_entries)
        if (e.job)
            loader().wait(*e.job);
    const bool async = m_async;
    m_async = false; // one unbounded poll
    for (auto& [key, e] : *m_entries) {
        takeFinished(e, async ? &m_problems : nullptr);
        bool visible = false;
        upload(e, ~std::uint64_t(0), visible);
    }
    m_async = async;
    updateSlots(async ? &m_problems : nullptr);
}

Problems TextureSet::takeProblems() {
    return std::exchange(m_problems, Problems{});
}

TextureLoadProgress TextureSet::progress() const {
    TextureLoadProgress p;
    std::uint64_t total = 0, done = 0;
    for (const auto& [key, e] : *m_entries) {
        ++p.total;
        const bool complete = !e.job && !e.data;
        if (complete)
            continue;
        ++p.loading;
        // A load not yet finished counts as nothing done of a size guessed from the last one.
        total += std::max<std::uint64_t>(e.bytesTotal, 1);
        done += e.job ? 0 : e.bytesDone;
    }
    p.fraction = total ? double(done) / double(total) : 1.0;
    return p;
}

std::uint64_t TextureSet::decodeCount() const {
    return m_loader ? m_loader->decodeCount() : 0;
}

std::uint64_t TextureSet::cacheHits() const {
    return m_loader ? m_loader->cacheHits() : 0;
}

std::uint32_t TextureSet::presentSlots() const {
    std::uint32_t present = 0;
    for (int i = 0; i < kTextureSlotCount; ++i)
        if ((*m_slots)[size_t(i)].valid)
            present |= 1u << i;
    return present;
}

void TextureSet::applyTo(GpuMaterial& g, const LobeChannelMap& lobes) const {
    std::uint32_t regions = 0;
    for (int i = 0; i < kTextureSlotCount; ++i) {
        const Slot& s = (*m_slots)[size_t(i)];
        if (s.valid && s.useRegion)
            regions |= 1u << i;
    }
    const std::uint32_t present = presentSlots();
    g.terms2.y = int(present);
    g.terms2.z = int(regions);
    const auto mean = [&](TextureSlot slot) { return (*m_slots)[size_t(slot)].mean; };
    // A lobe value without a G-buffer channel (the compact layout, or more varying values than
    // channels: render/lobe_channels.h) takes its texture's mean, times the parameter (glTF:
    // factor times texture), from the material table. The geometry pass samples only the slots
    // of the values it writes per pixel.
    const auto perMaterial = [&](TextureSlot slot, LobeValue value) {
        return bit(present, slot) && !lobes.perPixel(value);
    };
    if (perMaterial(TextureSlot::Clearcoat, LobeValue::Clearcoat))
        g.clearcoat.x *= mean(TextureSlot::Clearcoat).r;
    if (perMaterial(TextureSlot::ClearcoatRoughness, LobeValue::ClearcoatRoughness))
        g.clearcoat.y *= mean(TextureSlot::ClearcoatRoughness).g;
    if (perMaterial(TextureSlot::SheenColor, LobeValue::SheenColor))
        g.sheenColorRoughness *= glm::vec4(glm::vec3(mean(TextureSlot::SheenColor)), 1.0f);
    if (perMaterial(TextureSlot::SheenRoughness, LobeValue::SheenRoughness))
        g.sheenColorRoughness.a *= mean(TextureSlot::SheenRoughness).a;
    if (perMaterial(TextureSlot::Specular, LobeValue::SpecularWeight))
        g.specularColorWeight.a *= mean(TextureSlot::Specular).a;
    if (perMaterial(TextureSlot::SpecularColor, LobeValue::SpecularColor))
        g.specularColorWeight *= glm::vec4(glm::vec3(mean(TextureSlot::SpecularColor)), 1.0f);
    if (perMaterial(TextureSlot::SpecRoughMetal, LobeValue::SpecularWeight))
        g.specularColorWeight.a *= mean(TextureSlot::SpecRoughMetal).r;
    if (perMaterial(TextureSlot::Anisotropy, LobeValue::Anisotropy))
        g.sheenWeightAnisotropy.y *= mean(TextureSlot::Anisotropy).b;
}

UvTransformMatrix uvTransformMatrix(const UvTransform& uv) {
    // uv' = R (S uv) + o, R = [c -s; s c] (the Image node's velvetGraphUvTransform): columns of
    // R S are (c sx, s sx) and (-s sy, c sy).
    const float r = glm::radians(uv.rotation);
    const float c = std::cos(r), s = std::sin(r);
    return {glm::vec4(c * uv.scale.x, s * uv.scale.x, -s * uv.scale.y, c * uv.scale.y), uv.offset};
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
            glBindTextureUnit(GLuint(binding::kMaterialTexFirst + i), m_entries->at(s.key).texture);
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
    return s.valid ? m_entries->at(s.key).texture : 0u;
}

int TextureSet::finestLevel(TextureSlot slot) const {
    const Slot& s = (*m_slots)[size_t(slot)];
    return s.valid ? m_entries->at(s.key).finest : -1;
}

} // namespace velvet::render
