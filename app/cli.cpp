#include "app/cli.h"

#include <array>
#include <iostream>
#include <sstream>

namespace velvet::cli {

std::string Arguments::value(const std::string& name, const std::string& fallback) const {
    auto it = options.find(name);
    return it == options.end() ? fallback : it->second;
}

std::optional<Arguments> parseArguments(const std::vector<std::string>& args,
                                        const std::vector<OptionSpec>& specs, std::string* error) {
    Arguments out;
    bool onlyPositional = false;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (onlyPositional || a.size() < 2 || a[0] != '-') {
            out.positional.push_back(a);
            continue;
        }
        if (a == "--") {
            onlyPositional = true;
            continue;
        }
        // --name, --name=value, -x
        std::string name = a;
        std::optional<std::string> inlineValue;
        const OptionSpec* spec = nullptr;
        if (a.rfind("--", 0) == 0) {
            name = a.substr(2);
            if (auto eq = name.find('='); eq != std::string::npos) {
                inlineValue = name.substr(eq + 1);
                name = name.substr(0, eq);
            }
            for (const auto& s : specs)
                if (s.longName == name)
                    spec = &s;
        } else if (a.size() == 2) {
            for (const auto& s : specs)
                if (s.shortName == a[1])
                    spec = &s;
        }
        if (!spec) {
            *error = "unknown option '" + a + "'";
            return std::nullopt;
        }
        std::string value;
        if (spec->takesValue) {
            if (inlineValue) {
                value = *inlineValue;
            } else if (i + 1 < args.size()) {
                value = args[++i];
            } else {
                *error = "option '" + a + "' needs a value (" + std::string(spec->valueName) + ")";
                return std::nullopt;
            }
        } else if (inlineValue) {
            *error = "option '--" + name + "' takes no value";
            return std::nullopt;
        }
        out.options[std::string(spec->longName)] = value;
    }
    return out;
}

std::string optionsHelp(const std::vector<OptionSpec>& specs) {
    std::ostringstream s;
    s << "Options:\n";
    for (const auto& o : specs) {
        std::string left = "  ";
        left += o.shortName ? std::string("-") + o.shortName + ", " : "    ";
        left += "--" + std::string(o.longName);
        if (o.takesValue)
            left += " " + std::string(o.valueName);
        if (left.size() < 28)
            left.resize(28, ' ');
        else
            left += "  ";
        s << left << o.help << "\n";
    }
    return s.str();
}

namespace {
struct Subcommand {
    std::string_view name;
    std::string_view summary;
    int (*run)(const std::vector<std::string>&);
};
const std::array<Subcommand, 12> kSubcommands{{
    {"render", "render a scene or material preset to an image, headless", runRender},
    {"validate", "check presets and scenes, printing every problem", runValidate},
    {"info", "version, headless OpenGL and dependency versions", runInfo},
    {"schema", "print the JSON Schema of material presets, scenes or post chains", runSchema},
    {"bench", "measure renderer variants side by side (medians, ratios; --json)", runBench},
    {"pack", "pack grey material maps into one texture (glTF, Unreal ORM, HDRP mask)", runPack},
    {"unpack", "split a packed texture back into one grey image per map", runUnpack},
    {"export", "export materials: glTF 2.0, MaterialX, engine texture sets, presets", runExport},
    {"import", "import a glTF 2.0 or MaterialX material as a preset", runImport},
    {"reference", "path trace the same frame on the CPU (ground truth, .exr)", runReference},
    {"compare", "per-pixel CIEDE2000 between two images, with a heat map", runCompare},
    {"thumbnails", "render a thumbnail of every preset and scene in a folder", runThumbnails},
}};
/// Left out of --help: `import-mesh IN OUT` is the child process of the crash-isolated mesh
/// import (core/mesh_import.h); `post-catalogue` prints the effect table of
/// docs/post-effects.md; `sheen-table` regenerates core/sheen_albedo_table.inc,
/// `specular-table` core/specular_albedo_table.inc and `diffuse-table`
/// core/diffuse_albedo_table.inc.
const std::array<Subcommand, 5> kHiddenSubcommands{{
    {"sheen-table", "print core/sheen_albedo_table.inc (the sheen albedo tables)", runSheenTable},
    {"specular-table", "print core/specular_albedo_table.inc (the specular albedo table)",
     runSpecularTable},
    {"diffuse-table", "print core/diffuse_albedo_table.inc (the Burley diffuse albedo table)",
     runDiffuseTable},
    {"import-mesh", "import a mesh file into a mesh cache (internal)", runImportMesh},
    {"post-catalogue", "print the post-effect catalogue as Markdown (docs)", runPostCatalogue},
}};
} // namespace

bool isSubcommand(std::string_view name) {
    for (const auto& c : kSubcommands)
        if (c.name == name)
            return true;
    for (const auto& c : kHiddenSubcommands)
        if (c.name == name)
            return true;
    return false;
}

std::string topLevelHelp() {
    std::ostringstream s;
    s << "Usage: velvet [FILE] [--screenshot OUT]   open the editor (on FILE, or the default "
         "scene)\n"
         "       velvet COMMAND [ARGS]             run a headless command\n\n"
         "Commands:\n";
    for (const auto& c : kSubcommands) {
        std::string name(c.name);
        name.resize(12, ' '); // the longest name ("thumbnails") and two spaces
        s << "  " << name << c.summary << "\n";
    }
    s << "\nEditor options:\n"
         "  --screenshot OUT          save the window after its first frame to OUT, then exit\n"
         "  -h, --help                this text\n"
         "  --version                 print the version\n\n"
         "Run 'velvet COMMAND --help' for a command's options.\n"
         "Exit codes: 0 success, 1 usage error, 2 bad input, 3 rendering failure.\n";
    return s.str();
}

int run(const std::vector<std::string>& args) {
    for (const auto& c : kSubcommands)
        if (!args.empty() && c.name == args[0])
            return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
    for (const auto& c : kHiddenSubcommands)
        if (!args.empty() && c.name == args[0])
            return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
    std::cerr << "velvet: unknown command '" << (args.empty() ? "" : args[0]) << "'\n";
    return UsageError;
}

} // namespace velvet::cli
