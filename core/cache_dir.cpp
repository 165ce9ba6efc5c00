#include "core/cache_dir.h"

#include <cstdlib>
#include <cstring>

namespace velvet {

bool cachesDisabled() {
    const char* off = std::getenv("VELVET_NO_CACHE");
    return off && *off && std::strcmp(off, "0") != 0;
}

std::filesystem::path velvetCacheDir() {
    if (cachesDisabled())
        return {};
    if (const char* dir = std::getenv("VELVET_CACHE_DIR"); dir && *dir)
        return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return std::filesystem::path(xdg) / "velvet";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "velvet";
    return {};
}

} // namespace velvet
