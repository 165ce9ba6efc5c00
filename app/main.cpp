// velvet: the editor when run alone (or with a FILE), a headless CLI with a subcommand.
#include "app/cli.h"
#include "app/huge_pages.h"
#include "app/resource_root.h"
#include "core/image.h"
#include "core/mesh_import.h"
#include "ui/editor.h"

#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv) {
    // First of all (glibc reads its tunables at start only): huge pages for llvmpipe's textures
    // and targets, which otherwise spend seconds in page faults (app/huge_pages.h).
    velvet::app::reexecWithHugePages(argc, argv);
    velvet::app::locateResources(argv[0]);
    // Custom meshes are imported by this same executable in a child process (`velvet
    // import-mesh`), so a crashing importer cannot take the document down (DESIGN.md).
    {
        std::error_code ec;
        const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
        if (!ec)
            velvet::setMeshImportHelper(self);
    }
    std::vector<std::string> args(argv + 1, argv + argc);
    // VELVET_MAX_IMAGE_SIDE / VELVET_MAX_IMAGE_BYTES (core/image.h): a bad value stops here,
    // before anything reads an image under limits the user did not mean.
    if (const std::string problem = velvet::imageLimitsProblem(); !problem.empty()) {
        std::cerr << "velvet: " << problem << "\n";
        return velvet::cli::BadInput;
    }

    if (!args.empty() && velvet::cli::isSubcommand(args[0]))
        return velvet::cli::run(args);

    // Editor: velvet [FILE] [--screenshot OUT]
    velvet::ui::EditorOptions options;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a == "-h" || a == "--help") {
            std::cout << velvet::cli::topLevelHelp();
            return velvet::cli::Ok;
        }
        if (a == "--version") {
            std::cout << "velvet " << VELVET_VERSION << "\n";
            return velvet::cli::Ok;
        }
        if (a == "--screenshot") {
            if (i + 1 >= args.size()) {
                std::cerr << "velvet: --screenshot needs a file name\n";
                return velvet::cli::UsageError;
            }
            options.screenshotFile = args[++i];
        } else if (a.rfind("-", 0) == 0 && a.size() > 1) {
            // Qt's own options (-platform, -style …) pass through to QApplication.
            if (a.rfind("--", 0) == 0) {
                std::cerr << "velvet: unknown option '" << a << "'\n"
                          << velvet::cli::topLevelHelp();
                return velvet::cli::UsageError;
            }
        } else if (options.openFile.empty()) {
            options.openFile = a;
        } else {
            std::cerr << "velvet: unknown command '" << options.openFile
                      << "' or more than one FILE\n"
                      << "Run 'velvet --help' for usage.\n";
            return velvet::cli::UsageError;
        }
    }
    return velvet::ui::runEditor(argc, argv, options);
}
