#include "app/resource_root.h"

#include "core/resources.h"

#include <filesystem>

namespace velvet::app {

void locateResources(const char* argv0) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        exe = fs::absolute(argv0, ec);
    const fs::path dir = exe.parent_path();
    for (const fs::path& candidate :
         {dir / "resources", dir / ".." / "share" / "velvet" / "resources",
          dir / ".." / ".." / "resources"}) {
        if (fs::is_directory(candidate / "shaders", ec)) {
            resources::setRoot(fs::weakly_canonical(candidate, ec));
            return;
        }
    }
}

} // namespace velvet::app
