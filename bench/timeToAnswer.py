#!/usr/bin/env python3
"""Time to a right answer: how long each mesher takes to the smallest mesh whose drag is right.

bench/run --answer (bench/README.md, "Time to a right answer") meshes the
sphere of tutorials/sphereDrag (Re = 100) along five routes, each from
coarse to fine:

- pmshFoam with volumeMesher hxt (mpirun -np 2 pmshFoam -parallel),
- pmshFoam with volumeMesher netgen (the same),
- both again with the tutorial's 3 prism layers on the ball,
- snappyHexMesh: blockMesh, decomposePar and snappyHexMesh on 2 ranks
  (bench/cases/sphereDragSnappy at refinement levels 3, 4, 5);

solves each mesh with the tutorial's own schemes (simpleFoam -parallel,
stopped by the tutorial's convergence condition) and stops a route at its
first mesh whose Cd is within 1.5 % of 1.087. The table gives, per route,
that mesh's cells and its meshing wall time: the time from the geometry to
a case ready for simpleFoam -parallel. Every route is measured in the same
run, so the times compare. The meshes and solutions are those of the drag
study (bench/dragStudy.py: the same dictionaries, builders and answers).

Results: bench/results/time-to-answer.md and .json (--out DIR elsewhere).
"""

import argparse
import os
import sys

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, BENCH_DIR)
import dragStudy as ds  # noqa: E402
import pmshBench as pb  # noqa: E402

TOLERANCE = 0.015
SHIPPED_SCHEMES = "leastSquaresLimitedConvection"
PMSH_FACTORS = (2.0, 1.41, 1.0, 0.71, 0.5)
SNAPPY_LEVELS = (3, 4, 5)
# tutorials/sphereDrag's prism layers on the ball
TUTORIAL_LAYERS = "layers 3; firstLayerThickness 0.004; expansionRatio 1.2; "
TUTORIAL_LAYERS_NAME = "3 layers"


def routes(study):
    """Each route's meshes, coarse to fine"""
    out = []
    for mesher in ("hxt", "netgen"):
        out.append(("pmshFoam %s" % mesher,
                    [study.pmsh_mesh("%s-%g" % (mesher, f), "pmshFoam %s" % mesher, mesher, f)
                     for f in PMSH_FACTORS]))
    for mesher in ("hxt", "netgen"):
        family = "pmshFoam %s, %s" % (mesher, TUTORIAL_LAYERS_NAME)
        out.append((family,
                    [study.pmsh_mesh("%s-%g-layers3" % (mesher, f), family, mesher, f,
                                     layers=TUTORIAL_LAYERS)
                     for f in PMSH_FACTORS]))
    out.append(("snappyHexMesh", [
        {"name": "snappy-L%d" % level, "family": "snappyHexMesh", "builder": "snappy",
         "parallel": True, "entries": {"ballLevel": level, "wakeLevel": level - 2,
                                       "nLayers": 0}}
        for level in SNAPPY_LEVELS]))
    return out


def run_route(args, study, res, meshes):
    """Mesh and solve until the answer is within TOLERANCE; the rows tried"""
    tried = []
    for m in meshes:
        case = ds.build_mesh(args, study, m, res)
        mesh = res["meshes"][m["name"]]
        row = {"mesh": m["name"], "cells": mesh.get("cells"), "meshTime": mesh["meshTime"],
               "meshOK": mesh.get("meshOK"), "error": mesh.get("error")}
        if case:
            s = ds.solve(args, study, res, m["name"], case, SHIPPED_SCHEMES,
                         ds.SCHEMES[SHIPPED_SCHEMES][1])
            row.update({"solved": s.get("ok") and not s.get("diverged"),
                        "settled": s.get("settled"), "Cd": s.get("Cd"),
                        "CdPressure": s.get("CdPressure"), "CdViscous": s.get("CdViscous"),
                        "solveTime": s.get("solveTime"), "iterations": s.get("iterations")})
        tried.append(row)
        ds.save_json(res, os.path.join(args.out, "time-to-answer.json"))
        if row.get("solved") and abs(ds.error_of(study, row["Cd"])) <= TOLERANCE:
            row["answer"] = True
            break
    return tried


