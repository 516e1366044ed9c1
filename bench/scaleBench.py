#!/usr/bin/env python3
"""pmshFoam at scale: bench/run --coarse | --massive | --massive-layers | --scaling

  --coarse   stage 1 (coarse mesh) and stage 2 (partition) at 0.1, 0.5 and
             1 million coarse cells, coarseMesher netgen against hxt, on the
             three tutorial geometries; and the fine mesh's checkMesh quality
             with either coarse mesher (the default is the faster one at
             equal quality). Results: bench/results/coarse-stage.md.
  --massive  one run of 100 million cells or more on 2 ranks (hxt, binary):
             time per stage, peak memory per rank, bytes per cell, write
             throughput, and OpenFOAM's checks of what was written.
             Results: bench/results/massive.md.
  --massive-layers
             the same ball at 50 million cells or more with 5 prism layers
             on its wall, in pieces. Results: bench/results/massive-layers.md.
  --scaling  the same problem at P = 1, 2, 4, ..., 64 ranks (oversubscribed
             beyond the cores: work per rank, balance, messages, not time),
             per-stage serial costs, per-core rates, and a model that projects
             the paper's Table 2 configurations. Results:
             bench/results/scaling.md.

Every mode writes its own markdown (and JSON) into --out (default
bench/results). Nothing here is part of the tests.
"""

import argparse
import json
import math
import os
import re
import shutil
import statistics
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools"))
import foamCase as fc  # noqa: E402
import pmshBench as pb  # noqa: E402

GEOMETRIES = pb.GEOMETRIES
TUTORIAL_SIZE = {"sphere": 0.25, "shaft": 0.45, "sphereSTL": 0.3}


# ---------------------------------------------------------------------------
# Reading a pmshFoam log
# ---------------------------------------------------------------------------

def stage_blocks(text):
    """{stage number: text of that stage} of a pmshFoam log"""
    blocks = {}
    parts = re.split(r"^Stage (\d): ", text, flags=re.M)
    for i in range(1, len(parts) - 1, 2):
        blocks[int(parts[i])] = parts[i + 1].split("\nSummary")[0]
    return blocks


def stage_time(block):
    """Largest rank's wall time of a stage (serial or parallel log line)"""
    m = re.search(r"time \(s\) min/avg/max: [0-9.]+ / [0-9.]+ / ([0-9.]+)", block)
    if not m:
        m = re.search(r"time: ([0-9.]+) s", block)
    return float(m.group(1)) if m else None


def stage_peak_mib(block):
    m = re.search(r"peak memory(?: \(MiB\) max)?: ([0-9.]+)", block)
    return float(m.group(1)) if m else None


def coarse_cells(text):
    m = re.search(r"coarse cells: (\d+)", text)
    return int(m.group(1)) if m else None


def check_mesh(case, ranks):
    """OpenFOAM's checkMesh on a case: (ok, max non-orthogonality, average
    non-orthogonality, max skewness, log text)"""
    c = pb.check_mesh(case, ranks)
    with open(os.path.join(case, "log.checkMesh"), errors="replace") as f:
        text = f.read()
    return (c["meshOK"], c.get("maxNonOrtho"), c.get("avgNonOrtho"), c.get("maxSkewness"),
            text)


def fmt(v, digits=2):
    return pb.fmt(v, digits)


# ---------------------------------------------------------------------------
# --coarse
# ---------------------------------------------------------------------------

COARSE_TARGETS = [100000, 500000, 1000000]
# 1M coarse cells on the sphere only: Netgen takes minutes per run there
COARSE_TARGETS_OTHERS = [100000, 500000]


def coarse_case(args, geom, mesher, h, tag):
    name = "coarse-%s-%s-%s" % (geom["name"], mesher, tag)
    case = pb.make_case(args.work, name, geom["tutorial"], h, 0, "hxt")
    pb.set_entry(os.path.join(case, "system", "pmshDict"), "coarseMesher", mesher)
    return case


def run_coarse_stage(args, geom, mesher, h, tag, ranks=2):
    """Stages 1 and 2 of pmshFoam (stopped when stage 3 starts)"""
    case = coarse_case(args, geom, mesher, h, tag)
    run = pb.Run(pb.pmsh_command(args.pmshFoam, ranks, case) + ["-noMemoryCheck"],
                 case, "log.pmshFoam", stop_pattern=r"^Stage 3")
    text = run.text()
    blocks = stage_blocks(text)
    row = {"geometry": geom["name"], "coarseMesher": mesher, "maxCellSize": h,
           "ranks": ranks, "load": run.load_before}
    if 2 not in blocks or stage_time(blocks.get(2, "")) is None:
        row["error"] = pb.first_error(text) or run.tail()
        pb.log("    FAILED %s %s h=%.4g: %s" % (geom["name"], mesher, h, row["error"]))
        return row
    row.update({
        "coarseCells": coarse_cells(blocks[1]),
        "coarseTime": stage_time(blocks[1]),
        "partitionTime": stage_time(blocks[2]),
        "peakMiB": stage_peak_mib(blocks[2]),
        "filledBy": (re.search(r"volume filled by (\w+)", blocks[1]) or [None, None])[1],
    })
    pb.log("    %-9s coarseMesher %-6s maxCellSize %.4g: %8d coarse cells, stage 1 %.2f s"
           " (filled by %s), partition %.2f s, peak %.0f MiB, load %.1f"
           % (geom["name"], mesher, h, row["coarseCells"], row["coarseTime"],
              row["filledBy"], row["partitionTime"], row["peakMiB"], run.load_before))
    shutil.rmtree(case, ignore_errors=True)
    return row


def coarse_quality(args, geom, coarse_mesher, volume_mesher, levels=2, ranks=2):
    """The fine mesh's checkMesh figures with a given coarse mesher"""
    name = "quality-%s-%s-%s" % (geom["name"], coarse_mesher, volume_mesher)
    case = pb.make_case(args.work, name, geom["tutorial"], TUTORIAL_SIZE[geom["name"]],
                        levels, volume_mesher)
    pb.set_entry(os.path.join(case, "system", "pmshDict"), "coarseMesher", coarse_mesher)
    run = pb.Run(pb.pmsh_command(args.pmshFoam, ranks, case), case, "log.pmshFoam")
    row = {"geometry": geom["name"], "coarseMesher": coarse_mesher,
           "volumeMesher": volume_mesher, "r": levels, "ranks": ranks}
    if not run.ok:
        row["error"] = pb.first_error(run.text())
        return row
    s = fc.summary(case)
    ok, non_ortho, avg_non_ortho, skew, _ = check_mesh(case, ranks)
    row.update({"coarseCells": s["coarseCells"], "fineCells": s["fineCells"],
                "meshOK": ok, "maxNonOrtho": non_ortho, "avgNonOrtho": avg_non_ortho,
                "maxSkewness": skew})
    pb.log("    %-9s coarse %-6s volume %-6s: %d coarse, %d fine cells, checkMesh %s, "
           "non-ortho max %.1f avg %.1f, skewness %.2f"
           % (geom["name"], coarse_mesher, volume_mesher, s["coarseCells"], s["fineCells"],
              "OK" if ok else "FAILED", non_ortho or -1, avg_non_ortho or -1, skew or -1))
    shutil.rmtree(case, ignore_errors=True)
    return row


LOG_LINE = re.compile(r"^\s+(\w+)\s+coarseMesher (\w+)\s+maxCellSize ([0-9.eE+-]+):\s+(\d+) coarse "
                      r"cells, stage 1 ([0-9.]+) s \(filled by (\w+)\), partition ([0-9.]+) s, "
                      r"peak ([0-9.]+) MiB, load ([0-9.]+)", re.M)


