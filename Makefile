# Velvet — the two commands a newcomer needs are `make run` and `make test`.
# `make` alone builds Release into build/ (executable: build/bin/velvet).

BUILD_DIR ?= build
BUILD_TYPE ?= Release
GENERATOR := $(shell command -v ninja >/dev/null 2>&1 && echo Ninja || echo "Unix Makefiles")
JOBS ?= $(shell nproc)
# ccache, when installed, makes rebuilds in a second checkout (a worktree, a fresh clone) cheap;
# CCACHE_BASEDIR lets checkouts in different folders share the cache.
ifneq ($(shell command -v ccache 2>/dev/null),)
export CCACHE_BASEDIR ?= $(CURDIR)
LAUNCHER := -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
endif

.PHONY: all deps configure build run test format clean goldens install package

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
