"""Fits a whole collection of meshes on Dask, one task per mesh.

    python -m manifold_splines.batch INPUT_DIR|LIST --out OUT_DIR [--scheduler tcp://host:8786]
        [--workers N] [--fit-options KEY=VALUE ...] [--time-limit S] [--memory-limit BYTES]

INPUT_DIR is searched recursively for .obj/.off/.ply/.stl (also .gz); LIST is a text file of
mesh paths, one a line (relative paths from the list's folder). Without --scheduler a
distributed.LocalCluster of --workers processes runs the tasks; with it, an existing cluster.

Each task runs its mesh in a child process (so a crash, the time limit or the memory limit ends
that mesh alone) and writes OUT_DIR/meshes/KEY.glb, KEY.msp and KEY.json (the per-mesh report,
last and atomically). At the end the result table is rebuilt from every listed mesh's report and
written as OUT_DIR/results.parquet and results.csv: mesh, genus, faces, status, error, the fit's
figures, seconds and peak memory. A mesh that fails becomes a row with its error. Running again
skips the meshes that have a report (--retry-failed runs the failed ones again).
"""

import argparse
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

from ._task import write_json_atomically

MESH_SUFFIXES = (".obj", ".off", ".ply", ".stl")
FIT_OPTIONS = {
    "domain_faces": int,
    "degree": int,
    "fairness": int,
    "smoothing": float,
    "singularity": str,
    "fill_boundaries": bool,
    "density": int,
    "cone_refinement": int,
    "tolerance": float,
    "refine_rounds": int,
    "max_deviation": float,
    "fold_rounds": int,
    "adaptive_domain": bool,
    "small_holes": float,
    "tracked_parameters": bool,
}
COLUMNS = [
    "mesh", "genus", "faces", "status", "error", "error_type", "fit_rms_relative",
    "fit_max_relative", "seam_normal_jump_max_deg", "watertight", "domain_faces",
    "control_points", "seconds", "task_seconds", "peak_memory_mb",
]


def is_mesh(path):
    name = path.name.lower()
    if name.endswith(".gz"):
        name = name[:-3]
    return name.endswith(MESH_SUFFIXES)


def list_meshes(source):
    """The meshes of a folder (recursively, sorted) or of a list file, as absolute paths."""
    source = Path(source)
    if source.is_dir():
        return sorted(str(p.resolve()) for p in source.rglob("*") if p.is_file() and is_mesh(p))
    if not source.is_file():
        raise FileNotFoundError(f"{source}: no such folder or list file")
    meshes = []
    for line in source.read_text(encoding="utf-8").splitlines():
        line = line.strip()
        if line and not line.startswith("#"):
            meshes.append(str((source.parent / line).resolve()))
    return meshes


def mesh_keys(meshes):
    """Output names: each mesh's path relative to the meshes' common folder, '/' -> '__'."""
    if not meshes:
        return []
    root = os.path.commonpath([os.path.dirname(m) for m in meshes])
    return [os.path.relpath(m, root).replace(os.sep, "__") for m in meshes]


def parse_fit_options(items):
    """KEY=VALUE pairs of fit()'s options, typed; raises ValueError on a bad one."""
    options = {}
    for item in items or []:
        key, sep, text = item.partition("=")
        key = key.replace("-", "_")
        if not sep or key not in FIT_OPTIONS:
            raise ValueError(f"--fit-options: '{item}' is not KEY=VALUE with KEY one of "
                             + ", ".join(FIT_OPTIONS))
        kind = FIT_OPTIONS[key]
        if kind is bool:
            if text.lower() not in ("true", "false", "1", "0", "yes", "no"):
                raise ValueError(f"--fit-options: {key} must be true or false, not '{text}'")
            options[key] = text.lower() in ("true", "1", "yes")
        elif key == "singularity":
            options[key] = text if text == "auto" else int(text)
        else:
            options[key] = kind(text)
    return options


def error_report(mesh, message, error_type, seconds):
    return {"mesh": mesh, "status": "error", "error": message, "error_type": error_type,
            "seconds": seconds, "peak_memory_mb": None}


def run_mesh(mesh, prefix, options, time_limit, memory_limit):
    """The Dask task: fits one mesh in a child process and returns its report (never raises
    for the mesh's own failures: a crash, a timeout or a refusal is the report's error)."""
    started = time.perf_counter()
    command = [sys.executable, "-m", "manifold_splines._task", mesh, prefix,
               json.dumps(options), str(int(memory_limit))]
    report_path = prefix + ".json"
    message = None
    error_type = ""
    try:
        child = subprocess.run(command, capture_output=True, text=True,
                               timeout=time_limit if time_limit > 0 else None)
        if child.returncode != 0 or not os.path.exists(report_path):
            if child.returncode < 0:
                name = signal.Signals(-child.returncode).name
                message = f"the fit's process died ({name})"
                error_type = "WorkerDied"
            else:
                tail = (child.stderr.strip().splitlines() or ["no report written"])[-1]
                message = f"the fit's process failed (status {child.returncode}): {tail}"
                error_type = "WorkerFailed"
    except subprocess.TimeoutExpired:
        message = f"time limit of {time_limit:g} s exceeded"
        error_type = "TimeLimit"
    seconds = time.perf_counter() - started
    if message is not None:
        write_json_atomically(report_path, error_report(mesh, message, error_type, seconds))
    with open(report_path, encoding="utf-8") as f:
        report = json.load(f)
    report["task_seconds"] = seconds
    write_json_atomically(report_path, report)
    return report


