"""fit and Spline: the report of msp fit, evaluation as msp eval, editing as msp edit, the
spline file round trip, tessellation, closest points, Bezier pieces, bad input."""

import json

import numpy as np
import pytest

import manifold_splines as ms
from conftest import ROOT, model, msp_json, run_msp, same_figures


def sample_points(spline, count=40, seed=1):
    rng = np.random.default_rng(seed)
    faces = rng.choice(spline.shown_faces(), size=count)
    bary = rng.dirichlet([2.0, 2.0, 2.0], size=count)
    return faces, bary


def points_csv(path, faces, bary):
    path.write_text("".join(f"{int(f)}, {float(b[0])!r}, {float(b[1])!r}, {float(b[2])!r}\n"
                            for f, b in zip(faces, bary)))
    return path


def cli_eval(spline_file, csv):
    points = msp_json("eval", spline_file, "--points", csv)["points"]
    return {key: np.array([p[key] for p in points]) for key in
            ("position", "normal", "gaussian_curvature", "mean_curvature")}


def test_fit_report_is_msp_fits(fitted, cli_fit):
    report, _ = cli_fit
    same_figures(fitted.report, report, rel=1e-6)
    assert fitted.report["genus"] == 2 and fitted.report["watertight"] is True
    assert fitted.report["fit_rms_relative"] < 1e-2
    assert len(fitted.control_points) == fitted.report["control_points"]


def test_evaluate_as_msp_eval(fitted, cli_fit, tmp_path):
    _, spline_file = cli_fit
    loaded = ms.Spline.load(str(spline_file))
    faces, bary = sample_points(loaded)
    cli = cli_eval(spline_file, points_csv(tmp_path / "p.csv", faces, bary))
    d = loaded.evaluate(faces, bary, derivatives=True)
    assert np.array_equal(d["position"], cli["position"])  # same file, same code: bit for bit
    assert np.array_equal(loaded.normals(faces, bary), cli["normal"])
    k = loaded.curvatures(faces, bary)
    assert np.array_equal(k["gaussian"], cli["gaussian_curvature"])
    assert np.array_equal(k["mean"], cli["mean_curvature"])
    # The in-memory fit is the surface msp fit saved.
    assert np.allclose(fitted.evaluate(faces, bary), cli["position"], rtol=0, atol=1e-9)


def test_differential_geometry(fitted):
    faces, bary = sample_points(fitted)
    d = fitted.evaluate(faces, bary, derivatives=True)
    n = fitted.normals(faces, bary)
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0)
    assert np.allclose(np.einsum("ij,ij->i", n, d["du"]), 0.0, atol=1e-9)
    k = fitted.curvatures(faces, bary)
    assert (k["k1"] >= k["k2"]).all()
    assert np.allclose(k["k1"] * k["k2"], k["gaussian"], rtol=1e-6, atol=1e-9)
    assert np.allclose((k["k1"] + k["k2"]) / 2, k["mean"], rtol=1e-6, atol=1e-9)


def test_closest_points_of_offset_points(fitted):
    faces, bary = sample_points(fitted, count=20, seed=3)
    p = fitted.evaluate(faces, bary)
    h = 1e-3 * fitted.report["bbox_diagonal"]
    found = fitted.closest(p + h * fitted.normals(faces, bary))
    assert np.allclose(found["distance"], h, rtol=1e-3)
    assert np.allclose(found["position"], p, atol=1e-3 * h * 10)
    on_spline = found["fill"] < 0
    assert np.array_equal(found["face"][on_spline] >= 0, np.ones(on_spline.sum(), bool))


def test_save_load_round_trip(fitted, tmp_path):
    path = tmp_path / "round.msp"
    fitted.save(str(path))
    loaded = ms.Spline.load(str(path))
    assert loaded.report["provenance"] == {"tool": "manifold_splines"}
    assert loaded.report["control_points"] == len(fitted.control_points)
    faces, bary = sample_points(fitted)
    assert np.array_equal(loaded.evaluate(faces, bary), fitted.evaluate(faces, bary))
    assert np.array_equal(loaded.control_points, fitted.control_points)
    for a, b in zip(loaded.tessellate(3), fitted.tessellate(3)):
        assert np.array_equal(a, b)


