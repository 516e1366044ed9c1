#!/usr/bin/env python3
"""The estimate after stage 1 against what the run made: expected fine cells
and peak memory per rank (the log's "expected fine cells" line, summary.json's
estimatedFineCells and estimatedPeakMemoryPerRankBytes) over the measured
ones, on the tutorials, the test geometries, STL bodies in boxes with
curvature sizing and cases with local sizes, both volume meshers, 1 and 2
ranks. The estimate must be within 0.67-1.5 of the actual values, and may
err high but never more than 1.5x low. Writes bench/results/estimates.md
(and .json).

    bench/run --estimates              # every case (~20)
    bench/run --estimates --only NAME  # the cases whose name contains NAME
"""

import argparse
import json
import os
import re
import shutil
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
from foamCase import ROOT, SHIPPED_GEOMETRY, TutorialCase, extent, summary, write_bullet_in_box  # noqa: E402

GEOMETRY = os.path.join(ROOT, "tests", "data", "geometry")

SPHERE_BODY = {"body": "maxCellSize 0.1"}
BULLET = "bulletInBox.stl"
BULLET_BODY = {"body": "maxCellSize 0.002"}
BULLET_LAYERS = {"body": "maxCellSize 0.002; layers 5; firstLayerThickness 0.0001; expansionRatio 1.2"}
WAKE = "wake { type box; min (-1 -1 -1); max (4 1 1); maxCellSize 0.3; }"

