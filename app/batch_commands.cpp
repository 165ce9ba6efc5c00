// The batch forms of `velvet render` and `velvet export`, and `velvet thumbnails DIR -o OUTDIR`:
// the inputs (sharded with --shard K/N), one child command line each, run by app/batch.h with
// --jobs workers (docs/batch.md).
#include "app/batch_commands.h"

#include "app/batch.h"
#include "core/export_files.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <iostream>
#include <map>

namespace velvet::cli {
namespace {

namespace fs = std::filesystem;

int usage(const char* command, const std::string& message) {
    std::cerr << "velvet " << command << ": " << message << "\nRun 'velvet " << command
              << " --help' for usage.\n";
    return UsageError;
}

/// Refuses two inputs that would write the same output name (checked over all inputs, before
/// sharding, so every shard agrees), else Ok.
int checkDistinctStems(const std::vector<std::string>& inputs, const char* command) {
    std::map<std::string, std::string> byStem;
    for (const std::string& file : inputs) {
        const std::string stem = sanitizeFileStem(fs::path(file).stem().string());
        if (auto [it, fresh] = byStem.emplace(stem, file); !fresh && it->second != file)
            return usage(command, "\"" + it->second + "\" and \"" + file + "\" would both write " +
                                      stem + "; give them different names or run them apart");
    }
    return Ok;
}

int makeFolder(const fs::path& folder, const char* command) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder)) {
        std::cerr << "velvet " << command << ": cannot create the output folder " << folder.string()
                  << (ec ? ": " + ec.message() : "") << "\n";
        return BadInput;
    }
    return Ok;
}

/// Renders @p inputs (already sharded) into @p folder as STEM@p ext with @p extra options.
int renderEach(const std::vector<std::string>& inputs, const fs::path& folder,
               const std::string& ext, const std::vector<std::string>& extra, int jobs,
               const char* command) {
    if (const int code = makeFolder(folder, command); code != Ok)
        return code;
    std::vector<BatchJob> batch;
    for (const std::string& file : inputs) {
        BatchJob job{file, {"render", file, "-o"}};
        job.args.push_back(
            (folder / (sanitizeFileStem(fs::path(file).stem().string()) + ext)).string());
        job.args.insert(job.args.end(), extra.begin(), extra.end());
        batch.push_back(std::move(job));
    }
    return runBatch(batch, jobs, command);
}

} // namespace

bool isRenderBatch(const Arguments& args) {
    return args.positional.size() > 1 || args.has("jobs") || args.has("shard") ||
           args.has("format");
}

int runRenderBatch(const Arguments& args, const std::vector<OptionSpec>& specs) {
    BatchSettings batch;
    if (const int code = parseBatchSettings(args, "render", batch); code != Ok)
        return code;
    if (args.positional.empty())
        return usage("render", "a batch needs at least one FILE");
    const std::string format = args.value("format", "png");
    if (format != "png" && format != "exr")
        return usage("render", "--format expects png or exr, got '" + format + "'");
    const fs::path out = args.value("output");
    if (out.extension() == ".png" || out.extension() == ".exr")
        return usage("render", "with several FILEs (or --jobs, --shard, --format) -o names a "
                               "folder, got '" +
                                   out.string() + "'");
    if (const int code = checkDistinctStems(args.positional, "render"); code != Ok)
        return code;
    const auto extra = forwardOptions(args, specs, {"output", "jobs", "shard", "format"});
    return renderEach(shardInputs(args.positional, batch.shard), out, "." + format, extra,
                      batch.jobs, "render");
}

bool isExportBatch(const Arguments& args) {
    return args.positional.size() > 1 || args.has("jobs") || args.has("shard");
}

int runExportBatch(const Arguments& args, const std::vector<OptionSpec>& specs) {
    BatchSettings batch;
    if (const int code = parseBatchSettings(args, "export", batch); code != Ok)
        return code;
    const auto extra = forwardOptions(args, specs, {"output", "jobs", "shard"});
    std::vector<BatchJob> jobs;
    for (const std::string& file : shardInputs(args.positional, batch.shard)) {
        BatchJob job{file, {"export", file, "-o", args.value("output")}};
        job.args.insert(job.args.end(), extra.begin(), extra.end());
        jobs.push_back(std::move(job));
    }
    return runBatch(jobs, batch.jobs, "export");
}

