#pragma once
/// @file color_management.h
/// Colour management through OpenColorIO, behind a pimpl: OCIO headers appear only in
/// color_management.cpp. Velvet works in scene-linear Rec.709 (the config's `scene_linear` role);
/// textures are converted into it from their input colour space and the viewport is shown through
/// a display/view transform. docs/color-management.md describes the shipped config.
///
/// No GL here: the GPU display transform is handed to render/ as plain data (GLSL text, LUT
/// textures, uniforms) that it uploads itself.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace velvet {

struct Image;

/// @name sRGB transfer functions (IEC 61966-2-1:1999, section 4.2), for colour pickers
/// Pure functions on one channel, independent of any OCIO config. Inputs outside [0, 1] are
/// extended by odd symmetry (sign(x) * f(|x|)), as scene-linear values may be negative.
/// @{
/// sRGB-encoded value -> linear (the EOTF).
float srgbToLinear(float encoded);
/// Linear value -> sRGB-encoded (the inverse EOTF).
float linearToSrgb(float linear);
/// @}

/// What the viewport shows: display, view, optional look, exposure. Empty names mean the
/// config's default display, that display's default view, and no look.
struct DisplaySettings {
    std::string display;
    std::string view;
    std::string look;      ///< one look name (or OCIO's comma list); empty: none
    float exposure = 0.0f; ///< in stops (EV), applied in scene-linear: value * 2^exposure
    bool operator==(const DisplaySettings&) const = default;
};

/// One LUT texture of a GPU display transform, ready to upload as it is.
struct GpuLutTexture {
    enum class Interpolation { Nearest, Linear, Tetrahedral };
    std::string textureName; ///< OCIO's texture name (for debugging and caching)
    std::string samplerName; ///< the sampler uniform declared in the GLSL text
    int dimensions = 1;      ///< 1: sampler1D (height 1), 2: sampler2D, 3: sampler3D
    int width = 0;           ///< texels; for 3D the edge length
    int height = 1;          ///< 1 for 1D LUTs; for 3D the edge length
    int depth = 1;           ///< 1 except for 3D (edge length)
    int channels = 3;        ///< 1 (red only, e.g. GL_R32F) or 3 (GL_RGB32F)
    /// Filter to set: GL_NEAREST for Nearest, GL_LINEAR otherwise (as OCIO's own OpenGL helper
    /// does; Tetrahedral LUTs are blended by the GLSL, which samples at texel centres).
    Interpolation interpolation = Interpolation::Linear;
    std::vector<float> values; ///< width * height * depth * channels floats, row-major, red fastest
};

/// One uniform of a GPU display transform. The values are the ones at extraction time; the
/// exposure uniform (isExposure) should be refreshed from DisplaySettings::exposure each frame
/// without rebuilding the shader.
struct GpuUniform {
    enum class Type { Float, Bool, Float3, FloatArray, IntArray };
    std::string name; ///< the uniform's name in the GLSL text
    Type type = Type::Float;
    std::vector<float> floats; ///< Float / Bool (0 or 1) / Float3 / FloatArray values
    std::vector<int> ints;     ///< IntArray values
    bool isExposure = false;   ///< the dynamic exposure (stops)
};

/// The display transform as OCIO's own GPU shader, for the tone-mapping stage of the post chain.
/// The GLSL text (GLSL 4.0) defines `vec4 <functionName>(vec4 inPixel)` taking scene-linear RGBA
/// and returning display-encoded RGBA, plus the sampler and uniform declarations it needs.
struct GpuDisplayTransform {
    std::string glsl;
    std::string functionName;
    std::string cacheId; ///< OCIO's cache id of the shader: same id, same program
    std::vector<GpuLutTexture> textures;
    std::vector<GpuUniform> uniforms;
    /// gpuDisplayEncoding() only: set, with everything else empty, when the config has no
    /// encoding view for the display (an OCIO v1 config, or v2 without default_view_transform).
    /// One line naming the config file and the display; the caller encodes with the
    /// hand-written IEC 61966-2-1 sRGB curve instead and should show this as a warning.
    std::string fallbackWarning;
    bool isFallback() const { return glsl.empty(); }
};

/// Options for gpuDisplayTransform().
struct GpuTransformOptions {
    std::string functionName = "velvet_ocio_display"; ///< the GLSL function to define
    std::string resourcePrefix = "velvet_ocio";       ///< prefix of samplers and uniforms
};

