#pragma once
/// @file stage_test_rig.h
/// Test-only: the look-dev stage's known-answer tests' shared rig (test_render_shadows,
/// test_render_stage_occlusion): the process's renderer, a frame drawn at rest or as while the
/// camera moves (the `navigating` rows), and the stage scene seen from above.
#include "core/scene.h"
#include "render/offscreen.h"
#include "render/renderer.h"
#include "render_test_util.h"

#include <QtTest>
#include <glm/geometric.hpp>
#include <string>

namespace velvet::test {

/// The frames drawn as while the camera moves (FrameSettings::navigating): the `navigating` rows.
inline bool navigatingFrames = false;

/// Whether the frames let the occlusion ride in the shadow masks (FrameSettings::packOcclusion).
inline bool packOcclusionFrames = true;

/// The frame's size over the test's: 2 in the navigating rows, whose stage is drawn at a quarter
/// of the frame each way, not half, so that its texels cover what the rows at rest's do and the
/// known answers' margins (in world units) mean the same; at 1280 x 720 a quarter is 320 x 180.
inline int framePixelsPerStagePixel() {
    return navigatingFrames ? 2 : 1;
}

/// The `navigating` column: the frames at rest and the frames while the camera moves.
inline void addNavigatingRows() {
    QTest::addColumn<bool>("navigating");
    QTest::newRow("at rest") << false;
    QTest::newRow("navigating") << true;
}

/// The process's test::OffscreenRenderer, resized per test (renderLinear).
inline test::OffscreenRenderer* rig() {
    return test::processRenderer(128);
}

/// The next frame of @p r's renderer (its scene as it stands) in @p view, linear.
inline Image drawLinear(test::OffscreenRenderer* r, int size,
                        render::DebugView view = render::DebugView::Final,
                        render::LightPath path = render::LightPath::Auto) {
    std::string error;
    if (!r->target->resize(size, size, &error))
        qFatal("target: %s", error.c_str());
    r->size = size;
    render::FrameSettings fs;
    fs.width = fs.height = size;
    fs.view = view;
    fs.lightPath = path;
    fs.navigating = navigatingFrames;
    fs.packOcclusion = packOcclusionFrames;
    if (!r->renderer->render(fs, r->target->framebuffer(), &error))
        qFatal("render failed: %s", error.c_str());
    return r->renderer->readLinear();
}

inline Image renderLinear(const Scene& scene, int size,
                          render::DebugView view = render::DebugView::Final,
                          render::LightPath path = render::LightPath::Auto) {
    test::OffscreenRenderer* r = rig();
    Problems problems;
    r->renderer->setScene(scene, &problems);
    for (const Problem& p : problems.items)
        qWarning("%s", p.toString().c_str());
    return drawLinear(r, size, view, path);
}

/// A black environment, an orthographic camera looking down on the origin at 55°.
inline Scene stageScene(PreviewMeshKind mesh) {
    Scene scene = test::blackOrthographicScene();
    scene.mesh.kind = mesh;
    scene.camera.pitchDeg = 55.0f;
    scene.camera.yawDeg = 20.0f;
    scene.camera.orthoHeight = 6.0f;
    scene.camera.target = {0.0f, -1.0f, 0.0f};
    scene.environment.groundColor = glm::vec3(0.5f);
    scene.environment.groundRoughness = 1.0f;
    return scene;
}

inline float luminance(glm::vec4 c) {
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

} // namespace velvet::test