def rows_from_log(path, mesher):
    """The rows of an earlier --coarse run's log for one coarse mesher (the
    probe of each geometry first, then its targets in order)"""
    with open(path) as f:
        found = [m for m in LOG_LINE.finditer(f.read()) if m.group(2) == mesher]
    rows, seen = [], {}
    for m in found:
        geom = m.group(1)
        k = seen.get(geom, 0)
        seen[geom] = k + 1
        if k == 0:
            continue    # the probe
        targets = COARSE_TARGETS if geom == "sphere" else COARSE_TARGETS_OTHERS
        rows.append({"geometry": geom, "coarseMesher": mesher, "maxCellSize": float(m.group(3)),
                     "ranks": 2, "coarseCells": int(m.group(4)), "coarseTime": float(m.group(5)),
                     "filledBy": m.group(6), "partitionTime": float(m.group(7)),
                     "peakMiB": float(m.group(8)), "load": float(m.group(9)),
                     "target": targets[k - 1], "fromLog": path})
    return rows


def mode_coarse(args):
    res = {"machine": pb.machine_description(args), "stages": [], "quality": []}
    meshers = ("netgen", "hxt")
    if args.netgen_from_log:
        # Netgen's rows of an earlier run (its coarse path unchanged since)
        res["stages"] += rows_from_log(args.netgen_from_log, "netgen")
        res["netgenFromLog"] = args.netgen_from_log
        meshers = ("hxt",)
    for geom in GEOMETRIES:
        for mesher in meshers:
            # Coarse cells scale with 1/maxCellSize^3: a probe at the
            # tutorial's size, then one run per target
            h0 = TUTORIAL_SIZE[geom["name"]]
            probe = run_coarse_stage(args, geom, mesher, h0, "probe")
            if "error" in probe:
                continue
            targets = COARSE_TARGETS if geom["name"] == "sphere" else COARSE_TARGETS_OTHERS
            for target in targets:
                h = h0*(probe["coarseCells"]/float(target))**(1.0/3.0)
                row = run_coarse_stage(args, geom, mesher, h, "%d" % target)
                row["target"] = target
                res["stages"].append(row)
    for geom in GEOMETRIES:
        for volume in ("hxt", "netgen") if geom["name"] == "sphere" else ("hxt",):
            for coarse in ("netgen", "hxt"):
                res["quality"].append(coarse_quality(args, geom, coarse, volume))
    write_json(args, "coarse-stage.json", res)
    write_coarse_markdown(args, res)


def write_coarse_markdown(args, res):
    rows = []
    for r in res["stages"]:
        if "error" in r:
            rows.append([r["geometry"], r["coarseMesher"], "%.4g" % r["maxCellSize"],
                         "failed: " + r["error"][:60], "", "", "", ""])
            continue
        rows.append([r["geometry"], r["coarseMesher"], "%.4g" % r["maxCellSize"],
                     "%d" % r["coarseCells"], fmt(r["coarseTime"]),
                     "%.0f" % (r["coarseCells"]/r["coarseTime"]) if r["coarseTime"] else "-",
                     fmt(r["partitionTime"]), "%.0f" % r["peakMiB"]])
    # Side by side: hxt's time over netgen's at the same target
    ratios = []
    for geom in GEOMETRIES:
        for target in COARSE_TARGETS:
            pair = {r["coarseMesher"]: r for r in res["stages"]
                    if r["geometry"] == geom["name"] and r.get("target") == target
                    and "error" not in r}
            if len(pair) == 2:
                n, x = pair["netgen"], pair["hxt"]
                ratios.append([geom["name"], "%d" % target,
                               fmt(n["coarseTime"]), fmt(x["coarseTime"]),
                               fmt(x["coarseTime"]/n["coarseTime"]),
                               fmt((x["coarseCells"]/x["coarseTime"])
                                   / (n["coarseCells"]/n["coarseTime"]))])
    quality = []
    for q in res["quality"]:
        quality.append([q["geometry"], q["volumeMesher"], q["coarseMesher"],
                        "%d" % q.get("coarseCells", 0), "%d" % q.get("fineCells", 0),
                        "OK" if q.get("meshOK") else "FAILED " + q.get("error", ""),
                        fmt(q.get("maxNonOrtho"), 1), fmt(q.get("avgNonOrtho"), 1),
                        fmt(q.get("maxSkewness"), 2)])
    text = "\n".join([
        "# Coarse stage: coarseMesher netgen against hxt",
        "",
        "Measured by `bench/run --coarse` (bench/scaleBench.py). Stage 1 is Netgen's "
        "surface mesh of the geometry and its volume filled by the coarse mesher; "
        "stage 2 partitions the coarse mesh into 2 parts (metis). 2 ranks; the "
        "other rank sleeps during stage 1, the master may use every core. "
        "Sizes come from a probe at the tutorial's maxCellSize, scaled as 1/h^3: the "
        "coarse cell counts land off the targets, so compare cells per second. Netgen "
        "took 345 s for 0.77 M cells, so its 1 M target was not run.",
        "",
        ("The netgen rows come from an earlier run's log (%s; Netgen's coarse path is "
         "the same in both)." % os.path.basename(res["netgenFromLog"]))
        if res.get("netgenFromLog") else "",
        "",
        machine_table(res["machine"]),
        "",
        "## Time per coarse mesh",
        "",
        pb.md_table(["geometry", "coarseMesher", "maxCellSize", "coarse cells",
                     "stage 1 (s)", "coarse cells/s", "partition (s)", "peak MiB"], rows),
        "",
        "## hxt against netgen, same target size",
        "",
        pb.md_table(["geometry", "target coarse cells", "netgen (s)", "hxt (s)",
                     "time hxt/netgen", "cells/s hxt/netgen"], ratios),
        "",
        "## Fine mesh quality by coarse mesher (r = 2, 2 ranks, checkMesh -parallel)",
        "",
        pb.md_table(["geometry", "volumeMesher", "coarseMesher", "coarse cells",
                     "fine cells", "checkMesh", "max non-ortho", "avg non-ortho",
                     "max skewness"], quality),
        "",
    ])
    write_text(args, "coarse-stage.md", text)


# ---------------------------------------------------------------------------
# --massive
# ---------------------------------------------------------------------------

# sphere.geo at maxCellSize 0.1679, r = 5 gave 104.1 million cells with hxt
# on 2 ranks in pieces of 2M (2026-11-30; 107.0M in one call a rank at
# 90986d7): cells scale with 1/maxCellSize^3
MASSIVE = {"geometry": "sphere", "levels": 5, "ranks": 2, "targetCells": 110e6,
           "reference": (0.1679, 104.1e6), "results": "massive"}

# The same ball with 5 prism layers on its wall: the stacks about one fine
# wall cell thick (0.0074 against a wall edge near 0.007 at r = 5), the
# pieces layered too. The prisms (about 5 a wall triangle) are a few per
# cent of the cells, so the tets follow the same 1/maxCellSize^3.
MASSIVE_LAYERS = dict(MASSIVE, targetCells=50e6, results="massive-layers",
                      layers="layers 5; firstLayerThickness 0.001; expansionRatio 1.2;")

# checkMesh -parallel peaked at 3.9 GB per rank on 9.7 million cells per rank
CHECKMESH_BYTES_PER_CELL = 420.0


def mem_available():
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1])*1024
    return 0


def read_labels(path):
    """An OpenFOAM labelList (binary or ascii) as a numpy int64 array"""
    import numpy as np
    with open(path, "rb") as f:
        data = f.read()
    binary = re.search(rb"format\s+binary", data[:2000]) is not None
    header_end = data.find(b"}", data.find(b"FoamFile")) + 1
    body = data[header_end:]
    m = re.search(rb"(\d+)\s*\(", body)
    n = int(m.group(1))
    start = m.end()
    if binary:
        return np.frombuffer(body, dtype=np.int32, count=n, offset=start).astype(np.int64)
    return np.array(body[start:body.rfind(b")")].split(), dtype=np.int64)


