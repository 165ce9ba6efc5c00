#pragma once
/// @file load_document.h
/// Opens whatever the user named — a scene or a material preset — as a scene.

#include "app/cli.h"
#include "core/diagnostics.h"
#include "core/scene.h"

#include <filesystem>
#include <optional>

namespace velvet::cli {

/// The scene a material preset is shown in: the look-dev stage (core/default_stage.h,
/// stageSceneWithMaterial) or its thumbnail's (thumbnailScene: fabrics on the cloth drape).
enum class PresetScene { Stage, Thumbnail };

/// Loads @p file as a scene: a scene file as is, a material preset shown in @p presetScene.
/// nullopt when @p problems holds errors (missing file, malformed JSON, unknown format…).
std::optional<Scene> loadSceneOrPreset(const std::filesystem::path& file, Problems& problems,
                                       PresetScene presetScene = PresetScene::Stage);

/// The scene options `velvet render` and `velvet reference` share: FILE (args.positional[0];
/// none: the default scene), --light-rig and, where the command has it, --thumbnail (a preset
/// shown as its thumbnail). Returns Ok with @p scene set, BadInput (problems printed) or
/// UsageError (message printed, naming @p command).
int loadSceneArguments(const Arguments& args, const char* command, std::optional<Scene>& scene,
                       Problems& problems);
/// "WxH" with each side in [1, 8192].
bool parseSize(const std::string& text, int& w, int& h);
/// A finite number, the whole text.
bool parseFloat(const std::string& text, float& v);

/// Prints each problem as one line on stderr ("file: path: message", warnings marked).
void printProblems(const Problems& problems);

/// Ok when @p out's folder (the current one for a bare name) exists; otherwise BadInput, with a
/// message on stderr naming @p out and the folder. Commands check this before slow work, so bad
/// input fails fast and writes nothing.
int checkOutputFolder(const std::filesystem::path& out);

} // namespace velvet::cli
