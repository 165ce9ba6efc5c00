// velvet schema material|scene|post-chain: the JSON Schema generated from the parameter metadata
// (the files in resources/schemas/ are this output; a test keeps them equal). Also the hidden
// `velvet post-catalogue`: the Markdown effect catalogue embedded in docs/post-effects.md.
#include "app/cli.h"
#include "core/document_io.h"
#include "core/post_chain_io.h"
#include "core/post_effects.h"

#include <iostream>

namespace velvet::cli {

int runSchema(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{{"help", 'h', false, "", "this text"}};
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (args && args->has("help")) {
        std::cout << "Usage: velvet schema material|scene|post-chain\nPrints the JSON Schema "
                     "(draft 2020-12) of material presets, scenes or post-chain presets.\n\n"
                  << optionsHelp(options);
        return Ok;
    }
    const std::string kind = args && args->positional.size() == 1 ? args->positional[0] : "";
    if (kind != "material" && kind != "scene" && kind != "post-chain") {
        std::cerr << "velvet schema: "
                  << (args ? "expected 'material', 'scene' or 'post-chain'" : error)
                  << "\nRun 'velvet schema --help' for usage.\n";
        return UsageError;
    }
    if (kind == "post-chain")
        std::cout << postChainJsonSchema();
    else
        std::cout << jsonSchema(kind == "material" ? DocumentKind::Material : DocumentKind::Scene);
    return Ok;
}

int runPostCatalogue(const std::vector<std::string>& argv) {
    if (!argv.empty()) {
        std::cerr << "velvet post-catalogue: takes no arguments\n";
        return UsageError;
    }
    std::cout << postEffectCatalogueMarkdown();
    return Ok;
}

} // namespace velvet::cli
