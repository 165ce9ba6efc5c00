#pragma once
/// @file scene_copy.h
/// Render-private: how Renderer::update() takes the parts of a scene an edit names.

#include "core/scene.h"
#include "core/scene_parts.h"

namespace velvet::render {

/// Copies into @p dst the parts of @p src that @p parts names, and nothing else: a part the mask
/// does not name keeps @p dst's own, so what the renderer draws is what it uploaded. Material
/// parts are taken separately (values and names: MaterialValues; texture slots:
/// MaterialStructure; the graph: Graph).
void takeSceneParts(Scene& dst, const Scene& src, ScenePart parts);

} // namespace velvet::render
