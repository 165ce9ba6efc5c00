#include "app/huge_pages.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

namespace velvet::app {
namespace {

constexpr const char* kTunable = "glibc.malloc.hugetlb";

bool supported() {
#if defined(__SANITIZE_ADDRESS__)
    return false; // ASan's allocator replaces glibc's: the tunable would do nothing
#elif defined(__GLIBC__) && defined(__GLIBC_PREREQ)
#if __GLIBC_PREREQ(2, 35)
    return true;
#else
    return false;
#endif
#else
    return false;
#endif
}

} // namespace

bool hugePagesRequested() {
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    return tunables &&
           std::string(tunables).find(std::string(kTunable) + "=1") != std::string::npos;
}

std::string kernelHugePageMode() {
    std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(in, line); // "always [madvise] never": the chosen one in brackets
    const size_t open = line.find('['), close = line.find(']');
    return open != std::string::npos && close > open ? line.substr(open + 1, close - open - 1)
                                                     : std::string();
}

void reexecWithHugePages(int argc, char** argv) {
    (void)argc;
    if (!supported())
        return;
    if (const char* off = std::getenv("VELVET_HUGE_PAGES"); off && std::string(off) == "0")
        return;
    const char* existing = std::getenv("GLIBC_TUNABLES");
    const std::string tunables = existing ? existing : "";
    if (tunables.find(kTunable) != std::string::npos)
        return; // set already (by the first run, or by the user)
    const std::string value =
        (tunables.empty() ? "" : tunables + ":") + std::string(kTunable) + "=1";
    if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0)
        return;
    execv("/proc/self/exe", argv);
    // The exec failed (no /proc, say): go on without huge pages, and say nothing — this is a
    // speed-up, not a requirement. Keep the environment as it was for child processes.
    if (existing)
        setenv("GLIBC_TUNABLES", existing, 1);
    else
        unsetenv("GLIBC_TUNABLES");
}

} // namespace velvet::app
