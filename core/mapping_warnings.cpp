#include "core/mapping_warnings.h"

#include "core/baked_maps.h"
#include "core/graph/graph.h"

namespace velvet {

std::vector<std::string> mappingWarnings(const Material& m, std::string_view target) {
    std::vector<std::string> w;
    const std::string to(target);
    // glTF 2.0 defines one BRDF (Appendix B): GGX D, separable Smith-GGX V, Schlick F, Lambert
    // diffuse; MaterialX's shaders fix their own terms too, with no choice to carry these.
    for (ParamId id :
         {ParamId::Distribution, ParamId::Visibility, ParamId::Fresnel, ParamId::Diffuse}) {
        const ParamMeta& meta = paramMeta(id);
        const int c = m.choice(id);
        if (c != int(meta.defaultValue.x))
            w.push_back(std::string(meta.id) + " = " + std::string(meta.choices[size_t(c)]) + ": " +
                        to + " has no choice of BRDF terms (Velvet's default, " +
                        std::string(meta.choices[size_t(meta.defaultValue.x)]) +
                        ", is glTF 2.0 Appendix B's); viewers will shade with their own");
    }
    if (m.scalar(ParamId::SheenWeight) > 0.0f && m.sheenModel() != SheenModel::CharlieContyKulla) {
        const ParamMeta& meta = paramMeta(ParamId::SheenModel);
        w.push_back(std::string(meta.id) + " = " +
                    std::string(meta.choices[size_t(m.choice(ParamId::SheenModel))]) + ": " + to +
                    " has one sheen model (KHR_materials_sheen names Charlie D with "
                    "Conty-Kulla's visibility); viewers will shade with theirs");
    }
    if (m.graph) {
        const std::vector<std::string> inputs = graphDrivenInputs(m);
        std::string list;
        for (const std::string& s : inputs)
            list += (list.empty() ? "" : ", ") + s;
        w.push_back(
            inputs.empty()
                ? "graph: the material's node graph (" + std::to_string(m.graph->nodes().size()) +
                      " nodes) feeds no material input and is not exported"
                : "graph: the node graph drives " + list + "; not baked in this export to " + to +
                      " (velvet export and File > Export… bake it on the GPU): the "
                      "parameters' own values are exported instead");
    }
    return w;
}

} // namespace velvet
