"""batchccd: narrow-phase continuous collision detection over NumPy arrays.

The calls of the C++ library (batchccd/batch.hpp, ccd.hpp) on NumPy
arrays: mesh_ccd and batch_ccd for many candidates at once, evaluated in
parallel with the GIL released; vertex_face_ccd, edge_edge_ccd,
vertex_edge_ccd, vertex_vertex_ccd and query_ccd for one query. Every call
takes the library's options as keywords (default_options() lists them).

batchccd.ipc holds ipc-toolkit's per-query calls and NarrowPhase (its
TightInclusionCCD) under ipctk's names, arguments and answers (ipc.hpp).
"""

import sys as _sys

from ._batchccd import (  # noqa: F401
    STATUS_INVALID_INPUT,
    STATUS_OK,
    BatchResult,
    InputError,
    QueryResult,
    Status,
    __version__,
    available_isas,
    batch_ccd,
    default_options,
    edge_edge_ccd,
    ipc,
    kinds,
    make_query,
    mesh_ccd,
    modes,
    query_ccd,
    read_scene,
    resolve_isa,
    squared_distance,
    unique_edges,
    vertex_edge_ccd,
    vertex_face_ccd,
    vertex_vertex_ccd,
)

__all__ = [
    "STATUS_INVALID_INPUT", "STATUS_OK", "BatchResult", "InputError", "QueryResult", "Status", "__version__",
    "available_isas", "batch_ccd", "default_options", "edge_edge_ccd", "ipc", "kinds", "make_query", "mesh_ccd",
    "modes", "query_ccd", "read_scene", "resolve_isa", "squared_distance", "unique_edges",
    "vertex_edge_ccd", "vertex_face_ccd", "vertex_vertex_ccd",
]

# The compiled submodule, importable by its name too (import batchccd.ipc).
_sys.modules[__name__ + ".ipc"] = ipc
