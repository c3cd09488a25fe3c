"""One mesh of a batch, run in a child process of a Dask task (manifold_splines.batch): read,
fit, write PREFIX.msp and PREFIX.glb, then PREFIX.json (the per-mesh report, written last and
atomically: its presence marks the mesh done). Limits the process's address space when asked.

    python -m manifold_splines._task MESH PREFIX OPTIONS_JSON MEMORY_LIMIT_BYTES
"""

import json
import os
import resource
import sys
import time


def write_json_atomically(path, value):
    """Writes `value` as JSON through a temporary next to `path`, renamed into place."""
    temp = f"{path}.tmp.{os.getpid()}"
    with open(temp, "w", encoding="utf-8") as out:
        json.dump(value, out, indent=1)
        out.write("\n")
    os.replace(temp, path)


def peak_memory_mb():
    """Peak resident memory of this process in MiB (ru_maxrss is in KiB on Linux)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def run(mesh, prefix, options, memory_limit):
    if memory_limit > 0:
        resource.setrlimit(resource.RLIMIT_AS, (memory_limit, memory_limit))
    started = time.perf_counter()
    report = {"mesh": mesh, "status": "ok", "error": "", "error_type": ""}
    try:
        import manifold_splines as ms

        V, F = ms.read_mesh(mesh)
        spline = ms.fit(V, F, name=mesh, **options)
        spline.save(prefix + ".msp")
        spline.to_glb(prefix + ".glb")
        report["fit"] = spline.report
    except MemoryError:
        report.update(status="error", error_type="MemoryError",
                      error=f"out of memory (limit {memory_limit / 2**30:.3g} GiB)")
    except Exception as error:  # every failure becomes the mesh's row, never the batch's
        report.update(status="error", error_type=type(error).__name__,
                      error=str(error).splitlines()[0] if str(error) else repr(error))
    report["seconds"] = time.perf_counter() - started
    report["peak_memory_mb"] = peak_memory_mb()
    write_json_atomically(prefix + ".json", report)


if __name__ == "__main__":
    run(sys.argv[1], sys.argv[2], json.loads(sys.argv[3]), int(sys.argv[4]))
