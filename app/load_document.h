#pragma once
/// @file load_document.h
/// Opens whatever the user named — a scene or a material preset — as a scene.

#include "core/diagnostics.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>

namespace velvet::cli {

/// Loads @p file as a scene: a scene file as is, a material preset shown in the default scene.
/// nullopt when @p problems holds errors (missing file, malformed JSON, unknown format…).
std::optional<Scene> loadSceneOrPreset(const std::filesystem::path& file, Problems& problems);

/// Prints each problem as one line on stderr ("file: path: message", warnings marked).
void printProblems(const Problems& problems);

} // namespace velvet::cli
