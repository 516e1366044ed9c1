"""The report of bench/run --quick and --full (pmshBench.py): ratios
against the peers and the paper, the CSV tables, results.md and the plots.
"""

import csv
import math
import os

from benchPlan import GEOMETRIES, MATCH_TOLERANCE, PAPER_NETGEN_SERIAL_RATE, RANKS


def ratio(a, b):
    return a/b if (a is not None and b) else None


def compute_ratios(cases, paper):
    """One row per (geometry, r, mesher): pmshFoam against each peer"""
    out = []
    for c in cases:
        p1, p2 = c["runs"].get(1), c["runs"].get(2)
        ng, gm = c.get("netgenSerial"), c.get("gmsh")
        pr = paper.get(c["geometry"])
        row = {"geometry": c["geometry"], "r": c["r"], "mesher": c["mesher"]}
        for ranks, run in ((1, p1), (2, p2)):
            if not (run and run.get("ok")):
                continue
            sec_per_cell = run["paperTotal"]/run["fineCells"]
            if ng and ng.get("ok"):
                row["timePerCellVsNetgenSerial_P%d" % ranks] = \
                    ratio(sec_per_cell, ng["time"]/ng["cells"])
                row["fineRatePerCoreVsNetgenSerial_P%d" % ranks] = \
                    ratio(run["fineCellsPerSecondPerCore"], ng["cellsPerSecondPerCore"])
            if pr:
                # per core: seconds x cores per cell
                row["coreTimePerCellVsPaper_P%d" % ranks] = \
                    ratio(sec_per_cell*ranks, 1.0/pr["totalRatePerCore"])
                row["fineRatePerCoreVsPaper_P%d" % ranks] = \
                    ratio(run["fineCellsPerSecondPerCore"], pr["fineRatePerCore"])
        if p2 and p2.get("ok") and gm and gm.get("ok") and gm.get("time"):
            # geometry to a parallel-ready case, wall clock, both on 2 cores
            row["wallTimePerCellVsGmshChain_P2"] = \
                ratio(p2["wallTime"]/p2["fineCells"], gm["time"]/gm["cells"])
        if p1 and p2 and p1.get("ok") and p2.get("ok"):
            # at the same problem size: per-cell times (cell counts differ a little)
            row["speedupTotal"] = ratio(p1["paperTotal"]/p1["fineCells"],
                                        p2["paperTotal"]/p2["fineCells"])
            row["speedupFine"] = ratio(p1["fineTime"]/p1["fineCells"],
                                       p2["fineTime"]/p2["fineCells"])
            row["speedupWall"] = ratio(p1["wallTime"]/p1["fineCells"],
                                       p2["wallTime"]/p2["fineCells"])
        out.append(row)
    return out


# ---------------------------------------------------------------------------
# Output: CSV, Markdown, plots
# ---------------------------------------------------------------------------

RUN_COLUMNS = [
    "geometry", "mesher", "r", "maxCellSize", "ranks", "coarseCells", "fineCells",
    "coarseTime", "fineTime", "paperTotal", "writeTime", "totalTime", "wallTime",
    "fineCellsPerSecondPerCore", "peakMemoryMaxBytes", "peakRssTreeBytes", "bytesPerFineCell",
    "bytesPerFineCellPerRankMax", "summaryBytesPerFineCellPerRankMax", "baselineMemoryBytes",
    "bytesPerFineCellAboveBaseline", "loadBefore", "loadAfter", "volumeRetries", "ok",
]

PEER_COLUMNS = [
    "peer", "geometry", "r", "forMesher", "setting", "value", "targetCells", "cells", "cellRatio",
    "final", "time", "gmshTime", "gmshToFoamTime", "decomposeParTime",
    "cellsPerSecondPerCore", "peakMemoryBytes", "bytesPerCell", "checkMesh",
    "loadBefore", "loadAfter", "ok",
]


def fmt(v, digits=2):
    if v is None or v == "":
        return ""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        return ("%." + str(digits) + "f") % v
    return str(v)


