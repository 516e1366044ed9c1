#!/usr/bin/env python3
"""Before and after, in one run: the pmshFoam built here against another
pmshFoam (an older commit's build), on the 1M-cell sphere: the sphere
tutorial with maxCellSize 0.1, refinementLevels 2, volumeMesher hxt,
binary, 2 ranks (about 1M cells). The two alternate (before, after,
before, ...), so that the load of a shared machine hits them alike.

Per run: pmshFoam's own stage times and fine cells (summary.json), and
the whole command's wall time, CPU time (all processes) and the peak
memory of its largest process. Per build: checkMesh -parallel's verdict
and worst faces on the mesh of its first run. Reported as medians and
as after/before ratios per fine cell (the builds need not make the same
number of cells): the median of the pairs' ratios and the ratio of the
medians. Writes before-after.md and before-after.json into --out.

Usage: bench/run --before PMSHFOAM [--rounds 7] [--out DIR] [--work DIR]
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

RANKS = 2
SETTINGS = (("maxCellSize", 0.1), ("refinementLevels", 2), ("volumeMesher", "hxt"))


def build_environment(env, binary):
    """env for binary: its own libpmsh first when it has one beside it
    (a wmake build: <platform>/bin/pmshFoam and <platform>/lib)"""
    env = dict(env)
    lib = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(binary))), "lib")
    if os.path.exists(os.path.join(lib, "libpmsh.so")):
        env["LD_LIBRARY_PATH"] = lib + ":" + env.get("LD_LIBRARY_PATH", "")
    return env


def prepare(work, name):
    case = fc.copy_tutorial("sphere", os.path.join(work, name))
    pmshDict = os.path.join(case, "system", "pmshDict")
    for key, value in SETTINGS:
        fc.set_entry(pmshDict, key, value)
    fc.set_entry(os.path.join(case, "system", "controlDict"), "writeFormat", "binary")
    return case


def run_once(case, binary, env):
    """One pmshFoam run: the summary's figures and the command's resources"""
    start = time.time()
    with open(os.path.join(case, "log.pmshFoam"), "w") as out:
        proc = subprocess.Popen(fc.mpi(RANKS, [binary, "-case", case, "-overwrite"]), env=env,
                                cwd=case, stdout=out, stderr=subprocess.STDOUT,
                                stdin=subprocess.DEVNULL)
        _, status, usage = os.wait4(proc.pid, 0)
    row = {"exit": os.waitstatus_to_exitcode(status), "wall": time.time() - start,
           "cpu": usage.ru_utime + usage.ru_stime, "peakMiB": usage.ru_maxrss/1024.0}
    if row["exit"] == 0:
        s = fc.summary(case)
        row.update(cells=s["fineCells"], total=s["totalTime"], coarse=s["coarseTime"],
                   fine=s["fineTime"], write=s["writeTime"])
    return row


def median(rows, key):
    return statistics.median(r[key] for r in rows)


def report(args, rows, checks, load):
    before = [r for r in rows if r["build"] == "before"]
    after = [r for r in rows if r["build"] == "after"]
    pairs = list(zip(before, after))
    per_cell = lambda r, key: r[key]/r["cells"]
    lines = [
        "# Before and after: the 1M-cell sphere",
        "",
        "Produced by `bench/run --before` on %s UTC: the sphere tutorial, maxCellSize 0.1,"
        " r = 2, hxt, binary, %d ranks; %d rounds, before and after alternating; load average"
        " at the start %.1f." % (time.strftime("%Y-%m-%d %H:%M", time.gmtime()), RANKS,
                                 len(pairs), load[0]),
        "",
        "- before: `%s`" % args.before,
        "- after: `%s`" % args.after,
        "",
        "| | before | after | after/before per fine cell: median of the pairs"
        " | ratio of the medians |",
        "|---|---:|---:|---:|---:|",
        "| fine cells | %d | %d | | |" % (median(before, "cells"), median(after, "cells")),
    ]
    for key, what in (("coarse", "stage 1, coarse (s)"), ("fine", "stages 2-6, fine (s)"),
                      ("write", "stage 7, write (s)"), ("total", "total, pmshFoam's clock (s)"),
                      ("wall", "whole command, wall (s)"), ("cpu", "whole command, CPU (s)")):
        ratios = [per_cell(a, key)/per_cell(b, key) for b, a in pairs]
        lines.append("| %s | %.3f | %.3f | %.3f (%.3f-%.3f) | %.3f |" % (
            what, median(before, key), median(after, key), statistics.median(ratios),
            min(ratios), max(ratios),
            statistics.median(per_cell(a, key) for a in after)
            / statistics.median(per_cell(b, key) for b in before)))
    lines.append("| peak memory of the largest process (MiB) | %.0f | %.0f | | |"
                 % (median(before, "peakMiB"), median(after, "peakMiB")))
    lines.append("| checkMesh -parallel | %s | %s | | |" % tuple(
        "%s, %.1f degrees, skewness %.3f" % ("Mesh OK" if c.get("meshOK") else "FAILED",
                                             c.get("maxNonOrtho", float("nan")),
                                             c.get("maxSkewness", float("nan")))
        for c in (checks["before"], checks["after"])))
    return "\n".join(lines) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--before", required=True, help="the pmshFoam to compare against")
    parser.add_argument("--after", default=None, help="default: the one built here")
    parser.add_argument("--rounds", type=int, default=7)
    parser.add_argument("--out", default=os.path.join(fc.BENCH_DIR, "results"))
    parser.add_argument("--work", default=None)
    parser.add_argument("--no-build", action="store_true", help="(bench/run: do not build first)")
    args = parser.parse_args()
    env = fc.environment()
    args.after = args.after or os.path.join(env["FOAM_USER_APPBIN"], "pmshFoam")
    for binary in (args.before, args.after):
        if not os.access(binary, os.X_OK):
            sys.exit("Error: %s is not an executable pmshFoam" % binary)
    work = args.work or tempfile.mkdtemp(prefix="pmshFoam-beforeAfter-")
    builds = {"before": args.before, "after": args.after}
    cases = {name: prepare(work, name) for name in builds}
    envs = {name: build_environment(env, binary) for name, binary in builds.items()}
    load = os.getloadavg()
    rows, checks = [], {}
    for r in range(args.rounds):
        for name in ("before", "after"):
            row = dict(run_once(cases[name], builds[name], envs[name]), build=name, round=r + 1)
            print(json.dumps(row), flush=True)
            if row["exit"] != 0:
                sys.exit("Error: the %s build failed, see %s/log.pmshFoam" % (name, cases[name]))
            if name not in checks:
                checks[name] = fc.check_mesh(cases[name], RANKS, envs[name])
            rows.append(row)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "before-after.json"), "w") as f:
        json.dump({"before": args.before, "after": args.after, "loadAverageAtStart": load,
                   "checkMesh": checks, "runs": rows}, f, indent=1)
    text = report(args, rows, checks, load)
    with open(os.path.join(args.out, "before-after.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    main()
