"""Bad arguments raise ValueError/TypeError with the library's message; bad
coordinates follow the C++ contract (status invalid, no exception)."""
import math
import sys
import threading

import numpy as np
import pytest

import batchccd
from scenes import two_sheets


@pytest.fixture(scope="module")
def scene():
    return two_sheets(side=4)


def test_nan_and_inf_coordinates_mark_only_their_candidates(scene):
    x0, x1, faces, _, lists = scene
    clean = batchccd.mesh_ccd(x0, x1, faces, **lists)
    bad = x1.copy()
    bad[0, 2] = np.nan
    bad[5, 0] = np.inf
    result = batchccd.mesh_ccd(x0, bad, faces, **lists)
    reads = np.concatenate([
        np.isin(lists["vertex_face"][:, 0], [0, 5]) | np.isin(faces[lists["vertex_face"][:, 1]], [0, 5]).any(1),
        np.isin(lists["edge_edge"], [0, 5]).any(1),
        np.isin(lists["vertex_edge"], [0, 5]).any(1),
        np.isin(lists["vertex_vertex"], [0, 5]).any(1),
    ])
    assert reads.any()
    assert np.all(result.status[reads] == batchccd.STATUS_INVALID_INPUT)
    assert np.all(result.hit[reads]) and np.all(result.toi[reads] == 0)
    assert np.all(result.status[~reads] == batchccd.STATUS_OK)
    assert np.array_equal(result.toi[~reads], clean.toi[~reads])
    assert result.counters["invalid"] == reads.sum() and result.earliest_toi == 0
    single = batchccd.vertex_vertex_ccd([0, 0, math.nan], [0, 0, 0], [0, 0, 1], [0, 0, 0])
    assert single.status == batchccd.STATUS_INVALID_INPUT and single.hit and single.toi == 0


def test_ids_out_of_range_raise_the_librarys_message(scene):
    x0, x1, faces, _, lists = scene
    vf = lists["vertex_face"].copy()
    vf[3, 1] = len(faces)
    with pytest.raises(ValueError, match=rf"{len(faces)}"):
        batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf)
    ee = lists["edge_edge"].copy()
    ee[2, 0] = -1
    with pytest.raises(ValueError, match="-1"):
        batchccd.mesh_ccd(x0, x1, faces, edge_edge=ee)
    # Also in a list the options switch off (the C++ contract).
    with pytest.raises(ValueError):
        batchccd.mesh_ccd(x0, x1, faces, edge_edge=ee, evaluate_edge_edge=False)
    bad_faces = faces.copy()
    bad_faces[0, 0] = len(x0) + 10
    with pytest.raises(ValueError, match=str(len(x0) + 10)):
        batchccd.mesh_ccd(x0, x1, bad_faces, vertex_face=lists["vertex_face"])


def test_ids_that_do_not_fit_an_int_name_the_array_and_value(scene):
    x0, x1, faces, _, lists = scene
    vf = lists["vertex_face"].astype(np.int64)
    vf[0, 0] = 2**40
    with pytest.raises(ValueError, match=r"vertex_face: id 1099511627776"):
        batchccd.mesh_ccd(x0, x1, faces, vertex_face=vf)
    with pytest.raises(ValueError, match=r"faces: id -3000000000"):
        batchccd.mesh_ccd(x0, x1, np.full((1, 3), -3_000_000_000, np.int64))


