"""mesh_ccd on NumPy arrays of every layout: the same answers as the one-query calls."""
import numpy as np
import pytest

import batchccd
from scenes import KINDS, candidate_query, two_sheets


@pytest.fixture(scope="module")
def scene():
    return two_sheets()


def one_at_a_time(x0, x1, faces, lists, **options):
    hit, toi, status = [], [], []
    for kind, rows in lists.items():
        for row in rows:
            r = batchccd.query_ccd(KINDS[kind], candidate_query(kind, row, x0, x1, faces), **options)
            hit.append(r.hit), toi.append(r.toi), status.append(r.status)
    return np.array(hit), np.array(toi), np.array(status)


@pytest.mark.parametrize("mode", [m for m in batchccd.modes() if m in ("conservative", "exact")])
def test_mesh_equals_single_queries(scene, mode):
    x0, x1, faces, _, lists = scene
    result = batchccd.mesh_ccd(x0, x1, faces, **lists, mode=mode)
    hit, toi, status = one_at_a_time(x0, x1, faces, lists, mode=mode)
    assert np.array_equal(result.hit, hit) and np.array_equal(result.toi, toi)
    assert np.array_equal(result.status, status)
    assert 0 < hit.sum() < len(hit)  # the scene has both
    assert result.counters["candidates"] == len(hit) and result.counters["hits"] == hit.sum()
    assert result.earliest_toi == toi.min()
    assert isinstance(result.earliest_toi, float) and isinstance(result.counters, dict)


def test_layouts_read_in_place_or_copied_give_the_same_answers(scene):
    x0, x1, faces, _, lists = scene
    expected = batchccd.mesh_ccd(x0, x1, faces, **lists)
    n = len(x0)
    wide0, wide1 = np.zeros((n, 6)), np.zeros((n, 6))
    wide0[:, ::2], wide1[:, ::2] = x0, x1
    raw = np.zeros(n * 3 * 8 + 1, dtype=np.uint8)  # a misaligned float64 buffer
    misaligned = np.ndarray((n, 3), dtype=np.float64, buffer=raw, offset=1)
    misaligned[:] = x0
    big_endian = x0.astype(">f8")
    variants = {
        "fortran": (np.asfortranarray(x0), np.asfortranarray(x1)),
        "strided columns": (wide0[:, ::2], wide1[:, ::2]),
        "transposed": (np.ascontiguousarray(x0.T).T, np.ascontiguousarray(x1.T).T),
        "misaligned": (misaligned, x1),
        "big-endian": (big_endian, x1),
        "list": (x0.tolist(), x1.tolist()),
    }
    for name, (a, b) in variants.items():
        result = batchccd.mesh_ccd(a, b, faces, **lists)
        assert np.array_equal(result.hit, expected.hit), name
        assert np.array_equal(result.toi, expected.toi), name
    # Reversed rows (negative strides), ids renumbered to match.
    renumber = lambda ids: (n - 1 - ids).astype(np.int32)  # noqa: E731
    reversed_lists = {k: renumber(v) for k, v in lists.items() if k != "vertex_face"}
    reversed_lists["vertex_face"] = np.column_stack([renumber(lists["vertex_face"][:, 0]), lists["vertex_face"][:, 1]])
    result = batchccd.mesh_ccd(x0[::-1], x1[::-1], renumber(faces), **reversed_lists)
    assert np.array_equal(result.toi, expected.toi) and np.array_equal(result.hit, expected.hit)


def test_float32_positions_are_evaluated_as_given(scene):
    x0, x1, faces, _, lists = scene
    f0, f1 = x0.astype(np.float32), x1.astype(np.float32)
    result = batchccd.mesh_ccd(f0, f1, faces, **lists)
    exact = batchccd.mesh_ccd(f0.astype(np.float64), f1.astype(np.float64), faces, **lists)
    assert np.array_equal(result.toi, exact.toi) and np.array_equal(result.hit, exact.hit)
    fortran = batchccd.mesh_ccd(np.asfortranarray(f0), np.asfortranarray(f1), faces, **lists)
    assert np.array_equal(fortran.toi, exact.toi)


