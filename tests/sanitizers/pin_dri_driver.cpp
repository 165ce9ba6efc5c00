// Sanitizer builds only (VELVET_SANITIZE, `make test-asan`), linked into every target.
//
// Mesa dlcloses its DRI driver when the last display goes (eglTerminate, XCloseDisplay).
// LeakSanitizer checks at exit, after that, and can then name neither the driver's process-wide
// allocations nor their module ("<unknown module>"), so the driver suppressions of
// tests/sanitizers/lsan.supp cannot match them: every GL test reported the same two 56-byte
// blocks. Loading the driver once more with RTLD_NODELETE, before anything else does, keeps it
// mapped to the end; Mesa's own dlopen of the same path then finds this copy.
#include <dlfcn.h>

namespace {

struct PinDriDriver {
    PinDriDriver() { dlopen(VELVET_DRI_DRIVER, RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE); }
} pinDriDriver;

} // namespace
