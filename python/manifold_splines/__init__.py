"""Manifold splines from Python: Ricci flow, one-cone affine atlases and DMS spline surfaces
fitted to triangle meshes of any topology, on numpy arrays (V (n, 3) float, F (m, 3) int).

    import manifold_splines as ms
    V, F = ms.read_mesh("models/genus2.off")
    spline = ms.fit(V, F)
    spline.report["fit_rms_relative"]

The reports are the dicts the ``msp`` tool prints with ``--json``. Errors are the library's
own exception classes: InvalidInputError and TopologyError (ValueError), IOError (OSError),
SolverError (RuntimeError), all deriving from manifold_splines.Error. ``python -m
manifold_splines.batch`` fits whole collections on Dask.
"""

from ._core import (
    Atlas,
    Error,
    InfeasibleTargetError,
    InvalidInputError,
    IOError,
    SolverError,
    Spline,
    TopologyError,
    atlas,
    fit,
    flow,
    info,
    read_mesh,
    uniformize,
)

__all__ = [
    "Atlas",
    "Error",
    "IOError",
    "InfeasibleTargetError",
    "InvalidInputError",
    "SolverError",
    "Spline",
    "TopologyError",
    "atlas",
    "fit",
    "flow",
    "info",
    "read_mesh",
    "uniformize",
]
__version__ = "0.1.0"
