#!/usr/bin/env bash
# Configures and builds the project (Release, Ninja, ccache when present) into ./build.
# Extra arguments go to CMake's configure step, e.g. -DMSP_SANITIZE=ON.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD_DIR="${MSP_BUILD_DIR:-$ROOT/build}"
JOBS="${MSP_JOBS:-$(nproc)}"
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$BUILD_DIR" --parallel "$JOBS"
