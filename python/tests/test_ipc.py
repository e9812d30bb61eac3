"""batchccd.ipc: ipc-toolkit's calls and TightInclusionCCD under ipctk's names, answering (hit, toi)."""
import math
import pathlib
import re

import numpy as np
import pytest

import batchccd
import batchccd.ipc as ipc  # importable by name, as a port from ipctk would

O, B, C = np.array([0.0, 0, 0]), np.array([1.0, 0, 0]), np.array([0.0, 1, 0])  # the unit triangle
CLOSE = 2.0**-14  # a start this close: the conservative rescaling sets the separation


def planar_crossings(count, seed=28):
    """A 2D point reaching an edge's interior at a known time: (points t0 then t1, time)."""
    rng = np.random.default_rng(seed)
    for _ in range(count):
        p_t0, e0_t0, e1_t0, e0_t1, e1_t1 = rng.uniform(-1, 1, (5, 2))
        time, along = rng.uniform(0.05, 0.95), rng.uniform(0.1, 0.9)
        e0, e1 = e0_t0 + time * (e0_t1 - e0_t0), e1_t0 + time * (e1_t1 - e1_t0)
        p_t1 = p_t0 + (e0 + along * (e1 - e0) - p_t0) / time
        yield (p_t0, e0_t0, e1_t0, p_t1, e0_t1, e1_t1), time


def test_a_planar_point_edge_crossing_is_reported_no_later_than_it_happens():
    p_t0, p_t1, e0, e1 = np.array([0.5, 1.0]), np.array([0.5, -1.0]), np.zeros(2), np.array([1.0, 0])
    hit, toi = ipc.point_edge_ccd(p_t0, e0, e1, p_t1, e0, e1)
    assert hit is True and 0.5 - 1e-4 <= toi <= 0.5
    hit, toi = ipc.point_edge_ccd(p_t0, e0, e1, p_t1, e0, e1, min_distance=0.25)
    assert hit and 0 < toi <= 0.375
    for points, time in planar_crossings(200):
        hit, toi = ipc.point_edge_ccd(*points, min_distance=0.01)
        assert hit and 0 <= toi <= time
        # The same points in 3D at z = 0: the same answer.
        assert ipc.point_edge_ccd(*(np.append(x, 0.0) for x in points), min_distance=0.01) == (hit, toi)


def test_a_static_point_on_a_triangle_touches_at_zero():
    p = np.array([0.25, 0.25, 0.0])
    assert ipc.point_triangle_ccd(p, O, B, C, p, O, B, C) == (True, 0.0)
    # Within min_distance of it, also without motion.
    q = np.array([0.25, 0.25, 0.25])
    assert ipc.point_triangle_ccd(q, O, B, C, q, O, B, C, min_distance=0.25) == (True, 0.0)
    assert ipc.point_triangle_ccd(q, O, B, C, q, O, B, C, min_distance=0.125)[0] is False


def test_a_miss_answers_false_and_inf():
    p_t0, p_t1 = np.array([2.0, 2, 1]), np.array([2.0, 2, -1])
    answer = ipc.point_triangle_ccd(p_t0, O, B, C, p_t1, O, B, C)
    assert isinstance(answer, tuple) and len(answer) == 2
    assert answer[0] is False and math.isinf(answer[1])
    # A contact after tmax is no contact.
    p_t0, p_t1 = np.array([0.25, 0.25, 1]), np.array([0.25, 0.25, -1])
    assert ipc.point_triangle_ccd(p_t0, O, B, C, p_t1, O, B, C, tmax=0.25)[0] is False
    hit, toi = ipc.point_triangle_ccd(p_t0, O, B, C, p_t1, O, B, C, tmax=0.75)
    assert hit and toi <= 0.5


def test_lists_and_integer_arrays_are_points_too():
    assert ipc.point_point_ccd([0, 0, 1], [0, 0, 0], [0, 0, -1], [0, 0, 0]) == ipc.point_point_ccd(
        np.array([0.0, 0, 1]), O, np.array([0.0, 0, -1]), O
    )
    # Strided float64 views are read as the values they show.
    grid = np.array([[0.0, 9, 1, 9, 0], [0.0, 9, -1, 9, 0]])
    assert ipc.point_point_ccd(grid[0, ::2], O, grid[1, ::2], O) == ipc.point_point_ccd(
        np.array([0.0, 1, 0]), O, np.array([0.0, -1, 0]), O
    )


