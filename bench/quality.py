#!/usr/bin/env python3
"""Mesh quality and speed of the volume meshers side by side, judged by
OpenFOAM's checkMesh: every tutorial at r = 2 and 3 with netgen, hxt
(optimisationSteps 0: HXT alone) and hxt + quality pass (hxt's default
optimisationSteps: HXT's optimiser and pmshFoam's pass), serial and on 2 and 4 ranks (r = 2;
r = 3: serial and 2 ranks), all in one run. Writes bench/results/quality.md,
quality.json and one histogram of face non-orthogonality per tutorial
(serial, r = 2).

Usage: bench/run --quality [--work DIR] [--tutorials sphere,shaft] [--levels 2]
                     [--variants "hxt + pass"]
"""

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from foamCase import PolyMeshFiles  # noqa: E402
import foamCase as fc  # noqa: E402

VARIANTS = [
    ("netgen", {"volumeMesher": "netgen", "optimisationSteps": 3}),
    ("hxt", {"volumeMesher": "hxt", "optimisationSteps": 0}),
    ("hxt + pass", {"volumeMesher": "hxt"}),
]
RANKS = {2: [1, 2, 4], 3: [1, 2]}


def make_case(work, tutorial, r, variant, entries, np):
    name = "%s-r%d-%s-np%d" % (tutorial, r, variant.replace(" + ", "-"), np)
    case = fc.copy_tutorial(tutorial, os.path.join(work, name),
                            fc.RUN_LEFTOVERS + ("[1-9]*", ".*"))
    fc.set_entry(os.path.join(case, "system", "pmshDict"), "refinementLevels", r)
    for key, value in entries.items():
        fc.set_entry(os.path.join(case, "system", "pmshDict"), key, value)
    return case


def run(argv, case, log):
    with open(os.path.join(case, log), "w") as out:
        return subprocess.run(argv, stdout=out, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL).returncode


def check_mesh(case, np):
    c = fc.check_mesh(case, np)
    return {
        "cells": c.get("cells", 0),
        "maxNonOrth": c.get("maxNonOrtho", float("nan")),
        "avgNonOrth": c.get("avgNonOrtho", float("nan")),
        "maxSkewness": c.get("maxSkewness", float("nan")),
        "meshOK": c["meshOK"],
    }


def face_non_orthogonality(case):
    """Non-orthogonality (degrees) of every internal face of a serial tet
    mesh, as checkMesh computes it (cell centre = mean of the tet's points)."""
    import numpy as np
    mesh = PolyMeshFiles(os.path.join(case, "constant", "polyMesh"))
    points = np.array(mesh.points())
    faces = np.array(mesh.faces())
    owner = np.array(mesh.labels("owner"))
    neighbour = np.array(mesh.labels("neighbour"))
    n_cells = int(max(owner.max(), neighbour.max())) + 1
    # Each point of a tet lies on three of its four faces
    face_sum = points[faces].sum(axis=1)
    centres = np.zeros((n_cells, 3))
    np.add.at(centres, owner, face_sum)
    np.add.at(centres, neighbour, face_sum[:len(neighbour)])
    centres /= 12.0
    internal = faces[:len(neighbour)]
    a, b, c = points[internal[:, 0]], points[internal[:, 1]], points[internal[:, 2]]
    area = np.cross(b - a, c - a)
    d = centres[neighbour] - centres[owner[:len(neighbour)]]
    cos = (d * area).sum(axis=1) / np.linalg.norm(d, axis=1) / np.linalg.norm(area, axis=1)
    return np.degrees(np.arccos(np.clip(cos, -1, 1)))


