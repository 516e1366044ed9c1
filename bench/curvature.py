#!/usr/bin/env python3
"""STL curvature sizing: what it costs (cells) and what it buys (how far the
coarse boundary faces lie from the STL), for curvatureRefinement 0 and 3 at
several floors (minCellSize), on the STL test geometries and tutorials.

Each case is meshed serially at refinementLevels 0, so the written boundary
is the coarse one that every level refines: its error is what curvature
sizing controls (a level of refinement with projection divides it by about
4). The error of a face is the distance of its centroid from the STL's
triangles of the same solid; the table gives its maximum and mean over the
named solid. Writes bench/results/curvature.md (and .json).

    bench/run --curvature              # every case
    bench/run --curvature --quick      # one case, two settings (a smoke run)
"""

import argparse
import json
import math
import os
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from foamCase import ROOT, TutorialCase  # noqa: E402

GEOMETRY = os.path.join(ROOT, "tests", "data", "geometry")

# (label, STL file, solid measured, maxCellSize)
CASES = [
    ("sphereSTL (tutorial)", "sphere.stl", "sphere", 0.25),
    ("sphere, coarse", "sphere.stl", "sphere", 1.0),
    ("sphereInBox", "sphereInBox.stl", "body", 2.5),
    ("sphereInBox, finer", "sphereInBox.stl", "body", 1.0),
    ("cylinderInBox", "cylinderInBox.stl", "body", 2.5),
    ("cylinderInBox, finer", "cylinderInBox.stl", "body", 1.0),
    ("needleInBox", "needleInBox.stl", "body", 2.5),
]

# (label, pmshDict entries besides maxCellSize)
SETTINGS = [
    ("off (curvatureRefinement 0)", {"curvatureRefinement": 0}),
    ("3, no floor (minCellSize maxCellSize/1000)", {"curvatureRefinement": 3, "minCellSize": 1e-3}),
    ("3, minCellSize maxCellSize/16", {"curvatureRefinement": 3, "minCellSize": 1 / 16}),
    ("3, minCellSize maxCellSize/8 (default)", {"curvatureRefinement": 3}),
    ("3, minCellSize maxCellSize/4", {"curvatureRefinement": 3, "minCellSize": 1 / 4}),
]


def read_stl(path):
    """{solid: [(a, b, c)]} of an ascii STL."""
    solids, name, verts = {}, None, []
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "solid":
                name = w[1] if len(w) > 1 else "solid"
                solids.setdefault(name, [])
            elif w[0] == "vertex":
                verts.append(tuple(float(x) for x in w[1:4]))
                if len(verts) == 3:
                    solids[name].append(tuple(verts))
                    verts = []
    return solids


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def closest_on_triangle(p, a, b, c):
    """Ericson's closest point, as src/geometry/stlGeometry.C."""
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0 and d2 <= 0:
        return a
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0 and d4 <= d3:
        return b
    vc = d1 * d4 - d3 * d2
    if vc <= 0 and d1 >= 0 and d3 <= 0:
        t = d1 / (d1 - d3)
        return tuple(a[k] + t * ab[k] for k in range(3))
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0 and d5 <= d6:
        return c
    vb = d5 * d2 - d1 * d6
    if vb <= 0 and d2 >= 0 and d6 <= 0:
        t = d2 / (d2 - d6)
        return tuple(a[k] + t * ac[k] for k in range(3))
    va = d3 * d6 - d5 * d4
    if va <= 0 and (d4 - d3) >= 0 and (d5 - d6) >= 0:
        t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        return tuple(b[k] + t * (c[k] - b[k]) for k in range(3))
    den = 1 / (va + vb + vc)
    v, w = vb * den, vc * den
    return tuple(a[k] + v * ab[k] + w * ac[k] for k in range(3))


def distance_to(p, triangles):
    best = math.inf
    for a, b, c in triangles:
        lo = [min(a[k], b[k], c[k]) for k in range(3)]
        hi = [max(a[k], b[k], c[k]) for k in range(3)]
        box = sum(max(lo[k] - p[k], 0, p[k] - hi[k]) ** 2 for k in range(3))
        if box >= best * best:
            continue
        q = closest_on_triangle(p, a, b, c)
        best = min(best, math.sqrt(dot(sub(p, q), sub(p, q))))
    return best


