#include "core/color_management.h"

#include "core/image.h"
#include "core/resources.h"

#include <OpenColorIO/OpenColorIO.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace OCIO = OCIO_NAMESPACE;

namespace velvet {

// ---------------------------------------------------------------------------------------------
// sRGB transfer functions, IEC 61966-2-1:1999 section 4.2 (thresholds 0.04045 / 0.0031308,
// slope 12.92, exponent 2.4, offset 0.055). Odd extension below zero so that negative
// scene-linear values (out-of-gamut colours) survive a round trip.

float srgbToLinear(float encoded) {
    const float a = std::fabs(encoded);
    const float l = a <= 0.04045f ? a / 12.92f : std::pow((a + 0.055f) / 1.055f, 2.4f);
    return std::copysign(l, encoded);
}

float linearToSrgb(float linear) {
    const float a = std::fabs(linear);
    const float e = a <= 0.0031308f ? a * 12.92f : 1.055f * std::pow(a, 1.0f / 2.4f) - 0.055f;
    return std::copysign(e, linear);
}

// ---------------------------------------------------------------------------------------------

struct ColorManagement::Impl {
    OCIO::ConstConfigRcPtr config;
    std::filesystem::path path;

    bool fail(std::string* error, const std::string& message) const {
        if (error)
            *error = message;
        return false;
    }

    /// "<config>: <what>" so every message says which config it is about.
    std::string where(const std::string& what) const { return path.string() + ": " + what; }

    /// The canonical name of a colour space, alias or role, or "" when unknown.
    std::string colorSpaceName(const std::string& name) const {
        if (!config || name.empty())
            return {};
        OCIO::ConstColorSpaceRcPtr cs = config->getColorSpace(name.c_str());
        return cs ? cs->getName() : std::string();
    }

    bool hasDisplay(const std::string& display) const {
        return config->getDisplayAllByName(display.c_str()) >= 0;
    }

    bool hasView(const std::string& display, const std::string& view) const {
        const int n = config->getNumViews(display.c_str());
        for (int i = 0; i < n; ++i)
            if (view == config->getView(display.c_str(), i))
                return true;
        return false;
    }

    /// Scene-linear -> exposure -> look -> display/view. The exposure is an ExposureContrast op
    /// in its linear style (out = in * 2^exposure), dynamic on the GPU so that changing it only
    /// updates a uniform.
    OCIO::ConstProcessorRcPtr displayProcessor(const DisplaySettings& s, bool dynamicExposure,
                                               std::string* error) const {
        if (!config) {
            fail(error, "no OpenColorIO config is loaded");
            return nullptr;
        }
        const std::string display = s.display.empty() ? config->getDefaultDisplay() : s.display;
        if (!hasDisplay(display)) {
            fail(error, where("unknown display \"" + display + "\""));
            return nullptr;
        }
        const std::string view = s.view.empty() ? config->getDefaultView(display.c_str()) : s.view;
        if (!hasView(display, view)) {
            fail(error, where("display \"" + display + "\" has no view \"" + view + "\""));
            return nullptr;
        }
        try {
            auto group = OCIO::GroupTransform::Create();
            auto ec = OCIO::ExposureContrastTransform::Create();
            ec->setStyle(OCIO::EXPOSURE_CONTRAST_LINEAR);
            ec->setExposure(s.exposure);
            if (dynamicExposure)
                ec->makeExposureDynamic();
            group->appendTransform(ec);
            if (!s.look.empty()) {
                auto look = OCIO::LookTransform::Create();
                look->setSrc(OCIO::ROLE_SCENE_LINEAR);
                look->setDst(OCIO::ROLE_SCENE_LINEAR);
                look->setLooks(s.look.c_str());
                group->appendTransform(look);
            }
            auto dvt = OCIO::DisplayViewTransform::Create();
            dvt->setSrc(OCIO::ROLE_SCENE_LINEAR);
            dvt->setDisplay(display.c_str());
            dvt->setView(view.c_str());
            group->appendTransform(dvt);
            return config->getProcessor(group);
        } catch (const OCIO::Exception& e) {
            fail(error,
                 where("display \"" + display + "\", view \"" + view + "\"" +
                       (s.look.empty() ? "" : ", look \"" + s.look + "\"") + ": " + e.what()));
            return nullptr;
        }
    }