def write_csv(path, rows, columns):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(columns)
        for r in rows:
            w.writerow([fmt(r.get(c), 4) if isinstance(r.get(c), float) else fmt(r.get(c))
                        for c in columns])


def mib(b):
    return b/1048576.0 if b else None


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |",
             "|" + "|".join("---:" if i else "---" for i in range(len(header))) + "|"]
    for r in rows:
        lines.append("| " + " | ".join(r) + " |")
    return "\n".join(lines)


def target_value(v):
    if v is None:
        return ""
    return "%.4g" % v if v < 10 else "%.0f" % v


def balance(run):
    """Largest rank's fine cells over the mean"""
    cells = run.get("fineCellsPerRank") or []
    if len(cells) < 2 or not sum(cells):
        return None
    return max(cells)/(sum(cells)/float(len(cells)))


def verdict(value, target, higher_is_better=True):
    if value is None:
        return "not measured"
    met = value >= target if higher_is_better else value <= target
    return "**met**" if met else "**missed**"


def base_range(runs):
    """The baseline memory of the runs, as 'a-b MiB'"""
    base = [mib(r["baselineMemoryBytes"]) for r in runs if r.get("baselineMemoryBytes")]
    return "%.0f-%.0f MiB" % (min(base), max(base)) if base else "not reported"


def machine_section(L, res):
    m = res["machine"]
    L.append("# pmshFoam benchmark results (%s mode)" % res["mode"])
    L.append("")
    L.append("Produced by `bench/run --%s` on %s, in %.0f s. See [../README.md](../README.md) "
             "for what is measured and how." % (res["mode"], res["date"], res["elapsed"]))
    L.append("")
    L.append("## Machine")
    L.append("")
    L.append(md_table(["", ""], [[k, str(v)] for k, v in m.items()]
                      + [["load at end (1 min)", str(res["loadAtEnd"])]]))
    L.append("")
    L.append("Timings are wall clock on a machine shared with other work: the 1-minute "
             "load average before each run is in the `load` column (2 cores: a load "
             "above 2 means the runs did not have the cores to themselves).")
    L.append("")


def runs_section(L, res):
    L.append("## pmshFoam (the paper's Table 2 columns)")
    L.append("")
    L.append("Coarse = stage 1; fine = stages 2-6 (partition, surface refinement, volume "
             "meshing, numbering, balance); total = coarse + fine, as in the paper (I/O excluded); "
             "write = stage 7; wall = the whole command (start-up, reading, writing). "
             "Rank balance: the largest rank's fine cells over the mean. "
             "Memory: peak resident set per rank, the larger of pmshFoam's own figure "
             "(summary.json: each rank's VmHWM) and GNU time's maximum resident set over "
             "the whole process tree (which also sees volume meshing in a forked child); "
             "bytes per fine cell of the worst rank (with 2 ranks the tree's peak is "
             "divided by the larger rank's cells). Above base: the worst rank's peak "
             "less the peak after stage 1 (libraries, MPI, the coarse mesh: %s), per "
             "fine cell: what each further cell costs, the figure that matters at "
             "millions of cells." % base_range(res["runs"]))
    L.append("")
    header = ["geometry", "mesher", "r", "maxCellSize", "P", "coarse cells", "fine cells",
              "coarse (s)", "fine (s)", "total (s)", "write (s)", "wall (s)",
              "rank balance", "peak MiB/rank", "B/fine cell/rank",
              "B/fine cell above base", "fine cells/s/core", "load"]
    rows = []
    for r in res["runs"]:
        if not r.get("ok"):
            rows.append([r["geometry"], r["mesher"], str(r["r"]), fmt(r["maxCellSize"], 4),
                         str(r["ranks"]), "**FAILED**", "see notes"] + [""]*11)
            continue
        rows.append([r["geometry"], r["mesher"], str(r["r"]), fmt(r["maxCellSize"], 4),
                     str(r["ranks"]), str(r["coarseCells"]), str(r["fineCells"]),
                     fmt(r["coarseTime"]), fmt(r["fineTime"]), fmt(r["paperTotal"]),
                     fmt(r["writeTime"]), fmt(r["wallTime"]), fmt(balance(r)),
                     fmt(mib(r["peakMemoryMaxBytes"]), 1),
                     fmt(r["bytesPerFineCellPerRankMax"], 0),
                     fmt(r.get("bytesPerFineCellAboveBaseline"), 0),
                     fmt(r["fineCellsPerSecondPerCore"], 0), fmt(r["loadBefore"], 1)])
    if not res["hxt"]["available"]:
        rows.append(["*(hxt rows)*", "hxt", "", "", "", "*not measured: this pmshFoam does "
                     "not accept `volumeMesher hxt;`*"] + [""]*12)
    L.append(md_table(header, rows))
    L.append("")


