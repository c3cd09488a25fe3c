#!/usr/bin/env bash
# Renders a .glb to a PNG with three.js in headless Chromium (see tools/render.mjs for options).
# Usage: scripts/render-glb.sh FILE.glb OUT.png [--width W] [--height H] [--azimuth DEG] [--elevation DEG]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ ! -d "$root/tools/node_modules/puppeteer-core" ]]; then
  echo "render-glb: tools/node_modules missing; run scripts/install-deps.sh" >&2
  exit 2
fi
exec node "$root/tools/render.mjs" "$@"