def check_addressing(case, ranks):
    """The checks of the tests' procAddressing test, on the massive output:
    global points, faces and cells contiguous and each internal face once"""
    import numpy as np
    procs = [os.path.join(case, "processor%d" % p, "constant", "polyMesh")
             for p in range(ranks)]
    point_ids = [np.unique(read_labels(os.path.join(d, "pointProcAddressing")))
                 for d in procs]
    points = np.unique(np.concatenate(point_ids))
    faces = [read_labels(os.path.join(d, "faceProcAddressing")) for d in procs]
    cells = [read_labels(os.path.join(d, "cellProcAddressing")) for d in procs]
    all_cells = np.concatenate(cells)
    owned = np.concatenate([f[f > 0] - 1 for f in faces])
    flipped = np.concatenate([-f[f < 0] - 1 for f in faces])
    result = {
        "points": int(points.size),
        "pointsContiguous": bool(points[0] == 0 and points[-1] == points.size - 1),
        "cells": int(all_cells.size),
        "cellsContiguous": bool(np.array_equal(np.sort(all_cells),
                                               np.arange(all_cells.size))),
        "faces": int(np.unique(owned).size),
        "facesOwnedOnce": bool(np.unique(owned).size == owned.size),
        "facesContiguous": bool(np.array_equal(np.unique(owned),
                                               np.arange(np.unique(owned).size))),
        "processorFacesPaired": bool(np.isin(flipped, owned).all()),
    }
    result["ok"] = all(v for k, v in result.items() if isinstance(v, bool))
    return result


def directory_bytes(path):
    total = 0
    for root, _, files in os.walk(path):
        for name in files:
            total += os.path.getsize(os.path.join(root, name))
    return total


def add_wall_layers(case, layers):
    """The sphere tutorial's wall patch with prism layers"""
    path = os.path.join(case, "system", "pmshDict")
    with open(path) as f:
        text = f.read()
    text, n = re.subn(r"walls\s*\{\s*type\s+wall;\s*\}",
                      "walls { type wall; %s }" % layers, text)
    if n != 1:
        raise RuntimeError("%s: no 'walls { type wall; }' entry to add layers to" % path)
    with open(path, "w") as f:
        f.write(text)


def mode_massive(args, m=MASSIVE):
    geom = [g for g in GEOMETRIES if g["name"] == m["geometry"]][0]
    h_ref, cells_ref = m["reference"]
    h = round(h_ref*(cells_ref/m["targetCells"])**(1.0/3.0), 4)
    case = pb.make_case(args.work, m["results"], geom["tutorial"], h, m["levels"], "hxt")
    if "layers" in m:
        add_wall_layers(case, m["layers"])
    pb.log("Massive: %s, maxCellSize %g, r = %d, hxt, %d ranks, binary (target %.0f M cells)%s"
           % (geom["name"], h, m["levels"], m["ranks"], m["targetCells"]/1e6,
              ", walls: " + m["layers"] if "layers" in m else ""))
    run = pb.Run(pb.pmsh_command(args.pmshFoam, m["ranks"], case), case, "log.pmshFoam")
    res = {"machine": pb.machine_description(args), "maxCellSize": h,
           "refinementLevels": m["levels"], "ranks": m["ranks"], "wallTime": run.wall,
           "peakRssTreeBytes": run.max_rss, "ok": run.ok, "layers": m.get("layers", "")}
    json_name = m["results"] + ".json"
    if not run.ok:
        res["error"] = pb.first_error(run.text()) or run.tail()
        pb.log("FAILED: %s" % res["error"])
        write_json(args, json_name, res)
        return
    s = fc.summary(case)
    res["summary"] = s
    written = sum(directory_bytes(os.path.join(case, "processor%d" % p))
                  for p in range(m["ranks"]))
    res["writtenBytes"] = written
    res["writeMiBPerSecond"] = written/1048576.0/s["writeTime"]
    pb.log("  %d fine cells in %.0f s; peak %.2f GiB per rank; %.0f B per cell above base;"
           " wrote %.2f GiB at %.0f MiB/s"
           % (s["fineCells"], s["totalTime"], max(s["peakMemoryPerRankBytes"])/2**30,
              s["bytesPerFineCellAboveBase"], written/2**30, res["writeMiBPerSecond"]))

    # OpenFOAM's own check: checkMesh -parallel when both ranks' meshes fit
    # in memory together, else checkMesh on each processor directory in
    # turn (a serial run reads processor patches as plain patches)
    per_rank = max(s["fineCellsPerRank"])*CHECKMESH_BYTES_PER_CELL
    checks = []
    if m["ranks"]*per_rank < 0.9*mem_available():
        ok, non_ortho, avg, skew, text = check_mesh(case, m["ranks"])
        checks.append({"how": "checkMesh -parallel", "ok": ok, "maxNonOrtho": non_ortho,
                       "avgNonOrtho": avg, "maxSkewness": skew, "failed": failed_checks(text)})
    else:
        for p in range(m["ranks"]):
            ok, non_ortho, avg, skew, text = check_mesh(
                os.path.join(case, "processor%d" % p), 1)
            checks.append({"how": "checkMesh -case processor%d (serial)" % p, "ok": ok,
                           "maxNonOrtho": non_ortho, "avgNonOrtho": avg,
                           "maxSkewness": skew, "failed": failed_checks(text)})
    for c in checks:
        pb.log("  %s: %s" % (c["how"], "Mesh OK" if c["ok"] else "FAILED: " + "; ".join(c["failed"])))
    res["checkMesh"] = checks
    res["addressing"] = check_addressing(case, m["ranks"])
    pb.log("  procAddressing: %s" % ("OK" if res["addressing"]["ok"] else res["addressing"]))
    write_json(args, json_name, res)
    write_massive_markdown(args, res, m["results"] + ".md")
    # A case that failed a check stays for a look
    if not args.keep and all(c["ok"] for c in checks) and res["addressing"]["ok"]:
        shutil.rmtree(case, ignore_errors=True)


def failed_checks(text):
    """checkMesh's lines for the checks that failed ("***...")"""
    return [l.strip() for l in text.splitlines() if l.strip().startswith("***")]


