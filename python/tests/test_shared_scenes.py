"""The same answers as the C++ tool on the shared scenes (skipped without them)."""
import math
import pathlib
import subprocess
import sys

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
        # The earliest TOI is the first of the hits' (infinite without a hit).
        assert result.earliest_toi == (result.toi[result.hit].min() if result.hit.any() else math.inf), scene.name
        assert result.counters["hits"] == np.count_nonzero(result.hit), scene.name
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


def test_error_vs_time_example_prints_every_mode(shared_data, tmp_path):
    scene = shared_data / "scenes" / "cloth-funnel-227"
    if not scene.is_dir():
        pytest.skip("no cloth-funnel-227")
    example = pathlib.Path(__file__).resolve().parents[1] / "examples" / "error_vs_time.py"
    out = subprocess.run([sys.executable, str(example), str(scene), "--repeat", "1", "--plot", str(tmp_path / "p.png")],
                         check=True, capture_output=True, text=True).stdout
    rows = {line.split()[0]: line.split() for line in out.splitlines()[2:] if line.split()[0] in batchccd.modes()}
    assert set(rows) == set(batchccd.modes())
    for mode in MODES:
        assert rows[mode][2:4] == ["0", "0"], out  # no wrong decision in the certified modes
