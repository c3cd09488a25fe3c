#!/usr/bin/env bash
# Installs, from Debian packages, whatever the build, the tests and the demo need and is missing.
# Idempotent: when everything is present it changes nothing and does not touch the network.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libopenmesh-dev libcgal-dev libosd-dev
  libtinygltf-dev libstb-dev nlohmann-json3-dev zlib1g-dev
  libsuitesparse-dev libopenblas0-pthread
  libgtest-dev
  chromium fonts-dejavu-core
  python3-dev python3-pip python3-venv
)
# Node.js may come from another source (with its own npm); only ask Debian for it when absent.
command -v node >/dev/null 2>&1 || PACKAGES+=(nodejs)
command -v npm >/dev/null 2>&1 || PACKAGES+=(npm)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if ((${#missing[@]})); then
  echo "install-deps: installing ${missing[*]}" >&2
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all Debian packages present" >&2
fi

# Node tools (tools/package.json: glTF validator, three.js, puppeteer-core): install the locked
# versions when node_modules is missing or older than the lock file.
TOOLS="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools"
if [[ -f "$TOOLS/package-lock.json" ]]; then
  stamp="$TOOLS/node_modules/.package-lock.json"
  if [[ ! -f "$stamp" || "$TOOLS/package-lock.json" -nt "$stamp" ]]; then
    echo "install-deps: npm ci in tools/" >&2
    npm ci --prefix "$TOOLS" --no-audit --no-fund --loglevel=error >/dev/null
  else
    echo "install-deps: tools/node_modules up to date" >&2
  fi
fi

# Python packages of the binding (python/), its tests and the batch runs, from PyPI into the
# machine's python3 (the one CMake finds) when one of them is missing.
PY_PACKAGES=(nanobind scikit-build-core numpy pytest dask distributed pandas pyarrow tqdm)
PY_MODULES="nanobind,scikit_build_core,numpy,pytest,dask,distributed,pandas,pyarrow,tqdm"
if ! python3 -c "import $PY_MODULES" 2>/dev/null; then
  echo "install-deps: pip install ${PY_PACKAGES[*]}" >&2
  PIP_FLAGS=(--quiet --disable-pip-version-check)
  # Debian's python3 is "externally managed": pip needs to be told to install into it.
  if python3 -c "import sys, sysconfig, os; sys.exit(not os.path.exists(os.path.join(
      sysconfig.get_path('stdlib'), 'EXTERNALLY-MANAGED')))"; then
    PIP_FLAGS+=(--break-system-packages)
  fi
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  $SUDO python3 -m pip install "${PIP_FLAGS[@]}" "${PY_PACKAGES[@]}"
else
  echo "install-deps: Python packages present" >&2
fi
