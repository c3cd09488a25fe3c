"""flow, atlas and uniformize against the msp tool's JSON on the bundled models, and the
mathematics of their outputs."""

import numpy as np
import pytest

import manifold_splines as ms
from conftest import model, msp_json, same_figures

def test_flow_matches_the_cli_and_reaches_the_target():
    V, F = ms.read_mesh(model("genus1.off"))
    u, report = ms.flow(V, F, name=model("genus1.off"))
    same_figures(report, msp_json("flow", model("genus1.off")))
    assert report["status"] == "converged" and report["max_curvature_error"] < 1e-10
    assert u.shape == (len(V),) and np.isfinite(u).all()


def test_flow_options_and_refusals():
    V, F = ms.read_mesh(model("genus2.off"))
    u, report = ms.flow(V, F, geometry="hyperbolic", metric="circle-packing")
    assert report["geometry"] == "hyperbolic" and report["metric"] == "circle-packing"
    with pytest.raises(ms.InvalidInputError, match="geometry must be one of euclidean"):
        ms.flow(V, F, geometry="flat")
    with pytest.raises(ms.InvalidInputError, match="target must be uniform"):
        ms.flow(V, F, target="cones")
    with pytest.raises(ms.InvalidInputError, match="cone:VERTEX needs a vertex index"):
        ms.flow(V, F, target="cone:x")
    with pytest.raises(ms.InfeasibleTargetError):
        ms.flow(V, F, geometry="spherical")  # genus 2 has no spherical metric


def test_atlas_matches_the_cli_and_lays_out_without_flips():
    V, F = ms.read_mesh(model("genus2.off"))
    atlas = ms.atlas(V, F, name=model("genus2.off"))
    same_figures(atlas.report, msp_json("atlas", model("genus2.off")), rel=1e-6)
    assert atlas.report["genus"] == 2 and atlas.report["flipped_faces"] == 0
    assert len(atlas.transitions) > 0 and atlas.singularities == atlas.report["singularities"]
    # Corners of each domain face in the central chart: counter-clockwise, non-degenerate.
    uv = atlas.uv[atlas.in_domain]
    assert np.isfinite(uv).all()
    e1, e2 = uv[:, 1] - uv[:, 0], uv[:, 2] - uv[:, 0]
    assert (e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] > 0).all()
    # The cut graph's edges are mesh edges and pass through the cone.
    edges = {tuple(sorted(e)) for f in atlas.F for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    assert all(tuple(sorted(e)) in edges for e in atlas.cut_edges)
    assert atlas.cone_vertex in set(atlas.cut_edges.ravel())


def test_atlas_singularity_option():
    V, F = ms.read_mesh(model("genus2.off"))
    with pytest.raises(ms.InvalidInputError, match="singularity must be"):
        ms.atlas(V, F, singularity="centre")
    with pytest.raises(ms.InvalidInputError, match="singularity must be"):
        ms.atlas(V, F, singularity=-3)


def test_uniformize_matches_the_cli():
    V, F = ms.read_mesh(model("genus2.off"))
    report = ms.uniformize(V, F, name=model("genus2.off"))
    same_figures(report, msp_json("uniformize", model("genus2.off")), rel=1e-6)
    assert report["geometry"] == "hyperbolic" and len(report["generators"]) == 4
    # Klein matrices are Lorentz transformations: L^T J L = J, J = diag(1, -1, -1) (to the
    # rounding of entries of size |L|).
    J = np.diag([1.0, -1.0, -1.0])
    for g in report["generators"]:
        L = np.array(g["klein"])
        assert np.abs(L.T @ J @ L - J).max() < 1e-12 * np.abs(L).max() ** 2
