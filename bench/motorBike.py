#!/usr/bin/env python3
"""OpenFOAM's motorBike, meshed by OpenFOAM's own tutorial and by pmshFoam's, side by side.

bench/run --motorbike (bench/README.md, "motorBike") builds its cases in
its work directory, one after the other on the same machine:

- snappyHexMesh: OpenFOAM's tutorial incompressible/simpleFoam/motorBike
  of the OpenFOAM the build uses, as its Allrun runs it
  (surfaceFeatureExtract, blockMesh, decomposePar, snappyHexMesh, its 0.orig
  in each processor directory, potentialFoam -writephi, simpleFoam), on 2
  ranks and on the 6 of its Allrun (decomposeParDict.6; on 2 cores
  oversubscribed, so its times do not compare), and on 2 ranks again
  solved as pmshFoam's is, from the uniform fields without potentialFoam;
- pmshFoam: tutorials/motorBike as its Allrun runs it (pmshFoam -parallel,
  simpleFoam), on 2 ranks; and the same with the refinement box at the
  tutorial's level 4 (fine cells of 0.0625 instead of 0.125), at the
  resolution of snappyHexMesh's mesh there, with hxt's default
  optimisationSteps 1 and with 2 (Netgen's smoothing moves HXT's interior
  points at both since 2026-12-02, netgenSmoothingFromSteps; the level-4
  row at one step in results/motorbike.md is from before, HXT's points).

All solve with the same schemes, solvers, models and 500 iterations (the
tutorial's; pmshFoam's case copies them). For each: cells, meshing wall
time (from the surface to a case ready for simpleFoam -parallel), layer
coverage on the bike (snappyHexMesh: its mean layers per face over the
bike's faces, the tutorial asks one; pmshFoam: the share of the bike's
faces with their layer), checkMesh's worst faces, simpleFoam's time, and
the last Cd and Cl.

Results: bench/results/motorbike.md and .json (--out DIR elsewhere).
"""

import argparse
import json
import os
import re
import shutil
import sys
import time

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
PROJECT_DIR = os.path.dirname(BENCH_DIR)
sys.path.insert(0, BENCH_DIR)
sys.path.insert(0, os.path.join(PROJECT_DIR, "tools"))
import dragStudy as ds  # noqa: E402
import foamCase as fc  # noqa: E402

RANKS = 2
# OpenFOAM's Allrun decomposes the motorBike into 6 (decomposeParDict.6)
TUTORIAL_RANKS = 6
UNIFORM = "snappyHexMesh, no potentialFoam"
LEVEL4 = "pmshFoam, refinementBox at level 4"
LEVEL4_SMOOTHED = "pmshFoam, refinementBox at level 4, optimisationSteps 2"


def openfoam_tutorial():
    return os.path.join(fc.environment()["WM_PROJECT_DIR"], "tutorials", "incompressible",
                        "simpleFoam", "motorBike")


def bike_obj():
    return os.path.join(fc.environment()["WM_PROJECT_DIR"], "tutorials", "resources",
                        "geometry", "motorBike.obj.gz")


def snappy_case(case, ranks):
    """OpenFOAM's motorBike tutorial meshed as its Allrun does, on `ranks`
    ranks (its own decomposeParDict.6 for 6, hierarchical along x
    otherwise): (ok, meshing wall seconds, last log)"""
    shutil.copytree(openfoam_tutorial(), case)
    os.makedirs(os.path.join(case, "constant", "triSurface"), exist_ok=True)
    shutil.copy(bike_obj(), os.path.join(case, "constant", "triSurface"))
    decompose_dict = os.path.join(case, "system", "decomposeParDict")
    if ranks == TUTORIAL_RANKS:
        shutil.copy(decompose_dict + ".6", decompose_dict)
    else:
        with open(decompose_dict, "w") as f:
            f.write("FoamFile { version 2.0; format ascii; class dictionary;"
                    " object decomposeParDict; }\nnumberOfSubdomains %d;\n"
                    "method hierarchical;\nhierarchicalCoeffs { n (%d 1 1); order xyz; }\n"
                    % (ranks, ranks))
    done = ds.run_in_turn((
        lambda: ds.run(["surfaceFeatureExtract"], case, "log.surfaceFeatureExtract"),
        lambda: ds.run(["blockMesh"], case, "log.blockMesh"),
        lambda: ds.run(["decomposePar"], case, "log.decomposePar"),
        lambda: ds.run(["snappyHexMesh", "-overwrite"], case, "log.snappyHexMesh",
                       np=ranks)))
    if done[0]:
        ds.fields_into_processors(case, "0.orig")
    return done


def snappy_solve(case, ranks):
    return ds.run_in_turn((
        lambda: ds.run(["potentialFoam", "-writephi"], case, "log.potentialFoam", np=ranks),
        lambda: ds.run(["simpleFoam"], case, "log.simpleFoam", np=ranks)))