def write_massive_markdown(args, res, name="massive.md"):
    s = res["summary"]
    stages = [[k, fmt(v["seconds"]), "%.2f" % (v["peakMemoryBytes"]/2**30)]
              for k, v in s["stages"].items()]
    per_rank = [["%d" % p, "%d" % c, "%.2f" % (b/2**30), "%.0f" % (b/c)]
                for p, (c, b) in enumerate(zip(s["fineCellsPerRank"],
                                               s["peakMemoryPerRankBytes"]))]
    checks = [[c["how"], "Mesh OK" if c["ok"] else
               " ".join(["FAILED"] + c.get("failed", [])),
               fmt(c["maxNonOrtho"], 1),
               fmt(c["avgNonOrtho"], 1), fmt(c["maxSkewness"], 2)] for c in res["checkMesh"]]
    a = res["addressing"]
    layered = bool(res.get("layers"))
    layer_rows = [
        "| prisms | %d |" % s["prisms"],
        "| wall faces with all their layers | %.2f %% |"
        % (100*min(p["coverage"] for p in s["layers"].values())),
        "| volume-mesher calls, largest (fine cells) | %d, %d |"
        % (sum(s["volumeMesherCallsPerRank"]), max(s["largestVolumeMesherCallPerRank"])),
    ] if layered else []
    text = "\n".join([
        "# Massive run%s: %.1f million cells on one machine, 2 ranks"
        % (" with prism layers" if layered else "", s["fineCells"]/1e6),
        "",
        "Measured by `bench/run --massive%s` (bench/scaleBench.py): sphere.geo, "
        "maxCellSize %g, r = %d, volumeMesher hxt, coarseMesher %s, binary, %d ranks%s."
        % ("-layers" if layered else "", res["maxCellSize"], res["refinementLevels"],
           s.get("coarseMesher", "netgen"), res["ranks"],
           "; the wall: `%s`" % res["layers"] if layered else ""),
        "",
        machine_table(res["machine"]),
        "",
        "| figure | value |",
        "|---|---:|",
        "| coarse cells | %d |" % s["coarseCells"],
        "| fine cells | %d |" % s["fineCells"],
        "| expected after stage 1 | %.0f (measured/expected %.2f) |"
        % (s["estimatedFineCells"], s["fineCells"]/s["estimatedFineCells"]),
        "| wall time, whole command (s) | %.0f |" % res["wallTime"],
        "| total of the stages (s) | %.0f |" % s["totalTime"],
        "| fine cells/s per core (stages 2-6) | %.0f |" % s["fineCellsPerSecondPerCore"],
        "| peak memory, largest rank (GiB) | %.2f (expected %.2f) |"
        % (max(s["peakMemoryPerRankBytes"])/2**30, s["estimatedPeakMemoryPerRankBytes"]/2**30),
        "| bytes per fine cell, all ranks | %.0f |" % s["bytesPerFineCell"],
        "| bytes per fine cell above the stage-1 base, largest | %.0f |"
        % s["bytesPerFineCellAboveBase"],
        "| written (GiB) | %.2f |" % (res["writtenBytes"]/2**30),
        "| write throughput (MiB/s) | %.0f |" % res["writeMiBPerSecond"],
    ] + layer_rows + [
        "",
        "## Stages",
        "",
        pb.md_table(["stage", "seconds (largest rank)", "peak GiB so far"], stages),
        "",
        "## Ranks",
        "",
        pb.md_table(["rank", "fine cells", "peak GiB", "bytes per cell"], per_rank),
        "",
        "## Accepted by OpenFOAM",
        "",
        pb.md_table(["check", "result", "max non-ortho", "avg non-ortho", "max skewness"],
                    checks),
        "",
        "procAddressing (the tests' checks, with numpy): %d global points %s, %d cells %s, "
        "%d faces %s, each owned once: %s, every processor face paired: %s."
        % (a["points"], "contiguous" if a["pointsContiguous"] else "NOT contiguous",
           a["cells"], "contiguous" if a["cellsContiguous"] else "NOT contiguous",
           a["faces"], "contiguous" if a["facesContiguous"] else "NOT contiguous",
           a["facesOwnedOnce"], a["processorFacesPaired"]),
        "",
    ])
    write_text(args, name, text)


# ---------------------------------------------------------------------------
# --scaling
# ---------------------------------------------------------------------------

# The same problem on P = 1..64 ranks: sphere.geo with some 8000 coarse
# cells (about 120 per rank at P = 64), r = 2
SCALING = {"geometry": "sphere", "maxCellSize": 0.12, "levels": 2,
           "ranks": [1, 2, 4, 8, 16, 32, 64]}
# Per-core rates: the same coarse mesh refined once more, on 1 and 2 ranks
RATE_LEVELS = 3

# The fine stage's time per rank as a power law of its fine cells, fitted per
# volume mesher from serial runs of sphere.geo at sizes (maxCellSize, r) other
# than those of the runs the model is checked on (0.12 at r = 2 and 3), each
# repeated FINE_FIT_REPEAT times (median). Netgen's volume meshing is strongly
# superlinear in the cells it meshes at once, hxt's nearly linear.
FINE_FIT = {"netgen": [(0.24, 2), (0.2, 2), (0.16, 2), (0.14, 2), (0.13, 2)],
            "hxt": [(0.2, 2), (0.16, 2), (0.2, 3), (0.16, 3)]}
FINE_FIT_REPEAT = 3
# Netgen's exponent is not one number: its time is dominated by the point
# insertion of its Delaunay fill (AddDelaunayPoint's search of an ADTree),
# whose cost per point grows with the mesh, so that the local exponent rises
# (measured: 1.25 at 46k-187k cells, 1.5 at 187k-250k, 1.75 at 250k-372k,
# 2.1 at 250k-385k). The fit takes the
# sizes with at least this many cells, the range of the partitions the model
# is checked on (200k-400k); the smaller ones are measured and shown.
FINE_FIT_MIN_CELLS = {"netgen": 100000, "hxt": 0}

# The machine is shared: before each timed run wait (up to QUIET_WAIT s) for
# the 1-minute load to fall to QUIET_LOAD
QUIET_LOAD = 1.2
QUIET_WAIT = 600

# Assumed for the paper's machine (NTNU Vilje, SGI ICE X, FDR InfiniBand)
NETWORK = {"latency": 2e-6, "bandwidth": 5e9}
# The paper's serial Netgen rate on one Vilje core (section 5)
PAPER_NETGEN_RATE = 0.23e6/60.0


def wait_for_quiet(args):
    """Wait (QUIET_WAIT s at most) until the 1-minute load is QUIET_LOAD or
    less: other work shares the cores. Returns the seconds waited"""
    waited = 0
    while getattr(args, "quiet", True) and pb.load1() > QUIET_LOAD and waited < QUIET_WAIT:
        if waited == 0:
            pb.log("    load %.2f > %.1f: waiting (at most %d s)"
                   % (pb.load1(), QUIET_LOAD, QUIET_WAIT))
        time.sleep(30)
        waited += 30
    if waited:
        pb.log("    waited %d s, load now %.2f" % (waited, pb.load1()))
    return waited


def cpu_seconds(timefile):
    """User + system seconds from a GNU time -v report"""
    total = None
    try:
        with open(timefile) as f:
            for line in f:
                m = re.match(r"\s*(User|System) time \(seconds\): ([0-9.]+)", line)
                if m:
                    total = (total or 0.0) + float(m.group(2))
    except OSError:
        pass
    return total


