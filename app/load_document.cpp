#include "app/load_document.h"

#include "core/document_io.h"

#include <iostream>

namespace velvet::cli {

std::optional<Scene> loadSceneOrPreset(const std::filesystem::path& file, Problems& problems) {
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
            Scene scene = sceneWithMaterial(*material);
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

void printProblems(const Problems& problems) {
    for (const Problem& p : problems.items)
        std::cerr << (p.severity == Problem::Severity::Warning ? "warning: " : "") << p.toString()
                  << "\n";
}

} // namespace velvet::cli
