"""A small deterministic mesh scene shared by the tests."""
import numpy as np

import batchccd


def two_sheets(side=6):
    """A still sheet at z = 0 and a sheet falling and turning through it, with
    two particles, and every pair of primitives on different bodies as candidates."""
    g = np.linspace(0.0, 1.0, side)
    xs, ys = np.meshgrid(g, g, indexing="ij")
    flat = np.stack([xs.ravel(), ys.ravel(), np.zeros(side * side)], axis=1)
    angle = 0.3
    c, s = np.cos(angle), np.sin(angle)
    centred = flat[:, :2] - 0.5
    turned = np.stack([0.5 + c * centred[:, 0] - s * centred[:, 1], 0.5 + s * centred[:, 0] + c * centred[:, 1]], 1)
    upper0 = flat + [0.0, 0.0, 0.5]
    upper1 = np.column_stack([turned, -0.5 + 0.1 * flat[:, 0] * flat[:, 1]])
    particles0 = np.array([[0.3, 0.3, 0.2], [0.7, 0.2, 0.6]])
    particles1 = np.array([[0.35, 0.3, -0.9], [0.6, 0.25, -0.4]])
    x0 = np.vstack([flat, upper0, particles0])
    x1 = np.vstack([flat, upper1, particles1])
    n = side * side
    faces = []
    for sheet in range(2):
        for i in range(side - 1):
            for j in range(side - 1):
                v = sheet * n + i * side + j
                faces += [[v, v + side, v + side + 1], [v, v + side + 1, v + 1]]
    faces = np.array(faces, dtype=np.int32)
    edges = batchccd.unique_edges(faces)
    body = lambda v: min(v // n, 2)  # noqa: E731
    vf = [[v, f] for v in range(len(x0)) for f in range(len(faces)) if body(v) != body(faces[f, 0])]
    ee = [[*a, *b] for a in edges for b in edges if body(a[0]) == 0 and body(b[0]) == 1]
    ve = [[p, *e] for p in (2 * n, 2 * n + 1) for e in edges]
    vv = [[p, q] for p in (2 * n, 2 * n + 1) for q in range(2 * n)]
    lists = {
        "vertex_face": np.array(vf, dtype=np.int32),
        "edge_edge": np.array(ee, dtype=np.int32),
        "vertex_edge": np.array(ve, dtype=np.int32),
        "vertex_vertex": np.array(vv, dtype=np.int32),
    }
    return x0, x1, faces, edges, lists


KINDS = {"vertex_face": "vf", "edge_edge": "ee", "vertex_edge": "ve", "vertex_vertex": "vv"}


def candidate_query(kind, row, x0, x1, faces):
    """The Query mesh_ccd evaluates for one candidate (by vertex id)."""
    if kind == "vertex_face":
        ids = [row[0], *faces[row[1]]]
    else:
        ids = list(row)
    return batchccd.make_query(KINDS[kind], x0[ids], x1[ids])