def snappy_solve_from_uniform(case, ranks):
    """simpleFoam from 0.orig's uniform fields, as tutorials/motorBike
    starts: without potentialFoam"""
    return ds.run(["simpleFoam"], case, "log.simpleFoam", np=ranks)


def snappy_coverage(case):
    """Mean layers per face over the bike's patches, from snappyHexMesh's
    last layer table"""
    with open(os.path.join(case, "log.snappyHexMesh"), errors="replace") as f:
        text = f.read()
    table = text[text.rfind("overall thickness"):]
    rows = re.findall(r"^(motorBike\S*)\s+(\d+)\s+([0-9.eE+-]+)\s", table, re.M)
    faces = sum(int(n) for _, n, _ in rows)
    return sum(int(n) * float(layers) for _, n, layers in rows) / faces if faces else None


def copy_pmsh_tutorial(case):
    """tutorials/motorBike with the bike's OBJ, as its Allrun copies it"""
    shutil.copytree(os.path.join(PROJECT_DIR, "tutorials", "motorBike"), case)
    os.makedirs(os.path.join(case, "constant", "geometry"), exist_ok=True)
    shutil.copy(bike_obj(), os.path.join(case, "constant", "geometry"))


def pmsh_case(case, ranks):
    copy_pmsh_tutorial(case)
    return ds.run(["pmshFoam"], case, "log.pmshFoam", np=ranks)


def pmsh_level4_case(case, ranks, optimisation_steps=None):
    """tutorials/motorBike with its refinementBox's fine cells at 0.0625, the
    size of the tutorial's level 4 (its blockMesh cells of 1 halved 4 times),
    and optimisationSteps if given (hxt's default is 1)"""
    copy_pmsh_tutorial(case)
    dict_file = os.path.join(case, "system", "pmshDict")
    fc.substitute(dict_file, *fc.MOTORBIKE_LEVEL4_BOX)
    if optimisation_steps is not None:
        fc.set_entry(dict_file, "optimisationSteps", optimisation_steps)
    return ds.run(["pmshFoam"], case, "log.pmshFoam", np=ranks)


def pmsh_solve(case, ranks):
    return ds.run(["simpleFoam"], case, "log.simpleFoam", np=ranks)


def pmsh_coverage(case):
    """The share of the bike's wall faces with all their layers (its parts'
    patches, "name%n" as the OBJ's groups; not the floor's)"""
    layers = fc.summary(case).get("layers") or {}
    bike = [p for name, p in layers.items() if "%" in name]
    faces = sum(p["faces"] for p in bike)
    return sum(p["faces"] * p["coverage"] for p in bike) / faces if faces else None


def measure(name, ranks, work, build, solve, coverage):
    case = os.path.join(work, re.sub(r"\W", "", name) + str(ranks))
    shutil.rmtree(case, ignore_errors=True)
    print("%s: meshing" % name, flush=True)
    ok, mesh_wall, text = build(case, ranks)
    row = {"mesher": name, "ranks": ranks, "meshed": ok,
           "meshingSeconds": round(mesh_wall, 1)}
    if not ok:
        row["error"] = text[-2000:]
        return row
    checks = fc.check_mesh(case, ranks)
    row.update({k: checks.get(k) for k in ("cells", "meshOK", "maxNonOrtho", "maxSkewness")})
    row["layerCoverage"] = coverage(case)
    print("%s: %s cells in %.0f s; solving" % (name, row["cells"], mesh_wall), flush=True)
    ok, solve_wall, text = solve(case, ranks)
    row.update({"solved": ok, "solverSeconds": round(solve_wall, 1)})
    _, last = fc.last_force_coefficients(case)
    row["Cd"], row["Cl"] = last.get("Cd"), last.get("Cl")
    if not ok:
        row["error"] = text[-2000:]
    print("%s: Cd %s, Cl %s in %.0f s" % (name, row["Cd"], row["Cl"], solve_wall), flush=True)
    return row


