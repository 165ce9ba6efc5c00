#pragma once
/// @file cache_dir.h
/// Where Velvet keeps its disk caches (the DFG LUT, prefiltered environments, texture mip
/// chains): $VELVET_CACHE_DIR when set, else $XDG_CACHE_HOME/velvet (XDG Base Directory
/// Specification 0.8), else ~/.cache/velvet. VELVET_NO_CACHE=1 turns every cache off (tests and
/// benchmarks that must measure the uncached path): velvetCacheDir() is then empty, as it is
/// when none of the variables says where.

#include <filesystem>

namespace velvet {

/// The cache root, or empty when caching is off or has no place (see the file comment). Read
/// from the environment at each call, so a test may change it.
std::filesystem::path velvetCacheDir();

/// True when VELVET_NO_CACHE is set to anything but "" or "0".
bool cachesDisabled();

} // namespace velvet