    OCIO::ConstProcessorRcPtr conversion(const std::string& from, const std::string& to,
                                         std::string* error) const {
        if (!config) {
            fail(error, "no OpenColorIO config is loaded");
            return nullptr;
        }
        for (const std::string* name : {&from, &to}) {
            if (colorSpaceName(*name).empty()) {
                fail(error, where("unknown colour space \"" + *name + "\""));
                return nullptr;
            }
        }
        try {
            return config->getProcessor(from.c_str(), to.c_str());
        } catch (const OCIO::Exception& e) {
            fail(error, where("\"" + from + "\" -> \"" + to + "\": " + e.what()));
            return nullptr;
        }
    }

    /// OCIO's GLSL 4.0 shader, LUTs and uniforms of @p processor as plain data.
    std::optional<GpuDisplayTransform> extractGpu(const OCIO::ConstProcessorRcPtr& processor,
                                                  const GpuTransformOptions& options,
                                                  std::string* error) const;

    /// Runs @p processor on the image's colour channels. Grey images go through as RRR and come
    /// back as the luma of the result (the config's luma coefficients), so a neutral stays itself
    /// and a tinting view still gives a sensible grey. Alpha is never touched.
    bool apply(const OCIO::ConstProcessorRcPtr& processor, Image& image, std::string* error) const {
        if (image.empty())
            return true;
        if (image.channels < 1 || image.channels > 4 ||
            image.pixels.size() < size_t(image.width) * image.height * image.channels)
            return fail(error, "image has " + std::to_string(image.channels) +
                                   " channels or too few pixels for its size");
        try {
            OCIO::ConstCPUProcessorRcPtr cpu = processor->getDefaultCPUProcessor();
            if (cpu->isNoOp())
                return true;
            if (image.channels >= 3) {
                OCIO::PackedImageDesc desc(image.pixels.data(), image.width, image.height,
                                           image.channels);
                cpu->apply(desc);
                return true;
            }
            double luma[3];
            config->getDefaultLumaCoefs(luma);
            const size_t count = size_t(image.width) * image.height;
            std::vector<float> rgb(count * 3);
            for (size_t i = 0; i < count; ++i)
                std::fill_n(&rgb[i * 3], 3, image.pixels[i * image.channels]);
            OCIO::PackedImageDesc desc(rgb.data(), image.width, image.height, 3);
            cpu->apply(desc);
            for (size_t i = 0; i < count; ++i) {
                const float* p = &rgb[i * 3];
                image.pixels[i * image.channels] =
                    float(luma[0] * p[0] + luma[1] * p[1] + luma[2] * p[2]);
            }
            return true;
        } catch (const OCIO::Exception& e) {
            return fail(error, where(e.what()));
        }
    }
};

ColorManagement::ColorManagement() : m_impl(std::make_unique<Impl>()) {}
ColorManagement::~ColorManagement() = default;
ColorManagement::ColorManagement(ColorManagement&&) noexcept = default;
ColorManagement& ColorManagement::operator=(ColorManagement&&) noexcept = default;

std::filesystem::path ColorManagement::defaultConfigPath() {
    // Artists point every OCIO application at their studio config through $OCIO (the variable
    // OCIO's own GetCurrentConfig() reads); honour it before the shipped config.
    if (const char* env = std::getenv("OCIO"); env && *env)
        return env;
    return resources::path("ocio/config.ocio");
}

bool ColorManagement::loadDefault(std::string* error) {
    return loadFile(defaultConfigPath(), error);
}

bool ColorManagement::loadFile(const std::filesystem::path& file, std::string* error) {
    const std::string name = file.string();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        return m_impl->fail(error, name + ": cannot load OpenColorIO config: no such file");
    try {
        OCIO::ConstConfigRcPtr config = OCIO::Config::CreateFromFile(name.c_str());
        config->validate();
        m_impl->config = config;
        m_impl->path = file;
        return true;
    } catch (const OCIO::Exception& e) {
        return m_impl->fail(error, name + ": cannot load OpenColorIO config: " + e.what());
    }
}

bool ColorManagement::isLoaded() const {
    return m_impl->config != nullptr;
}
const std::filesystem::path& ColorManagement::configPath() const {
    return m_impl->path;
}

std::vector<std::string> ColorManagement::colorSpaces() const {
    std::vector<std::string> out;
    if (!m_impl->config)
        return out;
    const auto& c = *m_impl->config;
    const int n = c.getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ACTIVE);
    for (int i = 0; i < n; ++i)
        out.emplace_back(c.getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL,
                                                    OCIO::COLORSPACE_ACTIVE, i));
    return out;
}

