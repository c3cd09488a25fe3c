#!/usr/bin/env bash
# `pip install .` of the repository into a fresh virtual environment, then the README's Python
# example run with it. Offline: the venv sees the machine's packages (numpy, nanobind,
# scikit-build-core) and pip does not isolate the build.
# Usage: pip_install_test.sh ROOT [PYTHON [CXX]] (CXX: the project build's compiler, so that the
# compile commands, hence ccache's keys, are the same).
set -euo pipefail
ROOT="$1"
PYTHON="${2:-python3}"
if [[ -n "${3:-}" ]]; then export CXX="$3"; fi
WORK="$(mktemp -d)"
# The CMake build folder one level under ROOT like the project's build/: ccache keys hold include
# paths relative to the build folder (CCACHE_BASEDIR), so the same depth gives the same keys.
BUILD="$ROOT/build-pip-install-test-$$"
trap 'rm -rf "$WORK" "$BUILD"' EXIT
"$PYTHON" -m venv --system-site-packages "$WORK/venv"
# Same warning flags as the project's build, so ccache serves the libraries' objects.
"$WORK/venv/bin/python" -m pip install --no-build-isolation --no-deps --quiet \
  --config-settings=cmake.define.MSP_WERROR=ON --config-settings=build-dir="$BUILD" "$ROOT"
sed -n '/<!-- python example: begin -->/,/<!-- python example: end -->/p' "$ROOT/README.md" |
  sed '1,2d;$d' | sed '$d' > "$WORK/example.py"
ln -s "$ROOT/models" "$WORK/models"
cd "$WORK"
"$WORK/venv/bin/python" example.py
test -s genus2.msp && test -s genus2.glb
"$WORK/venv/bin/python" -c "import manifold_splines as ms, pathlib; \
  assert pathlib.Path(ms.__file__).is_relative_to(pathlib.Path('$WORK/venv')), ms.__file__; \
  assert (pathlib.Path(ms.__file__).parent / '_core.pyi').exists(); \
  print('installed', ms.__file__, ms.Spline.load('genus2.msp'))"