def histogram(tutorial, cases, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    bins = list(range(0, 91, 2))
    for label, case in cases:
        angles = face_non_orthogonality(case)
        ax.hist(angles, bins=bins, histtype="step", linewidth=1.5,
                label="%s (max %.1f)" % (label, angles.max()))
    ax.set_yscale("log")
    ax.set_xlabel("face non-orthogonality (degrees)")
    ax.set_ylabel("faces")
    ax.set_title("%s, r = 2, serial" % tutorial)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--work", help="scratch directory (kept)")
    parser.add_argument("--tutorials", default="sphere,shaft,sphereSTL")
    parser.add_argument("--levels", default="2,3")
    parser.add_argument("--variants", default=",".join(v for v, _ in VARIANTS),
                        help="which of: " + ", ".join(v for v, _ in VARIANTS))
    parser.add_argument("--out", default=os.path.join(ROOT, "bench", "results"))
    args = parser.parse_args()
    variants = [v for v in VARIANTS if v[0] in args.variants.split(",")]
    work = args.work or tempfile.mkdtemp(prefix="pmsh-quality-")
    os.makedirs(work, exist_ok=True)
    pmsh = os.environ.get("PMSH_BINARY") or shutil.which("pmshFoam")
    tutorials = args.tutorials.split(",")
    levels = [int(r) for r in args.levels.split(",")]

    results = []
    for tutorial in tutorials:
        for r in levels:
            for np in RANKS[r]:
                for variant, entries in variants:
                    case = make_case(work, tutorial, r, variant, entries, np)
                    start = time.time()
                    code = run(fc.mpi(np, [pmsh, "-case", case]), case, "log.pmshFoam")
                    row = {"tutorial": tutorial, "r": r, "variant": variant, "ranks": np,
                           "case": case, "wall": time.time() - start, "failed": code != 0}
                    if code == 0:
                        summary = fc.summary(case)
                        row.update(check_mesh(case, np))
                        row["fineTime"] = summary["fineTime"]
                        row["volumeTime"] = summary["stages"]["volume"]["seconds"]
                        row["usPerCell"] = 1e6 * summary["fineTime"] / summary["fineCells"]
                        row["logged"] = summary["quality"]
                        wanted = entries["volumeMesher"]
                        row["fellBack"] = sum(b != wanted for b in summary["volumeMesherPerRank"])
                    results.append(row)
                    print("%-9s r=%d np=%d %-10s %s" % (
                        tutorial, r, np, variant,
                        "FAILED" if row["failed"] else
                        "%7d cells %5.1f us/cell  non-orth %5.1f / %4.1f  skew %.2f  %s" % (
                            row["cells"], row["usPerCell"], row["maxNonOrth"],
                            row["avgNonOrth"], row["maxSkewness"],
                            "Mesh OK" if row["meshOK"] else "checkMesh FAILED")), flush=True)

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "quality.json"), "w") as f:
        json.dump([{k: v for k, v in row.items() if k != "case"} for row in results], f, indent=1)

    pngs = []
    if 2 in levels:
        for tutorial in tutorials:
            cases = [(row["variant"], row["case"]) for row in results
                     if row["tutorial"] == tutorial and row["r"] == 2 and row["ranks"] == 1
                     and not row["failed"]]
            png = "quality-nonOrthogonality-%s.png" % tutorial
            histogram(tutorial, cases, os.path.join(args.out, png))
            pngs.append((tutorial, png))

    def find(tutorial, r, np, variant):
        for row in results:
            if (row["tutorial"], row["r"], row["ranks"], row["variant"]) == (tutorial, r, np, variant):
                return row
        return None

    lines = [
        "# Mesh quality and speed: netgen, hxt, hxt + quality pass",
        "",
        "Produced by `bench/run --quality` on %s UTC, on %d cores shared with other work"
        " (times are wall times of one run, all cases run one after the other)."
        % (time.strftime("%Y-%m-%d %H:%M", time.gmtime()), os.cpu_count()),
        "",
        "- netgen: `volumeMesher netgen; optimisationSteps 3;` (Netgen's own optimiser)",
        "- hxt: `volumeMesher hxt; optimisationSteps 0;` (HXT alone)",
        "- hxt + pass: `volumeMesher hxt;` and hxt's default optimisationSteps (HXT's"
        " own optimiser, then pmshFoam's quality pass: src/qualityPass/tetQualityPass.H)",
        "",
        "Quality as OpenFOAM's checkMesh (`-parallel` on 2 and 4 ranks) reports it;"
        " time per cell = fine time (stages 2-6, wall, slowest rank) / fine cells.",
        "How the pass was chosen (cost and gain of each option): [quality-options.md](quality-options.md).",
        "",
        "| tutorial | r | ranks | mesher | cells | us/cell | max non-orth | avg non-orth | max skewness | checkMesh |",
        "|---|---:|---:|---|---:|---:|---:|---:|---:|---|",
    ]
    for row in results:
        if row["failed"]:
            lines.append("| %s | %d | %d | %s | FAILED | | | | | |" % (
                row["tutorial"], row["r"], row["ranks"], row["variant"]))
            continue
        lines.append("| %s | %d | %d | %s | %d | %.1f | %.1f | %.1f | %.2f | %s |" % (
            row["tutorial"], row["r"], row["ranks"],
            row["variant"] + (" (%d ranks fell back to netgen)" % row["fellBack"]
                              if row["fellBack"] else ""),
            row["cells"],
            row["usPerCell"], row["maxNonOrth"], row["avgNonOrth"], row["maxSkewness"],
            "Mesh OK" if row["meshOK"] else "FAILED"))

    lines += [
        "",
        "## hxt + pass against netgen, same case and ranks",
        "",
        "| tutorial | r | ranks | speed (netgen us/cell / hxt + pass us/cell) |"
        " max non-orth netgen / hxt + pass | max skewness netgen / hxt + pass | no worse |",
        "|---|---:|---:|---:|---:|---:|---|",
    ]
    for tutorial in tutorials:
        for r in levels:
            for np in RANKS[r]:
                n = find(tutorial, r, np, "netgen")
                h = find(tutorial, r, np, "hxt + pass")
                if not n or not h or n["failed"] or h["failed"]:
                    continue
                ok = h["maxNonOrth"] <= n["maxNonOrth"] and h["maxSkewness"] <= n["maxSkewness"]
                lines.append("| %s | %d | %d | %.1fx | %.1f / %.1f | %.2f / %.2f | %s |" % (
                    tutorial, r, np, n["usPerCell"] / h["usPerCell"],
                    n["maxNonOrth"], h["maxNonOrth"], n["maxSkewness"], h["maxSkewness"],
                    "yes" if ok else "**no**"))

    lines += [
        "",
        "## What the fixed partition interfaces cost (r = 2)",
        "",
        "Interface points and triangles are a pure function of their barycentric"
        " ids, so no mesher may move them: the cells at the interfaces are"
        " what each side can make of a fixed triangulated surface. Max"
        " non-orthogonality / max skewness:",
        "",
        "| tutorial | mesher | serial | 2 ranks | 4 ranks |",
        "|---|---|---:|---:|---:|",
    ]
    for tutorial in tutorials:
        for variant, _ in VARIANTS:
            cells = []
            for np in RANKS.get(2, []):
                row = find(tutorial, 2, np, variant)
                cells.append("%.1f / %.2f" % (row["maxNonOrth"], row["maxSkewness"])
                             if row and not row["failed"] else "-")
            lines.append("| %s | %s | %s |" % (tutorial, variant, " | ".join(cells)))

    if pngs:
        lines += ["", "## Face non-orthogonality (serial, r = 2)", ""]
        for tutorial, png in pngs:
            lines.append("![%s](%s)" % (tutorial, png))
    with open(os.path.join(args.out, "quality.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if not args.work:
        shutil.rmtree(work, ignore_errors=True)
    return 1 if any(row["failed"] or not row.get("meshOK") for row in results) else 0


if __name__ == "__main__":
    sys.exit(main())
