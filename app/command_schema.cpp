// velvet schema material|scene: the JSON Schema generated from the parameter metadata (the files
// in resources/schemas/ are this output; a test keeps them equal).
#include "app/cli.h"
#include "core/document_io.h"

#include <iostream>

namespace velvet::cli {

int runSchema(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{{"help", 'h', false, "", "this text"}};
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (args && args->has("help")) {
        std::cout << "Usage: velvet schema material|scene\nPrints the JSON Schema (draft 2020-12) "
                     "of material presets or scenes.\n\n"
                  << optionsHelp(options);
        return Ok;
    }
    if (!args || args->positional.size() != 1 ||
        (args->positional[0] != "material" && args->positional[0] != "scene")) {
        std::cerr << "velvet schema: " << (args ? "expected 'material' or 'scene'" : error)
                  << "\nRun 'velvet schema --help' for usage.\n";
        return UsageError;
    }
    std::cout << jsonSchema(args->positional[0] == "material" ? DocumentKind::Material
                                                              : DocumentKind::Scene);
    return Ok;
}

} // namespace velvet::cli
