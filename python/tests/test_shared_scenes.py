"""The same answers as the C++ tool on the shared scenes (skipped without them)."""
import math
import subprocess

import numpy as np
import pytest

import batchccd

MODES = [m for m in batchccd.modes() if m in ("conservative", "exact")]


def scenes(shared):
    return sorted(p for p in (shared / "scenes").iterdir() if (p / "t0.ply").exists())


def tool_results(cli, scene, mode, tmp_path):
    out = tmp_path / f"{scene.name}-{mode}.txt"
    subprocess.run([cli, "run", "--mode", mode, "--out", str(out), str(scene)], check=True,
                   stdout=subprocess.DEVNULL)
    rows = [line.split(",") for line in out.read_text().split()]
    return np.array([r[0] == "1" for r in rows]), np.array([float(r[1]) for r in rows])


@pytest.mark.parametrize("mode", MODES)
def test_shared_scenes_match_the_tool_bit_for_bit(shared_data, cli, mode, tmp_path):
    checked = 0
    for scene in scenes(shared_data):
        data = batchccd.read_scene(str(scene))
        lists = {k: data[k] for k in ("vertex_face", "edge_edge", "vertex_edge", "vertex_vertex")}
        result = batchccd.mesh_ccd(data["x0"], data["x1"], data["faces"], **lists, mode=mode)
        hit, toi = tool_results(cli, scene, mode, tmp_path)
        assert np.array_equal(result.hit, hit), scene.name
        assert np.array_equal(result.toi, toi), scene.name
        # The library's promises against the scene's truth.
        for name, rows in lists.items():
            truth = data[f"{name}_truth"]
            if truth is None or len(rows) == 0:
                continue
            start = sum(len(lists[k]) for k in list(lists)[: list(lists).index(name)])
            decided = result.hit[start:start + len(rows)]
            assert not np.any(truth & ~decided), f"{scene.name} {name}: a false negative"
            if mode == "exact":
                assert np.array_equal(truth, decided), f"{scene.name} {name}"
        checked += 1
    assert checked > 0
    assert math.isfinite(result.earliest_toi) or result.counters["hits"] == 0
