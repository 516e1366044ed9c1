#!/usr/bin/python3
"""Rank balance: max/mean of the fine cells per rank for the tutorials at
r = 2, P = 2..64 (mpirun --oversubscribe: the counts matter here, not the
times). Results go to bench/results/balance.json under a label, and
bench/results/balance.md is rewritten from all labels there, so that a
"before" from an older pmshFoam sits next to the "after":

    bench/run --balance --label after                       # this build
    bench/run --balance --label before --pmshFoam OLD/pmshFoam
    bench/run --balance --meshers netgen --np 2,4,8,16      # another row set
    bench/run --balance --rewrite                           # only the report

Not part of the tests (tests/tutorials/testBalance.py asserts P = 2, 4).
"""

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools"))
import foamCase as fc  # noqa: E402
RESULTS = os.path.join(ROOT, "bench", "results")
TUTORIALS = ("sphere", "shaft", "sphereSTL")


def run_case(pmshFoam, tutorial, mesher, np, r, work, env):
    case = fc.copy_tutorial(tutorial, os.path.join(work, "%s-%s-%d" % (tutorial, mesher, np)))
    dict_file = os.path.join(case, "system", "pmshDict")
    fc.set_entry(dict_file, "refinementLevels", r)
    fc.set_entry(dict_file, "volumeMesher", mesher)
    argv = fc.mpi(np, [pmshFoam, "-case", case])
    proc = subprocess.run(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, env=env)
    log = proc.stdout.decode(errors="replace")
    row = {"tutorial": tutorial, "mesher": mesher, "np": np, "r": r}
    s = fc.summary(case)
    if proc.returncode != 0 or s is None:
        lines = [l.strip() for l in log.splitlines() if l.strip()]
        fatal = [i for i, l in enumerate(lines) if "FATAL" in l]
        row["failed"] = lines[fatal[0] + 1] if fatal else "exit code %d" % proc.returncode
        return row
    fine = s["fineCellsPerRank"]
    row.update(coarseCells=s["coarseCells"], fineCells=s["fineCells"],
               fineCellsPerRank=fine, maxOverMean=max(fine) * len(fine) / sum(fine))
    m = re.search(r"expected fine cells per part max/mean: ([\d.]+) from the method, "
                  r"([\d.]+) after moving (\d+)", log)
    if m:
        row.update(expectedFromMethod=float(m.group(1)), expected=float(m.group(2)),
                   cellsMoved=int(m.group(3)))
    m = re.search(r"coarse cells per part min/avg/max: (\d+) / ([\d.]+) / (\d+)", log)
    if m:
        row["coarseCellsPerPart"] = [int(m.group(1)), float(m.group(2)), int(m.group(3))]
    return row


