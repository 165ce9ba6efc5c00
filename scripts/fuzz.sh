#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz) with clang into build-fuzz/, replays every seed and
# reproducer, then fuzzes each target for FUZZ_SECONDS (default 15; .ci/run: 7 targets, 105 s in
# all). Exit 1 on any crash, hang, leak or sanitizer report; libFuzzer writes the input that
# caused it to build-fuzz/findings/<target>/ — commit it to tests/fuzz/corpus/<target>/ with
# the fix, so it is replayed from then on. docs/reliability.md, "Fuzzed parsers".
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
build=${FUZZ_BUILD_DIR:-$root/build-fuzz}
seconds=${FUZZ_SECONDS:-15}
jobs=${JOBS:-$(nproc)}

if ! command -v clang++ >/dev/null; then
  echo "velvet fuzz: clang++ is missing (Debian package clang)" >&2
  exit 1
fi
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR=$root
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
generator=$(command -v ninja >/dev/null && echo Ninja || echo "Unix Makefiles")
# The same tree holds the core tests for scripts/sanitize-core.sh (BUILD_TESTING); only the
# fuzz targets are built here.
CXX=clang++ cmake -S . -B "$build" -G "$generator" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DVELVET_FUZZ=ON -DBUILD_TESTING=ON "${launcher[@]}" >/dev/null
targets=(fuzz_material fuzz_scene fuzz_post_chain fuzz_atlas fuzz_mesh_cache fuzz_gltf fuzz_mtlx)
cmake --build "$build" -j "$jobs" --target "${targets[@]}" fuzz_seeds >/dev/null

seeds=$build/seeds
rm -rf "$seeds" && "$build/fuzz/fuzz_seeds" "$seeds" resources/presets

# target -> read-only seed folders (besides its committed reproducers)
declare -A seed_dirs=(
  [fuzz_material]="resources/presets tests/data/malformed"
  [fuzz_scene]="$seeds/scene tests/data/malformed"
  [fuzz_post_chain]="resources/post-chains"
  [fuzz_atlas]="$seeds/atlas"
  [fuzz_mesh_cache]="$seeds/mesh_cache"
  [fuzz_gltf]="$seeds/gltf tests/fuzz/seeds/gltf"
  [fuzz_mtlx]="$seeds/mtlx tests/fuzz/seeds/mtlx"
)
# Bounded inputs and runs: a document over 64 KiB adds nothing a small one cannot reach, and a
# parser that spends a second on one input is a finding (a hang).
common=(-max_len=65536 -timeout=5 -rss_limit_mb=2048 -print_final_stats=0)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0
# Only leaks third-party libraries make by design or by their own bug (named there), never Velvet's.
export LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# The import targets write each input to a temporary folder; libFuzzer can end without running
# atexit handlers, so keep those folders in the build tree, emptied on every run.
export TMPDIR=$build/tmp
rm -rf "$TMPDIR" && mkdir -p "$TMPDIR"

failed=0
for target in "${targets[@]}"; do
  binary=$build/fuzz/$target
  repro=tests/fuzz/corpus/$target
  work=$build/corpus/$target
  findings=$build/findings/$target
  mkdir -p "$repro" "$work" "$findings"
  read -r -a seeds_of <<<"${seed_dirs[$target]}"
  # 1. Replay: every committed reproducer and seed must pass as it is.
  files=()
  for d in "$repro" "${seeds_of[@]}"; do
    for f in "$d"/*; do [[ -f $f ]] && files+=("$f"); done
  done
  if ! "$binary" "${common[@]}" "${files[@]}" >"$build/$target.replay.log" 2>&1; then
    echo "velvet fuzz: $target fails on a committed input; see $build/$target.replay.log" >&2
    tail -30 "$build/$target.replay.log" >&2
    failed=1
    continue
  fi
  # 2. Fuzz for a bounded time, growing the (ignored) work corpus from the seeds.
  if ! "$binary" "${common[@]}" -max_total_time="$seconds" -artifact_prefix="$findings/" \
      "$work" "$repro" "${seeds_of[@]}" >"$build/$target.log" 2>&1; then
    echo "velvet fuzz: $target found a failure; input in $findings/, log $build/$target.log" >&2
    tail -40 "$build/$target.log" >&2
    failed=1
    continue
  fi
  runs=$(grep -oE 'Done [0-9]+ runs' "$build/$target.log" | tail -1 | awk '{print $2}')
  echo "velvet fuzz: $target: ${#files[@]} committed inputs replayed, ${runs:-?} runs in ${seconds} s, no finding"
done
exit $failed