def measure(case, stl, solid, maxh, entries):
    c = TutorialCase("sphereSTL", maxCellSize=maxh, refinementLevels=0)
    try:
        import shutil
        shutil.copy(os.path.join(GEOMETRY, stl), os.path.join(c.dir, "constant", "geometry", stl))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % stl)
        path = os.path.join(c.dir, "system", "pmshDict")
        with open(path) as f:
            text = f.read()
        text = re.sub(r"(?ms)^patches\s*\{.*?^\}", "patches\n{\n    \".*\" { type wall; }\n}", text)
        with open(path, "w") as f:
            f.write(text)
        for key, value in entries.items():
            c.set_entry("system/pmshDict", key, value * maxh if key == "minCellSize" else value)
        start = time.time()
        _, log = c.run("pmshFoam")
        seconds = time.time() - start
        coarse = int(re.search(r"coarse cells: (\d+)", log).group(1))
        bfaces = int(re.search(r"boundary faces: (\d+)", log).group(1))
        added = re.search(r"^\s+%s: .* about (\d+) boundary faces at these sizes" % solid, log, re.M)
        mesh = c.polymesh()
        points, faces = mesh.points(), mesh.faces()
        triangles = read_stl(os.path.join(GEOMETRY, stl))[solid]
        errors = []
        for name, e in mesh.boundary():
            if name != solid:
                continue
            start_face, n = int(e["startFace"]), int(e["nFaces"])
            for f in faces[start_face:start_face + n]:
                centroid = tuple(sum(points[v][k] for v in f) / len(f) for k in range(3))
                errors.append(distance_to(centroid, triangles))
        return {"case": case, "stl": stl, "maxCellSize": maxh, "entries": entries,
                "coarseCells": coarse, "boundaryFaces": bfaces, "solidFaces": len(errors),
                "estimatedFaces": int(added.group(1)) if added else 0,
                "maxError": max(errors), "meanError": sum(errors) / len(errors),
                "seconds": seconds}
    finally:
        c.cleanup()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="one case, two settings")
    ap.add_argument("--output", default=os.path.join(HERE, "results", "curvature"))
    args = ap.parse_args()
    cases = CASES[2:3] if args.quick else CASES
    settings = [SETTINGS[0], SETTINGS[3]] if args.quick else SETTINGS
    rows = []
    for case in cases:
        for label, entries in settings:
            r = measure(*case, entries)
            r["setting"] = label
            rows.append(r)
            print("%-22s %-44s coarse cells %7d, %s faces %6d (log's estimate %6d),"
                  " error max %.4g mean %.4g" % (r["case"], label, r["coarseCells"], case[2],
                                                 r["solidFaces"], r["estimatedFaces"],
                                                 r["maxError"], r["meanError"]), flush=True)
    if args.quick:
        return
    with open(args.output + ".json", "w") as f:
        json.dump(rows, f, indent=1)
    with open(args.output + ".md", "w") as f:
        f.write("# STL curvature sizing: cells against geometric error\n\n"
                "Written by `bench/run --curvature` on %s (%s). Serial, refinementLevels 0:\n"
                "the coarse mesh every level refines. *error*: distance of the measured\n"
                "solid's coarse boundary face centroids from its STL triangles (a level\n"
                "of refinement with projection divides it by about 4). *log's estimate*:\n"
                "the stage-1 log's estimate of the solid's faces at the curvature sizes.\n\n"
                % (time.strftime("%Y-%m-%d"), os.uname().nodename))
        f.write("| case | maxCellSize | curvature sizing | coarse cells | solid faces |"
                " log's estimate | max error | mean error |\n|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write("| %s | %g | %s | %d | %d | %d | %.3g | %.3g |\n"
                    % (r["case"], r["maxCellSize"], r["setting"], r["coarseCells"],
                       r["solidFaces"], r["estimatedFaces"], r["maxError"], r["meanError"]))


if __name__ == "__main__":
    main()
