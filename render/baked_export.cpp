#include "render/baked_export.h"

#include "core/mtlx_export.h"
#include "core/mtlx_graph_export.h"
#include "render/material_bake.h"

namespace velvet::render {

ExportOutcome exportMaterialBaked(const Scene& scene, const std::filesystem::path& folder,
                                  std::string_view baseName, const ExportOptions& options,
                                  TextureCache* textures) {
    BakedMaterialMaps baked;
    // MaterialX writes what its standard nodes express as a nodegraph, and bakes the rest.
    baked.inputs = bakedInputsOf(
        scene.material,
        options.format == ExportFormat::Mtlx && scene.material.graph
            ? mtlx::mappableGraphInputs(scene.material, std::string(mtlxShaderId(options.shader)))
            : std::set<std::string>());
    if (options.format == ExportFormat::Preset || !scene.material.graph)
        return exportMaterial(scene, folder, baseName, options, textures);
    ExportOutcome outcome;
    Problems problems;
    std::string error;
    // A graph driving only inputs no map carries (the IOR) or only nodegraph inputs needs no
    // bake (nor an OpenGL context): applyBakedMaps says so.
    if (baked.inputs.any() && !bakeMaterialMaps(scene.material, options.bakeSize, options.bakeSize,
                                                baked.maps, &problems, &error)) {
        outcome.status = ExportOutcome::Status::Failed;
        outcome.error = "cannot bake the node graph's maps: " + error;
        return outcome;
    }
    // A texture that cannot be read is bad input, as for the unbaked export: nothing is written.
    std::vector<std::string> warnings;
    for (const Problem& p : problems.items) {
        if (p.severity == Problem::Severity::Error) {
            outcome.status = ExportOutcome::Status::BadInput;
            outcome.error = p.toString();
            return outcome;
        }
        warnings.push_back(p.toString());
    }
    baked.size = options.bakeSize;
    ExportOptions withMaps = options;
    withMaps.baked = &baked;
    outcome = exportMaterial(scene, folder, baseName, withMaps, textures);
    outcome.warnings.insert(outcome.warnings.begin(), warnings.begin(), warnings.end());
    return outcome;
}

} // namespace velvet::render
