"""Messages in the caller's words: Python's argument and keyword names, never
the C++ ones (positions_t0, Options::min_distance); statuses as an IntEnum."""
import enum
import math

import numpy as np
import pytest

import batchccd


def falling_point():
    """A vertex falling through a still triangle at t = 1/2, as a tiny mesh."""
    x0 = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0.25, 0.25, 1]])
    x1 = x0.copy()
    x1[3, 2] = -1
    return x0, x1, np.array([[0, 1, 2]], np.int32), np.array([[3, 0]], np.int32)


def library_names_absent(message):
    return all(name not in message for name in ("positions_t0", "positions_t1", "Options::", "batchccd::"))


def test_mesh_errors_name_x0_and_x1():
    x0, x1, faces, vf = falling_point()
    with pytest.raises(ValueError) as rows:
        batchccd.mesh_ccd(x0, x1[:3], faces, vertex_face=vf)
    assert "x0 has 4 rows but x1 has 3" in str(rows.value) and library_names_absent(str(rows.value))
    with pytest.raises(ValueError) as columns:
        batchccd.mesh_ccd(np.zeros((4, 4)), np.zeros((4, 4)), faces)
    assert "x0 must have 3 columns" in str(columns.value) and library_names_absent(str(columns.value))
    with pytest.raises(ValueError) as stepsize:
        batchccd.ipc.collision_free_stepsize(x0, x1[:, :2], faces, vertex_face=vf)
    assert "x0" in str(stepsize.value) and library_names_absent(str(stepsize.value))


def test_options_are_named_as_the_keywords():
    x0, x1, faces, vf = falling_point()
    calls = {
        "mesh_ccd": lambda **o: batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf, **o),
        "batch_ccd": lambda **o: batchccd.batch_ccd("vf", np.zeros((1, 8, 3)), **o),
        "vertex_vertex_ccd": lambda **o: batchccd.vertex_vertex_ccd([0, 0, 1], [0, 0, 0], [0, 0, -1], [0, 0, 0], **o),
    }
    for name, call in calls.items():
        with pytest.raises(ValueError) as separation:
            call(min_distance=-1.0)
        assert str(separation.value) == "option min_distance must be >= 0 and finite, got -1", name
        with pytest.raises(ValueError) as window:
            call(tmax=1.5)
        assert str(window.value) == "option tmax must be in (0, 1], got 1.5", name


def test_per_candidate_separations_are_named_as_the_argument():
    x0, x1, faces, vf = falling_point()
    calls = {
        "mesh_ccd, a dict": lambda d: batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf,
                                                        min_distances={"vertex_face": [d]}),
        "mesh_ccd, one array": lambda d: batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf, min_distances=[d]),
        "batch_ccd": lambda d: batchccd.batch_ccd("vf", np.zeros((1, 8, 3)), [d]),
    }
    for name, call in calls.items():
        with pytest.raises(ValueError) as separation:
            call(-1.0)
        message = str(separation.value)
        assert "candidate 0: its value in min_distances must be >= 0 and finite" in message, (name, message)
        assert library_names_absent(message), (name, message)
    # The keyword min_distance keeps its own name.
    with pytest.raises(ValueError, match="^option min_distance must be"):
        batchccd.batch_ccd("vf", np.zeros((1, 8, 3)), [0.0], min_distance=-1.0)


def test_ipc_errors_name_the_python_module():
    with pytest.raises(ValueError) as bad:
        batchccd.ipc.point_point_ccd([0, 0, 0], [1, 1, 1], [0, 0, 0], [1, 1, 1], min_distance=-1.0)
    assert str(bad.value).startswith("batchccd.ipc.point_point_ccd: min_distance must be >= 0")
    with pytest.raises(ValueError) as settings:
        batchccd.ipc.NarrowPhase(tolerance=-1.0).point_point_ccd([0, 0, 0], [1, 1, 1], [0, 0, 0], [1, 1, 1])
    assert str(settings.value).startswith("batchccd.ipc.NarrowPhase: tolerance must be positive")


def test_vertex_face_candidates_without_faces_say_so():
    x0, x1, _, vf = falling_point()
    for faces in (None, np.zeros((0, 3), np.int32)):
        with pytest.raises(ValueError, match="vertex-face candidates need faces, and no faces were given") as error:
            batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf)
        assert "out of range [0, 0)" not in str(error.value)
    # With faces, an id past them is still named with its range.
    with pytest.raises(ValueError, match=r"face 1 out of range \[0, 1\)"):
        batchccd.mesh_ccd(x0, x1, np.array([[0, 1, 2]]), vertex_face=np.array([[3, 1]]))


def test_status_is_an_int_enum():
    assert issubclass(batchccd.Status, enum.IntEnum)
    assert batchccd.STATUS_OK is batchccd.Status.OK and batchccd.STATUS_INVALID_INPUT is batchccd.Status.INVALID_INPUT
    assert batchccd.Status.OK == 0 and batchccd.Status.INVALID_INPUT == 1  # the ints they were
    hit = batchccd.vertex_vertex_ccd([0, 0, 1], [0, 0, 0], [0, 0, -1], [0, 0, 0])
    assert hit.status is batchccd.Status.OK and "status=Status.OK" in repr(hit)
    invalid = batchccd.vertex_vertex_ccd([0, 0, math.nan], [0, 0, 0], [0, 0, -1], [0, 0, 0])
    assert invalid.status is batchccd.Status.INVALID_INPUT and invalid.status == 1
    # The result arrays hold the ints; the members compare with them.
    x0, x1, faces, vf = falling_point()
    x1[0, 0] = math.inf
    result = batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf)
    assert result.status.dtype == np.int32
    assert result.status[0] == batchccd.Status.INVALID_INPUT
    assert batchccd.Status(int(result.status[0])).name == "INVALID_INPUT"