def table_row(report):
    """One row of the result table from a per-mesh report."""
    fit = report.get("fit") or {}
    return {
        "mesh": report.get("mesh"),
        "genus": fit.get("genus"),
        "faces": fit.get("input_faces"),
        "status": report.get("status"),
        "error": report.get("error", ""),
        "error_type": report.get("error_type", ""),
        "fit_rms_relative": fit.get("fit_rms_relative"),
        "fit_max_relative": fit.get("fit_max_relative"),
        "seam_normal_jump_max_deg": fit.get("seam_normal_jump_max_deg"),
        "watertight": fit.get("watertight"),
        "domain_faces": fit.get("domain_faces"),
        "control_points": fit.get("control_points"),
        "seconds": report.get("seconds"),
        "task_seconds": report.get("task_seconds"),
        "peak_memory_mb": report.get("peak_memory_mb"),
    }


def write_table(out_dir, rows):
    """results.parquet and results.csv (atomically), one row per mesh, sorted by mesh."""
    import pandas as pd

    table = pd.DataFrame(rows, columns=COLUMNS).sort_values("mesh", kind="stable")
    table = table.astype({"genus": "Int64", "faces": "Int64", "domain_faces": "Int64",
                          "control_points": "Int64", "watertight": "boolean"})
    for name, write in (("results.parquet", lambda p: table.to_parquet(p, index=False)),
                        ("results.csv", lambda p: table.to_csv(p, index=False))):
        temp = out_dir / f".{name}.tmp.{os.getpid()}"
        write(temp)
        os.replace(temp, out_dir / name)
    return table


def read_report(path):
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def default_memory_limit(workers):
    """Physical memory shared equally by the workers (bytes)."""
    try:
        import psutil

        return int(psutil.virtual_memory().total / max(workers, 1))
    except ImportError:
        return 0


def run_batch(meshes, out_dir, *, scheduler=None, workers=2, options=None, time_limit=3600.0,
              memory_limit=None, retry_failed=False, progress=True):
    """Fits `meshes` on Dask into `out_dir` (see the module's documentation); returns the
    result table (a pandas DataFrame) and writes it."""
    from dask.distributed import Client, LocalCluster, as_completed

    options = options or {}
    out_dir = Path(out_dir)
    (out_dir / "meshes").mkdir(parents=True, exist_ok=True)
    if memory_limit is None:
        memory_limit = default_memory_limit(workers)
    prefixes = {m: str(out_dir / "meshes" / k) for m, k in zip(meshes, mesh_keys(meshes))}
    todo = []
    for mesh in meshes:
        report = read_report(prefixes[mesh] + ".json")
        if report is None or (retry_failed and report.get("status") != "ok"):
            todo.append(mesh)
    if todo:
        if scheduler:
            cluster = None
            client = Client(scheduler)
        else:
            cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None, memory_limit=0)
            client = Client(cluster)
        try:
            futures = {client.submit(run_mesh, mesh, prefixes[mesh], options, time_limit,
                                     memory_limit, key=f"fit-{i}-{Path(mesh).name}", pure=False):
                       mesh for i, mesh in enumerate(todo)}
            done = as_completed(futures)
            if progress:
                from tqdm import tqdm

                done = tqdm(done, total=len(futures), file=sys.stderr, unit="mesh",
                            desc="manifold_splines.batch")
            for future in done:
                try:
                    future.result()
                except Exception as error:  # the Dask worker itself died or was lost
                    mesh = futures[future]
                    write_json_atomically(prefixes[mesh] + ".json", error_report(
                        mesh, f"the task failed on Dask: {error}", type(error).__name__, None))
        finally:
            client.close()
            if cluster is not None:
                cluster.close()
    rows = [table_row(read_report(prefixes[m] + ".json") or error_report(
        m, "no report", "Missing", None)) for m in meshes]
    return write_table(out_dir, rows)


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog="python -m manifold_splines.batch",
        description="Fit manifold splines to every mesh of a folder or list, on Dask.")
    parser.add_argument("input", help="a folder of meshes (searched recursively) or a list file")
    parser.add_argument("--out", required=True, help="output folder")
    parser.add_argument("--scheduler", help="address of a Dask scheduler (tcp://host:8786); "
                        "default: a LocalCluster")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                        help="LocalCluster worker processes (default: the cores)")
    parser.add_argument("--fit-options", nargs="*", default=[], metavar="KEY=VALUE",
                        help="fit() options: " + ", ".join(FIT_OPTIONS))
    parser.add_argument("--time-limit", type=float, default=3600.0,
                        help="seconds per mesh, 0: none (3600)")
    parser.add_argument("--memory-limit", type=float, default=None,
                        help="bytes of address space per mesh, 0: none (memory / workers)")
    parser.add_argument("--retry-failed", action="store_true",
                        help="run the meshes whose report is an error again")
    parser.add_argument("--quiet", action="store_true", help="no progress bar")
    args = parser.parse_args(argv)
    try:
        options = parse_fit_options(args.fit_options)
        meshes = list_meshes(args.input)
    except (ValueError, OSError) as error:
        parser.error(str(error))
    if args.workers < 1:
        parser.error("--workers must be at least 1")
    if not meshes:
        parser.error(f"{args.input}: no meshes")
    started = time.perf_counter()
    table = run_batch(meshes, args.out, scheduler=args.scheduler, workers=args.workers,
                      options=options, time_limit=args.time_limit,
                      memory_limit=None if args.memory_limit is None else int(args.memory_limit),
                      retry_failed=args.retry_failed, progress=not args.quiet)
    ok = int((table["status"] == "ok").sum())
    print(f"manifold_splines.batch: {len(table)} meshes, {ok} fitted, {len(table) - ok} "
          f"failed, {time.perf_counter() - started:.1f} s; {Path(args.out) / 'results.csv'}",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