std::vector<std::string> ColorManagement::displays() const {
    std::vector<std::string> out;
    if (!m_impl->config)
        return out;
    for (int i = 0; i < m_impl->config->getNumDisplays(); ++i)
        out.emplace_back(m_impl->config->getDisplay(i));
    return out;
}

std::vector<std::string> ColorManagement::views(const std::string& display) const {
    std::vector<std::string> out;
    if (!m_impl->config)
        return out;
    const int n = m_impl->config->getNumViews(display.c_str());
    for (int i = 0; i < n; ++i)
        out.emplace_back(m_impl->config->getView(display.c_str(), i));
    return out;
}

std::vector<std::string> ColorManagement::looks() const {
    std::vector<std::string> out;
    if (!m_impl->config)
        return out;
    for (int i = 0; i < m_impl->config->getNumLooks(); ++i)
        out.emplace_back(m_impl->config->getLookNameByIndex(i));
    return out;
}

std::string ColorManagement::defaultDisplay() const {
    return m_impl->config ? m_impl->config->getDefaultDisplay() : std::string();
}

std::string ColorManagement::defaultView(const std::string& display) const {
    return m_impl->config ? m_impl->config->getDefaultView(display.c_str()) : std::string();
}

std::string ColorManagement::roleColorSpace(const std::string& role) const {
    if (!m_impl->config || !m_impl->config->hasRole(role.c_str()))
        return {};
    return m_impl->colorSpaceName(role);
}

std::string ColorManagement::canonicalColorSpace(const std::string& nameOrAlias) const {
    return m_impl->colorSpaceName(nameOrAlias);
}

bool ColorManagement::isData(const std::string& colorSpace) const {
    if (!m_impl->config)
        return false;
    OCIO::ConstColorSpaceRcPtr cs = m_impl->config->getColorSpace(colorSpace.c_str());
    return cs && cs->isData();
}

std::string ColorManagement::colorSpaceForFile(const std::filesystem::path& file) const {
    if (!m_impl->config)
        return {};
    try {
        return m_impl->colorSpaceName(
            m_impl->config->getColorSpaceFromFilepath(file.string().c_str()));
    } catch (const OCIO::Exception&) {
        return {};
    }
}

bool ColorManagement::applyDisplay(Image& image, const DisplaySettings& settings,
                                   std::string* error) const {
    auto processor = m_impl->displayProcessor(settings, false, error);
    return processor && m_impl->apply(processor, image, error);
}

bool ColorManagement::applyDisplay(float rgb[3], const DisplaySettings& settings,
                                   std::string* error) const {
    auto processor = m_impl->displayProcessor(settings, false, error);
    if (!processor)
        return false;
    try {
        processor->getDefaultCPUProcessor()->applyRGB(rgb);
        return true;
    } catch (const OCIO::Exception& e) {
        return m_impl->fail(error, m_impl->where(e.what()));
    }
}

bool ColorManagement::toSceneLinear(Image& image, const std::string& inputSpace,
                                    std::string* error) const {
    return convert(image, inputSpace, OCIO::ROLE_SCENE_LINEAR, error);
}

bool ColorManagement::convert(Image& image, const std::string& from, const std::string& to,
                              std::string* error) const {
    auto processor = m_impl->conversion(from, to, error);
    return processor && m_impl->apply(processor, image, error);
}

namespace {

GpuLutTexture::Interpolation toInterpolation(OCIO::Interpolation i) {
    switch (i) {
    case OCIO::INTERP_NEAREST:
        return GpuLutTexture::Interpolation::Nearest;
    case OCIO::INTERP_TETRAHEDRAL:
        return GpuLutTexture::Interpolation::Tetrahedral;
    default:
        return GpuLutTexture::Interpolation::Linear;
    }
}

bool containsNoCase(std::string haystack, std::string needle) {
    auto lower = [](std::string& s) {
        std::transform(s.begin(), s.end(), s.begin(),
                       [](unsigned char c) { return std::tolower(c); });
    };
    lower(haystack);
    lower(needle);
    return haystack.find(needle) != std::string::npos;
}

} // namespace

