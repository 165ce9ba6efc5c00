#pragma once
/// @file batch_plan.h
/// Which inputs a batch run takes and how its progress reads (`velvet render|export|thumbnails
/// … --jobs N --shard K/N`, docs/batch.md): pure functions, so a shard's slice is the same on
/// every machine and a test can check that the slices cover the inputs exactly once.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace velvet {

/// Slice @ref index of @ref count (0 <= index < count).
struct Shard {
    int index = 0;
    int count = 1;
};

/// "K/N" with 0 <= K < N (K as Slurm's --array=0-… and a Kubernetes indexed Job's
/// JOB_COMPLETION_INDEX count from 0), N in [1, 100000]; nullopt for anything else.
std::optional<Shard> parseShard(std::string_view text);

/// The inputs of @p shard: @p inputs sorted (byte order) and with duplicates removed, then every
/// input whose position i in that order has i mod count == index. Independent of the order the
/// inputs were given in (a shell's glob, a file list), so N machines given the same set take
/// disjoint slices that together are the whole set; round-robin rather than contiguous blocks so
/// that a library sorted by kind spreads each kind over the shards.
std::vector<std::string> shardInputs(std::vector<std::string> inputs, Shard shard);

/// A duration for progress lines: "0:07", "12:34", "1:02:03" (seconds rounded up).
std::string formatDuration(double seconds);

/// The estimated time left after @p done of @p total inputs took @p elapsed seconds with
/// workers running in parallel: the throughput so far (inputs per second, all workers together)
/// applied to the inputs left.
/// 0 when nothing is left; nullopt before the first input is done.
std::optional<double> estimateRemaining(int done, int total, double elapsed);

} // namespace velvet
