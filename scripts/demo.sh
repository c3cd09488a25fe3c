#!/usr/bin/env bash
# The README's first command: install what is missing, build, and run the main job on a bundled
# genus-2 model: msp fit (scan -> spline -> watertight glTF) with its report, validated and
# rendered to a PNG. Outputs go to out/demo/ (listed at the end).
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

echo "demo: manifold spline fit, watertight tessellation and glTF export" >&2
"$MSP" fit "$MODEL" -o "$OUT/genus2.glb" --json "$OUT/genus2.json" --checkerboard --cut-loops

echo "demo: validating and rendering the glTF (Khronos validator, three.js in headless Chromium)" >&2
"$ROOT/scripts/validate-gltf.sh" "$OUT/genus2.glb" >&2
"$ROOT/scripts/render-glb.sh" "$OUT/genus2.glb" "$OUT/genus2.png" --width 800 --height 600 >&2

echo "demo: outputs in $OUT:" >&2
ls -1 "$OUT" >&2
