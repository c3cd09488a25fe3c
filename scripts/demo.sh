#!/usr/bin/env bash
# The README's first command: install what is missing, build, and run the main job on a bundled
# model. Outputs go to out/demo/ (printed at the end).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install-deps.sh"
"$ROOT/scripts/build.sh"
OUT="$ROOT/out/demo"
mkdir -p "$OUT"
MSP="${MSP_BUILD_DIR:-$ROOT/build}/apps/msp"
MODEL="$ROOT/models/genus2_eight.off"
[[ -f "$MODEL" ]] || MODEL="$ROOT/tests/data/good/tetrahedron.off"
echo "demo: msp info $MODEL" >&2
"$MSP" info "$MODEL" --json > "$OUT/info.json"
"$MSP" info "$MODEL"
echo "demo: outputs written to $OUT" >&2
