"""Shared fixtures: the bundled models (models/ of the repository), the msp tool for comparing
with the command line (MSP_BINARY, or msp on PATH; those tests skip without it), a fitted
spline of the genus-2 model and the CLI's report of the same fit."""

import json
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(os.environ.get("MSP_SOURCE_DIR", Path(__file__).resolve().parents[2]))
MODELS = ROOT / "models"


def model(name):
    return str(MODELS / name)


def msp_binary():
    binary = os.environ.get("MSP_BINARY") or shutil.which("msp")
    return binary if binary and os.path.exists(binary) else None


def run_msp(*args, check=True):
    """Runs the msp tool; returns the CompletedProcess (skips the test without the tool)."""
    binary = msp_binary()
    if binary is None:
        pytest.skip("the msp tool is not available (MSP_BINARY)")
    result = subprocess.run([binary, *map(str, args)], capture_output=True, text=True)
    if check and result.returncode != 0:
        raise AssertionError(f"msp {' '.join(map(str, args))} failed: {result.stderr}")
    return result


def msp_json(*args):
    return json.loads(run_msp(*args, "--json", "--quiet").stdout)


@pytest.fixture(scope="session")
def genus2():
    import manifold_splines as ms

    return ms.read_mesh(model("genus2.off"))


@pytest.fixture(scope="session")
def fitted(genus2):
    """fit() of the genus-2 model with msp fit's defaults."""
    import manifold_splines as ms

    V, F = genus2
    return ms.fit(V, F, name=model("genus2.off"))


@pytest.fixture(scope="session")
def cli_fit(tmp_path_factory):
    """msp fit of the same model: its report and its spline file."""
    folder = tmp_path_factory.mktemp("cli_fit")
    report, spline = folder / "genus2.json", folder / "genus2.msp"
    run_msp("fit", model("genus2.off"), "--json", report, "--spline", spline, "--quiet")
    return json.loads(report.read_text()), spline


# Figures that depend on the clock or on where the run happened.
VOLATILE = {"seconds", "cpu_seconds", "stage_seconds", "cpu_stage_seconds", "timings", "mesh"}


def close(a, b, rel):
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(close(a[k], b[k], rel) for k in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(close(x, y, rel) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return a == pytest.approx(b, rel=rel, abs=1e-14)
    return a == b


def same_figures(python, cli, rel=1e-9):
    """The two reports agree on every key but the volatile ones (numbers within rel)."""
    assert set(python) == set(cli)
    for key in set(python) - VOLATILE:
        assert close(python[key], cli[key], rel), (key, python[key], cli[key])
