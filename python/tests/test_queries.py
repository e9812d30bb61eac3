"""Known crossings and misses, for each kind and mode, one query at a time and in batches."""
import math

import numpy as np
import pytest

import batchccd

CERTIFIED = [m for m in batchccd.modes() if m in ("conservative", "exact")]

# Each kind: (points at t0, points at t1) of a clean crossing at t = 0.5 and of a miss.
# vf: p falls through the triangle (0,0,0), (1,0,0), (0,1,0); ee: an edge falls across
# another; ve: a point falls onto an edge; vv: a point falls onto a point.
SCENES = {
    "vf": {
        "hit": ([[0.25, 0.25, 1], [0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0.25, 0.25, -1], [0, 0, 0], [1, 0, 0], [0, 1, 0]]),
        "miss": ([[2, 2, 1], [0, 0, 0], [1, 0, 0], [0, 1, 0]], [[2, 2, -1], [0, 0, 0], [1, 0, 0], [0, 1, 0]]),
    },
    "ee": {
        "hit": ([[-1, 0, 0], [1, 0, 0], [0, -1, 1], [0, 1, 1]], [[-1, 0, 0], [1, 0, 0], [0, -1, -1], [0, 1, -1]]),
        "miss": ([[-1, 0, 0], [1, 0, 0], [5, -1, 1], [5, 1, 1]], [[-1, 0, 0], [1, 0, 0], [5, -1, -1], [5, 1, -1]]),
    },
    "ve": {
        "hit": ([[0, 0, 1], [-1, 0, 0], [1, 0, 0]], [[0, 0, -1], [-1, 0, 0], [1, 0, 0]]),
        "miss": ([[0, 3, 1], [-1, 0, 0], [1, 0, 0]], [[0, 3, -1], [-1, 0, 0], [1, 0, 0]]),
    },
    "vv": {
        "hit": ([[0, 0, 1], [0, 0, 0]], [[0, 0, -1], [0, 0, 0]]),
        "miss": ([[0, 0, 1], [1, 0, 0]], [[0, 0, -1], [1, 0, 0]]),
    },
}
SINGLE = {
    "vf": batchccd.vertex_face_ccd,
    "ee": batchccd.edge_edge_ccd,
    "ve": batchccd.vertex_edge_ccd,
    "vv": batchccd.vertex_vertex_ccd,
}


def check_crossing(mode, result):
    assert result.status == batchccd.STATUS_OK
    assert result.hit
    # Certified modes: never after the first contact, and close before it.
    assert result.toi <= 0.5
    assert result.toi >= 0.5 - (1e-11 if mode == "exact" else 1e-6)


@pytest.mark.parametrize("kind", SCENES)
@pytest.mark.parametrize("mode", CERTIFIED)
def test_single_query_crossing_and_miss(kind, mode):
    t0, t1 = SCENES[kind]["hit"]
    check_crossing(mode, SINGLE[kind](*t0, *t1, mode=mode))
    t0, t1 = SCENES[kind]["miss"]
    miss = SINGLE[kind](*t0, *t1, mode=mode)
    assert not miss.hit and math.isinf(miss.toi) and miss.status == batchccd.STATUS_OK


@pytest.mark.parametrize("kind", SCENES)
@pytest.mark.parametrize("mode", batchccd.modes())
def test_every_mode_finds_a_clean_crossing_of_triangles(kind, mode):
    if kind in ("ve", "vv") and mode not in CERTIFIED:
        pytest.skip("only the certified modes promise point-edge and point-point contacts")
    queries = np.stack([batchccd.make_query(kind, *SCENES[kind][c]) for c in ("hit", "miss")])
    result = batchccd.batch_ccd(kind, queries, mode=mode)
    assert result.hit.tolist() == [True, False]
    assert abs(result.toi[0] - 0.5) < 1e-6 and math.isinf(result.toi[1])
    assert result.counters["candidates"] == 2 and result.counters["hits"] == 1


@pytest.mark.parametrize("kind", SCENES)
@pytest.mark.parametrize("mode", CERTIFIED)
def test_batch_equals_single_queries(kind, mode):
    queries = np.stack([batchccd.make_query(kind, *SCENES[kind][c]) for c in ("hit", "miss")])
    batch = batchccd.batch_ccd(kind, queries, mode=mode)
    for i, query in enumerate(queries):
        single = batchccd.query_ccd(kind, query, mode=mode)
        assert (batch.hit[i], batch.toi[i], batch.status[i]) == (single.hit, single.toi, single.status)
    assert batch.earliest_toi == batch.toi[0]


def test_long_kind_names_and_flat_queries():
    query = batchccd.make_query("vf", *SCENES["vf"]["hit"])
    flat = batchccd.batch_ccd("vertex_face", query.reshape(1, 24))
    shaped = batchccd.batch_ccd("vf", query.reshape(1, 8, 3))
    assert flat.toi[0] == shaped.toi[0] and flat.hit[0]


def test_min_distance_and_tmax():
    t0, t1 = SCENES["vv"]["miss"]  # passes q at distance 1 at t = 0.5
    assert not batchccd.vertex_vertex_ccd(*t0, *t1).hit
    near = batchccd.vertex_vertex_ccd(*t0, *t1, min_distance=1.5)
    assert near.hit and near.toi < 0.5
    t0, t1 = SCENES["vf"]["hit"]
    assert not batchccd.vertex_face_ccd(*t0, *t1, tmax=0.4).hit
    assert batchccd.vertex_face_ccd(*t0, *t1, tmax=0.6).hit
    # One separation per query replaces min_distance.
    queries = np.stack([batchccd.make_query("vv", *SCENES["vv"]["miss"])] * 2)
    result = batchccd.batch_ccd("vv", queries, np.array([0.5, 1.5]))
    assert result.hit.tolist() == [False, True]