# One case per row: the call's name, the points (t0 then t1), min_distance, tmax.
CASES = [
    ("point_point_ccd", ([0, 0, 1], O, [0, 0, -1], O), 0.0, 1.0),
    ("point_point_ccd", ([0, 1], [0, 0], [0, -1], [0, 0]), 0.0, 1.0),
    ("point_point_ccd", ([0, 0, CLOSE], O, [0, 0, -CLOSE], O), 0.0, 1.0),
    ("point_point_ccd", ([-0.25, 0, 0], [-0.75, -0.25, -0.25], [-0.75, -0.25, -0.5], [-0.75, -0.25, -0.25]), 0.25, 1.0),
    ("point_edge_ccd", ([0.5, 1], [0, 0], [1, 0], [0.5, -1], [0, 0], [1, 0]), 0.25, 1.0),
    ("point_edge_ccd", ([0.5, CLOSE], [0, 0], [1, 0], [0.5, -CLOSE], [0, 0], [1, 0]), 0.0, 1.0),
    ("point_edge_ccd", ([0.25, -0.5], [0.75, 0.75], [0.5, 0], [0.25, 0.5], [0.75, 0.75], [0.5, 0]), 0.25, 1.0),
    ("point_edge_ccd", ([2, 1], [0, 0], [1, 0], [2, -1], [0, 0], [1, 0]), 0.5, 1.0),
    ("edge_edge_ccd", ([0, -1, 1], [0, 1, 1], [-1, 0, 0], B, [0, -1, -1], [0, 1, -1], [-1, 0, 0], B), 0.0, 1.0),
    ("edge_edge_ccd", ([0, -1, 1], [0, 1, 1], [-1, 0, 0], B, [0, -1, -1], [0, 1, -1], [-1, 0, 0], B), 0.0, 0.25),
    ("edge_edge_ccd", ([0, -1, CLOSE], [0, 1, CLOSE], [-1, 0, 0], B, [0, -1, -CLOSE], [0, 1, -CLOSE], [-1, 0, 0], B),
     0.0, 1.0),
    ("point_triangle_ccd", ([0.25, 0.25, 1], O, B, C, [0.25, 0.25, -1], O, B, C), 0.25, 1.0),
    ("point_triangle_ccd", ([0.25, 0.25, CLOSE], O, B, C, [0.25, 0.25, -CLOSE], O, B, C), 0.0, 1.0),
    ("point_triangle_ccd", ([0.25, -0.25, 0], [-0.25, 0, 0], [1, 0.75, 0.25], [0.5, 0.25, -0.25],
                            [-0.5, -0.25, 0], [-0.25, 0, 0], [1, 0.75, 0.25], [0.5, 0.25, -0.25]), 0.25, 1.0),
    ("point_triangle_ccd", ([2, 2, 1], O, B, C, [2, 2, -1], O, B, C), 0.0, 1.0),
    # Edge b turns about its middle over a's end, closest there at 1.07 times
    # the separation: a miss only a search over boxes proves (the others
    # are decided without one), so max_iterations 0 gives up: a contact.
    ("edge_edge_ccd", (O, [0.5 - 0.75 / 128, 0, 0], [0.5, -1, 1 + 1.625 / 128], [0.5, 1, -1 + 1.625 / 128],
                       O, [0.5 - 0.75 / 128, 0, 0], [0.5, -1, -1 + 1.625 / 128], [0.5, 1, 1 + 1.625 / 128]),
     0.01, 1.0),
]

SETTINGS = [
    {},
    {"tolerance": 0.05},
    {"max_iterations": 0},
    {"conservative_rescaling": 0.5},
    {"tolerance": 1e-4, "max_iterations": -1, "conservative_rescaling": 1.0},
]


def answers(call, **settings):
    return [call(name)(*(np.asarray(x, dtype=float) for x in points), min_distance, tmax, **settings)
            for name, points, min_distance, tmax in CASES]


@pytest.mark.parametrize("settings", SETTINGS, ids=lambda s: ",".join(s) or "defaults")
def test_the_class_answers_as_the_functions_given_its_attributes(settings):
    narrow_phase = ipc.NarrowPhase(**settings)
    by_method = answers(lambda name: getattr(narrow_phase, name))
    assert by_method == answers(lambda name: getattr(ipc, name), **settings)
    # Each setting but the tolerance changes some answer here, so one left
    # unforwarded shows. The tolerance only permits false positives, and
    # near misses at the separations these calls ask for are proven misses
    # whatever it is.
    if settings and set(settings) != {"tolerance"}:
        assert by_method != answers(lambda name: getattr(ipc.NarrowPhase(), name))


def test_the_class_reads_its_attributes_when_called():
    narrow_phase = ipc.NarrowPhase()
    assert (narrow_phase.tolerance, narrow_phase.max_iterations, narrow_phase.conservative_rescaling) == (
        1e-6, 10_000_000, 0.8)
    assert (ipc.DEFAULT_CCD_TOLERANCE, ipc.DEFAULT_CCD_MAX_ITERATIONS, ipc.DEFAULT_CCD_CONSERVATIVE_RESCALING) == (
        1e-6, 10_000_000, 0.8)
    narrow_phase.conservative_rescaling = 0.5
    narrow_phase.tolerance = 0.05
    narrow_phase.max_iterations = 0
    assert answers(lambda name: getattr(narrow_phase, name)) == answers(
        lambda name: getattr(ipc, name), tolerance=0.05, max_iterations=0, conservative_rescaling=0.5)
    assert "conservative_rescaling=0.5" in repr(narrow_phase)
    narrow_phase.conservative_rescaling = 0.0  # refused by the call, as the object may change at any time
    with pytest.raises(ValueError, match=r"point_triangle_ccd: conservative_rescaling must be in \(0, 1\]"):
        narrow_phase.point_triangle_ccd(O, O, B, C, O, O, B, C)


