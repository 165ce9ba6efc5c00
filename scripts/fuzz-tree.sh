# Sourced by scripts/fuzz.sh and scripts/sanitize-core.sh: configures build-fuzz/ (or
# FUZZ_BUILD_DIR) with clang, AddressSanitizer and UndefinedBehaviorSanitizer (VELVET_FUZZ) and
# the tests (BUILD_TESTING), through ccache when installed. Sets root, build and jobs; needs
# `tool` (the caller's name, for the message) and set -euo pipefail.
cd "$(dirname "${BASH_SOURCE[0]}")/.."
root=$PWD
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
jobs=${JOBS:-$(nproc)}

if ! command -v clang++ >/dev/null; then
  echo "velvet $tool: clang++ is missing (Debian package clang)" >&2
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