def peers_section(L, res):
    L.append("## Peers at matched cell counts")
    L.append("")
    L.append("Matched to the mean fine cell count of pmshFoam's 1- and 2-rank runs with "
             "the backend named; the hxt rows share the Netgen serial peer of the Netgen "
             "rows (hxt makes more cells, so their ratios to it compare rates, not equal "
             "meshes). "
             "(a) Netgen serial: pmshFoam serial with `refinementLevels 0`, stage 1 only "
             "(Netgen CSG/STL surface + volume + optimisation at the fine size), "
             "maxCellSize searched to match pmshFoam's fine cell count. (b) gmsh HXT "
             "(2 threads) filling pmshFoam's own fine boundary surface, then gmshToFoam, "
             "then decomposePar (simple, 2 subdomains); MeshSizeMax searched to match. "
             "Cells/s/core of (b) = cells / chain time / 2. Only the final (matched) runs "
             "are shown; every search run is in peers.csv.")
    L.append("")
    header = ["geometry", "r", "peer", "matched to", "setting", "target cells", "cells",
              "match", "time (s)", "cells/s/core", "peak MiB", "B/cell", "load", "notes"]
    rows = []
    for c in res["cases"]:
        for key in ("netgenSerial", "gmsh"):
            p = c.get(key)
            if not p or p.get("forMesher", c["mesher"]) != c["mesher"]:
                continue
            notes = ""
            if key == "gmsh" and p.get("ok"):
                notes = "gmsh %s + gmshToFoam %s + decomposePar %s s; checkMesh: %s" % (
                    fmt(p.get("gmshTime")), fmt(p.get("gmshToFoamTime")),
                    fmt(p.get("decomposeParTime")), p.get("checkMesh", "?"))
            if not p.get("ok"):
                notes = "FAILED"
            rows.append([c["geometry"], str(c["r"]),
                         "Netgen serial" if key == "netgenSerial" else "gmsh HXT chain",
                         "pmshFoam %s" % c["mesher"],
                         "%s %s" % (p.get("setting", ""), fmt(p.get("value"), 4)),
                         str(p.get("targetCells", "")), str(p.get("cells", "")),
                         ("%+.0f%%" % (100*(p["cellRatio"] - 1))
                          + ("" if abs(p["cellRatio"] - 1) <= MATCH_TOLERANCE else " (unmatched)"))
                         if p.get("cellRatio") else "",
                         fmt(p.get("time")), fmt(p.get("cellsPerSecondPerCore"), 0),
                         fmt(mib(p.get("peakMemoryBytes")), 1), fmt(p.get("bytesPerCell"), 0),
                         fmt(p.get("loadBefore"), 1), notes])
    L.append(md_table(header, rows))
    L.append("")
    L.append("(c) PMSH, published (Table 2, Vilje, 1024-8192 cores), mean over the "
             "geometry's rows; the paper's sequential Netgen rate is 0.23 M cells/min "
             "= %.0f cells/s." % PAPER_NETGEN_SERIAL_RATE)
    L.append("")
    rows = []
    for g in GEOMETRIES:
        pr = res["paper"].get(g["name"])
        if pr:
            rows.append([g["name"], g["paper"], str(pr["rows"]),
                         fmt(pr["fineRatePerCore"], 0), fmt(pr["totalRatePerCore"], 0)])
    L.append(md_table(["geometry", "paper geometry", "rows", "fine cells/s/core",
                       "total cells/s/core"], rows))
    L.append("")