def test_edit_in_python_reevaluates_as_msp_edit(cli_fit, tmp_path):
    _, spline_file = cli_fit
    spline = ms.Spline.load(str(spline_file))
    faces, bary = sample_points(spline, count=200, seed=5)
    before = spline.evaluate(faces, bary)
    view = spline.control_points
    assert view.flags.writeable and np.shares_memory(view, spline.control_points)
    # The control point nearest the first sample: its function reaches that sample's face.
    index = int(np.argmin(np.linalg.norm(view - before[0], axis=1)))
    move = np.array([0.01, -0.02, 0.03])
    view[index] += move
    after = spline.evaluate(faces, bary)
    changed = np.any(after != before, axis=1)
    assert changed.any() and not changed.all()  # only the moved function's support moves
    run_msp("edit", spline_file, "--move-point", index, *move, "-o", tmp_path / "e.msp",
            "--quiet")
    assert np.array_equal(ms.Spline.load(str(tmp_path / "e.msp")).evaluate(faces, bary), after)
    spline.save(str(tmp_path / "py.msp"))
    cli = cli_eval(tmp_path / "py.msp", points_csv(tmp_path / "p.csv", faces, bary))
    assert np.array_equal(cli["position"], after)
    with pytest.raises(ms.InvalidInputError, match="control_points must have"):
        spline.control_points = np.zeros((3, 3))


def test_tessellate_is_watertight_and_as_msp_tessellate(fitted, cli_fit, tmp_path):
    V, F, N, UV = fitted.tessellate()
    assert V.shape[1] == 3 and F.shape[1] == 3 and N.shape == V.shape and UV.shape == (len(F), 3, 2)
    assert np.allclose(np.linalg.norm(N, axis=1), 1.0)
    edges = {tuple(sorted(e)) for f in F for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
    assert len(V) - len(edges) + len(F) == -2  # closed genus 2
    _, spline_file = cli_fit
    cli = msp_json("tessellate", spline_file, "-o", tmp_path / "t.glb")
    assert (cli["vertices"], cli["triangles"]) == (len(V), len(F))
    fitted.to_glb(str(tmp_path / "s.glb"))
    assert (tmp_path / "s.glb").read_bytes()[:4] == b"glTF"
    with pytest.raises(ms.IOError):
        fitted.to_glb(str(tmp_path / "missing" / "s.glb"))


def test_bezier_patches_reproduce_the_spline(fitted, cli_fit, tmp_path):
    patches = fitted.bezier_patches()
    n = patches["degree"]
    P = len(patches["face"])
    assert patches["control_points"].shape == (P, (n + 1) * (n + 2) // 2, 3)
    # Control point (n, 0, 0) of a patch is the spline at the patch's first corner.
    first = [i for i, beta in enumerate(patches["multi_indices"]) if beta[0] == n][0]
    pick = np.arange(0, P, max(1, P // 50))
    at = fitted.evaluate(patches["face"][pick], patches["corners"][pick, 0])
    assert np.allclose(at, patches["control_points"][pick, first], atol=1e-9)
    _, spline_file = cli_fit
    run_msp("bezier", spline_file, "-o", tmp_path / "b.json", "--quiet")
    cli = json.loads((tmp_path / "b.json").read_text())
    assert (cli["faces"], len(cli["patches"])) == (patches["faces"], P)


@pytest.mark.parametrize("faces, bary, message", [
    ([-1], [[1 / 3] * 3], "face"),
    ([0, 1], [[1 / 3] * 3], "faces and bary must have as many rows (2 and 1)"),
    ([0], [[0.5, 0.5, 0.5]], "barycentric"),
    ([0], [[np.nan, 0.5, 0.5]], "barycentric"),
    ([[0]], [[1 / 3] * 3], "faces must have shape (n,), not (1, 1)"),
])
def test_bad_points_raise(fitted, faces, bary, message):
    with pytest.raises(ms.InvalidInputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        fitted.evaluate(faces, bary)


def test_tracked_parameters_on_a_genus_4_scan():
    """tracked_parameters (msp fit --tracked-parameters): on the intrinsic route the data are
    carried through the flow's flips; the report says whether they were."""
    V, F = ms.read_mesh(str(ROOT / "tests" / "data" / "meshes" / "closed_g4plus" / "anchor.off"))
    tracked = ms.fit(V, F, tracked_parameters=True).report
    assert tracked["genus"] == 4
    assert tracked["tracked_parameters"] is True
    assert tracked["watertight"] is True
    assert tracked["folds"]["count"] == 0
    assert ms.fit(V, F).report["tracked_parameters"] is False


def test_bad_options_and_files(genus2, tmp_path):
    V, F = genus2
    with pytest.raises(ms.InvalidInputError, match=r"degree must be in \[1, "):
        ms.fit(V, F, degree=0)
    with pytest.raises(ms.InvalidInputError, match="fairness must be"):
        ms.fit(V, F, fairness=5)
    with pytest.raises(ms.InvalidInputError, match=r"small_holes must be in \[0, 1\)"):
        ms.fit(V, F, small_holes=-0.1)
    with pytest.raises(TypeError):
        ms.fit(V, F, colour="red")
    bad = tmp_path / "bad.msp"
    bad.write_bytes(b"not a spline file")
    with pytest.raises(ms.IOError, match=str(bad)):
        ms.Spline.load(str(bad))
    with pytest.raises(ms.IOError):
        ms.Spline.load(str(tmp_path / "missing.msp"))
