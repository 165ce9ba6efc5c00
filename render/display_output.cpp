#include "render/display_output.h"

#include "render/gl_util.h"

#include <epoxy/gl.h>
#include <utility>

namespace velvet::render {

void DisplayOutput::setColorManagement(std::shared_ptr<const ColorManagement> colorManagement) {
    m_config = std::move(colorManagement);
    m_transformIds.clear();
    m_transformKey.clear();
    m_encodingIds.clear();
    m_configFailed = false;
}

const ColorManagement* DisplayOutput::config() {
    if (!m_config && !m_configFailed) {
        auto loaded = std::make_shared<ColorManagement>();
        std::string message;
        if (loaded->loadDefault(&message)) {
            m_config = std::move(loaded);
        } else {
            m_configFailed = true; // warned once: not tried again until another config is set
            m_warnings.warning(ColorManagement::defaultConfigPath().string(), "",
                               "no OpenColorIO config could be loaded (" + message +
                                   "); the display is encoded with the built-in sRGB curve "
                                   "instead of OCIO");
        }
    }
    return m_config.get();
}

std::shared_ptr<const ColorManagement> DisplayOutput::sharedConfig() {
    if (config())
        return m_config;
    // The default config failed: an unloaded one, so that the texture slots report their colour
    // space problems without loading the same file again.
    if (!m_unloaded)
        m_unloaded = std::make_shared<ColorManagement>();
    return m_unloaded;
}

Problems DisplayOutput::takeWarnings() {
    return std::exchange(m_warnings, {});
}

bool DisplayOutput::initialize(std::string* error) {
    return selectEncoding({}, error) && tonemapProgram(error);
}

bool DisplayOutput::ocioToneMaps(const FrameSettings& fs, bool& toneMaps, std::string* error) {
    toneMaps = false;
    if (!fs.usesColorManagement())
        return true;
    const ColorManagement* cm = config();
    if (!cm)
        return fail(error, "a display/view was chosen but no OpenColorIO config could be "
                           "loaded from " +
                               ColorManagement::defaultConfigPath().string());
    const std::optional<bool> encodes = cm->isEncodingView(fs.display, fs.displayView, error);
    if (!encodes)
        return false;
    toneMaps = !*encodes || !fs.look.empty();
    return true;
}

bool DisplayOutput::choose(const FrameSettings& fs, DisplayChoice& choice, std::string* error) {
    choice = {};
    if (!ocioToneMaps(fs, choice.ocioToneMaps, error))
        return false;
    choice.ocioDisplay = choice.ocioToneMaps && fs.view == DebugView::Final;
    if (choice.ocioDisplay && !selectDisplayTransform(fs, error))
        return false;
    if (!selectEncoding(fs.display, error))
        return false;
    choice.tonemap = tonemapProgram(error);
    return choice.tonemap != nullptr;
}

bool DisplayOutput::selectEncoding(const std::string& display, std::string* error) {
    const ColorManagement* cm = config();
    if (!cm) {
        m_encoding.selectFallback();
        return true;
    }
    if (const auto it = m_encodingIds.find(display);
        it != m_encodingIds.end() && m_encoding.selectCached(it->second))
        return true;
    const std::optional<GpuDisplayTransform> t =
        cm->gpuDisplayEncoding(display, error, DisplayEncoding::options());
    if (!t || !m_encoding.select(*t, error, &m_warnings))
        return false;
    m_encodingIds[display] = t->cacheId;
    return true;
}

ShaderProgram* DisplayOutput::tonemapProgram(std::string* error) {
    auto& program = m_tonemaps[m_encoding.cacheId()];
    if (program)
        return program.get();
    auto built = std::make_unique<ShaderProgram>();
    if (!buildTonemap(*built, m_encoding.cacheId(), error)) {
        m_tonemaps.erase(m_encoding.cacheId());
        return nullptr;
    }
    return (program = std::move(built)).get();
}

bool DisplayOutput::buildTonemap(ShaderProgram& program, const std::string& encodingId,
                                 std::string* error) {
    if (!program.build("fullscreen.vert", "display_output.frag", {}, m_encoding.sources(encodingId),
                       error))
        return false;
    m_encoding.setUniforms(program.id(), encodingId);
    ++m_compileCount;
    return true;
}

bool DisplayOutput::selectDisplayTransform(const FrameSettings& fs, std::string* error) {
    const std::string key = fs.display + '\n' + fs.displayView + '\n' + fs.look;
    if (key == m_transformKey && m_transform.hasSelection())
        return true;
    if (const auto it = m_transformIds.find(key);
        it != m_transformIds.end() && m_transform.selectCached(it->second)) {
        m_transformKey = key;
        return true;
    }
    if (!config())
        return fail(error, "no OpenColorIO config could be loaded from " +
                               ColorManagement::defaultConfigPath().string());
    const DisplaySettings settings{fs.display, fs.displayView, fs.look, 0.0f};
    const std::optional<GpuDisplayTransform> transform =
        m_config->gpuDisplayTransform(settings, error);
    if (!transform || !m_transform.select(*transform, error))
        return false;
    m_transformIds[key] = transform->cacheId;
    m_transformKey = key;
    return true;
}

void DisplayOutput::draw(const DisplayChoice& choice, unsigned hdrTexture, float exposureEv) {
    if (choice.ocioDisplay) {
        m_transform.draw(hdrTexture, exposureEv);
        return;
    }
    glBindTextureUnit(binding::kHdrTex, hdrTexture);
    m_encoding.bindLuts();
    glUseProgram(choice.tonemap->id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    m_encoding.unbindLuts();
}

bool DisplayOutput::inlineSource(const DisplayChoice& choice, InlinePost& out) const {
    if (choice.ocioDisplay)
        return false;
    // display_output.frag's final view as a function of the lit colour (frame.post.x: the
    // exposure, frame.modes.z: the curve), for the same encoding.
    out.key = "display@" + m_encoding.cacheId();
    out.sources = {
        {"inline_post.glsl",
         "#include \"common_frame.glsl\"\n"
         "#include \"common_tonemap.glsl\"\n"
         "#include \"display_encode.glsl\"\n"
         "vec4 postInline(vec4 c, ivec2 px) {\n"
         "    vec3 display = displayEncode(toneMap(c.rgb * frame.post.x, frame.modes.z));\n"
         "    return vec4(clamp(display, 0.0, 1.0), 1.0);\n"
         "}\n"}};
    for (auto& s : m_encoding.sources(m_encoding.cacheId()))
        out.sources.push_back(std::move(s));
    return true;
}

void DisplayOutput::bindInline(const std::vector<unsigned>& programs) const {
    for (unsigned program : programs)
        m_encoding.setUniforms(program, m_encoding.cacheId());
    m_encoding.bindLuts();
}

bool DisplayOutput::reload(std::string* error) {
    std::string errors;
    auto collect = [&](bool ok, const std::string& message) {
        if (!ok)
            errors += (errors.empty() ? "" : "\n") + message;
    };
    std::string message;
    collect(m_transform.reload(&message), message);
    for (auto& [id, program] : m_tonemaps)
        collect(buildTonemap(*program, id, &message), message);
    return errors.empty() || fail(error, errors);
}

} // namespace velvet::render
