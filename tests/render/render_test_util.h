#pragma once
// Shared helpers of the render tests: one headless context per test process, scenes built in code.

#include "core/scene.h"
#include "render/headless_context.h"

#include <memory>
#include <string>

namespace velvet::test {

inline render::HeadlessContext* headlessContext(std::string* error) {
    static std::string lastError;
    static std::unique_ptr<render::HeadlessContext> ctx =
        render::HeadlessContext::create(&lastError);
    if (!ctx && error)
        *error = lastError;
    return ctx.get();
}

/// The default scene of core/document_io.cpp, built in code (no JSON): the crimson velvet-ish
/// material on the sphere, a warm key light, the studio HDRI.
inline Scene defaultSceneInCode() {
    Scene scene;
    Material& m = scene.material;
    m.name = "Crimson velvet";
    m.setColor(ParamId::BaseColor, {0.35f, 0.02f, 0.05f});
    m.setScalar(ParamId::Roughness, 0.8f);
    m.setScalar(ParamId::SheenWeight, 1.0f);
    m.setColor(ParamId::SheenColor, {1.0f, 0.6f, 0.7f});
    m.setScalar(ParamId::SheenRoughness, 0.4f);
    Light key;
    key.type = LightType::Directional;
    key.name = "Key";
    key.color = {1.0f, 0.93f, 0.85f};
    key.intensity = 3.0f;
    key.direction = {0.5f, -0.6f, -0.62f};
    scene.lights.push_back(key);
    scene.environment.hdri = std::string(VELVET_SOURCE_DIR) + "/resources/hdri/studio.exr";
    return scene;
}

} // namespace velvet::test
