#!/usr/bin/env bash
# The sanitizer pass of .ci/run (docs/reliability.md, "Sanitizers"): the core tests (tests/core,
# label core: no GL context, no velvet executable) built with clang against the velvet_core that
# scripts/fuzz.sh instruments with AddressSanitizer and UndefinedBehaviorSanitizer, in the same
# tree (build-fuzz/), so the library is not built a second time; then run with LeakSanitizer on.
# Any sanitizer report fails its test (-fno-sanitize-recover=undefined, ASan aborts).
# The whole suite under the sanitizers is `make test-asan` (a full second build).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
jobs=${JOBS:-$(nproc)}

if ! command -v clang++ >/dev/null; then
  echo "velvet sanitize-core: clang++ is missing (Debian package clang)" >&2
  exit 1
fi
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=$root
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
generator=$(command -v ninja >/dev/null && echo Ninja || echo "Unix Makefiles")
CXX=clang++ cmake -S . -B "$build" -G "$generator" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DVELVET_FUZZ=ON -DBUILD_TESTING=ON "${launcher[@]}" >/dev/null
cmake --build "$build" -j "$jobs" >/dev/null
cd "$build"
QT_QPA_PLATFORM= \
  ASAN_OPTIONS=detect_leaks=1 \
  LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$jobs" -L core
