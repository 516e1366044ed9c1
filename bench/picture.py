#!/usr/bin/python3
"""The README's picture: the sphere and the shaft meshed by pmshFoam on 8
ranks, each rank's part drawn in its own colour and pulled apart from the
others (an exploded view), so that both the fine surface and the partition
show. Reads the boundary faces of processor*/constant/polyMesh with the
tests' reader; draws with matplotlib (Debian's python3-matplotlib).

    bench/run --picture [--np 8] [--r 1] [--out bench/results/partition.png]
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt                                 # noqa: E402
import numpy as np                                              # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection         # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from foamCase import PolyMeshFiles                          # noqa: E402
import foamCase as fc                                          # noqa: E402


def mesh(tutorial, np_, r, work, env):
    """pmshFoam on a copy of the tutorial; returns the case directory."""
    case = fc.copy_tutorial(tutorial, os.path.join(work, tutorial))
    dict_file = os.path.join(case, "system", "pmshDict")
    fc.set_entry(dict_file, "refinementLevels", r)
    fc.set_entry(dict_file, "volumeMesher", "hxt")
    subprocess.run(fc.mpi(np_, ["pmshFoam", "-case", case]), env=env, check=True,
                   stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
    return case


def part_surfaces(case, np_):
    """[(points, triangles of the part's closed boundary)] per rank."""
    parts = []
    for p in range(np_):
        m = PolyMeshFiles(os.path.join(case, "processor%d" % p, "constant", "polyMesh"))
        points = np.array(m.points())
        faces = m.faces()
        start = min(int(e["startFace"]) for _, e in m.boundary())
        parts.append((points, np.array(faces[start:])))
    return parts


def draw(ax, parts, explode, title, view, zoom):
    centre = np.mean([pts[tri].reshape(-1, 3).mean(0) for pts, tri in parts], axis=0)
    colours = plt.get_cmap("tab10" if len(parts) <= 10 else "tab20")
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    polys, shades = [], []
    for p, (pts, tri) in enumerate(parts):
        shift = explode * (pts[tri].reshape(-1, 3).mean(0) - centre)
        x = pts[tri] + shift
        n = np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0])
        n /= np.linalg.norm(n, axis=1)[:, None]
        brightness = 0.45 + 0.55 * np.abs(n @ light)
        base = np.array(colours(p % colours.N)[:3])
        polys.extend(x)
        shades.extend(np.clip(base[None, :] * brightness[:, None], 0, 1))
    ax.add_collection3d(Poly3DCollection(polys, facecolors=shades, edgecolors=(0, 0, 0, 0.25),
                                         linewidths=0.15))
    allx = np.concatenate(polys)
    lo, hi = allx.min(0), allx.max(0)
    for set_lim, a, b in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), lo, hi):
        set_lim(a, b)
    ax.set_box_aspect(hi - lo, zoom=zoom)
    ax.view_init(*view)
    ax.set_axis_off()
    ax.set_title(title, fontsize=11)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--np", type=int, default=8)
    parser.add_argument("--r", type=int, default=1)
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "partition.png"))
    args = parser.parse_args()

    env = fc.environment()
    work = tempfile.mkdtemp(prefix="pmshPicture-")
    try:
        fig = plt.figure(figsize=(12, 5), dpi=90)
        for i, (tutorial, explode, view, zoom) in enumerate(
                [("sphere", 0.45, (22, -60), 1.25), ("shaft", 0.35, (25, -70), 0.9)]):
            case = mesh(tutorial, args.np, args.r, work, env)
            parts = part_surfaces(case, args.np)
            ax = fig.add_axes([0, 0, 0.4, 0.93] if i == 0 else [0.4, 0, 0.6, 0.93],
                              projection="3d")
            fine = fc.summary(case)["fineCells"]
            draw(ax, parts, explode, "%s: %d cells on %d ranks (r = %d)"
                 % (tutorial, fine, args.np, args.r), view, zoom)
        fig.savefig(args.out)
        print("wrote %s (%d kB)" % (args.out, os.path.getsize(args.out) // 1024))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
