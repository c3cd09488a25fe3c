#!/usr/bin/env bash
# Validates .glb files with the Khronos glTF-Validator: exits non-zero on any error or warning.
# Usage: scripts/validate-gltf.sh FILE.glb... [--json] [--infos]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [[ ! -d "$root/tools/node_modules/gltf-validator" ]]; then
  echo "validate-gltf: tools/node_modules missing; run scripts/install-deps.sh" >&2
  exit 2
fi
exec node "$root/tools/validate.mjs" "$@"
