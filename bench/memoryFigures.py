#!/usr/bin/env python3
"""Measure the figures of pmshFoam's memory estimate (src/forecast/memoryEstimate.C).

For each tutorial geometry and a set of (volumeMesher, coarseMesher, r, ranks),
mesh a copy of the tutorial and read from its log and summary.json:

- fine cells / weightedFineCells (8^r times the sum of the coarse mesh's
  fineCellWeights: summary.json's "estimatedFineCells" divided by the
  estimate's own factor, "estimatedCellsPerWeighted");
- the largest rank's peak memory above the stage-1 base, per fine cell of
  that rank ("bytesPerFineCellAboveBase");
- the estimate's error (measured / expected) for cells and peak memory.

Usage (from the project root, with tools/environment sourced):
    bench/run --memory-figures [--work DIR] [--quick]
It prints a table to paste into memoryEstimate.C and writes
bench/results/memory-figures.md. Nothing here is part of the tests.
"""

import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pmshBench as pb  # noqa: E402

# (volumeMesher, coarseMesher, r, ranks)
RUNS = [
    ("netgen", "netgen", 2, 1),
    ("netgen", "netgen", 3, 2),
    ("netgen", "hxt", 2, 2),
    ("hxt", "netgen", 3, 1),
    ("hxt", "netgen", 4, 2),
    ("hxt", "hxt", 3, 2),
    ("hxt", "hxt", 4, 1),
]
QUICK_RUNS = [("netgen", "netgen", 2, 1), ("hxt", "netgen", 3, 2), ("hxt", "hxt", 3, 2)]

SIZES = {"sphere": 0.3, "shaft": 0.45, "sphereSTL": 0.3}


def run_one(args, geom, volume, coarse, levels, ranks):
    name = "%s-%s-%s-r%d-np%d" % (geom["name"], volume, coarse, levels, ranks)
    case = pb.make_case(args.work, name, geom["tutorial"], SIZES[geom["name"]],
                        levels, volume)
    pb.set_entry(os.path.join(case, "system", "pmshDict"), "coarseMesher", coarse)
    run = pb.Run(pb.pmsh_command(args.pmshFoam, ranks, case), case, "log.pmshFoam")
    s = pb.summary(case)
    if not run.ok or s is None:
        pb.log("    FAILED %s: %s" % (name, pb.first_error(run.text()) or run.tail()))
        return None
    weighted = s["estimatedFineCells"]/s["estimatedCellsPerWeighted"]
    cells = s["fineCellsPerRank"]
    row = {
        "geometry": geom["name"], "volumeMesher": volume, "coarseMesher": coarse,
        "r": levels, "ranks": ranks, "coarseCells": s["coarseCells"],
        "fineCells": s["fineCells"], "cellsPerWeighted": s["fineCells"]/weighted,
        "largestRankShare": max(cells)/(s["fineCells"]/float(ranks)),
        "bytesAboveBase": s["bytesPerFineCellAboveBase"],
        "baseMiB": s["stages"]["coarse"]["peakMemoryBytes"]/1048576.0,
        "peakMiB": max(s["peakMemoryPerRankBytes"])/1048576.0,
        "cellsMeasuredOverExpected": s["fineCells"]/s["estimatedFineCells"],
        "peakMeasuredOverExpected":
            max(s["peakMemoryPerRankBytes"])/s["estimatedPeakMemoryPerRankBytes"],
    }
    pb.log("    %-9s %-6s coarse %-6s r=%d P=%d: %8d cells, %.3f per weighted, "
           "%.0f B/cell above base, peak %.0f MiB (x%.2f of expected)"
           % (row["geometry"], volume, coarse, levels, ranks, row["fineCells"],
              row["cellsPerWeighted"], row["bytesAboveBase"], row["peakMiB"],
              row["peakMeasuredOverExpected"]))
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--work", help="scratch directory (default: a new temporary one)")
    parser.add_argument("--quick", action="store_true", help="three runs per geometry")
    parser.add_argument("--pmshFoam", default="pmshFoam")
    parser.add_argument("--out", default=os.path.join(pb.BENCH_DIR, "results",
                                                      "memory-figures.md"))
    args = parser.parse_args()
    args.work = args.work or tempfile.mkdtemp(prefix="pmshFoam-memory-")
    rows = []
    for geom in pb.GEOMETRIES:
        for volume, coarse, levels, ranks in (QUICK_RUNS if args.quick else RUNS):
            row = run_one(args, geom, volume, coarse, levels, ranks)
            if row:
                rows.append(row)

    lines = ["# Memory estimate figures", "",
             "Measured by `bench/run --memory-figures`; the estimate's figures in "
             "`src/forecast/memoryEstimate.C` come from this table.", "",
             "| geometry | volumeMesher | coarseMesher | r | ranks | coarse cells | fine cells "
             "| fine / weighted | largest rank / mean | B/cell above base | base MiB "
             "| peak MiB | cells measured/expected | peak measured/expected |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %s | %s | %d | %d | %d | %d | %.3f | %.3f | %.0f | %.0f | %.0f "
                     "| %.2f | %.2f |"
                     % (r["geometry"], r["volumeMesher"], r["coarseMesher"], r["r"],
                        r["ranks"], r["coarseCells"], r["fineCells"], r["cellsPerWeighted"],
                        r["largestRankShare"], r["bytesAboveBase"], r["baseMiB"],
                        r["peakMiB"], r["cellsMeasuredOverExpected"],
                        r["peakMeasuredOverExpected"]))
    lines.append("")
    for volume in sorted(set(r["volumeMesher"] for r in rows)):
        sel = [r for r in rows if r["volumeMesher"] == volume]
        f = [r["cellsPerWeighted"] for r in sel]
        b = [r["bytesAboveBase"] for r in sel if r["fineCells"] >= 100000]
        lines.append("- %s: fine / weighted %.3f .. %.3f (mean %.3f); B/cell above base "
                     "(runs of 100k cells or more) %s"
                     % (volume, min(f), max(f), sum(f)/len(f),
                        "%.0f .. %.0f (mean %.0f)" % (min(b), max(b), sum(b)/len(b))
                        if b else "-"))
    text = "\n".join(lines) + "\n"
    os.makedirs(os.path.dirname(args.out), exist_ok=True)
    with open(args.out, "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