def write(rows, out):
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "motorbike.json"), "w") as f:
        json.dump({"date": time.strftime("%Y-%m-%d"), "rows": rows}, f, indent=1)

    def fmt(v, spec):
        return "-" if v is None else spec % v

    lines = [
        "# OpenFOAM's motorBike: its tutorial's snappyHexMesh mesh and pmshFoam's",
        "",
        "Made by `bench/run --motorbike` (bench/motorBike.py) on %s, one case after the"
        " other on this machine (2 cores: 6 ranks are oversubscribed, their times do not"
        " compare). Each solved by simpleFoam with the tutorial's"
        " schemes, solvers, kOmegaSST and its 500 iterations, started as its Allrun does"
        " from potentialFoam, or from the uniform fields (\"no potentialFoam\", and"
        " pmshFoam's, as its Allrun does); Cd and Cl are the last"
        " iteration's (Aref 0.75, lRef 1.42, as the tutorial). Meshing: from the surface"
        " to a case ready for `simpleFoam -parallel`. Layers: the tutorial asks one on"
        " the bike; coverage is snappyHexMesh's mean layers per bike face and pmshFoam's"
        " share of bike faces with their layer." % time.strftime("%Y-%m-%d"),
        "",
        "| mesher | ranks | cells | meshing [s] | layer coverage | max non-orth | max skewness"
        " | checkMesh | simpleFoam [s] | Cd | Cl |",
        "|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|",
    ]
    for r in rows:
        lines.append("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            r["mesher"], r["ranks"], "{:,}".format(r["cells"]) if r.get("cells") else "-",
            fmt(r.get("meshingSeconds"), "%.0f"),
            fmt(r.get("layerCoverage") and 100 * r["layerCoverage"], "%.1f %%"),
            fmt(r.get("maxNonOrtho"), "%.1f"), fmt(r.get("maxSkewness"), "%.2f"),
            "Mesh OK" if r.get("meshOK") else ("failed" if r.get("meshed") else "-"),
            fmt(r.get("solverSeconds"), "%.0f"),
            fmt(r.get("Cd"), "%.3f") if r.get("solved") else "diverged",
            fmt(r.get("Cl"), "%.3f") if r.get("solved") else "-"))
    md = os.path.join(out, "motorbike.md")
    findings = written_sections(md)
    with open(md, "w") as f:
        f.write("\n".join(lines) + "\n" + findings)


def written_sections(md):
    """The sections written by hand below the table of an earlier
    motorbike.md (its findings), kept when the table is made again"""
    try:
        with open(md) as f:
            text = f.read()
    except FileNotFoundError:
        return ""
    start = text.find("\n## ")
    return text[start:] if start >= 0 else ""


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(BENCH_DIR, "results"))
    parser.add_argument("--work", default="/tmp/pmsh-bench-motorbike")
    parser.add_argument("--snappy-ranks", type=int, nargs="*", default=[RANKS, TUTORIAL_RANKS],
                        help="snappyHexMesh's runs (default: 2, and 6 as the tutorial)")
    parser.add_argument("--uniform-ranks", type=int, nargs="*", default=[RANKS],
                        help="snappyHexMesh's runs solved from the uniform fields, without"
                        " potentialFoam, as pmshFoam's (default: 2)")
    parser.add_argument("--pmsh", nargs="*", choices=["tutorial", "level4", "level4smoothed"],
                        default=["tutorial", "level4", "level4smoothed"],
                        help="pmshFoam's runs: its tutorial as shipped, with the"
                        " refinement box at the tutorial's level 4, and that with"
                        " optimisationSteps 2 (default: all three;"
                        " none: snappyHexMesh's only)")
    parser.add_argument("--merge", action="store_true",
                        help="keep the other rows of an earlier motorbike.json in --out")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = [measure("snappyHexMesh", n, args.work, snappy_case, snappy_solve, snappy_coverage)
            for n in args.snappy_ranks]
    rows += [measure(UNIFORM, n, args.work, snappy_case, snappy_solve_from_uniform,
                     snappy_coverage)
             for n in args.uniform_ranks]
    if "tutorial" in args.pmsh:
        rows.append(measure("pmshFoam", RANKS, args.work, pmsh_case, pmsh_solve,
                            pmsh_coverage))
    if "level4" in args.pmsh:
        rows.append(measure(LEVEL4, RANKS, args.work, pmsh_level4_case, pmsh_solve,
                            pmsh_coverage))
    if "level4smoothed" in args.pmsh:
        rows.append(measure(LEVEL4_SMOOTHED, RANKS, args.work,
                            lambda case, ranks: pmsh_level4_case(case, ranks, 2),
                            pmsh_solve, pmsh_coverage))
    if args.merge and os.path.exists(os.path.join(args.out, "motorbike.json")):
        with open(os.path.join(args.out, "motorbike.json")) as f:
            earlier = json.load(f)["rows"]
        for r in earlier:
            r.setdefault("ranks", RANKS)
        new = {(r["mesher"], r["ranks"]) for r in rows}
        rows = [r for r in earlier if (r["mesher"], r.get("ranks", RANKS)) not in new] + rows
        order = ["snappyHexMesh", UNIFORM, "pmshFoam", LEVEL4, LEVEL4_SMOOTHED]
        rows.sort(key=lambda r: (order.index(r["mesher"]), r.get("ranks", RANKS)))
    write(rows, args.out)
    return 0 if all(r.get("solved") for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
