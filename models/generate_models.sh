#!/usr/bin/env bash
# Regenerates the bundled meshes of models/ and models/INDEX.md with `msp generate`.
# Usage (from the repository root): models/generate_models.sh [path/to/msp]
set -euo pipefail
msp="${1:-build/apps/msp}"
cd "$(dirname "$0")/.."

# name | msp generate arguments (the output option is added below)
models=(
  "genus0.off|--genus 0 --faces 3000"
  "genus1.off|--genus 1 --faces 3000"
  "genus2.off|--genus 2 --faces 3000"
  "genus3.off|--genus 3 --faces 3500"
  "cap_open.off|--genus 0 --holes 1 --hole-depth 1.2 --faces 2000"
  "genus1_hole.off|--genus 1 --holes 1 --faces 3000"
  "genus2_hole.off|--genus 2 --holes 1 --faces 3000"
  "genus2_two_holes.off|--genus 2 --holes 2 --faces 3000"
  "genus3_two_holes.off|--genus 3 --holes 2 --faces 3500"
)

rows=""
for entry in "${models[@]}"; do
  name="${entry%%|*}"
  args="${entry#*|}"
  command="msp generate ${args} -o models/${name}"
  # shellcheck disable=SC2086
  json="$("$msp" generate ${args} -o "models/${name}" --json)"
  row="$(python3 -c '
import json, sys
j = json.loads(sys.argv[1])
print("| {} | {} | {} | {} | {} | {} | {:.1f} | `{}` |".format(
    sys.argv[2], j["vertices"], j["faces"], j["boundary_loops"], j["genus"],
    "yes" if j["manifold"] else "no", j["min_angle_deg"], sys.argv[3]))
print("{:.2f}".format(j["seconds"]), file=sys.stderr)
' "$json" "$name" "$command" 2> >(sed "s/^/${name}: seconds /" >&2))"
  rows+="${row}"$'\n'
done

cat > models/INDEX.md <<MD
# Bundled models

The project's own meshes, made by \`msp generate\` (libricci/ricci/mesh/generate.h): smooth
implicit surfaces (a blob of three fused spheres for genus 0; g tori R=1, r=0.35 along the x axis
fused by a smooth minimum for genus g >= 1) meshed by CGAL Mesh_3, isotropically remeshed with
vertices projected onto the implicit surface, and for open ones cut by planes near the x ends.
Regenerate all of them (and this file) with \`models/generate_models.sh build/apps/msp\`; the
output is deterministic for a given seed (default 1) and build.

Columns: **bdry loops** = boundary loops; **genus** from chi = V - E + F = 2 - 2g - b; **clean
manifold** = every vertex link is a single fan (OpenMesh is_manifold), one component, oriented
consistently (closed ones outward); **min angle** = smallest triangle angle in degrees; **how
made** = the exact command line, run from the repository root.

| file | V | F | bdry loops | genus | clean manifold | min angle | how made |
|---|---|---|---|---|---|---|---|
${rows}
MD
echo "wrote models/INDEX.md" >&2