std::string ColorManagement::encodingView(const std::string& display) const {
    const auto& config = m_impl->config;
    if (!config)
        return {};
    const std::string d = display.empty() ? config->getDefaultDisplay() : display;
    const std::string encoding = config->getDefaultViewTransformName();
    if (encoding.empty() || !m_impl->hasDisplay(d))
        return {};
    const int n = config->getNumViews(d.c_str());
    for (int i = 0; i < n; ++i) {
        const char* view = config->getView(d.c_str(), i);
        if (encoding == config->getDisplayViewTransformName(d.c_str(), view))
            return view;
    }
    return {};
}

std::optional<bool> ColorManagement::isEncodingView(const std::string& display,
                                                    const std::string& view,
                                                    std::string* error) const {
    const auto& config = m_impl->config;
    if (!config) {
        m_impl->fail(error, "no OpenColorIO config is loaded");
        return std::nullopt;
    }
    const std::string d = display.empty() ? config->getDefaultDisplay() : display;
    if (!m_impl->hasDisplay(d)) {
        m_impl->fail(error, m_impl->where("unknown display \"" + d + "\""));
        return std::nullopt;
    }
    const std::string v = view.empty() ? config->getDefaultView(d.c_str()) : view;
    if (!m_impl->hasView(d, v)) {
        m_impl->fail(error, m_impl->where("display \"" + d + "\" has no view \"" + v + "\""));
        return std::nullopt;
    }
    // Every view whose own view transform is the default one encodes, not only the first
    // (encodingView()); a view without a view transform (Raw: a colour space) never does.
    const std::string encoding = config->getDefaultViewTransformName();
    return !encoding.empty() &&
           encoding == config->getDisplayViewTransformName(d.c_str(), v.c_str());
}

std::optional<GpuDisplayTransform>
ColorManagement::gpuDisplayEncoding(const std::string& display, std::string* error,
                                    const GpuTransformOptions& options) const {
    const std::string view = encodingView(display);
    if (view.empty()) {
        if (!isEncodingView(display, {}, error))
            return std::nullopt; // unknown display (or no config): the message is set
        // Not an error: a config without an encoding view (OCIO v1 has no view transforms at
        // all) still renders, encoded by the caller's own sRGB curve.
        const auto& config = m_impl->config;
        const std::string d = display.empty() ? config->getDefaultDisplay() : display;
        const std::string transform = config->getDefaultViewTransformName();
        GpuDisplayTransform fallback;
        fallback.fallbackWarning = m_impl->where(
            "display \"" + d + "\" has no view using the default view transform" +
            (transform.empty() ? " (the config names none: an OCIO v1 config, or v2 without "
                                 "default_view_transform)"
                               : " \"" + transform + "\"") +
            "; the built-in curves are encoded with the hand-written sRGB curve instead of OCIO");
        return fallback;
    }
    auto processor = m_impl->displayProcessor({display, view, {}, 0.0f}, false, error);
    if (!processor)
        return std::nullopt;
    return m_impl->extractGpu(processor, options, error);
}

std::optional<GpuDisplayTransform>
ColorManagement::gpuDisplayTransform(const DisplaySettings& settings, std::string* error,
                                     const GpuTransformOptions& options) const {
    auto processor = m_impl->displayProcessor(settings, true, error);
    if (!processor)
        return std::nullopt;
    return m_impl->extractGpu(processor, options, error);
}

