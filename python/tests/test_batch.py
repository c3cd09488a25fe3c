"""python -m manifold_splines.batch on a 2-worker LocalCluster over the bundled models plus a
corrupt and a non-manifold file: every mesh is a row, the bad ones with their error; a resumed
run skips the done meshes and rebuilds the table from the per-mesh reports; the time limit."""

import os
import shutil
import subprocess
import sys

import pandas as pd
import pytest

import manifold_splines as ms
from conftest import MODELS

GENUS = {"genus0": 0, "genus1": 1, "genus2": 2, "genus3": 3, "cap_open": 0, "genus1_hole": 1,
         "genus2_hole": 2, "genus2_two_holes": 2, "genus3_two_holes": 3}


def run_batch(*args):
    result = subprocess.run([sys.executable, "-m", "manifold_splines.batch", *map(str, args)],
                            capture_output=True, text=True, timeout=900)
    assert result.returncode == 0, result.stderr
    return result


@pytest.fixture(scope="module")
def collection(tmp_path_factory):
    folder = tmp_path_factory.mktemp("collection")
    for name in GENUS:
        shutil.copy(MODELS / f"{name}.off", folder / f"{name}.off")
    bad = folder / "bad"
    bad.mkdir()
    (bad / "corrupt.off").write_text("OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 zero\n")
    (bad / "book.off").write_text("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                                  "3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    return folder


def test_batch_then_resume(collection, tmp_path):
    out = tmp_path / "out"
    first = run_batch(collection, "--out", out, "--workers", 2)
    assert "manifold_splines.batch" in first.stderr  # the progress bar and the summary
    table = pd.read_parquet(out / "results.parquet")
    csv = pd.read_csv(out / "results.csv")
    assert len(table) == len(csv) == len(GENUS) + 2
    rows = {os.path.basename(m).rsplit(".", 1)[0]: row for m, row in
            zip(table["mesh"], table.to_dict("records"))}
    for name, genus in GENUS.items():
        row = rows[name]
        assert row["status"] == "ok", row["error"]
        assert row["genus"] == genus and row["faces"] > 0 and row["watertight"]
        assert row["fit_rms_relative"] < 0.01 and row["peak_memory_mb"] > 0
        for suffix in (".glb", ".msp", ".json"):
            assert (out / "meshes" / f"{name}.off{suffix}").exists()
    for name, error in (("corrupt", ms.IOError), ("book", ms.TopologyError)):
        row = rows[name]
        assert row["status"] == "error" and row["error_type"] == error.__name__
        with pytest.raises(error) as raised:
            ms.read_mesh(str(collection / "bad" / f"{name}.off"))
        assert row["error"] == str(raised.value)
        assert not (out / "meshes" / f"bad__{name}.off.glb").exists()

    # Resume: one report gone; only that mesh runs again, the table is rebuilt whole.
    reports = {p.name: p.stat().st_mtime_ns for p in (out / "meshes").glob("*.json")}
    (out / "meshes" / "genus1.off.json").unlink()
    (out / "results.csv").unlink()
    run_batch(collection, "--out", out, "--workers", 2, "--quiet")
    again = pd.read_parquet(out / "results.parquet")
    assert len(again) == len(table) and (out / "results.csv").exists()
    for name, mtime in reports.items():
        if name != "genus1.off.json":
            assert (out / "meshes" / name).stat().st_mtime_ns == mtime, name
    keep = ["mesh", "genus", "faces", "status", "error", "fit_rms_relative", "watertight"]
    assert again[keep].reset_index(drop=True).equals(table[keep].reset_index(drop=True))


def test_time_limit_and_list_input(collection, tmp_path):
    listing = collection / "one.txt"
    listing.write_text("# one mesh\ngenus3.off\n")
    out = tmp_path / "out"
    run_batch(listing, "--out", out, "--workers", 1, "--time-limit", 0.2, "--quiet")
    row = pd.read_csv(out / "results.csv").iloc[0]
    assert row["status"] == "error" and row["error"] == "time limit of 0.2 s exceeded"


def test_bad_command_lines(collection, tmp_path):
    for args in (["--fit-options", "colour=red"], ["--fit-options", "degree"],
                 ["--workers", "0"]):
        result = subprocess.run([sys.executable, "-m", "manifold_splines.batch", str(collection),
                                 "--out", str(tmp_path / "o"), *args],
                                capture_output=True, text=True)
        assert result.returncode == 2 and "error:" in result.stderr
