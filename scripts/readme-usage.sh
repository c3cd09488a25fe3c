#!/usr/bin/env bash
# Regenerates the README's usage block (between the "msp usage" markers) from the built msp:
# the usage lines of `msp CMD --help` for every command `msp --help` lists. The test
# HelpText.ReadmeUsageBlockIsGenerated fails when the README and the tool disagree.
#   scripts/readme-usage.sh [path/to/msp]
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
MSP="${1:-${MSP_BUILD_DIR:-$ROOT/build}/apps/msp}"
README="$ROOT/README.md"
block="$(mktemp)"
trap 'rm -f "$block"' EXIT
{
  echo '```sh'
  for command in $("$MSP" --help | awk '/^commands:/ {on = 1; next} on && NF == 0 {exit} on {print $1}'); do
    "$MSP" "$command" --help | awk 'NF == 0 {exit} {print}'
  done
  echo '```'
} >"$block"
awk -v block="$block" '
  /<!-- msp usage: begin/ {print; while ((getline line < block) > 0) print line; skip = 1; next}
  /<!-- msp usage: end/ {skip = 0}
  !skip {print}' "$README" >"$README.tmp"
mv "$README.tmp" "$README"
