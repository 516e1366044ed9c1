#!/usr/bin/env python3
"""Prism-layer coverage at P = 1, 2 and 4: bench/run --coverage

Issue #36 item 3's three cases (sphereDrag with 5 layers on the ball, the
pipe as shipped with 12, OpenFOAM's bullet in a box with 5), each meshed
at 1, 2 and 4 ranks in binary: the share of wall faces that carry all
their layers, the stacks' mean thickness, the points thinned (and of
those, by a partition interface), checkMesh's worst faces, and whether
every prism (its six points' bits) is the one of the serial mesh.

Results: bench/results/layer-coverage.md and .json. Nothing here is part
of the tests.
"""

import argparse
import json
import os
import re
import shutil
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tools"))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "tutorials"))
import foamCase as fc  # noqa: E402
import pmshBench as pb  # noqa: E402
from benchReport import md_table  # noqa: E402
from testLayers import set_patches, prism_cells  # noqa: E402

BULLET_PATCHES = {"inlet": "type patch;", "outlet": "type patch;", "sides": "type patch;",
                  "body": "type wall; maxCellSize 0.002; layers 5;"
                          " firstLayerThickness 0.0001; expansionRatio 1.2;"}


def sphere_drag():
    c = fc.TutorialCase("sphereDrag")
    set_patches(c, {"\"(inlet|outlet)\"": "type patch;", "sides": "type symmetry;",
                    "ball": "type wall; maxCellSize 0.1; layers 5;"
                            " firstLayerThickness 0.004; expansionRatio 1.2;"})
    return c


def bullet():
    """The layers tests' bullet: bullet.stl in a box, no 0/ fields"""
    c = fc.TutorialCase("sphereSTL", maxCellSize=0.02, refinementLevels=1,
                        volumeMesher="hxt")
    fc.write_bullet_in_box(os.path.join(c.dir, "constant", "geometry", "bulletInBox.stl"))
    c.set_entry("system/pmshDict", "geometry", '"constant/geometry/bulletInBox.stl"')
    set_patches(c, BULLET_PATCHES)
    shutil.rmtree(os.path.join(c.dir, "0"), ignore_errors=True)
    return c


CASES = (("sphereDrag, 5 layers (hxt)", sphere_drag),
         ("pipe, 8 layers (netgen, as shipped)", lambda: fc.TutorialCase("pipe")),
         ("bullet in a box, 5 layers (hxt)", bullet))


def run_one(make, np):
    c = make()
    c.write_format("binary")
    _, log = c.run("pmshFoam", np=np)
    s = c.summary()
    thinned = re.search(r"for valid prisms and tops (\d+) \(partition interfaces (\d+)\)", log)
    check = fc.read_check_mesh(c.check_mesh(np))
    row = {"ranks": np, "cells": s["fineCells"], "prisms": s["prisms"],
           "coverage": min(p["coverage"] for p in s["layers"].values()),
           "meanThickness": min(p["thickness"][1] for p in s["layers"].values()),
           "thinned": int(thinned.group(1)), "thinnedAtInterfaces": int(thinned.group(2)),
           "layerSeconds": s["stages"]["layers"]["seconds"],
           "meshOK": check["meshOK"], "maxNonOrtho": check["maxNonOrtho"],
           "maxSkewness": check["maxSkewness"]}
    return row, prism_cells(c, np), c


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--coverage", action="store_true")
    parser.add_argument("--out", default=os.path.join(HERE, "results"))
    parser.add_argument("--ranks", default="1,2,4")
    parser.add_argument("--keep", action="store_true", help="keep the cases")
    parser.add_argument("--note", default="", help="a note in the machine table")
    parser.add_argument("--pmshFoam", default=os.environ.get("PMSH_BINARY")
                        or shutil.which("pmshFoam") or "pmshFoam")
    args = parser.parse_args()
    os.environ["PMSH_BINARY"] = args.pmshFoam
    ranks = [int(r) for r in args.ranks.split(",")]
    results = []
    for name, make in CASES:
        serial = None
        for np in ranks:
            row, prisms, c = run_one(make, np)
            if serial is None:
                serial = prisms
            row["prismsDifferingFromFirst"] = len(prisms ^ serial)
            row["case"] = name
            results.append(row)
            pb.log("%s, %d rank(s): coverage %.4f, %d thinned (%d at interfaces), %d prisms"
                   " unlike the first" % (name, np, row["coverage"], row["thinned"],
                                          row["thinnedAtInterfaces"],
                                          row["prismsDifferingFromFirst"]))
            if not args.keep:
                c.cleanup()
    write_results(args, results, ranks)


def write_results(args, results, ranks):
    os.makedirs(args.out, exist_ok=True)
    data = {"machine": pb.machine_description(args), "rows": results}
    with open(os.path.join(args.out, "layer-coverage.json"), "w") as f:
        json.dump(data, f, indent=1)
    rows = [[r["case"], str(r["ranks"]), "%.2f %%" % (100*r["coverage"]), "%.3g" % r["meanThickness"],
             "%d (%d)" % (r["thinned"], r["thinnedAtInterfaces"]), "%.1f" % r["maxNonOrtho"],
             "%.2f" % r["maxSkewness"], "Mesh OK" if r["meshOK"] else "FAILED",
             "-" if r["ranks"] == ranks[0] else
             ("same" if r["prismsDifferingFromFirst"] == 0 else
              "%d of %d differ" % (r["prismsDifferingFromFirst"], r["prisms"])),
             "%.1f" % r["layerSeconds"]] for r in results]
    text = "\n".join([
        "# Prism-layer coverage at P = %s" % ", ".join(map(str, ranks)),
        "",
        "Made by `bench/run --coverage` (bench/layerCoverage.py). Coverage: wall"
        " faces with all their layers (summary.json); thinned: points whose"
        " stacks were thinned for valid prisms and tops, in brackets those by a"
        " partition interface; prisms: every prism by its six points' bits"
        " against the first number of ranks.",
        "",
        md_table(["case", "ranks", "coverage", "mean stack", "thinned (interfaces)",
                  "max non-orth", "max skewness", "checkMesh", "prisms as at %d rank(s)"
                  % ranks[0], "stage 3b [s]"], rows),
        "",
    ])
    with open(os.path.join(args.out, "layer-coverage.md"), "w") as f:
        f.write(text)
    pb.log("Written: %s" % os.path.join(args.out, "layer-coverage.md"))


if __name__ == "__main__":
    main()