/// An OpenColorIO config and the conversions Velvet needs from it. Movable (a moved-from object
/// may only be assigned to or destroyed), not copyable. Const
/// member functions may be called from several threads at once (OCIO configs and processors are
/// thread-safe once built; OCIO caches processors itself).
class ColorManagement {
public:
    ColorManagement();
    ~ColorManagement();
    ColorManagement(ColorManagement&&) noexcept;
    ColorManagement& operator=(ColorManagement&&) noexcept;
    ColorManagement(const ColorManagement&) = delete;
    ColorManagement& operator=(const ColorManagement&) = delete;

    /// @name Loading
    /// @{
    /// The config an artist expects: the file named by the `OCIO` environment variable when it is
    /// set and non-empty, else the shipped resources::path("ocio/config.ocio").
    static std::filesystem::path defaultConfigPath();
    /// Loads defaultConfigPath(). See loadFile().
    bool loadDefault(std::string* error);
    /// Loads and validates @p file. On failure returns false, keeps the previously loaded config
    /// (if any) and sets @p error to one line naming the file and OCIO's message.
    bool loadFile(const std::filesystem::path& file, std::string* error);
    bool isLoaded() const;
    /// The file the loaded config came from (empty when none is loaded).
    const std::filesystem::path& configPath() const;
    /// @}

    /// @name What the config offers (empty lists when nothing is loaded)
    /// @{
    std::vector<std::string> colorSpaces() const; ///< all colour spaces, scene and display
    std::vector<std::string> displays() const;    ///< active displays, in config order
    std::vector<std::string> views(const std::string& display) const;
    std::vector<std::string> looks() const;
    std::string defaultDisplay() const;
    std::string defaultView(const std::string& display) const;
    /// The colour space a role names (e.g. "scene_linear", "data", "color_picking"); "" if none.
    std::string roleColorSpace(const std::string& role) const;
    /// The canonical name of a colour space given its name, an alias or a role; "" if unknown.
    std::string canonicalColorSpace(const std::string& nameOrAlias) const;
    /// True for non-colour data spaces (isdata), which are never converted.
    bool isData(const std::string& colorSpace) const;
    /// The config's file rules' colour space for an image path (e.g. EXR -> scene-linear).
    std::string colorSpaceForFile(const std::filesystem::path& file) const;
    /// The view of @p display (empty: the default display) that only encodes for the display: the
    /// first whose view transform is the config's default view transform (in the shipped config
    /// "Standard", whose "Un-tone-mapped" transform is a primaries matrix). "" when none.
    std::string encodingView(const std::string& display) const;
    /// Whether @p view of @p display (empty names: the defaults) only encodes, i.e. its view
    /// transform is the config's default view transform (any such view, not only the first one
    /// encodingView() names); nullopt + message naming the config on an unknown display or view.
    /// The renderer applies its built-in tone-mapping curve before such a view and none before a
    /// tone-mapping one (ACES, AgX) or a view without a view transform (Raw).
    std::optional<bool> isEncodingView(const std::string& display, const std::string& view,
                                       std::string* error) const;
    /// @}

    /// @name CPU conversions of float images in place (1 to 4 channels: grey is converted as
    /// grey, RRR; alpha is left alone). Each returns false with a message on a bad name.
    /// @{
    /// Scene-linear -> display-encoded through @p settings (exposure, look, display, view).
    bool applyDisplay(Image& image, const DisplaySettings& settings, std::string* error) const;
    /// One scene-linear RGB colour -> display-encoded (for colour pickers and swatches).
    bool applyDisplay(float rgb[3], const DisplaySettings& settings, std::string* error) const;
    /// A texture's pixels from @p inputSpace to scene-linear (data spaces: unchanged).
    bool toSceneLinear(Image& image, const std::string& inputSpace, std::string* error) const;
    /// Between any two colour spaces of the config.
    bool convert(Image& image, const std::string& from, const std::string& to,
                 std::string* error) const;
    /// @}

    /// @name GPU
    /// @{
    /// The display transform for @p settings as OCIO's GLSL 4.0 shader and its resources, or
    /// nullopt with @p error set.
    std::optional<GpuDisplayTransform>
    gpuDisplayTransform(const DisplaySettings& settings, std::string* error,
                        const GpuTransformOptions& options = {}) const;
    /// The display encoding of @p display (empty: the default display) as OCIO's GLSL: the
    /// display's encodingView() with no exposure and no look, for display-linear Rec.709 values
    /// a built-in tone-mapping curve produced (sRGB: the piecewise IEC 61966-2-1 curve; Display
    /// P3: the primaries matrix and that curve). nullopt + message on an unknown display; when
    /// the display has no encoding view, an empty transform whose fallbackWarning says so.
    std::optional<GpuDisplayTransform>
    gpuDisplayEncoding(const std::string& display, std::string* error,
                       const GpuTransformOptions& options = {}) const;
    /// @}

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace velvet
