# Type stub of batchccd.ipc (python/src/module.cpp): ipc-toolkit's calls
# under ipctk's names, arguments and answers (lib/include/batchccd/ipc.hpp).
from typing import Sequence, Union

import numpy.typing as npt

Point = Union[npt.ArrayLike, Sequence[float]]  # 1-D: 2 or 3 coordinates (point and edge calls), else 3

DEFAULT_CCD_TOLERANCE: float
DEFAULT_CCD_MAX_ITERATIONS: int
DEFAULT_CCD_CONSERVATIVE_RESCALING: float

# Each call returns (hit, toi); toi is inf without a hit.
def point_point_ccd(
    p0_t0: Point, p1_t0: Point, p0_t1: Point, p1_t1: Point,
    min_distance: float = 0.0, tmax: float = 1.0, tolerance: float = 1e-6,
    max_iterations: int = 10_000_000, conservative_rescaling: float = 0.8,
) -> tuple[bool, float]: ...
def point_edge_ccd(
    p_t0: Point, e0_t0: Point, e1_t0: Point, p_t1: Point, e0_t1: Point, e1_t1: Point,
    min_distance: float = 0.0, tmax: float = 1.0, tolerance: float = 1e-6,
    max_iterations: int = 10_000_000, conservative_rescaling: float = 0.8,
) -> tuple[bool, float]: ...
def edge_edge_ccd(
    ea0_t0: Point, ea1_t0: Point, eb0_t0: Point, eb1_t0: Point,
    ea0_t1: Point, ea1_t1: Point, eb0_t1: Point, eb1_t1: Point,
    min_distance: float = 0.0, tmax: float = 1.0, tolerance: float = 1e-6,
    max_iterations: int = 10_000_000, conservative_rescaling: float = 0.8,
) -> tuple[bool, float]: ...
def point_triangle_ccd(
    p_t0: Point, t0_t0: Point, t1_t0: Point, t2_t0: Point,
    p_t1: Point, t0_t1: Point, t1_t1: Point, t2_t1: Point,
    min_distance: float = 0.0, tmax: float = 1.0, tolerance: float = 1e-6,
    max_iterations: int = 10_000_000, conservative_rescaling: float = 0.8,
) -> tuple[bool, float]: ...

class NarrowPhase:
    tolerance: float
    max_iterations: int
    conservative_rescaling: float
    def __init__(
        self, tolerance: float = 1e-6, max_iterations: int = 10_000_000, conservative_rescaling: float = 0.8
    ) -> None: ...
    def point_point_ccd(
        self, p0_t0: Point, p1_t0: Point, p0_t1: Point, p1_t1: Point, min_distance: float = 0.0, tmax: float = 1.0
    ) -> tuple[bool, float]: ...
    def point_edge_ccd(
        self, p_t0: Point, e0_t0: Point, e1_t0: Point, p_t1: Point, e0_t1: Point, e1_t1: Point,
        min_distance: float = 0.0, tmax: float = 1.0,
    ) -> tuple[bool, float]: ...
    def edge_edge_ccd(
        self, ea0_t0: Point, ea1_t0: Point, eb0_t0: Point, eb1_t0: Point,
        ea0_t1: Point, ea1_t1: Point, eb0_t1: Point, eb1_t1: Point,
        min_distance: float = 0.0, tmax: float = 1.0,
    ) -> tuple[bool, float]: ...
    def point_triangle_ccd(
        self, p_t0: Point, t0_t0: Point, t1_t0: Point, t2_t0: Point,
        p_t1: Point, t0_t1: Point, t1_t1: Point, t2_t1: Point,
        min_distance: float = 0.0, tmax: float = 1.0,
    ) -> tuple[bool, float]: ...

# ipctk.compute_collision_free_stepsize over given candidates (rows of
# vertex ids, as batchccd.mesh_ccd takes them); positions n x 3 or n x 2.
def collision_free_stepsize(
    x0: npt.ArrayLike, x1: npt.ArrayLike, faces: npt.ArrayLike | None = None,
    vertex_face: npt.ArrayLike | None = None, edge_edge: npt.ArrayLike | None = None,
    vertex_edge: npt.ArrayLike | None = None, vertex_vertex: npt.ArrayLike | None = None,
    *, min_distance: float = 0.0, narrow_phase: NarrowPhase | None = None, threads: int = 0,
) -> float: ...