def ratios_and_targets_section(L, res):
    L.append("## Ratios")
    L.append("")
    L.append("Time per cell ratios are pmshFoam ÷ peer: below 1 means pmshFoam is faster. "
             "vs Netgen serial: pmshFoam's coarse + fine time per fine cell against "
             "Netgen's stage-1 time per cell. vs gmsh chain: wall clock from geometry "
             "(pmshFoam, 2 ranks) or surface (gmsh) to a decomposed case, per cell. vs paper: "
             "seconds x cores per cell (coarse + fine). Speedup 1 -> 2 ranks uses time per "
             "cell, because the 1- and 2-rank meshes differ in cell count (see the notes).")
    L.append("")
    header = ["geometry", "mesher", "r",
              "time/cell vs Netgen (P=1)", "time/cell vs Netgen (P=2)",
              "fine rate/core vs Netgen (P=1)", "fine rate/core vs Netgen (P=2)",
              "wall/cell vs gmsh chain (P=2)", "core-time/cell vs paper (P=2)",
              "speedup total", "speedup fine", "speedup wall"]
    rows = []
    for q in res["ratios"]:
        rows.append([q["geometry"], q["mesher"], str(q["r"])] + [
            fmt(q.get(k)) for k in (
                "timePerCellVsNetgenSerial_P1", "timePerCellVsNetgenSerial_P2",
                "fineRatePerCoreVsNetgenSerial_P1", "fineRatePerCoreVsNetgenSerial_P2",
                "wallTimePerCellVsGmshChain_P2", "coreTimePerCellVsPaper_P2",
                "speedupTotal", "speedupFine", "speedupWall")])
    L.append(md_table(header, rows))
    L.append("")

    L.append("## Targets (measured, never asserted)")
    L.append("")
    t = res["targets"]
    rows = []
    for item in t:
        rows.append([item["target"], item["where"],
                     target_value(item["value"]), item["verdict"]])
    L.append(md_table(["target", "where", "measured", "verdict"], rows))
    L.append("")


def plots_and_notes_section(L, res):
    L.append("## Plots")
    L.append("")
    for name, title in (("fig6-time-vs-ranks.png", "Time vs ranks per problem size (cf. the paper's Fig. 6)"),
                        ("rates-vs-peers.png", "Cells/s per core against the peers")):
        if name in res["plots"]:
            L.append("%s:" % title)
            L.append("")
            L.append("![%s](%s)" % (title, name))
            L.append("")
    if not res["plots"]:
        L.append("No plots: python3-matplotlib is not installed.")
        L.append("")

    if res["notes"]:
        L.append("## Notes")
        L.append("")
        for n in res["notes"]:
            L.append("- " + n)
        L.append("")
    L.append("Files: [runs.csv](runs.csv) (every pmshFoam run), [peers.csv](peers.csv) "
             "(every peer run, search runs included), [ratios.csv](ratios.csv), "
             "[results.json](results.json) (everything, raw).")
    L.append("")


def write_markdown(path, res):
    L = []
    for section in (machine_section, runs_section, peers_section,
                    ratios_and_targets_section, plots_and_notes_section):
        section(L, res)
    with open(path, "w") as f:
        f.write("\n".join(L))


