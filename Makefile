# Velvet — the two commands a newcomer needs are `make run` and `make test`.
# `make` alone builds Release into build/ (executable: build/bin/velvet).

BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
# Ninja and ccache are looked for when a build folder is configured (recursively expanded: after
# `deps` has run), so the first build on a fresh machine, whose `make test` installs them, uses
# them too. ccache makes rebuilds in a second checkout (a worktree, a fresh clone) cheap;
# CCACHE_BASEDIR lets checkouts in different folders share the cache.
GENERATOR = $(shell command -v ninja >/dev/null 2>&1 && echo Ninja || echo "Unix Makefiles")
export CCACHE_BASEDIR ?= $(CURDIR)
LAUNCHER = $(if $(shell command -v ccache 2>/dev/null),-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)

.PHONY: all deps configure build run test test-asan test-asan-core fuzz format clean goldens install package \
  bench-peers

all: build

deps:
	@scripts/install-deps.sh

$(BUILD_DIR)/CMakeCache.txt:
	cmake -S . -B $(BUILD_DIR) -G "$(GENERATOR)" -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(LAUNCHER)

configure: deps $(BUILD_DIR)/CMakeCache.txt

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Opens the editor on the default scene; without a display says so and points to the CLI.
run: build
	@if [ -z "$$DISPLAY" ] && [ -z "$$WAYLAND_DISPLAY" ]; then \
	  echo "velvet: no display found (DISPLAY/WAYLAND_DISPLAY unset); render headless with: $(BUILD_DIR)/bin/velvet render -o out.png"; \
	else \
	  $(BUILD_DIR)/bin/velvet; \
	fi

# Builds and runs the whole suite headless (widget tests under xvfb-run, render tests on EGL).
test: build
	cd $(BUILD_DIR) && QT_QPA_PLATFORM= ctest --output-on-failure -j $(JOBS)

# The libFuzzer targets (tests/fuzz, clang): replays every committed input, then fuzzes each
# parser for FUZZ_SECONDS (default 15). docs/reliability.md.
fuzz: deps
	scripts/fuzz.sh

# The core tests under AddressSanitizer and UndefinedBehaviorSanitizer, built in build-fuzz/ against
# the velvet_core `make fuzz` instruments (no second build of the library): .ci/run's sanitizer
# pass. docs/reliability.md, "Sanitizers".
test-asan-core: deps
	scripts/sanitize-core.sh

# The whole suite built with AddressSanitizer and UndefinedBehaviorSanitizer in build-asan/.
# Left out, each for a reason that is the sanitizer's and not Velvet's (docs/reliability.md):
# the hostile-mesh test, whose memory hog needs the import child's address-space limit, which
# sanitizer builds do not set (ASan reserves terabytes of shadow address space at start, so any
# RLIMIT_AS kills the child before it reads a byte). About 45 minutes on 2 cores (a 21-minute
# build, 24 minutes of tests): not part of .ci/run, which runs test-asan-core.
ASAN_BUILD_DIR ?= build-asan
ASAN_EXCLUDE ?= test_app_hostile_meshes
test-asan: deps
	@[ -f $(ASAN_BUILD_DIR)/CMakeCache.txt ] || cmake -S . -B $(ASAN_BUILD_DIR) -G "$(GENERATOR)" \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVELVET_SANITIZE=ON $(LAUNCHER)
	cmake --build $(ASAN_BUILD_DIR) -j $(JOBS)
	cd $(ASAN_BUILD_DIR) && QT_QPA_PLATFORM= \
	  ASAN_OPTIONS=detect_leaks=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers/lsan.supp \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --output-on-failure -j $(JOBS) -E '$(ASAN_EXCLUDE)'

# Velvet's steady preview frame beside three.js's frame of the same scene on the same driver
# (issue 16; bench/peers/three/run.mjs, BENCHMARKS.md "Peer: three.js"): installs Chromium and the
# peer's npm packages (scripts/install-bench-peers.sh), then alternates the two renderers three
# times. Not part of `make test`. BENCH_PEERS_ARGS passes options, e.g. "--rounds 5 --json".
bench-peers: build
	@scripts/install-bench-peers.sh
	node bench/peers/three/run.mjs --velvet $(BUILD_DIR)/bin/velvet $(BENCH_PEERS_ARGS)

# Installs the editor, its resources, .desktop entry and icon under PREFIX (DESTDIR for staging).
PREFIX ?= /usr/local
install: build
	DESTDIR=$(DESTDIR) cmake --install $(BUILD_DIR) --prefix $(PREFIX)

# A Debian package (build/velvet_VERSION_ARCH.deb) whose Depends dpkg-shlibdeps computes.
package: build
	cd $(BUILD_DIR) && cpack -G DEB

# Regenerates the golden images from the current renderer (review the diff before committing).
goldens: build
	VELVET_UPDATE_GOLDENS=1 ctest --test-dir $(BUILD_DIR) -R golden --output-on-failure

format:
	find core render ui app tests -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