def test_integer_dtypes_and_non_contiguous_lists(scene):
    x0, x1, faces, _, lists = scene
    expected = batchccd.mesh_ccd(x0, x1, faces, **lists)
    for dtype in (np.int64, np.uint16, np.int16, np.uint32):
        converted = {k: v.astype(dtype) for k, v in lists.items()}
        result = batchccd.mesh_ccd(x0, x1, faces.astype(dtype), **converted)
        assert np.array_equal(result.toi, expected.toi), dtype
    padded = {k: np.hstack([v, np.full((len(v), 1), -7, np.int32)])[:, :-1] for k, v in lists.items()}
    assert not padded["edge_edge"].flags.c_contiguous
    result = batchccd.mesh_ccd(x0, x1, np.asfortranarray(faces), **padded)
    assert np.array_equal(result.toi, expected.toi)


def test_edge_ids_equal_vertex_ids(scene):
    x0, x1, faces, edges, lists = scene
    index = {tuple(e): i for i, e in enumerate(edges.tolist())}
    ee = np.array([[index[tuple(r[:2])], index[tuple(r[2:])]] for r in lists["edge_edge"].tolist()], np.int32)
    ve = np.array([[r[0], index[tuple(r[1:])]] for r in lists["vertex_edge"].tolist()], np.int32)
    by_id = batchccd.mesh_ccd(x0, x1, faces, edges, lists["vertex_face"], ee, ve, lists["vertex_vertex"])
    by_vertex = batchccd.mesh_ccd(x0, x1, faces, **lists)
    assert np.array_equal(by_id.toi, by_vertex.toi) and np.array_equal(by_id.hit, by_vertex.hit)
    with pytest.raises(ValueError, match="edges matrix"):
        batchccd.mesh_ccd(x0, x1, faces, edge_edge=ee)
    with pytest.raises(ValueError, match="both"):
        batchccd.mesh_ccd(x0, x1, faces, edges, edge_edge=ee, vertex_edge=lists["vertex_edge"])


def test_per_candidate_separations(scene):
    x0, x1, faces, _, lists = scene
    total = sum(len(v) for v in lists.values())
    uniform = batchccd.mesh_ccd(x0, x1, faces, **lists, min_distance=0.05)
    flat = batchccd.mesh_ccd(x0, x1, faces, **lists, min_distances=np.full(total, 0.05))
    assert np.array_equal(uniform.toi, flat.toi)
    by_list = batchccd.mesh_ccd(x0, x1, faces, **lists, min_distance=0.05,
                                min_distances={"edge_edge": np.full(len(lists["edge_edge"]), 0.05)})
    assert np.array_equal(uniform.toi, by_list.toi)
    assert uniform.counters["hits"] > batchccd.mesh_ccd(x0, x1, faces, **lists).counters["hits"]
    with pytest.raises(ValueError, match="candidates"):
        batchccd.mesh_ccd(x0, x1, faces, **lists, min_distances=np.zeros(total - 1))


def test_lists_switched_off_and_hit_list(scene):
    x0, x1, faces, _, lists = scene
    full = batchccd.mesh_ccd(x0, x1, faces, **lists)
    sparse = batchccd.mesh_ccd(x0, x1, faces, **lists, per_candidate_results=False, hit_list=True)
    assert np.array_equal(sparse.hit_candidates, np.flatnonzero(full.hit))
    assert np.array_equal(sparse.hit_tois, full.toi[full.hit])
    assert sparse.earliest_toi == full.earliest_toi and sparse.counters == full.counters
    only_vf = batchccd.mesh_ccd(x0, x1, faces, **lists, evaluate_edge_edge=False, evaluate_vertex_edge=False,
                                evaluate_vertex_vertex=False)
    assert only_vf.counters["candidates"] == len(lists["vertex_face"])


