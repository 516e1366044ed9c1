#!/usr/bin/env python3
"""How fast each volume mesher's cells grow away from the body: the mean
edge length in bands of distance from the wall, for Netgen and HXT on the
same dictionary, side by side (HXT's sizes must follow the size
field Netgen's follow, within 15 % in every band).

- sphereDrag as shipped (distance from the ball of radius 0.5; its 3
  prism layers fill the first 0.015, both meshers alike);
- the pipe as shipped, 8 prism layers on its wall (distance from the
  wall of radius 0.5: the layers fill the first 0.29, both meshers alike).

Each mesh: pmshFoam on 2 ranks, its cells and wall time, checkMesh's
worst faces. Writes size-grading.md, size-grading.json and
size-grading.png into --out (default bench/results).

Usage: bench/run --grading [--out DIR] [--work DIR]
"""

import argparse
import json
import math
import os
import sys
import tempfile
import time
import subprocess

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(BENCH_DIR)
sys.path.insert(0, BENCH_DIR)
sys.path.insert(0, os.path.join(ROOT, "tools"))
import foamCase as fc  # noqa: E402
from foamCase import PolyMeshFiles  # noqa: E402

RANKS = 2
MESHERS = ("netgen", "hxt")
CASES = {
    # distance from the body of an edge's midpoint (x, y, z)
    "sphereDrag": {
        "bands": [0, 0.05, 0.1, 0.2, 0.35, 0.6, 1, 1.5, 2.5, 4, 8],
        "distance": lambda x, y, z: math.sqrt(x*x + y*y + z*z) - 0.5,
        "what": "distance from the ball",
    },
    "pipe": {
        "bands": [0, 0.1, 0.2, 0.3, 0.4, 0.5],
        "distance": lambda x, y, z: 0.5 - math.sqrt(y*y + z*z),
        "what": "distance from the wall",
    },
}


def mesh(case, mesher, env):
    """pmshFoam with this volume mesher: (cells, wall seconds)"""
    fc.set_entry(os.path.join(case, "system", "pmshDict"), "volumeMesher", mesher)
    start = time.time()
    with open(os.path.join(case, "log.pmshFoam"), "w") as out:
        subprocess.run(fc.mpi(RANKS, ["pmshFoam", "-case", case]), cwd=case, env=env,
                       stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                       check=True)
    return time.time() - start


def mean_edges(case, bands, distance):
    """Mean edge length and edge count per band, over every processor mesh
    (an edge on a processor boundary counts once per side)"""
    sums = [0.0]*(len(bands) - 1)
    counts = [0]*(len(bands) - 1)
    for proc in sorted(p for p in os.listdir(case) if p.startswith("processor")):
        m = PolyMeshFiles(os.path.join(case, proc, "constant", "polyMesh"))
        points = m.points()
        edges = set()
        for f in m.faces():
            for i, a in enumerate(f):
                b = f[(i + 1) % len(f)]
                edges.add((min(a, b), max(a, b)))
        for a, b in edges:
            pa, pb = points[a], points[b]
            d = distance(*((pa[k] + pb[k])/2 for k in range(3)))
            for k in range(len(bands) - 1):
                if bands[k] <= d < bands[k + 1]:
                    sums[k] += math.dist(pa, pb)
                    counts[k] += 1
                    break
    return [s/c if c else None for s, c in zip(sums, counts)], counts


def plot(results, path):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("No matplotlib: no plot")
        return False
    fig, axes = plt.subplots(1, len(CASES), figsize=(11, 4))
    for ax, (name, spec) in zip(axes, CASES.items()):
        bands = spec["bands"]
        mids = [(a + b)/2 for a, b in zip(bands[:-1], bands[1:])]
        for mesher in MESHERS:
            r = results[name][mesher]
            ax.plot(mids, r["meanEdge"], "o-", label="%s (%d cells)" % (mesher, r["cells"]))
        ax.set_xlabel(spec["what"])
        ax.set_ylabel("mean edge length")
        ax.set_title(name)
        ax.grid(True, alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return True


def report(results, out):
    lines = ["# Cell size against distance from the wall: Netgen and HXT",
             "",
             "Made by `bench/run --grading` (bench/sizeGrading.py): each tutorial as"
             " shipped, meshed on %d ranks by each volume mesher, the mean length of"
             " the edges whose midpoints lie in each band of distance from the body."
             " Raw figures in [size-grading.json](size-grading.json)." % RANKS,
             "", "![Mean edge against distance](size-grading.png)", ""]
    for name, spec in CASES.items():
        n, h = results[name]["netgen"], results[name]["hxt"]
        lines += ["## %s" % name, "",
                  "| %s | netgen | hxt | hxt / netgen |" % spec["what"],
                  "|---|---:|---:|---:|"]
        bands = spec["bands"]
        for k in range(len(bands) - 1):
            a, b = n["meanEdge"][k], h["meanEdge"][k]
            ratio = "%.2f" % (b/a) if a and b else "-"
            lines.append("| %g - %g | %s | %s | %s |" % (
                bands[k], bands[k + 1], "%.4f" % a if a else "-", "%.4f" % b if b else "-",
                ratio))
        lines += ["",
                  "| | netgen | hxt |", "|---|---:|---:|",
                  "| cells | %d | %d |" % (n["cells"], h["cells"]),
                  "| meshing wall time [s] | %.1f | %.1f |" % (n["seconds"], h["seconds"]),
                  "| max non-orthogonality | %.1f | %.1f |" % (n["maxNonOrtho"], h["maxNonOrtho"]),
                  "| max skewness | %.2f | %.2f |" % (n["maxSkewness"], h["maxSkewness"]),
                  ""]
    with open(os.path.join(out, "size-grading.md"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--grading", action="store_true", help="(the mode's own flag)")
    parser.add_argument("--no-build", action="store_true", help="(bench/run's: use the pmshFoam built)")
    parser.add_argument("--out", default=os.path.join(BENCH_DIR, "results"))
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    env = fc.environment()
    work = args.work or tempfile.mkdtemp(prefix="pmsh-grading-")
    results = {}
    for name, spec in CASES.items():
        results[name] = {}
        for mesher in MESHERS:
            case = fc.copy_tutorial(name, os.path.join(work, "%s-%s" % (name, mesher)))
            seconds = mesh(case, mesher, env)
            quality = fc.check_mesh(case, RANKS, env)
            edges, counts = mean_edges(case, spec["bands"], spec["distance"])
            results[name][mesher] = {
                "cells": quality.get("cells", 0), "seconds": seconds,
                "maxNonOrtho": quality.get("maxNonOrtho", float("nan")),
                "maxSkewness": quality.get("maxSkewness", float("nan")),
                "meanEdge": edges, "edges": counts,
            }
            print("%s %s: %d cells in %.1f s, mean edges %s" % (
                name, mesher, results[name][mesher]["cells"], seconds,
                " ".join("%.3f" % e if e else "-" for e in edges)), flush=True)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "size-grading.json"), "w") as f:
        json.dump({"bands": {n: s["bands"] for n, s in CASES.items()}, "results": results},
                  f, indent=1)
    plot(results, os.path.join(args.out, "size-grading.png"))
    report(results, args.out)
    print("Written: %s" % os.path.join(args.out, "size-grading.md"))


if __name__ == "__main__":
    main()
