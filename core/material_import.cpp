#include "core/material_import.h"

#include "core/gltf_import.h"
#include "core/mtlx_import.h"

#include <algorithm>
#include <cctype>

namespace velvet {
namespace fs = std::filesystem;
namespace {

enum class Format { Gltf, Mtlx, None };

Format formatOf(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".gltf" || ext == ".glb")
        return Format::Gltf;
    if (ext == ".mtlx")
        return Format::Mtlx;
    return Format::None;
}

std::string describe(const fs::path& file, const ImportProblem& p) {
    return file.string() + ": " + (p.place.empty() ? std::string() : p.place + ": ") + p.message;
}

std::string listNames(const std::vector<std::string>& names) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i)
        s += (i ? ", " : "") + std::to_string(i) + " \"" + names[i] + "\"";
    return s;
}

} // namespace

bool selectMaterial(const std::vector<std::string>& names, std::string_view select, size_t& index,
                    ImportProblem& problem) {
    if (names.empty()) {
        problem = {ImportProblem::Kind::Malformed, "", "the file holds no material"};
        return false;
    }
    if (select.empty()) {
        if (names.size() == 1) {
            index = 0;
            return true;
        }
        problem = {ImportProblem::Kind::Selection, "",
                   std::to_string(names.size()) + " materials (" + listNames(names) +
                       "); choose one with --material NAME|INDEX"};
        return false;
    }
    if (std::all_of(select.begin(), select.end(),
                    [](unsigned char c) { return std::isdigit(c); }) &&
        select.size() < 10) {
        const size_t i = std::stoul(std::string(select));
        if (i < names.size()) {
            index = i;
            return true;
        }
        problem = {ImportProblem::Kind::Selection, "",
                   "no material " + std::string(select) + ": the file holds " +
                       std::to_string(names.size()) + " (" + listNames(names) + ")"};
        return false;
    }
    const auto it = std::find(names.begin(), names.end(), select);
    if (it != names.end()) {
        index = size_t(it - names.begin());
        return true;
    }
    problem = {ImportProblem::Kind::Selection, "",
               "no material named \"" + std::string(select) + "\"; materials: " + listNames(names)};
    return false;
}

bool isImportableFile(const fs::path& file) {
    return formatOf(file) != Format::None;
}

bool listImportableMaterials(const fs::path& file, std::vector<std::string>& names,
                             std::string* error) {
    ImportProblem problem;
    bool ok = false;
    switch (formatOf(file)) {
    case Format::Gltf:
        ok = readGltfMaterialNames(file, names, problem);
        break;
    case Format::Mtlx:
        ok = readMtlxMaterialNames(file, names, problem);
        break;
    case Format::None:
        problem.message = "not a glTF (.gltf, .glb) or MaterialX (.mtlx) file";
        break;
    }
    if (!ok)
        *error = describe(file, problem);
    return ok;
}

ImportOutcome importMaterialFile(const fs::path& file, const ImportOptions& options) {
    ImportOutcome outcome;
    const Format format = formatOf(file);
    if (format == Format::None) {
        outcome.status = ImportOutcome::Status::Failed;
        outcome.error = file.string() + ": not a glTF (.gltf, .glb) or MaterialX (.mtlx) file";
        return outcome;
    }
    std::string listError;
    listImportableMaterials(file, outcome.materialNames, &listError);
    const std::string stem = sanitizeFileStem(
        options.imageStem.empty() ? file.stem().string() : options.imageStem, "imported");
    const fs::path folder = options.imageFolder.empty() ? fs::path(".") : options.imageFolder;
    ImportedMaterial imported;
    ImportProblem problem;
    const bool ok = format == Format::Gltf
                        ? importGltfMaterial(file, options.material, fs::absolute(folder), stem,
                                             imported, problem)
                        : importMtlxMaterial(file, options.material, imported, problem);
    if (!ok) {
        outcome.status = problem.kind == ImportProblem::Kind::Selection
                             ? ImportOutcome::Status::Selection
                             : ImportOutcome::Status::Malformed;
        outcome.error = describe(file, problem);
        return outcome;
    }
    if (!imported.images.empty()) {
        std::string error;
        switch (
            writeExportFiles(folder, imported.images, options.force, &error, &outcome.written)) {
        case ExportWriteError::None:
            break;
        case ExportWriteError::Exists:
            outcome.status = ImportOutcome::Status::Exists;
            outcome.error = error;
            return outcome;
        default:
            outcome.status = ImportOutcome::Status::Failed;
            outcome.error = error;
            return outcome;
        }
    }
    outcome.material = std::move(imported.material);
    outcome.hasMesh = imported.hasMesh;
    outcome.warnings = std::move(imported.warnings);
    return outcome;
}

} // namespace velvet
