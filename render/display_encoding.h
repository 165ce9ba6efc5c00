#pragma once
/// @file display_encoding.h
/// The display encoding after a built-in tone-mapping curve: OCIO's own GPU shader for the
/// current display's un-tone-mapped view (ColorManagement::gpuDisplayEncoding), composed into the
/// tone-mapping programs (display_output.frag, the chain's fused tone map) as the generated include
/// "display_encode.glsl", which defines `vec3 displayEncode(vec3 displayLinear)`. So the curve
/// and OCIO's encoding stay one pass. Encodings are cached by OCIO's cache id (LUT textures
/// uploaded once); a program built for an id is valid for as long as this object lives.
///
/// When no OCIO config can be loaded at all, selectFallback() gives the hand-written
/// IEC 61966-2-1 sRGB OETF of common_math.glsl (cache id ""); select() takes it too for the empty
/// transform gpuDisplayEncoding() returns when the config has no encoding view (OCIO v1), and
/// reports that transform's warning once (to the caller's problem list, never to stderr). Needs a
/// current OpenGL 4.5 context from construction to destruction.

#include "core/color_management.h"
#include "core/diagnostics.h"
#include "render/shader_program.h"

#include <map>
#include <memory>
#include <set>
#include <string>

namespace velvet::render {

class DisplayEncoding {
public:
    /// The generated include's name.
    static constexpr const char* kInclude = "display_encode.glsl";
    /// The GLSL function name and resource prefix gpuDisplayEncoding() should use.
    static GpuTransformOptions options();

    DisplayEncoding();
    ~DisplayEncoding();
    DisplayEncoding(const DisplayEncoding&) = delete;
    DisplayEncoding& operator=(const DisplayEncoding&) = delete;

    /// Makes @p encoding current, uploading its LUTs the first time its cache id is seen. False +
    /// message when the context lacks texture units for its LUTs (the selection stays). An empty
    /// transform (GpuDisplayTransform::isFallback) selects the fallback; its fallbackWarning goes
    /// to @p warnings (path "display") the first time this object sees it.
    bool select(const GpuDisplayTransform& encoding, std::string* error,
                Problems* warnings = nullptr);
    /// Switches to an encoding seen before (the fallback's id "" always); false when @p cacheId
    /// is unknown.
    bool selectCached(const std::string& cacheId);
    /// The hand-written sRGB OETF (no OCIO config).
    void selectFallback();
    /// The current encoding's cache id ("" for the fallback).
    const std::string& cacheId() const { return m_current; }
    bool isFallback() const { return m_current.empty(); }

    /// The generated include for encoding @p cacheId (the current one by default).
    GeneratedSources sources(const std::string& cacheId) const;
    GeneratedSources sources() const { return sources(m_current); }
    /// Sampler units and uniforms of encoding @p cacheId on a freshly linked @p program.
    void setUniforms(unsigned program, const std::string& cacheId) const;
    /// Binds / unbinds the current encoding's LUTs (units kDisplayLutTexFirst …).
    void bindLuts() const;
    void unbindLuts() const;

private:
    struct Entry;
    std::map<std::string, std::unique_ptr<Entry>> m_entries;
    std::string m_current;
    std::set<std::string> m_warned; ///< fallback warnings reported already
};

} // namespace velvet::render