def test_out_reuses_storage_but_never_under_a_live_view(scene):
    x0, x1, faces, _, lists = scene
    first = batchccd.mesh_ccd(x0, x1, faces, **lists)
    toi = first.toi
    kept = toi.copy()
    again = batchccd.mesh_ccd(x0, x1, faces, vertex_face=lists["vertex_face"][:3], out=first)
    assert again is first and len(first.toi) == 3
    assert np.array_equal(toi, kept)  # the old view still reads the old answers
    assert not toi.flags.writeable
    del toi
    third = batchccd.mesh_ccd(x0, x1, faces, **lists, out=first)
    assert np.array_equal(third.toi, kept)


def test_no_candidates_and_an_empty_mesh():
    empty = batchccd.mesh_ccd(np.zeros((0, 3)), np.zeros((0, 3)))
    assert empty.earliest_toi == float("inf") and empty.counters["candidates"] == 0
    assert len(empty.hit) == 0 and empty.toi.dtype == np.float64 and empty.status.dtype == np.int32
    none = batchccd.batch_ccd("vf", np.zeros((0, 8, 3)), hit_list=True)
    assert len(none.hit_candidates) == 0 and none.earliest_toi == float("inf")


def test_one_query_calls_take_integer_coordinates_and_check_their_size():
    query = [[0, 0, 1], [0, 0, 1], [0, 0, 0], [0, 0, 0], [0, 0, -1], [0, 0, -1], [0, 0, 0], [0, 0, 0]]
    assert batchccd.query_ccd("vv", query).hit
    assert batchccd.squared_distance("vv", query) == 1.0
    with pytest.raises(ValueError, match=r"query: expected 8 x 3 coordinates \(2D: 8 x 2\), got 21"):
        batchccd.query_ccd("vv", np.zeros((7, 3)))


def test_counters_add_up(scene):
    x0, x1, faces, _, lists = scene
    c = batchccd.mesh_ccd(x0, x1, faces, **lists).counters
    assert set(c) == {"candidates", "culled", "culled_by_sign", "culled_by_separation", "culled_by_pieces",
                      "culled_by_swept_box", "solved", "hits", "undecided", "invalid", "exact_escalations"}
    assert all(isinstance(v, int) for v in c.values())
    assert c["candidates"] == c["culled"] + c["solved"] and c["culled"] > 0
    assert c["culled"] == (c["culled_by_sign"] + c["culled_by_separation"] + c["culled_by_pieces"]
                           + c["culled_by_swept_box"])


def test_a_2d_mesh_is_the_mesh_lifted_to_z_0():
    rng = np.random.default_rng(5)
    n = 30
    x0 = np.round(rng.uniform(-1, 1, (n, 2)) * 2**16) / 2**16
    x1 = x0 + np.round(rng.uniform(-0.5, 0.5, (n, 2)) * 2**16) / 2**16
    edges = np.array([[e, e + 1] for e in range(0, n - 1, 2)], dtype=np.int32)
    vertex_edge = np.array([[v, a, b] for v in range(n) for a, b in edges if v not in (a, b)], dtype=np.int32)
    vertex_vertex = np.array([[v, w] for v in range(n) for w in range(v + 1, n)], dtype=np.int32)
    lift = lambda x: np.column_stack([x, np.zeros(n)])  # noqa: E731
    for options in ({}, {"mode": "exact"}, {"min_distance": 0.05}):
        flat = batchccd.mesh_ccd(x0, x1, vertex_edge=vertex_edge, vertex_vertex=vertex_vertex, **options)
        lifted = batchccd.mesh_ccd(lift(x0), lift(x1), vertex_edge=vertex_edge, vertex_vertex=vertex_vertex, **options)
        assert np.array_equal(flat.hit, lifted.hit) and np.array_equal(flat.toi, lifted.toi)
        assert 0 < flat.hit.sum() < len(flat.hit)
    with pytest.raises(ValueError, match="a mesh is 2D or 3D at both times"):
        batchccd.mesh_ccd(x0, lift(x1), vertex_edge=vertex_edge)
