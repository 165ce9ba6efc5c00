#pragma once
/// @file cli.h
/// The headless command-line interface: `velvet render|validate|info|schema …`.
/// Exit codes (DESIGN.md): 0 success, 1 usage error, 2 bad input, 3 rendering failure.

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {
struct Scene;
}

namespace velvet::cli {

enum ExitCode : int { Ok = 0, UsageError = 1, BadInput = 2, RenderFailure = 3 };

/// Parsed arguments of one subcommand: positionals and `--name value` / `-x value` options.
struct Arguments {
    std::vector<std::string> positional;
    std::map<std::string, std::string> options; ///< keyed by the long name, without dashes
    bool has(const std::string& name) const { return options.count(name) != 0; }
    std::string value(const std::string& name, const std::string& fallback = {}) const;
};

/// One option a subcommand accepts.
struct OptionSpec {
    std::string_view longName; ///< "output"
    char shortName;            ///< 'o', or 0
    bool takesValue;
    std::string_view valueName; ///< "FILE" for help
    std::string_view help;
};

/// Parses @p args (after the subcommand name) against @p specs. On an unknown option or a
/// missing value returns nullopt and fills @p error.
std::optional<Arguments> parseArguments(const std::vector<std::string>& args,
                                        const std::vector<OptionSpec>& specs, std::string* error);
/// The options part of a --help text.
std::string optionsHelp(const std::vector<OptionSpec>& specs);

/// True when @p name is a subcommand (so main() takes the CLI path, not the editor).
bool isSubcommand(std::string_view name);
/// Runs subcommand args[0] with the rest. Returns the process exit code.
int run(const std::vector<std::string>& args);
/// The top-level `velvet --help` text.
std::string topLevelHelp();

// Subcommands (one file each).
int runRender(const std::vector<std::string>& args);
int runValidate(const std::vector<std::string>& args);
int runInfo(const std::vector<std::string>& args);
int runSchema(const std::vector<std::string>& args);
int runBench(const std::vector<std::string>& args);
/// `velvet bench --textures` (app/command_bench_textures.cpp).
int runTextureBench(bool json, bool quick);
/// The median of @p values (the mean of the two middle ones for an even count; NaN when empty):
/// every velvet bench figure (command_bench.cpp).
double median(std::vector<double> values);
/// `velvet bench --frame` (app/command_bench_frame.cpp): the forward peer's scene, its frame.
int runFrameBench(bool json, bool quick);
/// velvet bench's G-buffer layout figures (app/command_bench_gbuffer.cpp): the 24-byte layout
/// with lobe channels beside the compact 16-byte one, side by side. Needs a current context.
bool gbufferLayoutFigures(int width, int height, int frames,
                          std::vector<std::pair<std::string, double>>& figures, std::string* error);
int runPack(const std::vector<std::string>& args);
int runUnpack(const std::vector<std::string>& args);
int runExport(const std::vector<std::string>& args);
int runImport(const std::vector<std::string>& args);
int runReference(const std::vector<std::string>& args);
int runCompare(const std::vector<std::string>& args);
int runThumbnails(const std::vector<std::string>& args);
/// Hidden: the child process of the crash-isolated mesh import (command_import_mesh.cpp).
int runImportMesh(const std::vector<std::string>& args);
/// Hidden: prints the post-effect catalogue as Markdown for docs/post-effects.md
/// (command_schema.cpp).
int runPostCatalogue(const std::vector<std::string>& args);
/// Hidden: prints core/sheen_albedo_table.inc (command_schema.cpp).
int runSheenTable(const std::vector<std::string>& args);
/// Hidden: prints core/specular_albedo_table.inc (command_schema.cpp).
int runSpecularTable(const std::vector<std::string>& args);
/// Hidden: prints core/diffuse_albedo_table.inc (command_schema.cpp).
int runDiffuseTable(const std::vector<std::string>& args);

} // namespace velvet::cli
