#pragma once
/// @file batch_commands.h
/// The hooks `velvet render` and `velvet export` call for their batch forms (several FILEs,
/// --jobs, --shard), and `velvet thumbnails` (app/batch_commands.cpp; docs/batch.md).

#include "app/cli.h"

#include <vector>

namespace velvet::cli {

/// `velvet render` is a batch with several FILEs or any of --jobs, --shard, --format.
bool isRenderBatch(const Arguments& args);
/// Renders each FILE (sharded) into the folder -o names as STEM.png (or --format exr) through
/// child `velvet render FILE -o …` processes with the other options of @p args (@p specs: the
/// render command's option table, to write them back).
int runRenderBatch(const Arguments& args, const std::vector<OptionSpec>& specs);

/// `velvet export` is a batch with several FILEs or --jobs or --shard.
bool isExportBatch(const Arguments& args);
/// Exports each FILE (sharded) through child `velvet export FILE …` processes (the caller has
/// checked the options and that no two FILEs write the same name).
int runExportBatch(const Arguments& args, const std::vector<OptionSpec>& specs);

} // namespace velvet::cli