std::optional<GpuDisplayTransform>
ColorManagement::Impl::extractGpu(const OCIO::ConstProcessorRcPtr& processor,
                                  const GpuTransformOptions& options, std::string* error) const {
    try {
        // GLSL 4.0 is the newest language OCIO 2.1 writes; the renderer's GLSL 4.50 core accepts
        // it. The default GPU processor is exact (analytic ops, LUTs only where the transform
        // itself has them), unlike the legacy one that bakes everything into a 3D LUT.
        OCIO::GpuShaderDescRcPtr desc = OCIO::GpuShaderDesc::CreateShaderDesc();
        desc->setLanguage(OCIO::GPU_LANGUAGE_GLSL_4_0);
        desc->setFunctionName(options.functionName.c_str());
        desc->setResourcePrefix(options.resourcePrefix.c_str());
        processor->getDefaultGPUProcessor()->extractGpuShaderInfo(desc);

        GpuDisplayTransform out;
        out.glsl = desc->getShaderText();
        out.functionName = options.functionName;
        out.cacheId = desc->getCacheID();

        for (unsigned i = 0; i < desc->getNumTextures(); ++i) {
            const char* textureName = nullptr;
            const char* samplerName = nullptr;
            unsigned width = 0, height = 0;
            OCIO::GpuShaderDesc::TextureType channel = OCIO::GpuShaderDesc::TEXTURE_RGB_CHANNEL;
            OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
            desc->getTexture(i, textureName, samplerName, width, height, channel, interpolation);
            const float* values = nullptr;
            desc->getTextureValues(i, values);
            GpuLutTexture t;
            t.textureName = textureName;
            t.samplerName = samplerName;
            // OCIO 2.1 declares a sampler1D when the height is 1 and a sampler2D otherwise (long
            // 1D LUTs are folded into rows of at most getTextureMaxWidth() texels).
            t.dimensions = height > 1 ? 2 : 1;
            t.width = int(width);
            t.height = int(height);
            t.channels = channel == OCIO::GpuShaderDesc::TEXTURE_RED_CHANNEL ? 1 : 3;
            t.interpolation = toInterpolation(interpolation);
            t.values.assign(values, values + size_t(width) * height * t.channels);
            out.textures.push_back(std::move(t));
        }
        for (unsigned i = 0; i < desc->getNum3DTextures(); ++i) {
            const char* textureName = nullptr;
            const char* samplerName = nullptr;
            unsigned edge = 0;
            OCIO::Interpolation interpolation = OCIO::INTERP_LINEAR;
            desc->get3DTexture(i, textureName, samplerName, edge, interpolation);
            const float* values = nullptr;
            desc->get3DTextureValues(i, values);
            GpuLutTexture t;
            t.textureName = textureName;
            t.samplerName = samplerName;
            t.dimensions = 3;
            t.width = t.height = t.depth = int(edge);
            t.channels = 3;
            t.interpolation = toInterpolation(interpolation);
            t.values.assign(values, values + size_t(edge) * edge * edge * 3);
            out.textures.push_back(std::move(t));
        }
        for (unsigned i = 0; i < desc->getNumUniforms(); ++i) {
            OCIO::GpuShaderDesc::UniformData data;
            GpuUniform u;
            u.name = desc->getUniform(i, data);
            switch (data.m_type) {
            case OCIO::UNIFORM_DOUBLE:
                u.type = GpuUniform::Type::Float;
                u.floats = {float(data.m_getDouble())};
                break;
            case OCIO::UNIFORM_BOOL:
                u.type = GpuUniform::Type::Bool;
                u.floats = {data.m_getBool() ? 1.0f : 0.0f};
                break;
            case OCIO::UNIFORM_FLOAT3: {
                u.type = GpuUniform::Type::Float3;
                const OCIO::Float3& f = data.m_getFloat3();
                u.floats = {f[0], f[1], f[2]};
                break;
            }
            case OCIO::UNIFORM_VECTOR_FLOAT: {
                u.type = GpuUniform::Type::FloatArray;
                const int n = data.m_vectorFloat.m_getSize();
                const float* v = data.m_vectorFloat.m_getVector();
                u.floats.assign(v, v + n);
                break;
            }
            case OCIO::UNIFORM_VECTOR_INT: {
                u.type = GpuUniform::Type::IntArray;
                const int n = data.m_vectorInt.m_getSize();
                const int* v = data.m_vectorInt.m_getVector();
                u.ints.assign(v, v + n);
                break;
            }
            default:
                continue;
            }
            // The only dynamic property Velvet makes is the exposure of its ExposureContrast op;
            // OCIO names that uniform "<prefix>_exposureVal" (a double, in stops).
            u.isExposure = u.type == GpuUniform::Type::Float && containsNoCase(u.name, "exposure");
            out.uniforms.push_back(std::move(u));
        }
        return out;
    } catch (const OCIO::Exception& e) {
        fail(error, where(std::string("GPU shader: ") + e.what()));
        return std::nullopt;
    }
}

} // namespace velvet
