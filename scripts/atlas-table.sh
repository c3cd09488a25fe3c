#!/usr/bin/env bash
# Runs `msp atlas --json` on the bundled models (models/) and, when a model collection's folder
# is given (second argument, or the environment variable MSP_SHARED_MODELS), on its closed_g*,
# open and bench meshes too, and prints a markdown table of its figures. The singularity is
# chosen automatically up to 20k faces and put at vertex 0 above (as in the collection's bench
# README's comparison).
# Usage: scripts/atlas-table.sh [MSP] [MODEL_COLLECTION]
set -uo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
MSP="${1:-${MSP_BUILD_DIR:-$ROOT/build}/apps/msp}"
SHARED="${2:-${MSP_SHARED_MODELS:-}}"
if [[ -n "$SHARED" && ! -d "$SHARED" ]]; then
  echo "atlas-table.sh: '$SHARED' is not a folder" >&2
  exit 2
fi
FILES=("$ROOT"/models/*.off)
if [[ -n "$SHARED" ]]; then
  FILES=("$SHARED"/closed_g*/*.* "$SHARED"/open/*.* "$SHARED"/bench/*.obj "${FILES[@]}")
fi
echo "| mesh | F | genus | bdry | kind | cone angle/pi | splits | metric | Newton it. | max K error | transition residual | flipped | uncovered | edge rel. error | area distortion | angle ratio p05/p50/p95 | QC mean | s (choice/flow/atlas) |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for f in "${FILES[@]}"; do
  case "$f" in *.md|*.py) continue ;; esac
  faces=$("$MSP" info "$f" --json 2>/dev/null | python3 -c "import sys,json; print(json.load(sys.stdin)['faces'])" 2>/dev/null || echo 0)
  singular=auto
  [[ "$faces" -gt 20000 ]] && singular=0
  name="${f#"$ROOT"/}"
  [[ -n "$SHARED" ]] && name="${name#"$SHARED"/}"
  out=$("$MSP" atlas "$f" --singularity "$singular" --json --quiet 2>&1)
  echo "$out" | python3 -c "
import sys, json, math
name, faces = sys.argv[1], sys.argv[2]
text = sys.stdin.read()
try:
    d = json.loads(text)
except Exception:
    print(f'| {name} | {faces} | | | failed: {text.strip()[:160]} |'); sys.exit()
cone = d['singularities'][0].get('cone_angle') if d['singularities'] else None
cone = f'{cone/math.pi:.3f}' if cone else '-'
s = d['stage_seconds']
print(f\"| {name} | {d['faces']} | {d['genus']} | {d['boundary_loops']} | {d['kind']} | {cone} | {d['valence_splits']} | {d['metric']} | {d['newton_iterations']} | {d['max_curvature_error']:.1e} | {d['transition_residual']:.1e} | {d['flipped_faces']} | {d['uncovered_faces']} | {d['domain_length_error']:.1e} | {d['area_distortion']:.3g} | {d['angle_ratio_p05']:.2f}/{d['angle_ratio_p50']:.2f}/{d['angle_ratio_p95']:.2f} | {d['quasi_conformal_mean']:.3f} | {d['seconds']:.2f} ({s['choice']:.2f}/{s['flow']:.2f}/{s['atlas']:.2f}) |\")
" "$name" "$faces"
done
