"""read_mesh, info and the errors: the CLI's JSON and one-line messages, bad arrays refused."""

import numpy as np
import pytest

import manifold_splines as ms
from conftest import model, msp_json, run_msp

MODELS = ["genus0.off", "genus2.off", "cap_open.off", "genus2_two_holes.off"]


def test_exception_classes():
    assert issubclass(ms.InvalidInputError, ValueError)
    assert issubclass(ms.TopologyError, ms.InvalidInputError)
    assert issubclass(ms.InfeasibleTargetError, ms.InvalidInputError)
    assert issubclass(ms.IOError, OSError)
    assert issubclass(ms.SolverError, RuntimeError)
    for cls in (ms.InvalidInputError, ms.IOError, ms.SolverError):
        assert issubclass(cls, ms.Error)


@pytest.mark.parametrize("name", MODELS)
def test_read_mesh_and_info_match_the_cli(name):
    V, F = ms.read_mesh(model(name))
    assert V.shape[1] == 3 and V.dtype == np.float64
    assert F.shape[1] == 3 and F.dtype == np.int32
    assert F.min() == 0 and F.max() == len(V) - 1
    report = ms.info(V, F, name=model(name))
    assert report == msp_json("info", model(name))


def test_info_describes_defects_without_refusing():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [np.nan, 0, 0]], float)
    F = np.array([[0, 1, 2], [0, 1, 3], [1, 0, 2]])
    report = ms.info(V, F)
    assert report["non_finite_vertices"] == 1
    assert report["unreferenced_vertices"] == 1
    assert report["clean_manifold"] is False and report["problems"]


def test_arrays_of_any_layout_and_integer_type(genus2):
    V, F = genus2
    reference = ms.info(V, F)
    assert ms.info(np.ascontiguousarray(V), F.astype(np.int64)) == reference
    assert ms.info(np.asfortranarray(V), F) == reference
    rounded = V.astype(np.float32)  # float32 is read as is, not copied to float64 first
    assert ms.info(rounded, F) == ms.info(rounded.astype(np.float64), F)
    stacked = np.concatenate([V, V], axis=1)[:, :3]  # a strided view
    assert ms.info(stacked, F.astype(np.uint32)) == reference
    assert ms.info(V.tolist(), F.tolist()) == reference


@pytest.mark.parametrize("V, F, message", [
    (np.zeros((3, 2)), [[0, 1, 2]], "V must have shape (n, 3), not (3, 2)"),
    (np.zeros(9), [[0, 1, 2]], "V must have shape (n, 3), not (9,)"),
    (np.zeros((3, 3), dtype=np.int64), [[0, 1, 2]], "V must hold float64 or float32 numbers"),
    (np.eye(3), [[0, 1, 2.0]], "F must hold integers"),
    (np.eye(3), [[0, 1, 3]], "F[0, 2] = 3 is not a vertex index in [0, 3)"),
    (np.eye(3), [[0, -1, 2]], "F[0, 1] = -1 is not a vertex index in [0, 3)"),
    (np.eye(3), [[0, 1]], "F must have shape (n, 3), not (1, 2)"),
    (["a", "b", "c"], [[0, 1, 2]], "V must be a numeric array"),
])
def test_bad_arrays_raise(V, F, message):
    for call in (ms.info, ms.fit, ms.flow, ms.atlas, ms.uniformize):
        with pytest.raises(ms.InvalidInputError) as error:
            call(V, F)
        assert str(error.value) == message


def test_nan_and_degenerate_faces_are_refused_by_the_pipeline(genus2):
    V, F = genus2
    bad = V.copy()
    bad[7, 1] = np.nan
    with pytest.raises(ms.InvalidInputError, match="vertex 7"):
        ms.fit(bad, F)
    with pytest.raises(ms.InvalidInputError):
        ms.flow(V, np.concatenate([F, F[:1]]))  # a duplicated face


def test_errors_have_the_cli_messages(tmp_path):
    corrupt = tmp_path / "corrupt.off"
    corrupt.write_text("OFF\n3 1 0\n0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n")
    nonmanifold = tmp_path / "book.off"
    nonmanifold.write_text("OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n"
                           "3 0 1 2\n3 1 0 3\n3 0 1 4\n")
    for path, error in ((corrupt, ms.IOError), (nonmanifold, ms.TopologyError),
                        (tmp_path / "missing.off", ms.IOError)):
        with pytest.raises(error) as raised:
            ms.read_mesh(str(path))
        cli = run_msp("fit", path, "--json", tmp_path / "r.json", "--quiet", check=False)
        assert cli.returncode == 1
        assert cli.stderr.strip().splitlines()[-1] == f"msp fit: error: {raised.value}"