def run_scaling_case(args, ranks, levels, volume, coarse_mesher, h=None, tag=""):
    geom = [g for g in GEOMETRIES if g["name"] == SCALING["geometry"]][0]
    h = SCALING["maxCellSize"] if h is None else h
    name = "scaling-%s-%s-h%g-r%d-np%d%s" % (volume, coarse_mesher, h, levels, ranks, tag)
    case = pb.make_case(args.work, name, geom["tutorial"], h, levels, volume)
    pb.set_entry(os.path.join(case, "system", "pmshDict"), "coarseMesher", coarse_mesher)
    waited = wait_for_quiet(args)
    run = pb.Run(pb.pmsh_command(args.pmshFoam, ranks, case), case, "log.pmshFoam")
    row = {"ranks": ranks, "r": levels, "maxCellSize": h, "volumeMesher": volume,
           "coarseMesher": coarse_mesher, "wallTime": run.wall, "load": run.load_before,
           "waitedForLoad": waited}
    s = fc.summary(case)
    if not run.ok or s is None:
        row["error"] = pb.first_error(run.text()) or run.tail()
        pb.log("    FAILED P=%d: %s" % (ranks, row["error"]))
        return row
    # The cores the run had: CPU seconds of the whole command over its wall
    # time and ranks (below 1: other work shared the cores)
    cpu = cpu_seconds(run.timefile)
    row["cpuSeconds"] = cpu
    row["cpuShare"] = cpu/(run.wall*ranks) if cpu is not None and run.wall else None
    cells = s["fineCellsPerRank"]
    mean = s["fineCells"]/float(ranks)
    # Processor faces per rank, from the boundary files written
    proc_faces, neighbours = [], []
    for p in range(ranks if ranks > 1 else 0):
        with open(os.path.join(case, "processor%d" % p, "constant", "polyMesh",
                               "boundary")) as f:
            text = f.read()
        found = re.findall(r"procBoundary\d+to\d+\s*\{[^}]*?nFaces\s+(\d+)", text)
        proc_faces.append(sum(int(n) for n in found))
        neighbours.append(len(found))
    row.update({
        "coarseCells": s["coarseCells"], "fineCells": s["fineCells"],
        "fineCellsPerRank": cells, "balance": max(cells)/mean,
        "stages": {k: v["seconds"] for k, v in s["stages"].items()},
        "stageSecondsPerRank": {k: v["secondsPerRank"] for k, v in s["stages"].items()},
        "fineCellsPerSecondPerCore": s["fineCellsPerSecondPerCore"],
        "peakMemoryPerRankBytes": s["peakMemoryPerRankBytes"],
        "broadcastBytes": s.get("broadcastBytes", 0),
        "messagesPerRank": s.get("messagesPerRank", []),
        "bytesSentPerRank": s.get("bytesSentPerRank", []),
        "processorFacesPerRank": proc_faces, "neighboursPerRank": neighbours,
        "totalTime": s["totalTime"], "coarseTime": s["coarseTime"],
        "fineTime": s["fineTime"], "writeTime": s["writeTime"],
        "volumeAttemptsPerRank": s.get("volumeAttemptsPerRank"),
    })
    pb.log("    P=%-3d %-6s h=%g r=%d: %8d cells, max/mean %.3f, fine %.2f s, messages/rank"
           " max %d, bytes/rank max %.0f, load %.2f, cpu share %.2f"
           % (ranks, volume, h, levels, s["fineCells"], row["balance"], s["fineTime"],
              max(row["messagesPerRank"] or [0]), max(row["bytesSentPerRank"] or [0]),
              run.load_before, row["cpuShare"] or float("nan")))
    if not args.keep:
        shutil.rmtree(case, ignore_errors=True)
    return row


def fit_power(xs, ys):
    """y = a x^b through the points (least squares in log space)"""
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    n = float(len(xs))
    mx, my = sum(lx)/n, sum(ly)/n
    sxx = sum((x - mx)**2 for x in lx)
    b = sum((x - mx)*(y - my) for x, y in zip(lx, ly))/sxx if sxx > 0 else 1.0
    return math.exp(my - b*mx), b


class Model:
    """pmshFoam's wall time (stages 1-5, I/O excluded as in the paper) on P
    cores of a cluster, from per-stage costs measured here:

      coarse(Nc)           = a Nc^b       (Netgen surface + fill, master alone)
      broadcast(Nc, P)     = ceil(log2 P) (latency + bytesPerCoarseCell Nc / bandwidth)
      partition(Nc, P)     = c Nc (1 + d log2 P)   (metis on the master)
      fine(F, P)           = k (balance F / P)^e  (stages 3-4, one core per rank:
                             k, e per volume mesher from serial runs at three
                             or more sizes; Netgen's e well above 1)
      numbering(F, P)      = the per-rank time measured here at the same fine
                             cells per rank, plus the messages' latency and
                             bandwidth on the cluster's network
    """

    def __init__(self, coarse_fit, partition_fit, bytes_per_coarse_cell, fine_fit, balance,
                 numbering_per_cell, messages_per_rank, bytes_per_fine_cell_sent, speed):
        self.coarse_fit = coarse_fit
        self.partition_fit = partition_fit
        self.bytes_per_coarse_cell = bytes_per_coarse_cell
        self.fine_fit = fine_fit     # (k, e): seconds = k cells^e per rank
        self.balance = balance
        self.numbering_per_cell = numbering_per_cell
        self.messages_per_rank = messages_per_rank
        self.bytes_per_fine_cell_sent = bytes_per_fine_cell_sent
        self.speed = speed      # the cluster's core over this machine's

    def stages(self, coarse_cells, fine_cells, P, network=NETWORK, speed=None):
        speed = self.speed if speed is None else speed
        a, b = self.coarse_fit
        c, d = self.partition_fit
        k, e = self.fine_fit
        steps = math.ceil(math.log2(P)) if P > 1 else 0
        per_rank = self.balance(P)*fine_cells/P
        return {
            "coarse": a*coarse_cells**b/speed,
            "broadcast": steps*(network["latency"] + self.bytes_per_coarse_cell*coarse_cells
                                / network["bandwidth"]),
            "partition": c*coarse_cells*(1 + d*math.log2(P))/speed if P > 1 else 0.0,
            "fine": k*per_rank**e/speed,
            "numbering": (per_rank*self.numbering_per_cell/speed
                          + (self.messages_per_rank(P)*network["latency"]
                             + per_rank*self.bytes_per_fine_cell_sent/network["bandwidth"])
                          if P > 1 else per_rank*self.numbering_per_cell/speed),
        }

    def total(self, coarse_cells, fine_cells, P, **kw):
        return sum(self.stages(coarse_cells, fine_cells, P, **kw).values())


def load_coarse_fits(args):
    """Stage 1 and 2 costs from coarse-stage.json (bench/run --coarse)"""
    path = os.path.join(args.out, "coarse-stage.json")
    with open(path) as f:
        data = json.load(f)
    fits = {}
    for mesher in ("netgen", "hxt"):
        rows = [r for r in data["stages"] if r["coarseMesher"] == mesher and "error" not in r]
        fits[mesher] = {
            "coarse": fit_power([r["coarseCells"] for r in rows],
                                [r["coarseTime"] for r in rows]),
            "partitionPerCell": sum(r["partitionTime"]/r["coarseCells"] for r in rows)/len(rows),
            "rate": sum(r["coarseCells"]/r["coarseTime"] for r in rows
                        if r["geometry"] == "sphere")/max(1, len([r for r in rows
                                                                 if r["geometry"] == "sphere"])),
        }
    return fits


SCALING_PARTS = ("runs", "rates", "fit")


def run_fine_fit(args, kept):
    """The serial runs of FINE_FIT, args.repeat times each, less the runs of
    that size already in kept (one round of every size after the other, so
    that a slow spell of the machine does not fall on one size alone)"""
    def have(mesher, h, levels):
        return len([r for r in kept + rows if "error" not in r and r["volumeMesher"] == mesher
                    and r["maxCellSize"] == h and r["r"] == levels])
    rows = []
    for i in range(args.repeat):
        for mesher, sizes in FINE_FIT.items():
            for h, levels in sizes:
                if have(mesher, h, levels) >= args.repeat:
                    continue
                row = run_scaling_case(args, 1, levels, mesher, mesher, h=h,
                                       tag="-%d" % have(mesher, h, levels))
                row["repeat"] = i
                rows.append(row)
    return rows


