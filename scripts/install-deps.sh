#!/usr/bin/env bash
# Installs the Debian 12 packages Velvet needs to build, run and test, only those missing, and
# two pinned npm packages into the ignored project folder tools/node: the Khronos glTF-Validator
# and mikktspace (the reference MikkTSpace tangent generator, for a known-answer test).
# Runs apt-get as root, or through sudo. Quiet and quick when everything is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config ccache
  qt6-base-dev qt6-base-dev-tools libqt6opengl6-dev libgl-dev
  libglm-dev libepoxy-dev libegl-dev libgl1-mesa-dri libegl-mesa0
  libassimp-dev libopenimageio-dev libopencolorio-dev nlohmann-json3-dev libpng-dev
  libxxhash-dev libimath-dev
  libembree-dev libtbb-dev libpugixml-dev
  clang libclang-rt-14-dev
  xvfb xauth
  nodejs
)

# The glTF export tests (tests/app/test_app_export.cpp) validate every file they write with
# this version, through scripts/gltf-validate.js.
gltf_validator_version=2.0.0-dev.3.10
# tests/core/test_core_mikktspace.cpp compares Velvet's MikkTSpace tangents (core/mikktspace.h)
# with this WebAssembly build of the reference algorithm, through scripts/mikktspace-reference.js.
mikktspace_version=1.1.1
node_tools="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/node"

installed_version() { # package version
  local manifest="$node_tools/node_modules/$1/package.json"
  [[ -f "$manifest" ]] && grep -q "\"version\": \"$2\"" "$manifest"
}

install_node_tools() {
  if installed_version gltf-validator "$gltf_validator_version" &&
     installed_version mikktspace "$mikktspace_version"; then
    return 0
  fi
  if ! command -v npm >/dev/null; then
    echo "velvet: npm is missing (Debian package npm, or Node.js's own); cannot install gltf-validator and mikktspace" >&2
    exit 1
  fi
  echo "velvet: installing gltf-validator $gltf_validator_version and mikktspace $mikktspace_version into tools/node"
  npm install --prefix "$node_tools" --no-save --no-audit --no-fund --loglevel=error \
    "gltf-validator@$gltf_validator_version" "mikktspace@$mikktspace_version"
}

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
if [[ ${#missing[@]} -eq 0 ]] && command -v npm >/dev/null; then
  install_node_tools
  exit 0
fi

if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null; then
  sudo=(sudo)
else
  echo "velvet: these packages are missing and neither root nor sudo is available: ${missing[*]:-npm}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
if [[ ${#missing[@]} -gt 0 ]]; then
  echo "velvet: installing missing Debian packages: ${missing[*]}"
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# Debian's nodejs comes without npm (Node.js's own packages include it).
command -v npm >/dev/null || "${sudo[@]}" apt-get install -y -qq --no-install-recommends npm
install_node_tools
