#!/usr/bin/env bash
# The README's first command: install what is missing, build, and run the main job on a bundled
# genus-2 model. Outputs go to out/demo/ (listed at the end).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
"$ROOT/scripts/install-deps.sh"
"$ROOT/scripts/build.sh"
OUT="$ROOT/out/demo"
mkdir -p "$OUT"
MSP="${MSP_BUILD_DIR:-$ROOT/build}/apps/msp"
MODEL="$ROOT/models/genus2.off"

echo "demo: describing $MODEL" >&2
"$MSP" info "$MODEL" --json > "$OUT/info.json"

echo "demo: one-cone flat metric, cut graph, layout and affine atlas" >&2
"$MSP" atlas "$MODEL" --json -o "$OUT/atlas.svg" --checkerboard "$OUT/checkerboard.glb" > "$OUT/atlas.json"

echo "demo: outputs in $OUT:" >&2
ls -1 "$OUT" >&2