def mode_scaling(args):
    """All of --scaling, or (--parts, --ranks) some of it: the rest is kept
    from the scaling.json in --out, marked with the session that measured it"""
    parts = [p for p in args.parts.split(",") if p] if args.parts else list(SCALING_PARTS)
    unknown = set(parts) - set(SCALING_PARTS)
    if unknown:
        sys.exit("Error: --parts: unknown %s (known: %s)"
                 % (",".join(sorted(unknown)), ",".join(SCALING_PARTS)))
    ranks = [int(p) for p in args.ranks.split(",")] if args.ranks else SCALING["ranks"]
    machine = pb.machine_description(args)
    res = {"machine": machine, "network": NETWORK, "problem": SCALING,
           "sessions": [machine], "runs": [], "rates": [], "fineFit": []}
    now = 0
    if set(parts) != set(SCALING_PARTS) or ranks != SCALING["ranks"]:
        with open(os.path.join(args.out, "scaling.json")) as f:
            old = json.load(f)
        sessions = old.get("sessions") or [old["machine"]]
        now = len(sessions)
        res["sessions"] = sessions + [machine]
        for key in ("runs", "rates", "fineFit"):
            res[key] = old.get(key, [])
            for r in res[key]:
                r.setdefault("session", 0)
    if "runs" in parts:
        pb.log("Same problem, P = %s (hxt)" % ranks)
        new = [run_scaling_case(args, P, SCALING["levels"], "hxt", args.coarseMesher)
               for P in ranks]
        for r in new:
            r["session"] = now
        res["runs"] = sorted([r for r in res["runs"] if r["ranks"] not in ranks] + new,
                             key=lambda r: r["ranks"])
    if "rates" in parts:
        pb.log("Per-core rates, r = %d, P = 1, 2" % RATE_LEVELS)
        res["rates"] = []
        for volume in ("hxt", "netgen"):
            for P in (1, 2):
                levels = RATE_LEVELS if volume == "hxt" else SCALING["levels"]
                mesher = "hxt" if volume == "hxt" else "netgen"
                row = run_scaling_case(args, P, levels, volume, mesher)
                row["session"] = now
                res["rates"].append(row)
    if "fit" in parts:
        pb.log("Fine stage against cells, serial, %d runs per size" % args.repeat)
        new = run_fine_fit(args, res["fineFit"])
        for r in new:
            r["session"] = now
        res["fineFit"] += new
    write_json(args, "scaling.json", res)
    write_scaling_markdown(args, res)


def fine_seconds(run):
    """Stages 3-4 (surface refinement + volume meshing) of the largest rank"""
    return run["stages"]["surface"] + run["stages"]["volume"]


def fine_fit_points(rows, mesher):
    """One point per size of the fit runs: medians of the fine cells and of
    the stage 3-4 seconds over its repeats"""
    groups = {}
    for r in rows:
        if r["volumeMesher"] == mesher and "error" not in r:
            groups.setdefault((r["maxCellSize"], r["r"]), []).append(r)
    points = []
    for (h, levels), g in groups.items():
        seconds = [fine_seconds(r) for r in g]
        points.append({"maxCellSize": h, "r": levels, "runs": len(g),
                       "fineCells": statistics.median(r["fineCells"] for r in g),
                       "seconds": statistics.median(seconds),
                       "min": min(seconds), "max": max(seconds),
                       "loads": [r["load"] for r in g],
                       "cpuShares": [r.get("cpuShare") for r in g]})
    return sorted(points, key=lambda p: p["fineCells"])


def build_models(args, res):
    fits = load_coarse_fits(args)
    runs = [r for r in res["runs"] if "error" not in r]
    by_p = {r["ranks"]: r for r in runs}
    # Balance: measured max/mean at each P, the last one for larger P
    def balance(P):
        known = sorted(p for p in by_p if p <= P)
        return by_p[known[-1]]["balance"] if known else 1.0
    # Partition time grows with log2 P: fit d from the measured runs
    part = [(r["ranks"], r["stages"]["partition"]) for r in runs if r["ranks"] > 1]
    coarse_cells = runs[0]["coarseCells"]
    # ... from the smallest and the largest P measured (2 and 64)
    (p0, t0), (p1, t1) = part[0], part[-1]
    d = max(0.0, (t1/t0 - 1)/(math.log2(p1) - math.log2(p0))) if t0 > 0 else 0.0
    bytes_per_coarse = by_p[2]["broadcastBytes"]/coarse_cells if 2 in by_p else 60.0
    def messages(P):
        known = sorted(p for p in by_p if 1 < p <= P)
        return max(by_p[known[-1]]["messagesPerRank"]) if known else 0
    sent = [max(r["bytesSentPerRank"])/(max(r["fineCellsPerRank"])) for r in runs
            if r["ranks"] > 1]
    bytes_sent = max(sent) if sent else 0.0
    models, fine = {}, {}
    for mesher in ("netgen", "hxt"):
        rate_runs = [r for r in res["rates"] if r["volumeMesher"] == mesher and "error" not in r
                     and r["ranks"] == 1]
        if not rate_runs:
            continue
        r1 = rate_runs[0]
        points = fine_fit_points(res.get("fineFit", []), mesher)
        for p in points:
            p["inFit"] = p["fineCells"] >= FINE_FIT_MIN_CELLS.get(mesher, 0)
        used = [p for p in points if p["inFit"]]
        if len(used) >= 3:
            fine_fit = fit_power([p["fineCells"] for p in used], [p["seconds"] for p in used])
            fine[mesher] = {"fit": fine_fit, "points": points, "used": used, "from": "fit",
                            "allSizes": fit_power([p["fineCells"] for p in points],
                                                  [p["seconds"] for p in points])}
        else:
            # An older scaling.json without the fit runs: a constant rate
            # from the P = 1 run
            fine_fit = (fine_seconds(r1)/r1["fineCells"], 1.0)
            fine[mesher] = {"fit": fine_fit, "points": [], "from": "rate"}
        # Numbering's own work per fine cell of the largest rank, where there
        # are interfaces to number (P = 2)
        r2 = [r for r in res["rates"] if r["volumeMesher"] == mesher and "error" not in r
              and r["ranks"] == 2] or [r1]
        numbering_per_cell = r2[0]["stages"]["numbering"]/max(r2[0]["fineCellsPerRank"])
        a, b = fits[mesher]["coarse"]
        c = fits[mesher]["partitionPerCell"]
        models[mesher] = Model((a, b), (c/(1 + d), d), bytes_per_coarse, fine_fit, balance,
                               numbering_per_cell, messages, bytes_sent, 1.0)
    # The cluster's core speed relative to this machine's: the paper's
    # Netgen coarse rate against Netgen's here
    speed = PAPER_NETGEN_RATE/fits["netgen"]["rate"]
    return models, speed, fits, d, bytes_per_coarse, bytes_sent, fine


def session_of(res, r):
    """Which session measured a row ("s1", "s2", ...) when there are several"""
    return "s%d" % (r.get("session", 0) + 1) if len(res.get("sessions") or []) > 1 else ""


def sessions_text(res):
    sessions = res.get("sessions") or [res["machine"]]
    if len(sessions) == 1:
        return machine_table(sessions[0])
    keys = []
    for m in sessions:
        keys += [k for k in m if k not in keys]
    header = ["machine"] + ["s%d%s" % (i + 1, " (last)" if i == len(sessions) - 1 else "")
                            for i in range(len(sessions))]
    rows = [[k] + [str(m.get(k, "")) for m in sessions] for k in keys]
    measured = []
    for i in range(len(sessions)):
        what = [name for key, name in (("runs", "P = %s"), ("rates", "the r = 2, 3 runs on "
                                                              "P = 1, 2"),
                                       ("fineFit", "the fine-stage fit runs"))
                if any(r.get("session", 0) == i for r in res.get(key, []))]
        what = [w % ", ".join(str(r["ranks"]) for r in res["runs"]
                              if r.get("session", 0) == i) if "%s" in w else w for w in what]
        if what:
            measured.append("s%d measured %s." % (i + 1, "; ".join(what)))
    return "\n".join(["This report joins runs of %d sessions (`--parts`, `--ranks`): %s"
                      % (len(sessions), " ".join(measured)), "",
                      pb.md_table(header, rows)])