def test_need_toi_false_keeps_decisions():
    t0, t1 = SCENES["ee"]["hit"]
    result = batchccd.edge_edge_ccd(*t0, *t1, need_toi=False)
    assert result.hit and result.toi <= 0.5


def test_hit_list_and_no_per_candidate_results():
    queries = np.stack([batchccd.make_query("vf", *SCENES["vf"][c]) for c in ("miss", "hit", "miss", "hit")])
    result = batchccd.batch_ccd("vf", queries, per_candidate_results=False, hit_list=True)
    assert result.hit is None and result.toi is None and result.status is None
    assert result.hit_candidates.tolist() == [1, 3]
    assert np.all(result.hit_tois <= 0.5) and result.hit_statuses.tolist() == [0, 0]
    assert result.earliest_toi == result.hit_tois.min()


def test_squared_distance():
    query = batchccd.make_query("vv", *SCENES["vv"]["miss"])
    assert batchccd.squared_distance("vv", query) == pytest.approx(2.0)
    assert batchccd.squared_distance("vv", query, t=0.5) == pytest.approx(1.0)


def test_isas_and_options():
    assert batchccd.available_isas()[0] == "scalar"
    assert batchccd.resolve_isa("auto") in batchccd.available_isas()
    query = np.stack([batchccd.make_query("ee", *SCENES["ee"]["hit"])])
    answers = {isa: batchccd.batch_ccd("ee", query, isa=isa).toi[0] for isa in batchccd.available_isas()}
    assert len(set(answers.values())) == 1
    defaults = batchccd.default_options()
    assert defaults["mode"] == "conservative" and defaults["tmax"] == 1.0 and defaults["need_toi"] is True
    assert set(defaults) == {
        "mode", "min_distance", "tmax", "need_toi", "evaluate_vertex_face", "evaluate_edge_edge",
        "evaluate_vertex_edge", "evaluate_vertex_vertex",
        "per_candidate_results", "hit_list", "isa", "threads", "tolerance", "toi_tolerance", "max_iterations",
        "exact_stage_iterations"}


def test_2d_queries_are_the_queries_lifted_to_z_0():
    rng = np.random.default_rng(7)
    for kind, points in (("vf", 4), ("ee", 4), ("ve", 3), ("vv", 2)):
        flat = []
        for i in range(200):
            start = np.round(rng.uniform(-1, 1, (points, 2)) * 2**16) / 2**16
            end = start + np.round(rng.uniform(-0.8, 0.8, (points, 2)) * 2**16) / 2**16
            if kind == "vv" and i % 3 == 0:
                end[1] = end[0]  # the points meet at t = 1
            flat.append(batchccd.make_query(kind, start, end))
        flat = np.array(flat)
        assert flat.shape == (200, 8, 2)
        lifted = np.concatenate([flat, np.zeros((200, 8, 1))], axis=2)
        for options in ({}, {"mode": "exact"}, {"min_distance": 0.05}):
            in_2d = batchccd.batch_ccd(kind, flat, **options)
            in_3d = batchccd.batch_ccd(kind, lifted, **options)
            assert np.array_equal(in_2d.hit, in_3d.hit) and np.array_equal(in_2d.toi, in_3d.toi)
            assert 0 < in_2d.hit.sum() < len(in_2d.hit), (kind, options)
            rows = batchccd.batch_ccd(kind, flat.reshape(200, 16), np.full(200, 0.01), **options)
            assert np.array_equal(rows.hit, batchccd.batch_ccd(kind, lifted, np.full(200, 0.01), **options).hit)
        default = batchccd.batch_ccd(kind, lifted)
        for i in range(0, 200, 17):
            one = batchccd.query_ccd(kind, flat[i])
            assert (one.hit, one.toi) == (default.hit[i], default.toi[i])
    with pytest.raises(ValueError, match=r"N x 8 x 2 or N x 16\), got 5 x 8 x 4"):
        batchccd.batch_ccd("ve", np.zeros((5, 8, 4)))
    with pytest.raises(ValueError, match="2D and 3D points mixed"):
        batchccd.make_query("vv", np.zeros((2, 2)), np.zeros((2, 3)))


def test_point_kind_calls_take_2d_points_as_the_plane_z_0():
    rng = np.random.default_rng(8)
    calls = {"ve": (batchccd.vertex_edge_ccd, 3), "vv": (batchccd.vertex_vertex_ccd, 2)}
    for kind, (call, points) in calls.items():
        hits = 0
        for _ in range(100):
            start = np.round(rng.uniform(-1, 1, (points, 2)) * 2**10) / 2**10
            end = start + np.round(rng.uniform(-0.8, 0.8, (points, 2)) * 2**10) / 2**10
            lifted = batchccd.make_query(kind, np.column_stack([start, np.zeros(points)]),
                                         np.column_stack([end, np.zeros(points)]))
            for options in ({}, {"min_distance": 0.1, "mode": "exact"}):
                flat = call(*start, *end, **options)
                spatial = batchccd.query_ccd(kind, lifted, **options)
                assert (flat.hit, flat.toi, flat.status) == (spatial.hit, spatial.toi, spatial.status)
                hits += flat.hit
        assert 0 < hits < 200, kind
