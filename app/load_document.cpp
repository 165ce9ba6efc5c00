#include "app/load_document.h"

#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/light_rigs.h"

#include <charconv>
#include <cmath>
#include <iostream>

namespace velvet::cli {

std::optional<Scene> loadSceneOrPreset(const std::filesystem::path& file, Problems& problems,
                                       PresetScene presetScene) {
    std::error_code ec;
    if (!std::filesystem::exists(file, ec)) {
        problems.error(file.string(), "", "no such file");
        return std::nullopt;
    }
    switch (detectDocumentKind(file)) {
    case DocumentKind::Scene:
        return loadSceneFile(file, problems);
    case DocumentKind::Material:
        if (auto material = loadMaterialFile(file, problems)) {
            // The look-dev stage, as for no FILE, or the library thumbnail's (fabrics on the
            // drape): one rule for the editor and `velvet thumbnails` (core/default_stage.h).
            Scene scene = presetScene == PresetScene::Thumbnail ? thumbnailScene(*material)
                                                                : stageSceneWithMaterial(*material);
            scene.materialPreset = file.string();
            return scene;
        }
        return std::nullopt;
    case DocumentKind::Unknown:
        break;
    }
    // Not recognisably either: the material reader names the exact problem (parse error with line
    // and column, missing or unknown "format", …).
    if (loadMaterialFile(file, problems) && !problems.hasErrors())
        problems.error(file.string(), "format", "not a Velvet scene or material preset");
    return std::nullopt;
}

int loadSceneArguments(const Arguments& args, const char* command, std::optional<Scene>& scene,
                       Problems& problems) {
    // No FILE: the look-dev stage (core/default_stage.h); the golden image keeps defaultScene().
    if (args.positional.empty())
        scene = stageScene(&problems);
    else
        scene =
            loadSceneOrPreset(args.positional[0], problems,
                              args.has("thumbnail") ? PresetScene::Thumbnail : PresetScene::Stage);
    if (!scene || problems.hasErrors()) {
        printProblems(problems);
        return BadInput;
    }
    if (args.has("light-rig")) {
        auto lights = lightRigLights(args.value("light-rig"));
        if (!lights) {
            std::cerr << "velvet " << command << ": --light-rig: unknown rig '"
                      << args.value("light-rig") << "'\nRun 'velvet " << command
                      << " --help' for usage.\n";
            return UsageError;
        }
        scene->lights = std::move(*lights);
    }
    return Ok;
}

bool parseSize(const std::string& text, int& w, int& h) {
    auto x = text.find_first_of("xX");
    if (x == std::string::npos)
        return false;
    auto parse = [](std::string_view s, int& v) {
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        return ec == std::errc() && ptr == s.data() + s.size() && v >= 1 && v <= 8192;
    };
    return parse(std::string_view(text).substr(0, x), w) &&
           parse(std::string_view(text).substr(x + 1), h);
}

bool parseFloat(const std::string& text, float& v) {
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(v);
}

void printProblems(const Problems& problems) {
    for (const Problem& p : problems.items)
        std::cerr << (p.severity == Problem::Severity::Warning ? "warning: " : "") << p.toString()
                  << "\n";
}

int checkOutputFolder(const std::filesystem::path& out) {
    const std::filesystem::path folder = out.parent_path().empty() ? "." : out.parent_path();
    std::error_code ec;
    if (std::filesystem::is_directory(folder, ec))
        return Ok;
    std::cerr << out.string() << ": the folder '" << folder.string() << "' does not exist\n";
    return BadInput;
}

} // namespace velvet::cli