namespace {

const std::vector<OptionSpec> kThumbnailOptions{
    {"output", 'o', true, "OUTDIR", "the folder the thumbnails go to, as STEM.png"},
    {"size", 's', true, "N", "thumbnail width and height in pixels (default 256)"},
    {"light-rig", 0, true, "ID", "replace each scene's lights with a rig (as velvet render)"},
    kJobsOption,
    kShardOption,
    {"help", 'h', false, "", "this text"},
};

const char* kThumbnailHelp =
    "Usage: velvet thumbnails DIR|FILE... -o OUTDIR [--size N] [--jobs N] [--shard K/N]\n"
    "Renders a thumbnail of every material preset and scene (*.json, not *.atlas.json) in each\n"
    "DIR (and its subfolders) and of each FILE, as OUTDIR/STEM.png, through velvet render\n"
    "--thumbnail (a preset as the editor's Library shows it: fabrics and leather on the cloth\n"
    "drape, other materials on the sphere). Runs --jobs renders at a time, each in its own "
    "process;\n"
    "prints progress on stderr; a failed input is reported and the others go on.\n"
    "Exit codes: 0 success, 1 usage error, 2 any input failed.\n\n";

/// The documents under @p dir: *.json except atlases and autosaves, sorted.
std::vector<std::string> documentsIn(const fs::path& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::end(it);
         it.increment(ec)) {
        const fs::path& p = it->path();
        const std::string name = p.filename().string();
        if (!it->is_regular_file(ec) || p.extension() != ".json")
            continue;
        if (name.ends_with(".atlas.json") || name.find(".autosave") != std::string::npos)
            continue;
        files.push_back(p.string());
    }
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace

int runThumbnails(const std::vector<std::string>& argv) {
    std::string error;
    auto args = parseArguments(argv, kThumbnailOptions, &error);
    if (!args)
        return usage("thumbnails", error);
    if (args->has("help")) {
        std::cout << kThumbnailHelp << optionsHelp(kThumbnailOptions);
        return Ok;
    }
    if (args->positional.empty() || !args->has("output"))
        return usage("thumbnails", "needs DIR (or FILE) and -o OUTDIR");
    BatchSettings batch;
    if (const int code = parseBatchSettings(*args, "thumbnails", batch); code != Ok)
        return code;
    int size = 256;
    if (args->has("size")) {
        const std::string text = args->value("size");
        auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), size);
        if (ec != std::errc() || ptr != text.data() + text.size() || size < 1 || size > 8192)
            return usage("thumbnails", "--size expects 1 to 8192, got '" + text + "'");
    }
    std::vector<std::string> inputs;
    for (const std::string& p : args->positional) {
        std::error_code ec;
        if (fs::is_directory(p, ec)) {
            const auto found = documentsIn(p);
            inputs.insert(inputs.end(), found.begin(), found.end());
        } else if (fs::is_regular_file(p, ec)) {
            inputs.push_back(p);
        } else {
            std::cerr << "velvet thumbnails: " << p << ": no such folder or file\n";
            return BadInput;
        }
    }
    if (inputs.empty()) {
        std::cerr << "velvet thumbnails: no *.json documents found\n";
        return BadInput;
    }
    if (const int code = checkDistinctStems(inputs, "thumbnails"); code != Ok)
        return code;
    // --thumbnail: a preset on the scene the editor's Library shows it in (fabrics on the drape).
    std::vector<std::string> extra{"--size=" + std::to_string(size) + "x" + std::to_string(size),
                                   "--thumbnail"};
    if (args->has("light-rig"))
        extra.push_back("--light-rig=" + args->value("light-rig"));
    return renderEach(shardInputs(inputs, batch.shard), args->value("output"), ".png", extra,
                      batch.jobs, "thumbnails");
}

} // namespace velvet::cli
