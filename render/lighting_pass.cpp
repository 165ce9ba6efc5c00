#include "render/lighting_pass.h"

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

bool LightingPass::buildVariant(Variant v, std::string* error) {
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
    if (!m_programs[v].build("fullscreen.vert", "lighting.frag", defines, error))
        return false;
    ++m_compileCount;
    return true;
}

bool LightingPass::build(std::string* error, bool keepGoing) {
    std::string errors;
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
                                                  GroundMode ground, BackgroundMode background) {
    Variant v = variantFor(view);
    if (v == kFinal && ground == GroundMode::ShadowCatcher)
        v = kFinalCatcherGround;
    else if (v == kFinal && ground == GroundMode::Plain)
        v = Variant(kFinalPlainGround + modeIndex(background));
    return variant(v, error);
}

bool LightingPass::drawCatcher(bool emission, BackgroundMode background, std::string* error) {
    const ShaderProgram* program = variant(Variant(kCatcher + modeIndex(background)), error);
    if (!program)
        return false;
    drawSurfaces(*program, emission);
    return true;
}

void LightingPass::drawBackground(BackgroundMode mode, bool prefilteredReady) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_EQUAL);
    if (mode == BackgroundMode::Blurred && !prefilteredReady)
        mode = BackgroundMode::Sharp;
    const int m = int(mode) >= 0 && int(mode) <= 3 ? int(mode) : 0; // unknown: Sharp (as GLSL)
    glUseProgram(m_programs[kBackground + m].id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

void LightingPass::drawSurfaces(const ShaderProgram& program, bool emission) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    if (emission) {
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
    } else {
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
