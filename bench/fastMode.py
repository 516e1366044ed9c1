#!/usr/bin/env python3
"""The price of each optimisationSteps setting: 0 (the fast mode: sliver
removal only), 1 and 3 (the default), on the sphere with hxt at about 1M
cells (maxCellSize 0.1, r = 2, 2 ranks, binary: the before/after case of bench/beforeAfter.py) and on
the shaft with netgen (r = 2, 2 ranks). The settings alternate within each
round, so that the load of a shared machine hits them alike. Per run:
stage 4's time (slowest rank), fine cells, the attempts each rank needed,
and checkMesh -parallel's verdict, max non-orthogonality and skewness.
Writes bench/results/fast-mode.md and fast-mode.json.

Usage: bench/run --fast-mode [--rounds 2] [--work DIR]
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools"))
import foamCase as fc  # noqa: E402

CASES = [
    # tutorial, volumeMesher, maxCellSize
    ("sphere", "hxt", 0.1),
    ("shaft", "netgen", 0.3),
]
STEPS = [0, 1, 3]
RANKS = 2
LEVELS = 2


def run_one(work, env, tutorial, mesher, size, steps, tag):
    case = fc.copy_tutorial(tutorial, os.path.join(work, "%s-%s-%d-%s" % (tutorial, mesher, steps, tag)),
                            fc.RUN_LEFTOVERS + ("[1-9]*", ".*"))
    pmshDict = os.path.join(case, "system", "pmshDict")
    for key, value in (("volumeMesher", mesher), ("optimisationSteps", steps),
                       ("refinementLevels", LEVELS), ("maxCellSize", size)):
        fc.set_entry(pmshDict, key, value)
    fc.set_entry(os.path.join(case, "system", "controlDict"), "writeFormat", "binary")
    start = time.time()
    with open(os.path.join(case, "log.pmshFoam"), "w") as out:
        rc = subprocess.run(fc.mpi(RANKS, [env["PMSH_BINARY"], "-case", case]), env=env, cwd=case,
                            stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL).returncode
    row = {"case": tutorial, "mesher": mesher, "maxCellSize": size, "steps": steps,
           "round": tag, "exit": rc, "wall": time.time() - start}
    if rc == 0:
        summary = fc.summary(case)
        row.update(stage4=summary["stages"]["volume"]["seconds"], cells=summary["fineCells"],
                   attempts=summary["volumeAttemptsPerRank"],
                   meshers=summary["volumeMesherPerRank"])
        row.update(fc.check_mesh(case, RANKS, env))
    print(json.dumps(row), flush=True)
    return row


def table(rows):
    lines = [
        "| case | volumeMesher | optimisationSteps | stage 4 (s), median | stage 4 (s), each run"
        " | fine cells | attempts per rank | checkMesh | max non-orth | max skewness |",
        "|---|---|---:|---:|---|---:|---|---|---:|---:|"]
    for tutorial, mesher, _ in CASES:
        for steps in STEPS:
            g = [r for r in rows if r["case"] == tutorial and r["steps"] == steps]
            done = [r for r in g if r["exit"] == 0]
            if not done:
                lines.append("| %s | %s | %d | failed | | | | | | |" % (tutorial, mesher, steps))
                continue
            distinct = lambda key, fmt: ", ".join(fmt % v for v in sorted({r[key] for r in done}))
            lines.append("| %s | %s | %d | %.1f | %s | %s | %s | %s | %s | %s |" % (
                tutorial, mesher, steps, statistics.median(r["stage4"] for r in done),
                ", ".join("%.1f" % r["stage4"] for r in done), distinct("cells", "%d"),
                ", ".join(sorted({str(r["attempts"]) for r in done})),
                ", ".join(sorted({"Mesh OK" if r["meshOK"] else "FAILED" for r in done})),
                distinct("maxNonOrtho", "%.1f"), distinct("maxSkewness", "%.2f")))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rounds", type=int, default=2)
    parser.add_argument("--work", default=None)
    args = parser.parse_args()
    env = fc.environment()
    env.setdefault("PMSH_BINARY", os.path.join(env["FOAM_USER_APPBIN"], "pmshFoam"))
    work = args.work or tempfile.mkdtemp(prefix="pmshFoam-fastMode-")
    load = os.getloadavg()
    rows = []
    for r in range(args.rounds):
        for steps in STEPS:
            for tutorial, mesher, size in CASES:
                rows.append(run_one(work, env, tutorial, mesher, size, steps, "round%d" % (r + 1)))
    results = os.path.join(fc.BENCH_DIR, "results")
    with open(os.path.join(results, "fast-mode.json"), "w") as f:
        json.dump({"loadAverageAtStart": load, "runs": rows}, f, indent=1)
    with open(os.path.join(results, "fast-mode.md"), "w") as f:
        f.write("# optimisationSteps 0, 1 and 3: speed and quality\n\n"
                "Produced by `bench/run --fast-mode` on %s UTC, %d rounds, the settings alternating"
                " within each round; load average at the start %.1f on 2 shared cores.\n\n"
                % (time.strftime("%Y-%m-%d %H:%M", time.gmtime()), args.rounds, load[0]))
        f.write(table(rows) + "\n")


if __name__ == "__main__":
    main()