# (name, tutorial, geometry file from tests/data or None, ranks, entries,
#  patch sizes {patch: entries}, refinementRegions text)
CASES = [
    ("sphere netgen r2", "sphere", None, 1, {"refinementLevels": 2}, {}, None),
    ("sphere hxt r2 P2", "sphere", None, 2, {"refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("shaft netgen r2 P2", "shaft", None, 2, {"refinementLevels": 2}, {}, None),
    ("shaft hxt r2 P2", "shaft", None, 2, {"refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("sphereSTL netgen r2", "sphereSTL", None, 1, {"refinementLevels": 2}, {}, None),
    ("sphereSTL hxt r2 P2", "sphereSTL", None, 2, {"refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("heatSinkCHT hxt r1 P2", "heatSinkCHT", None, 2, {}, {}, None),
    ("sphereDrag netgen r2 P2 (local sizes, 3 layers)", "sphereDrag", None, 2,
     {"volumeMesher": "netgen"}, {}, None),
    ("sphereDrag hxt r2 P2 (local sizes, 3 layers)", "sphereDrag", None, 2,
     {"volumeMesher": "hxt"}, {}, None),
    ("sphereInBox.stl netgen r1", "sphereSTL", "sphereInBox.stl", 1,
     {"maxCellSize": 1, "refinementLevels": 1}, {}, None),
    ("sphereInBox.stl hxt r2 P2", "sphereSTL", "sphereInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("cylinderInBox.stl hxt r2 P2", "sphereSTL", "cylinderInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("cylinderInBox.stl hxt r2 P2, no floor", "sphereSTL", "cylinderInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt", "minCellSize": 0.001}, {}, None),
    ("cylinderInBox.stl netgen r1 P2, no floor", "sphereSTL", "cylinderInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 1, "minCellSize": 0.001}, {}, None),
    ("needleInBox.stl hxt r1 P2", "sphereSTL", "needleInBox.stl", 2,
     {"maxCellSize": 2.5, "refinementLevels": 1, "volumeMesher": "hxt", "curvatureRefinement": 0}, {}, None),
    ("sphereInBox.geo hxt r2 P2", "sphereSTL", "sphereInBox.geo", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
    ("sphereInBox.stl hxt r2 P2, body size", "sphereSTL", "sphereInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt"}, SPHERE_BODY, None),
    ("sphereInBox.stl netgen r1 P2, body size + wake", "sphereSTL", "sphereInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 1}, SPHERE_BODY, WAKE),
    ("sphereInBox.stl hxt r2 P2, wake", "sphereSTL", "sphereInBox.stl", 2,
     {"maxCellSize": 1, "refinementLevels": 2, "volumeMesher": "hxt"}, {}, WAKE),
    ("shaft hxt r3 P2", "shaft", None, 2, {"refinementLevels": 3, "volumeMesher": "hxt"}, {}, None),
    ("pipe netgen r1 P2 (8 layers)", "pipe", None, 2, {"volumeMesher": "netgen"}, {}, None),
    ("pipe hxt r1 P2 (8 layers)", "pipe", None, 2, {"volumeMesher": "hxt"}, {}, None),
    # OpenFOAM's bullet in a box (write_bullet_in_box), at two sizes, with
    # and without 5 layers on the body
    ("bullet hxt 0.02 r1 P2", "sphereSTL", BULLET, 2,
     {"maxCellSize": 0.02, "refinementLevels": 1, "volumeMesher": "hxt"}, BULLET_BODY, None),
    ("bullet hxt 0.02 r1 P2 (5 layers)", "sphereSTL", BULLET, 2,
     {"maxCellSize": 0.02, "refinementLevels": 1, "volumeMesher": "hxt"}, BULLET_LAYERS, None),
    ("bullet hxt 0.01 r1 P2", "sphereSTL", BULLET, 2,
     {"maxCellSize": 0.01, "refinementLevels": 1, "volumeMesher": "hxt"}, {}, None),
    ("bullet netgen 0.02 r1 P2 (5 layers)", "sphereSTL", BULLET, 2,
     {"maxCellSize": 0.02, "refinementLevels": 1, "volumeMesher": "netgen"}, BULLET_LAYERS, None),
    ("bullet hxt 0.01 r2 P2", "sphereSTL", BULLET, 2,
     {"maxCellSize": 0.01, "refinementLevels": 2, "volumeMesher": "hxt"}, {}, None),
] + [
    # OpenFOAM's shipped surfaces in the dictionary's domain box (as
    # tests/tutorials/testShippedSurfaces.py): d the surface's extent, the
    # body at d/20, maxCellSize d/2 and d/4, with and without 3 layers
    ("%s hxt d/%d r1 P2%s" % (name, divisor, " (3 layers)" if layered else ""), "sphereSTL",
     (surface, divisor, layered), 2, {"refinementLevels": 1, "volumeMesher": "hxt"}, {}, None)
    for name, surface in (("blob", "blob.stl.gz"), ("flange", "flange.stl.gz"),
                          ("DTC hull", "DTC-scaled.stl.gz"))
    for divisor in (2, 4) for layered in (False, True)
]


def shipped_case(tutorial, surface, divisor, layered):
    """A shipped surface in a domain box one extent d beyond it: the box's
    patch farfield, the body's walls at d/20, maxCellSize d/divisor"""
    c = TutorialCase(tutorial)
    source = os.path.join(SHIPPED_GEOMETRY, surface)
    lo, hi = extent(source)
    d = max(h - l for l, h in zip(lo, hi))
    shutil.copy(source, os.path.join(c.dir, "constant", "geometry", surface))
    shutil.rmtree(os.path.join(c.dir, "0"), ignore_errors=True)
    c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % surface)
    c.set_entry("system/pmshDict", "maxCellSize", d / divisor)
    c.set_entry("system/pmshDict", "domain",
                "{ type box; min (%s); max (%s); patches { default farfield; } }"
                % (" ".join("%r" % (x - d) for x in lo), " ".join("%r" % (x + d) for x in hi)))
    layers = "layers 3; firstLayerThickness %r; " % (d / 2000) if layered else ""
    c.substitute("system/pmshDict", r"(?ms)^patches\s*\{.*?^\}",
                 "patches\n{\n    farfield { type patch; }\n"
                 "    \".*\" { type wall; maxCellSize %r; %s}\n}" % (d / 20, layers))
    if surface.startswith("DTC"):
        c.set_entry("system/pmshDict", "coarseSurface", "remesh")
    return c


def make_case(tutorial, geometry, entries, patch_sizes, regions):
    if isinstance(geometry, tuple):
        c = shipped_case(tutorial, *geometry)
        for key, value in entries.items():
            c.set_entry("system/pmshDict", key, value)
        return c
    c = TutorialCase(tutorial)
    if geometry == BULLET:
        write_bullet_in_box(os.path.join(c.dir, "constant", "geometry", geometry))
    elif geometry:
        shutil.copy(os.path.join(GEOMETRY, geometry), os.path.join(c.dir, "constant", "geometry", geometry))
    if geometry:
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % geometry)
        # The solids of the test geometries: no field templates for them
        shutil.rmtree(os.path.join(c.dir, "0"), ignore_errors=True)
    path = os.path.join(c.dir, "system", "pmshDict")
    with open(path) as f:
        text = f.read()
    if geometry or patch_sizes:
        patches = "".join('    %s { type wall; %s; }\n' % p for p in patch_sizes.items())
        text = re.sub(r"(?ms)^patches\s*\{.*?^\}", "", text)
        text += '\npatches\n{\n%s    ".*" { type wall; }\n}\n' % patches
    if regions:
        text = re.sub(r"(?ms)^refinementRegions\s*\{.*?^\}", "", text)
        text += "\nrefinementRegions\n{\n    %s\n}\n" % regions
    with open(path, "w") as f:
        f.write(text)
    for key, value in entries.items():
        c.set_entry("system/pmshDict", key, value)
    return c


def measure(name, tutorial, geometry, np, entries, patch_sizes, regions):
    c = make_case(tutorial, geometry, entries, patch_sizes, regions)
    try:
        start = time.time()
        code, log = c.run("pmshFoam", np=np, check=False, timeout=3600)
        seconds = time.time() - start
        s = summary(c.dir)
        if code != 0 or s is None:
            return {"case": name, "error": log[-1500:]}
        peak = max(s["peakMemoryPerRankBytes"])
        return {"case": name, "ranks": np, "volumeMesher": s["volumeMesher"],
                "coarseCells": s["coarseCells"], "fineCells": s["fineCells"],
                "expectedFineCells": s["estimatedFineCells"],
                "largestRankFineCells": max(s["fineCellsPerRank"]),
                "expectedLargestRankFineCells": s["estimatedFineCellsLargestRank"],
                "peakBytes": peak, "expectedPeakBytes": s["estimatedPeakMemoryPerRankBytes"],
                "cellsExpectedOverActual": s["estimatedFineCells"] / s["fineCells"],
                "peakExpectedOverActual": s["estimatedPeakMemoryPerRankBytes"] / peak,
                "shares": s.get("estimateShares"),
                "bytesPerFineCellAboveBase": s.get("bytesPerFineCellAboveBase"),
                "refinementLevels": s["refinementLevels"],
                "seconds": seconds}
    finally:
        c.cleanup()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", help="the cases whose name contains this")
    ap.add_argument("--output", default=os.path.join(HERE, "results", "estimates"))
    args = ap.parse_args()
    cases = [c for c in CASES if not args.only or args.only in c[0]]
    rows = []
    for case in cases:
        r = measure(*case)
        rows.append(r)
        if "error" in r:
            print("%-48s FAILED: %s" % (r["case"], r["error"][-300:]), flush=True)
        else:
            print("%-48s fine cells %9d expected %9.0f (%.2f), peak %4.0f MiB expected %4.0f (%.2f)"
                  % (r["case"], r["fineCells"], r["expectedFineCells"], r["cellsExpectedOverActual"],
                     r["peakBytes"] / 2**20, r["expectedPeakBytes"] / 2**20,
                     r["peakExpectedOverActual"]), flush=True)
    if args.only:
        return
    with open(args.output + ".json", "w") as f:
        json.dump(rows, f, indent=1)
    ok = [r for r in rows if "error" not in r]
    within = sum(0.67 <= r["cellsExpectedOverActual"] <= 1.5 and 0.67 <= r["peakExpectedOverActual"] <= 1.5
                 for r in ok)
    with open(args.output + ".md", "w") as f:
        f.write("# The estimate after stage 1 against the run\n\n"
                "Written by `bench/run --estimates` on %s (%s). *expected/actual*: the\n"
                "estimate over the measured value; the goal is 0.67-1.5 (high rather\n"
                "than low). %d of %d cases within it for both.\n\n"
                % (time.strftime("%Y-%m-%d"), os.uname().nodename, within, len(ok)))
        f.write("| case | ranks | coarse cells | fine cells | expected | expected/actual |"
                " peak MiB | expected MiB | expected/actual |\n"
                "|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            if "error" in r:
                f.write("| %s | failed | | | | | | | |\n" % r["case"])
                continue
            f.write("| %s | %d | %d | %d | %.0f | %.2f | %.0f | %.0f | %.2f |\n"
                    % (r["case"], r["ranks"], r["coarseCells"], r["fineCells"], r["expectedFineCells"],
                       r["cellsExpectedOverActual"], r["peakBytes"] / 2**20,
                       r["expectedPeakBytes"] / 2**20, r["peakExpectedOverActual"]))


if __name__ == "__main__":
    main()