def scaling_rows(res, runs, several):
    """The table of the same problem on P ranks"""
    rows = []
    for r in runs:
        rows.append(["%d" % r["ranks"], "%d" % r["fineCells"],
                     "%d" % max(r["fineCellsPerRank"]), "%.3f" % r["balance"],
                     fmt(r["stages"]["partition"], 3),
                     "%d" % max(r["processorFacesPerRank"] or [0]),
                     "%d" % max(r["neighboursPerRank"] or [0]),
                     "%d" % max(r["messagesPerRank"] or [0]),
                     "%.0f" % (max(r["bytesSentPerRank"] or [0])/1024.0),
                     "%.0f" % (r["broadcastBytes"]/1024.0),
                     "%.0f" % (max(r["peakMemoryPerRankBytes"])/2**20),
                     fmt(r.get("load"), 2)] + ([session_of(res, r)] if several else []))
    return rows


def fine_fit_rows(fine):
    """The fine stage's fit points, and a line per volume mesher on its fit"""
    fit_rows, fit_text = [], []
    for mesher in ("netgen", "hxt"):
        if mesher not in fine:
            continue
        f = fine[mesher]
        for p in f["points"]:
            fit_rows.append([mesher, "%g" % p["maxCellSize"], "%d" % p["r"],
                             "%d" % p["fineCells"], fmt(p["seconds"]),
                             "%s-%s" % (fmt(p["min"]), fmt(p["max"])), "%d" % p["runs"],
                             ", ".join("%.2f" % l for l in p["loads"]),
                             ", ".join(fmt(c, 2) for c in p.get("cpuShares", [])),
                             "yes" if p.get("inFit") else "no"])
        k, e = f["fit"]
        if f["from"] == "fit":
            fit_text.append("%s: k = %.3g s, e = %.3f (n = %d to %d cells%s)"
                            % (mesher, k, e, f["used"][0]["fineCells"],
                               f["used"][-1]["fineCells"],
                               "; over every size measured, %d to %d, e would be %.2f"
                               % (f["points"][0]["fineCells"], f["points"][-1]["fineCells"],
                                  f["allSizes"][1])
                               if len(f["used"]) < len(f["points"]) else ""))
        else:
            fit_text.append("%s: no fit runs in scaling.json, a constant rate from its P = 1 "
                            "run (k = %.3g s, e = 1)" % (mesher, k))
    return fit_rows, fit_text


def model_checks(res, runs, models, several):
    """The model's error on the runs with one core per rank"""
    checks = []
    for r in [x for x in res["rates"] + runs if "error" not in x and x["ranks"] <= 2]:
        mesher = r["volumeMesher"]
        if mesher not in models:
            continue
        m = models[mesher]
        local = {"latency": 0, "bandwidth": float("inf")}
        predicted = m.total(r["coarseCells"], r["fineCells"], r["ranks"], network=local,
                            speed=1.0)
        predicted_fine = m.stages(r["coarseCells"], r["fineCells"], r["ranks"], network=local,
                                  speed=1.0)["fine"]
        measured = r["coarseTime"] + r["fineTime"]
        checks.append(["%s/%s" % (r["coarseMesher"], mesher), "%d" % r["r"],
                       "%d" % r["ranks"], "%d" % r["fineCells"],
                       "%d" % max(r["fineCellsPerRank"]), fmt(measured),
                       fmt(predicted), "%+.0f%%" % (100*(predicted/measured - 1)),
                       fmt(fine_seconds(r)), fmt(predicted_fine), fmt(r.get("load"), 2),
                       fmt(r.get("cpuShare"), 2)]
                      + ([session_of(res, r)] if several else []))
    return checks


def paper_projection(models, speed, runs):
    """The paper's Table 2 rows, projected; and the fine cells per rank of each"""
    projection, per_rank = [], []
    for row in pb.read_paper_table():
        if row["geometry"] not in ("sphere.geo", "shaft.geo", "sphere.stl"):
            continue
        Nc, F, P = row["coarseMcells"]*1e6, row["fineMcells"]*1e6, int(row["cores"])
        cells = ["%s" % row["geometry"], "%d" % P, "%d" % row["r"],
                 "%.1f" % row["coarseMcells"], "%.0f" % row["fineMcells"],
                 fmt(row["coarseTime"], 0), fmt(row["totalTime"], 0)]
        for mesher in ("netgen", "hxt"):
            if mesher in models:
                st = models[mesher].stages(Nc, F, P, speed=speed)
                cells += [fmt(st["coarse"], 0), fmt(st["fine"], 0), fmt(sum(st.values()), 0),
                          fmt(row["totalTime"]/sum(st.values()), 1)]
        per_rank.append(runs[-1]["balance"]*F/P)
        projection.append(cells)
    return projection, per_rank


