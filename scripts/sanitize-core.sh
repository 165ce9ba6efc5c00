#!/usr/bin/env bash
# The sanitizer pass of .ci/run (docs/reliability.md, "Sanitizers"): the core tests (tests/core,
# label core: no GL context, no velvet executable) built with clang against the velvet_core that
# scripts/fuzz.sh instruments with AddressSanitizer and UndefinedBehaviorSanitizer, in the same
# tree (build-fuzz/), so the library is not built a second time; then run with LeakSanitizer on.
# Any sanitizer report fails its test (-fno-sanitize-recover=undefined, ASan aborts).
# The whole suite under the sanitizers is `make test-asan` (a full second build).
set -euo pipefail
tool=sanitize-core
# shellcheck source=scripts/fuzz-tree.sh
source "$(dirname "$0")/fuzz-tree.sh"
cmake --build "$build" -j "$jobs" >/dev/null
cd "$build"
QT_QPA_PLATFORM= \
  ASAN_OPTIONS=detect_leaks=1 \
  LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$jobs" -L core
