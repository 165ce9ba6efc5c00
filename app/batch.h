#pragma once
/// @file batch.h
/// Many inputs in one command (`velvet render|export|thumbnails … --jobs N --shard K/N`,
/// docs/batch.md): each input runs as a child process of this same executable with the
/// single-input command line, so every worker has its own OpenGL context (EGL contexts are per
/// thread and a driver's state per process: separate processes share nothing and a crash or a
/// hang in one input cannot take the others down). Progress on stderr; a failed input is one line
/// and the others go on; the exit code is 2 when any input failed.

#include "app/cli.h"
#include "core/batch_plan.h"

#include <string>
#include <string_view>
#include <vector>

namespace velvet::cli {

/// The options every batch command takes (appended to its own option table; constexpr so the
/// commands' static option tables may copy them in any initialisation order).
inline constexpr OptionSpec kJobsOption{"jobs", 'j', true, "N",
                                        "inputs processed in parallel, each in its own process "
                                        "with its own GL context (default: the core count)"};
inline constexpr OptionSpec kShardOption{
    "shard", 0, true, "K/N",
    "only the K-th of N deterministic slices of the inputs (K from 0: a Slurm array index or a "
    "Kubernetes JOB_COMPLETION_INDEX)"};

/// --jobs and --shard of a command line.
struct BatchSettings {
    int jobs = 1;       ///< parallel workers: --jobs, else the core count
    Shard shard;        ///< --shard, else 0/1 (everything)
    bool asked = false; ///< --jobs or --shard was given
};

/// Reads --jobs (1 to 256) and --shard from @p args into @p out. UsageError (message printed,
/// naming @p command) on a bad value, else Ok.
int parseBatchSettings(const Arguments& args, const char* command, BatchSettings& out);

/// One input's child command line (after the executable: the subcommand and its arguments).
struct BatchJob {
    std::string input;             ///< what progress and failure lines name
    std::vector<std::string> args; ///< e.g. {"render", "a.json", "-o", "out/a.png", …}
};

/// The options of @p args as command-line words again (`--name=value`, `--name`), leaving out
/// those named in @p skip: what a child gets besides its input and output.
std::vector<std::string> forwardOptions(const Arguments& args, const std::vector<OptionSpec>& specs,
                                        const std::vector<std::string_view>& skip);

/// Runs @p jobs, at most @p parallel at a time, as children of this executable. Each child's
/// stdout is passed through, its stderr passed through when it ends (whole, so lines of two
/// inputs never interleave); after each, a progress line on stderr: "velvet COMMAND: [done/total]
/// INPUT ok|FAILED …, ETA m:ss". A failed input (non-zero exit, or killed by a signal) gets one
/// line "velvet COMMAND: FAILED INPUT: …" and the rest go on. Returns Ok, or BadInput when any
/// input failed (a final line counts them).
int runBatch(const std::vector<BatchJob>& jobs, int parallel, const char* command);

} // namespace velvet::cli
