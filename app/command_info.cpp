// velvet info: version, the headless OpenGL context, dependency versions.
#include "app/cli.h"
#include "app/huge_pages.h"
#include "core/resources.h"
#include "core/versions.h"
#include "render/headless_context.h"

#include <QtGlobal>
#include <iostream>

namespace velvet::cli {

int runInfo(const std::vector<std::string>& argv) {
    const std::vector<OptionSpec> options{{"help", 'h', false, "", "this text"}};
    std::string error;
    auto args = parseArguments(argv, options, &error);
    if (!args || !args->positional.empty()) {
        std::cerr << "velvet info: " << (args ? "takes no FILE" : error) << "\n";
        return UsageError;
    }
    if (args->has("help")) {
        std::cout << "Usage: velvet info\nPrints Velvet's version, the headless OpenGL context "
                     "(vendor, renderer, version) and dependency versions.\n\n"
                  << optionsHelp(options);
        return Ok;
    }
    std::cout << "Velvet " << VELVET_VERSION << "\n";
    // Where shaders, presets and HDRIs come from (beside the binary, an installed
    // share/velvet, the source tree, or VELVET_RESOURCES): the first question when one is missing.
    std::cout << "Resources: " << resources::root().string() << "\n";
    int code = Ok;
    if (auto context = render::HeadlessContext::create(&error)) {
        std::cout << "OpenGL (headless, EGL " << context->platform() << ")\n"
                  << "  vendor:   " << context->vendor() << "\n"
                  << "  renderer: " << context->renderer() << "\n"
                  << "  version:  " << context->version() << "\n";
    } else {
        std::cout << "OpenGL (headless): unavailable: " << error << "\n";
        code = RenderFailure;
    }
    // app/huge_pages.h: llvmpipe's textures and targets fault in 2 MiB at a time, not 4 KiB.
    const std::string thp = app::kernelHugePageMode();
    std::cout << "Memory: transparent huge pages for large allocations "
              << (app::hugePagesRequested() ? "on (GLIBC_TUNABLES glibc.malloc.hugetlb=1)" : "off")
              << "; kernel: " << (thp.empty() ? "unknown" : thp) << "\n";
    std::cout << "Dependencies\n  Qt: " << qVersion() << "\n";
    for (const auto& [name, version] : dependencyVersions())
        std::cout << "  " << name << ": " << version << "\n";
    return code;
}

} // namespace velvet::cli
