// velvet validate FILE...: checks presets and scenes and prints every problem.
#include "app/cli.h"
#include "app/load_document.h"

#include <iostream>

namespace velvet::cli {

int runValidate(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{
        {"quiet", 'q', false, "", "print problems only, not the files that pass"},
        {"help", 'h', false, "", "this text"},
    };
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (!args) {
        std::cerr << "velvet validate: " << error << "\n";
        return UsageError;
    }
    if (args->has("help")) {
        std::cout << "Usage: velvet validate FILE...\n"
                     "Checks material presets and scenes; prints each problem as\n"
                     "'file: json.path: message' on stderr. Exit 2 when any file has an error.\n\n"
                  << optionsHelp(options);
        return Ok;
    }
    if (args->positional.empty()) {
        std::cerr << "velvet validate: no FILE given\nRun 'velvet validate --help' for usage.\n";
        return UsageError;
    }
    int failed = 0;
    for (const std::string& file : args->positional) {
        Problems problems;
        const bool ok = loadSceneOrPreset(file, problems).has_value() && !problems.hasErrors();
        printProblems(problems);
        if (!ok)
            ++failed;
        else if (!args->has("quiet"))
            std::cout << file << ": ok\n";
    }
    if (failed > 0 && args->positional.size() > 1)
        std::cerr << failed << " of " << args->positional.size() << " files have errors\n";
    return failed > 0 ? BadInput : Ok;
}

} // namespace velvet::cli
