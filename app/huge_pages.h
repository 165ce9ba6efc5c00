#pragma once
/// @file huge_pages.h
/// Transparent huge pages for the process's large allocations (BENCHMARKS.md, "Huge pages").
/// On Mesa's llvmpipe a texture, a render target or a buffer is plain heap memory, and in a
/// virtual machine each 4 KiB page fault on first touch is expensive: an 85 MB texture took
/// 230 ms to allocate, a whole `velvet render` spent half its time faulting pages in. glibc's
/// malloc backs its large (mmap'd) chunks with transparent huge pages when the tunable
/// glibc.malloc.hugetlb=1 is set (glibc 2.35), and tunables are read only at process start, so
/// Velvet sets it and executes itself again once, before anything else runs.

#include <string>

namespace velvet::app {

/// Re-executes this program with glibc.malloc.hugetlb=1 added to GLIBC_TUNABLES, unless it is
/// already there (or any glibc.malloc.hugetlb value is: the user's choice), VELVET_HUGE_PAGES=0
/// is set, the C library is not glibc 2.35 or later, or the build has AddressSanitizer (which
/// replaces malloc). Returns only when it does not re-execute (or the exec failed).
void reexecWithHugePages(int argc, char** argv);

/// Whether glibc.malloc.hugetlb=1 is set for this process (`velvet info` says so).
bool hugePagesRequested();
/// The kernel's transparent huge page mode ("always", "madvise" or "never"; "" where unknown):
/// glibc's request takes effect under "always" and "madvise".
std::string kernelHugePageMode();

} // namespace velvet::app
