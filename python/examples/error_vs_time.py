#!/usr/bin/python3
"""Wrong decisions against run time, for every mode, on one scene.

    PYTHONPATH=<prefix>/lib/python3/dist-packages /usr/bin/python3 error_vs_time.py [SCENE] [--plot FILE]

SCENE is a scene directory (t0.ply, t1.ply, vf.csv, ee.csv, ...; default
../shared/data/scenes/cloth-funnel-227 beside the repository). Decisions
are compared with the scene's truth files, or with exact mode's where it
has none. With matplotlib installed the table is also drawn (FILE, default
error_vs_time.png).
"""
import argparse
import pathlib
import sys
import time

import numpy as np

import batchccd

LISTS = ("vertex_face", "edge_edge", "vertex_edge", "vertex_vertex")
DEFAULT_SCENE = pathlib.Path(__file__).resolve().parents[3] / "shared" / "data" / "scenes" / "cloth-funnel-227"


def ground_truth(scene, x0, x1, faces, lists):
    truths = [scene[f"{name}_truth"] for name in LISTS if len(scene[name])]
    if all(t is not None for t in truths):
        return np.concatenate(truths) if truths else np.zeros(0, bool), "the scene's truth files"
    return batchccd.mesh_ccd(x0, x1, faces, **lists, mode="exact").hit.copy(), "exact mode"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", nargs="?", default=str(DEFAULT_SCENE))
    parser.add_argument("--plot", default="error_vs_time.png")
    parser.add_argument("--repeat", type=int, default=5, help="calls per mode; the fastest counts")
    args = parser.parse_args()
    if not pathlib.Path(args.scene).is_dir():
        sys.exit(f"no scene directory {args.scene}: pass one (t0.ply, t1.ply, vf.csv, ee.csv)")

    scene = batchccd.read_scene(args.scene)
    x0, x1, faces = scene["x0"], scene["x1"], scene["faces"]
    lists = {name: scene[name] for name in LISTS}
    truth, source = ground_truth(scene, x0, x1, faces, lists)

    rows = []
    for mode in batchccd.modes():
        best = float("inf")
        for _ in range(args.repeat):
            start = time.perf_counter()
            result = batchccd.mesh_ccd(x0, x1, faces, **lists, mode=mode)
            best = min(best, time.perf_counter() - start)
        hit = result.hit
        rows.append((mode, best, int(np.sum(truth & ~hit)), int(np.sum(~truth & hit)), int(hit.sum())))

    print(f"{pathlib.Path(args.scene).name}: {len(truth):,} candidates, {int(truth.sum())} contacts ({source})")
    print(f"{'mode':<14}{'seconds':>10}{'false neg':>11}{'false pos':>11}{'hits':>8}")
    for mode, seconds, false_negatives, false_positives, hits in rows:
        print(f"{mode:<14}{seconds:>10.5f}{false_negatives:>11}{false_positives:>11}{hits:>8}")

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(matplotlib not installed: no plot)")
        return
    figure, axes = plt.subplots(figsize=(6, 4))
    for mode, seconds, false_negatives, false_positives, _ in rows:
        axes.scatter(seconds, false_negatives + false_positives, label=mode)
    axes.set_xscale("log")
    axes.legend()
    axes.set_xlabel("seconds per call (fastest of %d)" % args.repeat)
    axes.set_ylabel("wrong decisions")
    axes.set_title(pathlib.Path(args.scene).name)
    figure.tight_layout()
    figure.savefig(args.plot)
    print(f"plot: {args.plot}")


if __name__ == "__main__":
    main()
