#!/usr/bin/env bash
# What `make bench-peers` needs beyond scripts/install-deps.sh: Debian's Chromium (about 350 MB
# installed, so not among the packages every build installs) and the peer page's npm packages
# (three, puppeteer-core; pinned by bench/peers/three/package-lock.json) in the ignored
# bench/peers/three/node_modules. Only what is missing; quick when everything is present.
set -euo pipefail

peer="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/bench/peers/three"

packages=(chromium nodejs)
missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$p")
done
command -v npm >/dev/null || missing+=(npm) # Debian's nodejs comes without npm

if [[ ${#missing[@]} -gt 0 ]]; then
  if [[ $(id -u) -eq 0 ]]; then
    sudo=()
  elif command -v sudo >/dev/null; then
    sudo=(sudo)
  else
    echo "bench-peers: these packages are missing and neither root nor sudo is available: ${missing[*]}" >&2
    exit 2
  fi
  echo "bench-peers: installing missing Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm ci reinstalls from the lock file; a stamp of the lock's hash skips it when nothing changed.
stamp="$peer/node_modules/.velvet-lock-sha256"
lock_sha=$(sha256sum "$peer/package-lock.json" | cut -d' ' -f1)
if [[ ! -f "$stamp" || "$(cat "$stamp")" != "$lock_sha" ]]; then
  echo "bench-peers: installing the peer page's npm packages into bench/peers/three/node_modules"
  npm ci --prefix "$peer" --no-audit --no-fund --loglevel=error
  echo "$lock_sha" >"$stamp"
fi
