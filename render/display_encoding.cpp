#include "render/display_encoding.h"

#include "render/ocio_gpu.h"

#include <algorithm>
#include <epoxy/gl.h>

namespace velvet::render {

struct DisplayEncoding::Entry {
    GpuDisplayTransform source; ///< LUT values dropped after upload
    std::vector<GLuint> luts;
    ~Entry() {
        if (!luts.empty())
            glDeleteTextures(GLsizei(luts.size()), luts.data());
    }
};

GpuTransformOptions DisplayEncoding::options() {
    GpuTransformOptions o;
    o.functionName = "velvet_ocio_encode";
    o.resourcePrefix = "velvet_enc";
    return o;
}

DisplayEncoding::DisplayEncoding() = default;
DisplayEncoding::~DisplayEncoding() = default;

bool DisplayEncoding::select(const GpuDisplayTransform& encoding, std::string* error,
                             Problems* warnings) {
    if (encoding.isFallback()) { // the config has no encoding view for the display
        if (!encoding.fallbackWarning.empty() && m_warned.insert(encoding.fallbackWarning).second &&
            warnings)
            warnings->warning("", "display", encoding.fallbackWarning);
        selectFallback();
        return true;
    }
    if (selectCached(encoding.cacheId))
        return true;
    GLint maxUnits = 0;
    glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &maxUnits);
    maxUnits = std::min(maxUnits, GLint(binding::kIblIrradianceTex)); // the units above are taken
    if (binding::kDisplayLutTexFirst + int(encoding.textures.size()) > maxUnits) {
        if (error)
            *error = "the display encoding needs " + std::to_string(encoding.textures.size()) +
                     " LUT textures but the GL context has " + std::to_string(maxUnits) +
                     " texture units";
        return false;
    }
    auto entry = std::make_unique<Entry>();
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
    glPixelStorei(GL_UNPACK_IMAGE_HEIGHT, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (const GpuLutTexture& lut : encoding.textures)
        entry->luts.push_back(uploadOcioLut(lut));
    entry->source = encoding;
    for (GpuLutTexture& lut : entry->source.textures)
        lut.values = {};
    m_current = encoding.cacheId;
    m_entries[m_current] = std::move(entry);
    return true;
}

bool DisplayEncoding::selectCached(const std::string& cacheId) {
    if (cacheId.empty()) {
        selectFallback();
        return true;
    }
    if (!m_entries.count(cacheId))
        return false;
    m_current = cacheId;
    return true;
}

void DisplayEncoding::selectFallback() {
    m_current.clear();
}

GeneratedSources DisplayEncoding::sources(const std::string& cacheId) const {
    const auto it = m_entries.find(cacheId);
    if (cacheId.empty() || it == m_entries.end())
        return {{kInclude,
                 "// No OpenColorIO config could be loaded: the hand-written IEC 61966-2-1 sRGB\n"
                 "// OETF (common_math.glsl) encodes instead of OCIO.\n"
                 "vec3 displayEncode(vec3 c) { return srgbEncode(c); }\n"}};
    const GpuDisplayTransform& t = it->second->source;
    // OCIO's function takes and returns RGBA; the curve's output is opaque.
    return {{kInclude, t.glsl + "\nvec3 displayEncode(vec3 c) { return " + t.functionName +
                           "(vec4(c, 1.0)).rgb; }\n"}};
}

void DisplayEncoding::setUniforms(unsigned program, const std::string& cacheId) const {
    const auto it = m_entries.find(cacheId);
    if (cacheId.empty() || it == m_entries.end())
        return;
    const GpuDisplayTransform& t = it->second->source;
    for (size_t i = 0; i < t.textures.size(); ++i) {
        const GLint loc = glGetUniformLocation(program, t.textures[i].samplerName.c_str());
        if (loc >= 0)
            glProgramUniform1i(program, loc, binding::kDisplayLutTexFirst + int(i));
    }
    for (const GpuUniform& u : t.uniforms)
        setOcioUniform(program, u);
}

void DisplayEncoding::bindLuts() const {
    const auto it = m_entries.find(m_current);
    if (m_current.empty() || it == m_entries.end())
        return;
    const auto& luts = it->second->luts;
    for (size_t i = 0; i < luts.size(); ++i)
        glBindTextureUnit(GLuint(binding::kDisplayLutTexFirst + int(i)), luts[i]);
}

void DisplayEncoding::unbindLuts() const {
    const auto it = m_entries.find(m_current);
    if (m_current.empty() || it == m_entries.end())
        return;
    for (size_t i = 0; i < it->second->luts.size(); ++i)
        glBindTextureUnit(GLuint(binding::kDisplayLutTexFirst + int(i)), 0);
}

} // namespace velvet::render