def cd_text(study, row):
    if row.get("Cd") is None:
        return "failed: %s" % (row.get("error") or "no answer")
    if not row.get("solved"):
        return "diverged (%s)" % ds.fmt(row["Cd"], 3)
    return "%.4f (%+.1f %%)%s" % (row["Cd"], 100*ds.error_of(study, row["Cd"]),
                                 "" if row.get("settled") else ", not settled")


def write_report(study, res, out):
    answers = dict((name, next((r for r in rows if r.get("answer")), None))
                   for name, rows in res["routes"].items())
    snappy = answers.get("snappyHexMesh")
    lines = ["# Time to a right answer: sphereDrag, Cd within %.1f %% of %.3f" % (
                 100*TOLERANCE, study.reference), "",
             "Made by `bench/run --answer` (bench/timeToAnswer.py) in one run on %d ranks;"
             " raw results in [time-to-answer.json](time-to-answer.json). Each route meshes"
             " from coarse to fine and stops at the first mesh whose Cd, solved by simpleFoam"
             " with the tutorial's own schemes, is within %.1f %%. Meshing time is wall time"
             " from the geometry to a case ready for `simpleFoam -parallel` (snappyHexMesh:"
             " blockMesh + decomposePar + snappyHexMesh on %d ranks)." % (
                 res.get("np", 2), 100*TOLERANCE, res.get("np", 2)), "",
             "## The answer per route", ""]
    rows = []
    for name, row in answers.items():
        if row is None:
            rows.append([name, "none within %.1f %%" % (100*TOLERANCE), "", "", "", ""])
            continue
        ratio = ("%.2f" % (row["meshTime"]/snappy["meshTime"])) if snappy else "-"
        rows.append([name, row["mesh"], "%d" % row["cells"], cd_text(study, row),
                     "%.1f" % row["meshTime"], ratio])
    lines += [pb.md_table(["route", "mesh", "cells", "Cd", "meshing [s]",
                           "meshing / snappyHexMesh's"], rows), ""]
    lines += ["## Every mesh tried", ""]
    rows = []
    for name, tried in res["routes"].items():
        for r in tried:
            rows.append([name, r["mesh"], "%d" % r["cells"] if r.get("cells") else "-",
                         cd_text(study, r),
                         "p %s, v %s" % (ds.fmt(r.get("CdPressure")), ds.fmt(r.get("CdViscous"))),
                         "%.1f" % r["meshTime"],
                         ds.fmt(r.get("solveTime"), 1), str(r.get("iterations", "-"))])
    lines += [pb.md_table(["route", "mesh", "cells", "Cd", "parts", "meshing [s]",
                           "solving [s]", "iterations"], rows), ""]
    lines += res.get("findings", [])
    lines += ["", "Machine: %s" % res.get("machine", "?"), ""]
    path = os.path.join(out, "time-to-answer.md")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    pb.log("Written: %s" % path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--answer", action="store_true", help="(the mode bench/run passes)")
    parser.add_argument("--work", default=os.path.join(os.environ.get("TMPDIR", "/tmp"),
                                                       "pmshFoam-answer"))
    parser.add_argument("--out", default=os.path.join(BENCH_DIR, "results"))
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--routes", default="",
                        help="comma-separated routes to run (default: all)")
    parser.add_argument("--rewrite", action="store_true", help="only rewrite the report")
    parser.add_argument("--no-build", action="store_true")
    parser.add_argument("--pmshFoam", default=None)
    args = parser.parse_args()
    args.redo, args.keep, args.gradients = set(), False, False
    os.makedirs(os.path.join(args.work, "sphere"), exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    study = next(s for s in ds.STUDIES if s.name == "sphere")
    path = os.path.join(args.out, "time-to-answer.json")

    if args.rewrite:
        res = ds.load_json(path)
    else:
        # One run: nothing is taken from an earlier one
        res = {"meshes": {}, "solutions": {}, "routes": {}, "np": args.np,
               "findings": ds.load_json(path).get("findings", []),
               "machine": ds.machine_text()}
        wanted = set(filter(None, args.routes.split(",")))
        for name, meshes in routes(study):
            if not wanted or name in wanted:
                pb.log("Route: %s" % name)
                res["routes"][name] = run_route(args, study, res, meshes)
    write_report(study, res, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
