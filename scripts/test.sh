#!/usr/bin/env bash
# The README's second command: install what is missing, build with warnings as errors, and run
# the whole test suite with ctest.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install-deps.sh"
"$ROOT/scripts/build.sh" -DMSP_WERROR=ON
cd "${MSP_BUILD_DIR:-$ROOT/build}"
ctest --output-on-failure --parallel "$(nproc)" --timeout 900
