#include "render/lighting_pass.h"

#include "render/background_dome.h"
#include "render/background_downsample.h"

#include <algorithm>
#include <epoxy/gl.h>
#include <vector>

namespace velvet::render {

LightingPass::Variant LightingPass::variantFor(DebugView view) {
    if (view == DebugView::Final)
        return kFinal;
    if (isLightView(view)) // the lobe views and LightsPerPixel
        return kLobeViews;
    return kGBufferViews;
}

std::vector<std::string> LightingPass::variantDefines(Variant v) {
    std::vector<std::string> defines{"FULLSCREEN_FAR_PLANE"};
    if (v == kLobeViews)
        defines.emplace_back("LIGHTING_LOBE_VIEWS");
    else if (v == kGBufferViews)
        defines.emplace_back("LIGHTING_GBUFFER_VIEWS");
    else if (v == kFinalCatcherGround)
        defines.emplace_back("STAGE_GROUND_CATCHER");
    else if (v >= kFinalPlainGround && v < kCatcher) {
        defines.emplace_back("STAGE_GROUND_PLAIN");
        defines.emplace_back("BACKGROUND_MODE " + std::to_string(v - kFinalPlainGround));
    } else if (v >= kCatcher && v < kBackground) {
        defines.emplace_back("LIGHTING_CATCHER");
        defines.emplace_back("BACKGROUND_MODE " + std::to_string(v - kCatcher));
    } else if (v >= kBackground) {
        defines.emplace_back("LIGHTING_BACKGROUND");
        defines.emplace_back("BACKGROUND_MODE " + std::to_string(v - kBackground));
    }
    return defines;
}

bool LightingPass::buildVariant(Variant v, std::string* error) {
    if (!m_programs[v].build("fullscreen.vert", "lighting.frag", variantDefines(v), error))
        return false;
    ++m_compileCount;
    return true;
}

bool LightingPass::build(std::string* error, bool keepGoing) {
    std::string errors;
    m_specialised.clear(); // rebuilt from the new sources when next drawn
    for (int v = 0; v < kCount && (keepGoing || errors.empty()); ++v) {
        // The debug families and the stage's variants only once they have been used.
        if (v != kFinal && v < kBackground && m_programs[v].id() == 0)
            continue;
        std::string message;
        if (!buildVariant(Variant(v), &message))
            errors += (errors.empty() ? "" : "\n") + message;
    }
    if (!errors.empty() && error)
        *error = errors;
    return errors.empty();
}

const ShaderProgram* LightingPass::variant(Variant v, std::string* error) {
    if (m_programs[v].id() == 0 && !buildVariant(v, error))
        return nullptr;
    return &m_programs[v];
}

namespace {
int modeIndex(BackgroundMode mode) {
    return int(mode) >= 0 && int(mode) <= 3 ? int(mode) : 0; // unknown: Sharp (as GLSL)
}
} // namespace

const ShaderProgram* LightingPass::surfaceProgram(DebugView view, std::string* error,
                                                  GroundMode ground, BackgroundMode background,
                                                  const LightingFeatures& features, bool mayBuild) {
    Variant v = variantFor(view);
    if (v == kFinal && ground == GroundMode::ShadowCatcher)
        v = kFinalCatcherGround;
    else if (v == kFinal && ground == GroundMode::Plain)
        v = Variant(kFinalPlainGround + modeIndex(background));
    m_lastSpecialised = m_lastDeferred = false;
    const bool finalImage =
        v == kFinal || v == kFinalCatcherGround || (v >= kFinalPlainGround && v < kCatcher);
    if (finalImage && !features.isGeneric())
        if (const ShaderProgram* p = specialised(v, features, mayBuild)) {
            m_lastSpecialised = true;
            return p;
        }
    return variant(v, error);
}

const ShaderProgram* LightingPass::specialised(Variant v, const LightingFeatures& features,
                                               bool mayBuild, const InlinePost* inlinePost) {
    return specialised(v, features.defines(), mayBuild, inlinePost);
}

const ShaderProgram* LightingPass::specialised(Variant v, std::vector<std::string> featureDefines,
                                               bool mayBuild, const InlinePost* inlinePost) {
    auto key = std::make_tuple(int(v), std::move(featureDefines),
                               inlinePost ? inlinePost->key : std::string());
    auto it = m_specialised.find(key);
    if (it == m_specialised.end()) {
        if (!mayBuild) {
            m_lastDeferred = true;
            return nullptr;
        }
        if (m_specialised.size() >= kMaxSpecialised) // evict the least recently used
            m_specialised.erase(std::min_element(
                m_specialised.begin(), m_specialised.end(),
                [](const auto& a, const auto& b) { return a.second.lastUse < b.second.lastUse; }));
        // The variant's own defines, then the features'.
        std::vector<std::string> defines = variantDefines(v);
        defines.insert(defines.end(), std::get<1>(key).begin(), std::get<1>(key).end());
        if (inlinePost)
            defines.emplace_back("LIGHTING_INLINE_POST");
        auto program = std::make_unique<ShaderProgram>();
        std::string message;
        if (program->build("fullscreen.vert", "lighting.frag", defines,
                           inlinePost ? inlinePost->sources : GeneratedSources{}, &message)) {
            ++m_compileCount;
        } else {
            program.reset(); // remembered as failed: not retried every frame
            ++m_specialisationFailures;
            m_specialisationError = message;
        }
        it = m_specialised.emplace(std::move(key), Specialised{std::move(program), 0}).first;
    }
    it->second.lastUse = ++m_useClock;
    return it->second.program.get();
}

bool LightingPass::drawCatcher(bool emission, BackgroundMode background, std::string* error,
                               const LightingFeatures& features, bool mayBuild) {
    // The catcher covers most of the stage's frame: its shadow lookups cost the whole frame's
    // worth even when no light casts a shadow (llvmpipe runs both sides of the branch), so it is
    // specialised like the surfaces (BENCHMARKS.md, the look-dev stage).
    const Variant v = Variant(kCatcher + modeIndex(background));
    const ShaderProgram* program = nullptr;
    if (!features.isGeneric())
        program = specialised(v, features, mayBuild);
    if (!program)
        program = variant(v, error);
    if (!program)
        return false;
    drawSurfaces(*program, emission);
    return true;
}

void LightingPass::drawBackground(BackgroundMode mode, bool prefilteredReady) {
    if (mode == BackgroundMode::Blurred && !prefilteredReady)
        mode = BackgroundMode::Sharp;
    drawBackground(m_programs[kBackground + modeIndex(mode)]);
}

void LightingPass::drawBackground(const ShaderProgram& program) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    glUseProgram(program.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

bool LightingPass::inlinePrograms(BackgroundMode background, bool prefilteredReady,
                                  const LightingFeatures& features, const InlinePost& inlinePost,
                                  bool mayBuild, const ShaderProgram*& backgroundProgram,
                                  const ShaderProgram*& surfaces) {
    if (features.isGeneric())
        return false;
    if (background == BackgroundMode::Blurred && !prefilteredReady)
        background = BackgroundMode::Sharp;
    // The background depends on no material feature: one program per mode and display step.
    backgroundProgram = specialised(Variant(kBackground + modeIndex(background)),
                                    std::vector<std::string>{}, mayBuild, &inlinePost);
    surfaces = specialised(kFinal, features, mayBuild, &inlinePost);
    return backgroundProgram && surfaces;
}

const ShaderProgram* LightingPass::downsampledBackground(BackgroundMode background,
                                                         bool prefilteredReady, int factor,
                                                         const InlinePost& inlinePost,
                                                         bool mayBuild) {
    if (background == BackgroundMode::Blurred && !prefilteredReady)
        background = BackgroundMode::Sharp;
    return specialised(Variant(kBackground + modeIndex(background)),
                       std::vector<std::string>{"BACKGROUND_DOWNSAMPLE " + std::to_string(factor)},
                       mayBuild, &inlinePost);
}

const ShaderProgram* LightingPass::equirectBackground(BackgroundMode background,
                                                      bool prefilteredReady,
                                                      const InlinePost& inlinePost, bool mayBuild) {
    if (background == BackgroundMode::Blurred && !prefilteredReady)
        background = BackgroundMode::Sharp;
    return specialised(Variant(kBackground + modeIndex(background)),
                       std::vector<std::string>{"BACKGROUND_EQUIRECT " +
                                                std::to_string(BackgroundDome::kCacheScale)},
                       mayBuild, &inlinePost);
}

void LightingPass::drawSurfaces(const ShaderProgram& program, bool emission, bool displayValues) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    if (emission) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    } else if (!displayValues) { // alpha: the emission kept (see the header), 1 from the clear
        glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_FALSE);
    }
    glUseProgram(program.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
}

} // namespace velvet::render
