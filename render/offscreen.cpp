#include "render/offscreen.h"

#include "render/gbuffer.h"
#include "render/headless_context.h"

#include <epoxy/gl.h>

namespace velvet::render {

struct OffscreenTarget::Impl {
    ColorTarget target;
};
OffscreenTarget::OffscreenTarget() : m_impl(std::make_unique<Impl>()) {}
OffscreenTarget::~OffscreenTarget() = default;
bool OffscreenTarget::resize(int width, int height, std::string* error) {
    return m_impl->target.resize(width, height, GL_RGBA8, error);
}
unsigned OffscreenTarget::framebuffer() const {
    return m_impl->target.framebuffer();
}

bool renderSceneOffscreen(const Scene& scene, const FrameSettings& settings, Image* linear,
                          Image* display, std::string* error, Problems* problems,
                          std::shared_ptr<const ColorManagement> colorManagement) {
    std::unique_ptr<HeadlessContext> context;
    if (!HeadlessContext::isAnyContextCurrent()) {
        context = HeadlessContext::create(error);
        if (!context)
            return false;
    }
    bool ok = false;
    {
        // Renderer and target live inside this scope so their GL objects die with the context
        // still current.
        Renderer renderer;
        if (!renderer.initialize(error))
            return false;
        // The config first: a new config drops the textures, which would then load twice.
        if (colorManagement)
            renderer.setColorManagement(std::move(colorManagement));
        renderer.setScene(scene, problems);
        renderer.finishEnvironment(); // the whole IBL bake before the one frame
        renderer.finishGraph();       // and the material graph's program
        renderer.finishTextures();    // and every texture, complete (never a proxy)
        ColorTarget target;
        if (!target.resize(settings.width, settings.height, GL_RGBA8, error))
            return false;
        if (!renderer.render(settings, target.framebuffer(), error))
            return false;
        if (linear)
            *linear = renderer.readLinear();
        if (display)
            *display = renderer.readDisplay();
        if (problems) // no OCIO config, no encoding view: reported once, never printed here
            for (Problem& p : renderer.takeWarnings().items)
                problems->items.push_back(std::move(p));
        ok = true;
    }
    return ok;
}

} // namespace velvet::render