def report(results):
    """balance.md from every label in results."""
    labels = list(results["labels"])
    rows = [row for label in labels for row in results["labels"][label]["rows"]]
    nps = sorted({row["np"] for row in rows})
    keys = []
    for row in rows:
        key = (row["tutorial"], row["mesher"])
        if key not in keys:
            keys.append(key)
    keys.sort(key=lambda k: (TUTORIALS.index(k[0]) if k[0] in TUTORIALS else 9, k[1] != "hxt"))

    def cell(label, key, np):
        for row in results["labels"][label]["rows"]:
            if (row["tutorial"], row["mesher"], row["np"]) == key + (np,):
                if "failed" in row:
                    return "failed"
                return "%.3f" % row["maxOverMean"]
        return ""

    out = ["# Rank balance: max/mean fine cells per rank, r = 2", "",
           "Produced by `bench/run --balance` (rewritten %s UTC). Each entry is the largest"
           % time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
           "rank's fine cells over the mean (`fineCellsPerRank` of",
           "postProcessing/pmshFoam/summary.json); target <= 1.05. Runs are",
           "oversubscribed on this machine (counts, not times).", ""]
    for label in labels:
        meta = results["labels"][label]
        out.append("- **%s**: %s" % (label, meta.get("note", "")))
    out += ["", "| tutorial | mesher | " + " | ".join("P = %d" % n for n in nps) + " |",
            "|---|---|" + "---:|" * len(nps)]
    for key in keys:
        entries = []
        for np in nps:
            values = [cell(label, key, np) for label in labels]
            entries.append(" -> ".join(v if v else "-" for v in values))
        out.append("| %s | %s | %s |" % (key[0], key[1], " | ".join(entries)))
    out += ["", "Entries read %s." % " -> ".join(labels), ""]

    # What the weights promised: the balance of the expected fine cells
    last = labels[-1]
    out += ["Expected fine cells (the weights) per part, max/mean, from the method"
            " -> after the balance pass, in the last label (%s):" % last, "",
            "| tutorial | mesher | " + " | ".join("P = %d" % n for n in nps) + " |",
            "|---|---|" + "---:|" * len(nps)]
    for key in keys:
        entries = []
        for np in nps:
            row = next((x for x in results["labels"][last]["rows"]
                        if (x["tutorial"], x["mesher"], x["np"]) == key + (np,)
                        and "expected" in x), None)
            entries.append("%.3f -> %.3f" % (row["expectedFromMethod"], row["expected"])
                           if row else "")
        out.append("| %s | %s | %s |" % (key[0], key[1], " | ".join(entries)))
    out.append("")

    # Coarse granularity: what one coarse cell is worth per part
    out += ["Coarse cells per part (min / mean / max) in the last label (%s), hxt:" % last, "",
            "| tutorial | coarse cells | " + " | ".join("P = %d" % n for n in nps) + " |",
            "|---|---:|" + "---:|" * len(nps)]
    for tutorial in TUTORIALS:
        byNp = {row["np"]: row for row in results["labels"][last]["rows"]
                if row["tutorial"] == tutorial and row["mesher"] == "hxt" and "failed" not in row}
        if not byNp:
            continue
        coarse = next(iter(byNp.values()))["coarseCells"]
        entries = []
        for np in nps:
            c = byNp.get(np, {}).get("coarseCellsPerPart")
            entries.append("%d / %.0f / %d" % (c[0], c[1], c[2]) if c else "")
        out.append("| %s | %d | %s |" % (tutorial, coarse, " | ".join(entries)))
    notes = results.get("notes")
    if notes:
        out += ["", notes.strip()]
    return "\n".join(out) + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--label", default="after")
    parser.add_argument("--note", default="", help="what the label measured (build, commit)")
    parser.add_argument("--pmshFoam", help="the executable (default: build this tree)")
    parser.add_argument("--meshers", default="hxt")
    parser.add_argument("--np", default="2,4,8,16,32,64")
    parser.add_argument("--tutorials", default=",".join(TUTORIALS))
    parser.add_argument("--r", type=int, default=2)
    parser.add_argument("--rewrite", action="store_true", help="only rewrite balance.md")
    parser.add_argument("--work", help="scratch directory (kept)")
    args = parser.parse_args()

    store = os.path.join(RESULTS, "balance.json")
    results = {"labels": {}}
    if os.path.exists(store):
        with open(store) as f:
            results = json.load(f)

    if not args.rewrite:
        env = fc.environment()
        pmshFoam = args.pmshFoam
        if not pmshFoam:
            subprocess.run(["./Allwmake"], cwd=ROOT, env=env, check=True,
                           stdout=subprocess.DEVNULL)
            pmshFoam = os.path.join(env["FOAM_USER_APPBIN"], "pmshFoam")
        work = args.work or tempfile.mkdtemp(prefix="pmshBalance-")
        entry = results["labels"].setdefault(args.label, {"rows": []})
        if args.note:
            entry["note"] = args.note
        for tutorial in args.tutorials.split(","):
            for mesher in args.meshers.split(","):
                for np in (int(n) for n in args.np.split(",")):
                    row = run_case(pmshFoam, tutorial, mesher, np, args.r, work, env)
                    print("%-10s %-7s P = %-3d %s" % (tutorial, mesher, np,
                          row.get("failed") or "max/mean %.3f" % row["maxOverMean"]),
                          flush=True)
                    entry["rows"] = [x for x in entry["rows"]
                                     if (x["tutorial"], x["mesher"], x["np"], x["r"])
                                     != (tutorial, mesher, np, args.r)] + [row]
                    with open(store, "w") as f:
                        json.dump(results, f, indent=1)
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)

    with open(os.path.join(RESULTS, "balance.md"), "w") as f:
        f.write(report(results))
    print(open(os.path.join(RESULTS, "balance.md")).read())


if __name__ == "__main__":
    sys.exit(main())