def make_plots(out, res):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return []
    made = []

    # Fig. 6: time vs ranks, one curve per problem size (|T|, |T''|)
    geoms = [g["name"] for g in GEOMETRIES if any(x["geometry"] == g["name"] for x in res["runs"])]
    if not geoms:
        return made
    fig, axes = plt.subplots(1, len(geoms), figsize=(5*len(geoms), 5.6), squeeze=False)
    for ax, g in zip(axes[0], geoms):
        for mesher, style in (("netgen", "-o"), ("hxt", "--s")):
            for r in sorted({x["r"] for x in res["runs"]}):
                pts = [x for x in res["runs"] if x["geometry"] == g and x["r"] == r
                       and x["mesher"] == mesher and x.get("ok")]
                if not pts:
                    continue
                pts.sort(key=lambda x: x["ranks"])
                label = "%s r=%d (%.2gk, %.3gM)" % (
                    mesher, r, pts[0]["coarseCells"]/1e3,
                    sum(x["fineCells"] for x in pts)/len(pts)/1e6)
                ax.plot([x["ranks"] for x in pts], [x["paperTotal"] for x in pts], style,
                        label=label)
        ax.set_title(g)
        ax.set_xlabel("ranks P")
        ax.set_ylabel("coarse + fine time (s)")
        ax.set_xticks(RANKS)
        ax.set_yscale("log")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7, title="backend r (|T|, |T''|)", title_fontsize=7,
                  loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    fig.suptitle("pmshFoam: mesh generation time vs ranks per problem size (cf. PMSH Fig. 6)")
    fig.tight_layout()
    name = "fig6-time-vs-ranks.png"
    fig.savefig(os.path.join(out, name), dpi=110)
    plt.close(fig)
    made.append(name)

    # Cells/s per core against the peers, at each geometry's largest case
    def hxt_rate(c, ranks):
        for h in res["cases"]:
            if h["geometry"] == c["geometry"] and h["r"] == c["r"] and h["mesher"] == "hxt":
                return (h["runs"].get(ranks) or {}).get("fineCellsPerSecondPerCore")
        return None

    series = [
        ("pmshFoam fine P=1", lambda c: c["runs"].get(1, {}).get("fineCellsPerSecondPerCore")),
        ("pmshFoam fine P=2", lambda c: c["runs"].get(2, {}).get("fineCellsPerSecondPerCore")),
        ("pmshFoam total P=2", lambda c: (c["runs"][2]["fineCells"]/c["runs"][2]["paperTotal"]/2)
         if c["runs"].get(2, {}).get("ok") else None),
        ("pmshFoam hxt fine P=1", lambda c: hxt_rate(c, 1)),
        ("pmshFoam hxt fine P=2", lambda c: hxt_rate(c, 2)),
        ("Netgen serial", lambda c: (c.get("netgenSerial") or {}).get("cellsPerSecondPerCore")),
        ("gmsh HXT chain (2 thr.)", lambda c: (c.get("gmsh") or {}).get("cellsPerSecondPerCore")),
        ("PMSH paper fine", lambda c: (res["paper"].get(c["geometry"]) or {}).get("fineRatePerCore")),
        ("PMSH paper total", lambda c: (res["paper"].get(c["geometry"]) or {}).get("totalRatePerCore")),
    ]
    largest = []
    for g in geoms:
        cs = [c for c in res["cases"] if c["geometry"] == g and c["mesher"] == "netgen"]
        if cs:
            largest.append(max(cs, key=lambda c: c["r"]))
    if largest:
        fig, ax = plt.subplots(figsize=(12.5, 5))
        width = 0.8/len(series)
        missing = []
        for i, (label, f) in enumerate(series):
            xs, ys = [], []
            for j, c in enumerate(largest):
                v = f(c)
                x = j + (i - len(series)/2.0 + 0.5)*width
                if v:
                    xs.append(x)
                    ys.append(v)
                else:
                    missing.append(x)
            ax.bar(xs, ys, width, label=label)
        ax.set_xticks(range(len(largest)))
        ax.set_xticklabels(["%s r=%d\n(%.2gM cells)" % (
            c["geometry"], c["r"],
            (c["runs"].get(1) or c["runs"].get(2) or {}).get("fineCells", 0)/1e6)
            for c in largest])
        ax.set_yscale("log")
        for x in missing:
            ax.text(x, ax.get_ylim()[0]*1.15, "failed / n.a.", rotation=90, fontsize=7,
                    ha="center", va="bottom", color="0.4")
        ax.set_ylabel("cells / s / core (log)")
        ax.set_yscale("log")
        ax.set_title("Meshing rate per core at each geometry's largest case: pmshFoam vs peers")
        ax.grid(True, axis="y", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
        fig.tight_layout()
        name = "rates-vs-peers.png"
        fig.savefig(os.path.join(out, name), dpi=110)
        plt.close(fig)
        made.append(name)
    return made