def test_lengths_that_do_not_fit_raise_value_error_naming_the_argument():
    planar, spatial, four = np.zeros(2), np.zeros(3), np.zeros(4)
    with pytest.raises(ValueError, match="point_triangle_ccd: p_t0 must be of length 3, got 2"):
        ipc.point_triangle_ccd(*[planar] * 8)
    with pytest.raises(ValueError, match="edge_edge_ccd: eb1_t1 must be of length 3"):
        ipc.edge_edge_ccd(*[spatial] * 7, planar)
    with pytest.raises(ValueError, match="point_edge_ccd: e1_t0 must be of length 2 like p_t0, got 3"):
        ipc.point_edge_ccd(planar, planar, spatial, planar, planar, planar)
    with pytest.raises(ValueError, match="point_point_ccd: p0_t0 must be of length 2 or 3, got 4"):
        ipc.point_point_ccd(four, four, four, four)
    with pytest.raises(ValueError, match="point_edge_ccd: p_t0 must be of length 2 or 3, got 4"):
        ipc.NarrowPhase().point_edge_ccd(*[four] * 6)
    with pytest.raises(ValueError, match="1-D"):
        ipc.point_point_ccd(np.zeros((1, 3)), spatial, spatial, spatial)


def test_bad_settings_raise_value_error_naming_them():
    p_t0, p_t1 = np.array([0.0, 0, 1]), np.array([0.0, 0, -1])
    with pytest.raises(ValueError, match="point_point_ccd: min_distance must be >= 0 and finite, got -1"):
        ipc.point_point_ccd(p_t0, O, p_t1, O, min_distance=-1)
    with pytest.raises(ValueError, match="point_point_ccd: tmax must be in"):
        ipc.NarrowPhase().point_point_ccd(p_t0, O, p_t1, O, tmax=2)
    with pytest.raises(ValueError, match="NarrowPhase: tolerance must be positive and finite, got 0"):
        ipc.NarrowPhase(tolerance=0)
    with pytest.raises(ValueError, match="NarrowPhase: conservative_rescaling must be in"):
        ipc.NarrowPhase(conservative_rescaling=1.5)


def test_the_stub_beside_the_module_names_everything():
    package = pathlib.Path(batchccd.__file__).parent
    stub = (package / "ipc.pyi").read_text()
    assert re.search(r"^from \. import ipc as ipc$", (package / "__init__.pyi").read_text(), re.MULTILINE)
    for name in (n for n in dir(ipc) if not n.startswith("_")):
        assert re.search(rf"\b{name}\b", stub), name
    for name in ("point_point_ccd", "point_edge_ccd", "edge_edge_ccd", "point_triangle_ccd"):
        assert len(getattr(ipc, name).__doc__) > 40 and len(getattr(ipc.NarrowPhase, name).__doc__) > 40


def test_collision_free_stepsize_is_the_minimum_of_the_calls():
    # Random 2D segments and vertices: the batch step equals the per-query
    # calls' minimum, for both thread counts and a custom narrow phase.
    rng = np.random.default_rng(8)
    n = 24
    x0 = np.round(rng.uniform(-0.5, 0.5, (n, 2)) * 2**20) / 2**20
    x1 = x0 + np.round(rng.uniform(-0.25, 0.25, (n, 2)) * 2**20) / 2**20
    vertex_edge = np.array([[v, e, e + 1] for v in range(n) for e in range(0, n - 1, 2) if v not in (e, e + 1)],
                           dtype=np.int32)
    for narrow_phase in (batchccd.ipc.NarrowPhase(), batchccd.ipc.NarrowPhase(conservative_rescaling=0.5)):
        for min_distance in (0.0, 1e-3):
            expected = 1.0
            for v, a, b in vertex_edge:
                hit, toi = narrow_phase.point_edge_ccd(x0[v], x0[a], x0[b], x1[v], x1[a], x1[b], min_distance)
                if hit:
                    expected = min(expected, toi)
            assert expected < 1
            for threads in (1, 2):
                step = batchccd.ipc.collision_free_stepsize(x0, x1, vertex_edge=vertex_edge, min_distance=min_distance,
                                                            narrow_phase=narrow_phase, threads=threads)
                assert step == expected
    with pytest.raises(ValueError, match="min_distance must be >= 0"):
        batchccd.ipc.collision_free_stepsize(x0, x1, vertex_edge=vertex_edge, min_distance=-1.0)
    with pytest.raises(ValueError, match="vertex-edge candidate 0: vertex 99"):
        batchccd.ipc.collision_free_stepsize(x0, x1, vertex_edge=np.array([[99, 0, 1]], dtype=np.int32))
