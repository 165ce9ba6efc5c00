#include "core/resources.h"

#include <cstdlib>

#ifndef VELVET_RESOURCE_DIR
#define VELVET_RESOURCE_DIR "resources"
#endif

namespace velvet::resources {
namespace {
std::filesystem::path& appRoot() {
    static std::filesystem::path root;
    return root;
}
} // namespace

void setRoot(const std::filesystem::path& r) {
    appRoot() = r;
}

std::filesystem::path root() {
    if (const char* env = std::getenv("VELVET_RESOURCES"); env && *env)
        return env;
    if (!appRoot().empty())
        return appRoot();
    return VELVET_RESOURCE_DIR;
}

std::filesystem::path path(const std::filesystem::path& relative) {
    return root() / relative;
}

} // namespace velvet::resources
