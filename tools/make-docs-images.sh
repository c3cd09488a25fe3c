#!/usr/bin/env bash
# Regenerates the README pictures in docs/images from the shared models: the atlas SVGs
# (rasterised) and renders of the checkerboard .glb files. Needs a built msp and tools/node_modules.
# Usage: tools/make-docs-images.sh [MSP_BINARY] [MODELS_DIR]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
msp="${1:-$root/build/apps/msp}"
models="${2:-$root/../shared/models}"
out="$root/docs/images"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$out"

# name model singularity azimuth elevation svg-width (PNGs stay under 300 KB)
while read -r name model singularity azimuth elevation width; do
  args=(atlas "$models/$model" --quiet -o "$work/$name.svg" --checkerboard "$work/$name.glb")
  [[ "$singularity" != auto ]] && args+=(--singularity "$singularity")
  "$msp" "${args[@]}" >/dev/null
  # Caption shows the model's path relative to the models folder.
  sed -i "s|$models/||" "$work/$name.svg"
  node "$root/tools/validate.mjs" "$work/$name.glb"
  node "$root/tools/render.mjs" "$work/$name.svg" "$out/atlas_$name.png" --width "$width"
  node "$root/tools/render.mjs" "$work/$name.glb" "$out/checkerboard_$name.png" --width 800 --height 600 \
    --azimuth "$azimuth" --elevation "$elevation"
done <<'LIST'
genus1_elk closed_g1/elk.off auto 30 20 1000
genus2_eight closed_g2/eight.off 570 20 35 1000
genus3 closed_g3/genus3.off 17 0 60 860
LIST

# msp match: the head against a copy stretched by 1.3 across the face and bent (z += 0.4 y^2 in
# units of the head's size, about its centre), the nose-bridge vertex 185 as the feature on both.
awk 'NR == 2 {n = $1} NR > 2 && NR <= n + 2 {
       cx = -0.28916; cy = 8.6530005; cz = 0.005765; s = 17.414001
       x = ($1 - cx) / s * 1.3; y = ($2 - cy) / s; z = ($3 - cz) / s + 0.4 * y * y
       printf "%.9g %.9g %.9g\n", x * s + cx, y * s + cy, z * s + cz; next} {print}' \
  "$models/open/head.off" >"$work/head_deformed.off"
"$msp" match "$models/open/head.off" "$work/head_deformed.off" --feature-a 185 --feature-b 185 \
  -o "$work/head.map" --glb "$work/match_head.glb" --checker-squares 40 --quiet >/dev/null
node "$root/tools/validate.mjs" "$work/match_head.glb"
node "$root/tools/render.mjs" "$work/match_head.glb" "$out/match_head.png" --width 1000 --height 500 \
  --azimuth 0 --elevation 0
# msp module: the circle domain of the lion (the intrinsic Delaunay route); PNGs under 200 KB.
"$msp" module "$models/open/lion.off" --quiet -o "$work/module_lion.svg" >/dev/null
sed -i "s|$models/||" "$work/module_lion.svg"
node "$root/tools/render.mjs" "$work/module_lion.svg" "$out/module_lion_circle_domain.png" \
  --width 520

# msp index: the circle domains of the open scans with four boundary loops, side by side.
{
  echo '<svg xmlns="http://www.w3.org/2000/svg" width="3000" height="1100" viewBox="0 0 3000 1100">'
  i=0
  for name in eight_open intersection_quads mech-holes-shark; do
    "$msp" module "$models/open/$name.off" --quiet -o "$work/index_$name.svg" >/dev/null
    sed -i "s|$models/||" "$work/index_$name.svg"
    # Each picture nested at its offset: its <svg> tag replaced, the XML declaration dropped.
    awk -v x=$((i * 1000)) 'FNR == 1 && /^<\?xml/ {next}
      /^<svg / && !done {
        sub(/<svg [^>]*>/, "<svg x=\"" x "\" y=\"0\" width=\"1000\" height=\"1100\" " \
            "viewBox=\"0 0 1000 1100\">")
        done = 1
      }
      {print}' "$work/index_$name.svg"
    i=$((i + 1))
  done
  echo '</svg>'
} >"$work/index_four_loops.svg"
node "$root/tools/render.mjs" "$work/index_four_loops.svg" "$out/index_four_loops.png" --width 900
ls -l "$out"