def test_wrong_shapes(scene):
    x0, x1, faces, _, lists = scene
    with pytest.raises(ValueError, match="x0: expected a 2-D array"):
        batchccd.mesh_ccd(x0.ravel(), x1, faces)
    with pytest.raises(ValueError, match="a mesh is 2D or 3D at both times"):
        batchccd.mesh_ccd(x0, x1[:, :2], faces)
    with pytest.raises(ValueError, match=r"x1 must have 3 columns \(2 for a 2D mesh\), it has 4"):
        batchccd.mesh_ccd(x0, np.column_stack([x1, x1[:, :1]]), faces)
    with pytest.raises(ValueError, match="row"):
        batchccd.mesh_ccd(x0, x1[:-1], faces)
    with pytest.raises(ValueError, match="edge_edge: expected 4 or 2 columns, got 3"):
        batchccd.mesh_ccd(x0, x1, faces, edge_edge=lists["edge_edge"][:, :3])
    with pytest.raises(ValueError, match=r"N x 8 x 3 or N x 24 \(2D: N x 8 x 2 or N x 16\), got 2 x 7 x 3"):
        batchccd.batch_ccd("vf", np.zeros((2, 7, 3)))
    with pytest.raises(ValueError, match="batchccd.vertex_vertex_ccd: q_t0 must be of length 2 like p_t0, got 3"):
        batchccd.vertex_vertex_ccd([0, 0], [0, 0, 0], [0, 0, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="batchccd.vertex_face_ccd: p_t0 must be of length 3, got 2"):
        batchccd.vertex_face_ccd(*[[0, 0]] * 8)
    with pytest.raises(ValueError, match="batchccd.vertex_edge_ccd: p_t0 must be of length 2 or 3, got 4"):
        batchccd.vertex_edge_ccd(*[[0, 0, 0, 0]] * 6)
    with pytest.raises(ValueError, match="min_distances"):
        batchccd.batch_ccd("vf", np.zeros((2, 8, 3)), np.zeros(3))


def test_wrong_dtypes_raise_type_error(scene):
    x0, x1, faces, _, lists = scene
    with pytest.raises(TypeError, match="x0: positions must be float64 or float32, got int64"):
        batchccd.mesh_ccd(x0.astype(np.int64), x1, faces)
    with pytest.raises(TypeError, match="x1: positions must be float64 or float32, got complex128"):
        batchccd.mesh_ccd(x0, x1.astype(complex), faces)
    with pytest.raises(TypeError, match="faces: ids must be an integer array, got float64"):
        batchccd.mesh_ccd(x0, x1, faces.astype(float))
    with pytest.raises(TypeError, match="vertex_face: ids must be an integer array, got bool"):
        batchccd.mesh_ccd(x0, x1, faces, vertex_face=lists["vertex_face"] > 0)
    with pytest.raises(TypeError, match="queries"):
        batchccd.batch_ccd("vf", np.zeros((1, 8, 3), np.int32))
    with pytest.raises(TypeError, match="out"):
        batchccd.mesh_ccd(x0, x1, faces, out=object())


def test_bad_options():
    q = np.zeros((1, 8, 3))
    with pytest.raises(ValueError, match="min_distance"):
        batchccd.batch_ccd("vf", q, min_distance=-1.0)
    with pytest.raises(ValueError, match="tmax"):
        batchccd.batch_ccd("vf", q, tmax=1.5)
    with pytest.raises(ValueError, match="unknown mode 'precise'"):
        batchccd.batch_ccd("vf", q, mode="precise")
    with pytest.raises(ValueError, match="unknown instruction set"):
        batchccd.batch_ccd("vf", q, isa="sve")
    if "neon" not in batchccd.available_isas():  # a set of another processor family
        with pytest.raises(ValueError, match="instruction set neon is not in this build"):
            batchccd.batch_ccd("vf", q, isa="neon")
    with pytest.raises(ValueError, match="unknown kind"):
        batchccd.batch_ccd("triangle", q)
    with pytest.raises(TypeError, match="unexpected keyword argument 'sign_filter'"):
        batchccd.batch_ccd("vf", q, sign_filter=False)
    with pytest.raises(TypeError, match="need_toi must be a bool"):
        batchccd.batch_ccd("vf", q, need_toi=1)
    with pytest.raises(TypeError, match="threads must be an int"):
        batchccd.batch_ccd("vf", q, threads="two")
    with pytest.raises(ValueError, match="candidate 0: its value in min_distances must be >= 0 and finite, got nan"):
        batchccd.batch_ccd("vf", q, np.array([np.nan]))
    with pytest.raises(ValueError):
        batchccd.make_query("ve", np.zeros((4, 3)), np.zeros((4, 3)))


def test_several_python_threads_at_once_get_the_same_answers(scene):
    x0, x1, faces, _, lists = two_sheets(side=7)
    expected = batchccd.mesh_ccd(x0, x1, faces, **lists, threads=1)
    queries = np.stack([np.concatenate([x0[[0, 1, 2, 3]], x1[[0, 1, 2, 3]]])] * 64)
    expected_batch = batchccd.batch_ccd("ee", queries, mode="exact")
    answers, errors = [None] * 8, []

    def work(i):
        try:
            mode = "exact" if i % 2 else "conservative"
            r = batchccd.mesh_ccd(x0, x1, faces, **lists, threads=2, mode=mode)
            b = batchccd.batch_ccd("ee", queries, mode="exact")
            answers[i] = (mode, r.toi.copy(), r.hit.copy(), b.toi.copy())
        except Exception as error:  # noqa: BLE001 - reported below
            errors.append(error)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    exact = batchccd.mesh_ccd(x0, x1, faces, **lists, mode="exact")
    for mode, toi, hit, batch_toi in answers:
        reference = expected if mode == "conservative" else exact
        assert np.array_equal(toi, reference.toi) and np.array_equal(hit, reference.hit)
        assert np.array_equal(batch_toi, expected_batch.toi)


def test_the_gil_is_released_during_a_call():
    # Edges that meet exactly at their midpoints: each query goes to exact
    # arithmetic, so 2,000 of them keep one thread in the library a while.
    query = batchccd.make_query("ee", [[-1, 0, 0], [1, 0, 0], [0, -1, 1], [0, 1, 1]],
                                [[-1, 0, 0], [1, 0, 0], [0, -1, -1], [0, 1, -1]])
    queries = np.repeat(query[None], 2000, axis=0)
    calling, returned = threading.Event(), threading.Event()

    def call():
        calling.set()
        batchccd.batch_ccd("ee", queries, mode="exact", threads=1)
        returned.set()

    # With a switch interval far longer than the call, the worker's Python
    # code never hands the GIL over on a timer: from calling.set() to
    # returned.set() this thread can run only while the call itself has
    # released it. Holding it, the call would let this thread in only
    # after `returned` was set.
    interval = sys.getswitchinterval()
    sys.setswitchinterval(60)
    try:
        worker = threading.Thread(target=call)
        worker.start()
        calling.wait()
        ran_during_the_call = not returned.is_set()  # Python code, run while the call was in progress
    finally:
        sys.setswitchinterval(interval)
    worker.join()
    assert returned.is_set()
    assert ran_during_the_call