def write_scaling_markdown(args, res):
    models, speed, fits, d, bytes_per_coarse, bytes_sent, fine = build_models(args, res)
    runs = [r for r in res["runs"] if "error" not in r]
    several = len(res.get("sessions") or []) > 1
    rows = scaling_rows(res, runs, several)
    fit_rows, fit_text = fine_fit_rows(fine)
    checks = model_checks(res, runs, models, several)
    projection, per_rank = paper_projection(models, speed, runs)
    # Sessions from before the wait for a quiet machine
    older = sorted(set(session_of(res, r) for k in ("runs", "rates", "fineFit")
                       for r in res.get(k, []) if "waitedForLoad" not in r))
    unwaited = ("; the runs of %s did not wait, and have no cpu share" % ", ".join(older)
                if older and several else "")
    # Netgen's local exponents, between successive sizes 20 % or more apart
    ng = fine.get("netgen", {}).get("points", [])
    steps, last = [], ng[0] if ng else None
    for p in ng[1:]:
        if p["fineCells"] >= 1.2*last["fineCells"]:
            steps.append("%.0fk-%.0fk: %.2f" % (
                last["fineCells"]/1e3, p["fineCells"]/1e3,
                math.log(p["seconds"]/last["seconds"])/math.log(p["fineCells"]/last["fineCells"])))
            last = p
    steep = (" Its local exponents, between sizes 20%% or more apart: %s." % ", ".join(steps)
             if steps else "")
    largest_fit = max([p["fineCells"] for p in fine.get("netgen", {}).get("points", [])] or [0])
    netgen_e = fine["netgen"]["fit"][1] if "netgen" in fine else float("nan")
    hxt_e = fine["hxt"]["fit"][1] if "hxt" in fine else float("nan")
    beyond = len([n for n in per_rank if n > largest_fit])
    text = "\n".join([
        "# Scaling: P = 1 to 64 measured, the paper's Table 2 projected",
        "",
        "Measured by `bench/run --scaling` (bench/scaleBench.py) on this 2-core machine; "
        "beyond 2 ranks the ranks share the cores, so those runs give work per rank, "
        "balance and messages, not time. The machine is shared: each timed run waits "
        "(at most %d s) for the 1-minute load to fall to %.1f; the load at its start is "
        "in the tables, and the cpu share, the run's CPU seconds over its wall time and "
        "ranks (below 1: it did not have its cores to itself)%s."
        % (QUIET_WAIT, QUIET_LOAD, unwaited),
        "",
        sessions_text(res),
        "",
        "## The same problem on P ranks",
        "",
        "sphere.geo, maxCellSize %g, r = %d, volumeMesher hxt, coarseMesher %s."
        % (SCALING["maxCellSize"], SCALING["levels"], args.coarseMesher),
        "",
        pb.md_table(["P", "fine cells", "largest rank", "max/mean", "partition (s)",
                     "processor faces (max)", "neighbours (max)", "messages (max)",
                     "KiB sent (max)", "broadcast KiB", "peak MiB", "load"]
                    + (["session"] if several else []), rows),
        "",
        "## The model",
        "",
        "```",
        Model.__doc__.strip(),
        "```",
        "",
        "Fitted here: coarse stage (netgen) %.3g Nc^%.2f s, (hxt) %.3g Nc^%.2f s; "
        "partition %.3g s per coarse cell (2 parts), growing by %.2f per doubling of P; "
        "broadcast %.0f bytes per coarse cell; %.1f bytes sent per fine cell of the largest "
        "rank in numbering and addressing; fine stage per rank k n^e, %s."
        % (fits["netgen"]["coarse"][0], fits["netgen"]["coarse"][1],
           fits["hxt"]["coarse"][0], fits["hxt"]["coarse"][1],
           fits["hxt"]["partitionPerCell"], d, bytes_per_coarse, bytes_sent,
           "; ".join(fit_text)),
        "",
        "### The fine stage: k n^e from serial runs",
        "",
        "Stages 3-4 (surface refinement and volume meshing) of serial runs of sphere.geo, "
        "coarse mesher = volume mesher, at sizes other than those of the runs the model "
        "is checked on below; per size the median of its runs, fitted by least squares "
        "in log-log. A constant rate (e = 1) is wrong for Netgen, whose volume meshing "
        "time grows much faster than its cells: on 2 ranks each rank meshes half the "
        "cells in a fraction of the serial time. Most of that time is Netgen's Delaunay "
        "fill inserting points (AddDelaunayPoint searching its ADTree: 30 of 45 stacks "
        "sampled with gdb in a serial 398k-cell run here), whose cost per point "
        "grows with the mesh: "
        "the local exponent rises with n, so one power law cannot hold over the whole "
        "range, and the fit takes the "
        "sizes of %s cells or more (netgen), the range of the partitions it is checked "
        "on.%s" % ("{:,}".format(FINE_FIT_MIN_CELLS["netgen"]), steep),
        "",
        pb.md_table(["volume mesher", "maxCellSize", "r", "fine cells n",
                     "stages 3-4 (s), median", "min-max (s)", "runs", "load at start",
                     "cpu share", "in fit"],
                    fit_rows),
        "",
        "Assumed for the paper's cluster: network latency %.0f us and bandwidth %.0f GB/s "
        "per link (FDR InfiniBand), a tree broadcast, one rank per core; the core's speed "
        "relative to this machine's from Netgen's coarse meshing rate, the paper's %.0f "
        "cells/s against %.0f here: factor %.2f, applied to every stage; the paper's fine "
        "cell counts; fine cells per rank balanced as measured here at the largest P "
        "(%.3f). "
        % (NETWORK["latency"]*1e6, NETWORK["bandwidth"]/1e9, PAPER_NETGEN_RATE,
           fits["netgen"]["rate"], speed, runs[-1]["balance"])
        + ("The fine stage of a rank is k n^e of its n = balance F / P fine cells, "
           "with this machine's k and e per volume mesher (netgen e = %.2f, hxt e = %.2f). "
           "Netgen's exponent is measured on partitions of up to %d cells here and "
           "extrapolated beyond: Table 2's configurations have %.0f k to %.1f M fine cells "
           "per rank, %d of its %d rows more than %d, where netgen's projected times rest "
           "on that extrapolation (a Netgen whose superlinearity levels off, or the paper's "
           "older Netgen, would be faster there)."
           % (netgen_e, hxt_e, largest_fit, min(per_rank)/1e3, max(per_rank)/1e6, beyond,
              len(per_rank), largest_fit)
           if fine.get("netgen", {}).get("from") == "fit" else
           "The fine stage is a constant rate per core (e = 1) from the P = 1 runs: this "
           "scaling.json has no fit runs."),
        "",
        "### Its error on the runs measured here (one core per rank)",
        "",
        "The whole model (stages 1-5, this machine's speed, no network) against the "
        "measured coarse + fine time; the fine stage (3-4) alone in the last columns. "
        "None of these runs is a fit point.",
        "",
        pb.md_table(["coarse/volume mesher", "r", "P", "fine cells", "largest rank",
                     "measured (s)", "model (s)", "error", "stages 3-4 measured (s)",
                     "stages 3-4 model (s)", "load", "cpu share"]
                    + (["session"] if several else []),
                    checks),
        "",
        "## The paper's Table 2 and pmshFoam projected",
        "",
        pb.md_table(["geometry", "cores", "r", "coarse M", "fine M", "paper coarse (s)",
                     "paper total (s)", "netgen: coarse (s)", "netgen: fine (s)",
                     "netgen: total (s)", "paper/netgen", "hxt: coarse (s)", "hxt: fine (s)",
                     "hxt: total (s)", "paper/hxt"],
                    projection),
        "",
    ])
    write_text(args, "scaling.md", text)


# ---------------------------------------------------------------------------
# Shared output
# ---------------------------------------------------------------------------

def machine_table(machine):
    return pb.md_table(["machine", ""], [[k, str(v)] for k, v in machine.items()])


def write_json(args, name, data):
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, name), "w") as f:
        json.dump(data, f, indent=1)


def write_text(args, name, text):
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, name)
    with open(path, "w") as f:
        f.write(text)
    pb.log("Written: %s" % path)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    group = parser.add_mutually_exclusive_group(required=True)
    for mode in ("coarse", "massive", "massive-layers", "scaling"):
        group.add_argument("--" + mode, dest="mode", action="store_const", const=mode)
    parser.add_argument("--out", default=os.path.join(pb.BENCH_DIR, "results"))
    parser.add_argument("--work", help="scratch directory (default: a new temporary one)")
    parser.add_argument("--pmshFoam", default=shutil.which("pmshFoam") or "pmshFoam")
    parser.add_argument("--note", default="")
    parser.add_argument("--keep", action="store_true", help="keep the scratch cases")
    parser.add_argument("--netgen-from-log", metavar="LOG",
                        help="--coarse: take coarseMesher netgen's rows from an earlier run's log")
    parser.add_argument("--no-build", action="store_true",
                        help="(bench/run: do not build first)")
    parser.add_argument("--coarseMesher", default="hxt",
                        help="coarse mesher of the --scaling runs (default hxt)")
    parser.add_argument("--parts", metavar="LIST",
                        help="--scaling: run only these of %s (comma-separated); the rest "
                        "is kept from the scaling.json in --out" % ",".join(SCALING_PARTS))
    parser.add_argument("--ranks", metavar="LIST",
                        help="--scaling: the P of the 'runs' part (default %s); the other "
                        "P are kept from the scaling.json in --out"
                        % ",".join(str(p) for p in SCALING["ranks"]))
    parser.add_argument("--repeat", type=int, default=FINE_FIT_REPEAT,
                        help="--scaling: runs per size of the fine-stage fit (median; "
                        "default %d)" % FINE_FIT_REPEAT)
    parser.add_argument("--no-wait", dest="quiet", action="store_false",
                        help="--scaling: do not wait for the load to fall to %.1f before "
                        "each run" % QUIET_LOAD)
    parser.add_argument("--rewrite", action="store_true",
                        help="--coarse, --scaling: only rewrite the report from its JSON")
    args = parser.parse_args()
    args.work = args.work or tempfile.mkdtemp(prefix="pmshFoam-%s-" % args.mode)
    os.makedirs(args.work, exist_ok=True)
    if args.rewrite:
        rewrite = {"scaling": write_scaling_markdown, "coarse": write_coarse_markdown}
        with open(os.path.join(args.out, "%s.json" % {"scaling": "scaling",
                                                       "coarse": "coarse-stage"}[args.mode])) as f:
            rewrite[args.mode](args, json.load(f))
        return
    {"coarse": mode_coarse, "massive": mode_massive,
     "massive-layers": lambda a: mode_massive(a, MASSIVE_LAYERS),
     "scaling": mode_scaling}[args.mode](args)


if __name__ == "__main__":
    main()
