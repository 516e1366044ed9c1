#!/usr/bin/env python3
"""pmshFoam benchmark: pmshFoam against its peers in one run.

Runs pmshFoam on the sphere, shaft and sphereSTL tutorials at r = 1, 2(, 3)
with P = 1 and 2 ranks, reads each run's postProcessing/pmshFoam/summary.json,
and measures, at matched cell counts (within 20 %):

  (a) Netgen serial: pmshFoam itself, serial, refinementLevels 0 and
      maxCellSize about the fine size, so that stage 1 (the coarse mesh) is
      Netgen meshing the geometry directly at the fine size. The run is
      stopped once stage 1 is over (the rest would remesh the same volume);
      cells and seconds are stage 1's.
  (b) gmsh HXT, 2 threads, on pmshFoam's own fine boundary surface, then
      gmshToFoam, then decomposePar (simple, 2 subdomains): the time from a
      surface to a parallel-ready case.
  (c) PMSH's published Table 2 (bench/paperTable2.csv): per-core rates.

Writes results.md, runs.csv, peers.csv, ratios.csv, results.json and two
PNG plots into the output directory. Started by bench/run; see
bench/README.md.
"""

import argparse
import csv
import datetime
import json
import math
import os
import platform
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

# The case helpers every bench script shares; pb.set_entry, pb.check_mesh
# etc. for the scripts that import this module as pb
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tools"))
from foamCase import (BENCH_DIR, ROOT, check_mesh, copy_case, copy_tutorial,  # noqa: E402,F401
                       mpi, set_entry, summary)

# What is measured (geometries, modes, ranks, targets) and how it is reported
from benchPlan import (GEOMETRIES, MATCH_TOLERANCE, MODES,  # noqa: E402,F401
                       PAPER_NETGEN_SERIAL_RATE, RANKS, TARGET_BYTES_PER_CELL_PER_RANK,
                       TARGET_RATE_VS_NETGEN, TARGET_SPEEDUP_1_TO_2)
from benchReport import (PEER_COLUMNS, RUN_COLUMNS, compute_ratios,  # noqa: E402,F401
                         fmt, make_plots, md_table, mib, target_value, verdict,
                         write_csv, write_markdown)

SEARCH_TOLERANCE = 0.15     # what the size searches aim for ...
SLOW_RUN = 60.0             # ... unless a run takes longer than this: then 20 %
MAX_SEARCH_RUNS = 5         # size search runs per peer and case (set by the mode)


# ---------------------------------------------------------------------------
# Small helpers
# ---------------------------------------------------------------------------

def log(msg=""):
    print(msg, flush=True)


def load1():
    """The 1-minute load average (other work on the machine)"""
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return float("nan")


def command_output(cmd):
    try:
        out = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True, timeout=60)
        return out.stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""


def parse_time_v(path):
    """Wall clock seconds and max RSS (bytes) from a GNU time -v report"""
    wall, rss = None, None
    try:
        with open(path) as f:
            for line in f:
                line = line.strip()
                if line.startswith("Maximum resident set size"):
                    rss = int(line.split(":")[1])*1024
                elif line.startswith("Elapsed (wall clock) time"):
                    value = line.rsplit(" ", 1)[1]
                    parts = [float(p) for p in value.split(":")]
                    wall = 0.0
                    for p in parts:
                        wall = wall*60 + p
    except OSError:
        pass
    return wall, rss


def first_error(text):
    """The line that says what went wrong, from a log's text"""
    lines = [l.strip() for l in (text or "").splitlines()]
    for pattern in (r"Signal: ", r"exited on signal", r"FOAM FATAL"):
        for i, l in enumerate(lines):
            if re.search(pattern, l):
                if pattern == r"FOAM FATAL":
                    rest = [x for x in lines[i + 1:i + 4] if x]
                    return (l + " " + " ".join(rest)).strip()
                return re.sub(r"^\[[^]]*\]\s*", "", l)
    for l in reversed(lines):
        if re.search(r"rror|fail", l, re.I):
            return l
    return ""


def child_pids(pid):
    pids = []
    try:
        for task in os.listdir("/proc/%d/task" % pid):
            with open("/proc/%d/task/%s/children" % (pid, task)) as f:
                pids += [int(p) for p in f.read().split()]
    except OSError:
        pass
    return pids


class Run:
    """One command run under GNU time -v, its output into a log file"""

    def __init__(self, cmd, cwd, logname, stop_pattern=None):
        self.cmd = cmd
        self.cwd = cwd
        self.log = os.path.join(cwd, logname)
        self.timefile = self.log + ".time"
        self.stopped = False
        self.load_before = load1()
        full = ["/usr/bin/time", "-v", "-o", self.timefile, "stdbuf", "-oL"] + cmd
        start = time.perf_counter()
        with open(self.log, "w") as out:
            proc = subprocess.Popen(full, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                                    stdin=subprocess.DEVNULL)
            if stop_pattern is None:
                proc.wait()
            else:
                # Stop the command (the child of time, by its id) as soon as
                # its log shows stop_pattern: time still reports its usage
                regex = re.compile(stop_pattern, re.M)
                while proc.poll() is None:
                    time.sleep(0.1)
                    with open(self.log, errors="replace") as f:
                        if regex.search(f.read()):
                            for pid in child_pids(proc.pid):
                                try:
                                    os.kill(pid, signal.SIGTERM)
                                except OSError:
                                    pass
                            self.stopped = True
                            proc.wait()
                            break
        self.wall = time.perf_counter() - start
        self.rc = proc.returncode
        self.load_after = load1()
        _, self.max_rss = parse_time_v(self.timefile)

    @property
    def ok(self):
        return self.rc == 0 or self.stopped

    def text(self):
        with open(self.log, errors="replace") as f:
            return f.read()

    def tail(self, n=15):
        return "\n".join(self.text().splitlines()[-n:])


# ---------------------------------------------------------------------------
# pmshFoam runs
# ---------------------------------------------------------------------------

def make_case(work, name, tutorial, max_cell_size, levels, mesher):
    """A copy of a tutorial with the given mesh settings (binary output)"""
    case = copy_tutorial(tutorial, os.path.join(work, name), ("polyMesh", ".polyMesh*"),
                         ("0", "constant", "system"))
    dict_path = os.path.join(case, "system", "pmshDict")
    set_entry(dict_path, "maxCellSize", "%.6g" % max_cell_size)
    set_entry(dict_path, "refinementLevels", str(levels))
    set_entry(dict_path, "volumeMesher", mesher)
    set_entry(os.path.join(case, "system", "controlDict"), "writeFormat", "binary")
    return case


def pmsh_command(exe, ranks, case):
    return mpi(ranks, [exe, "-case", case])


def run_pmsh(args, geom, levels, max_cell_size, ranks, mesher):
    name = "%s-r%d-np%d-%s" % (geom["name"], levels, ranks, mesher)
    case = make_case(args.work, name, geom["tutorial"], max_cell_size, levels, mesher)
    run = Run(pmsh_command(args.pmshFoam, ranks, case), case, "log.pmshFoam")
    row = {
        "geometry": geom["name"], "mesher": mesher, "r": levels,
        "maxCellSize": max_cell_size, "ranks": ranks, "ok": run.ok,
        "wallTime": round(run.wall, 3),
        "loadBefore": run.load_before, "loadAfter": run.load_after, "case": case,
    }
    s = summary(case)
    if not run.ok or s is None:
        row["ok"] = False
        row["error"] = first_error(run.text()) or run.tail()
        log("    FAILED (%s), see %s" % (name, run.log))
        return row
    retries = volume_retries(s, run.text())
    if retries:
        row["volumeRetries"] = retries
    row.update({
        "coarseCells": s["coarseCells"],
        "fineCells": s["fineCells"],
        "fineCellsPerRank": s.get("fineCellsPerRank", []),
        "coarseTime": s["coarseTime"],
        "fineTime": s["fineTime"],
        "paperTotal": s["coarseTime"] + s["fineTime"],
        "writeTime": s["writeTime"],
        "totalTime": s["totalTime"],
        "stages": {k: v["seconds"] for k, v in s["stages"].items()},
        "fineCellsPerSecondPerCore": s["fineCellsPerSecondPerCore"],
        "peakMemoryPerRankBytes": s.get("peakMemoryPerRankBytes", []),
        "bytesPerFineCell": s["bytesPerFineCell"],
        "baselineMemoryBytes": s["stages"].get("coarse", {}).get("peakMemoryBytes"),
        "peakRssTreeBytes": run.max_rss,
    })
    memory_fields(row)
    log("    %-10s r=%d P=%d %-6s: %9d cells (coarse %d) coarse %.2f s, fine %.2f s, "
        "write %.2f s, %.0f cells/s/core, %.0f B/cell/rank, load %.1f"
        % (geom["name"], levels, ranks, mesher, row["fineCells"], row["coarseCells"],
           row["coarseTime"], row["fineTime"], row["writeTime"],
           row["fineCellsPerSecondPerCore"], row["bytesPerFineCellPerRankMax"] or 0,
           run.load_before))
    return row


def volume_retries(summary, log_text):
    """Partitions whose volume meshing needed more than one attempt, from
    summary.json (volumeMesherPerRank, volumeAttemptsPerRank); from the log
    for a pmshFoam whose summary lacks them"""
    attempts = summary.get("volumeAttemptsPerRank")
    if attempts is None:
        found = re.findall(r"partition (\d+) meshed by (\w+) at attempt (\d+)", log_text)
    else:
        found = [(str(p), summary["volumeMesherPerRank"][p], "%d" % a)
                 for p, a in enumerate(attempts) if a > 1]
    return "; ".join("partition %s: %s at attempt %s" % r for r in found)


def memory_fields(row):
    """Peak memory per rank and bytes per fine cell of the worst rank.

    pmshFoam's summary.json reports each rank's own VmHWM; volume meshing may
    run in a forked child whose memory that misses. GNU time's maximum
    resident set size covers the whole process tree (the largest single
    process in it), so the peak per rank is taken as the larger of the two;
    with several ranks the tree's largest process is paired with the rank
    that has the most fine cells."""
    cells = row.get("fineCellsPerRank") or []
    memory = row.get("peakMemoryPerRankBytes") or []
    own = [m/c for m, c in zip(memory, cells) if c > 0]
    row["summaryBytesPerFineCellPerRankMax"] = max(own) if own else None
    tree = row.get("peakRssTreeBytes")
    row["peakMemoryMaxBytes"] = max(memory + ([tree] if tree else [])) if memory or tree else None
    per_rank = list(own)
    if tree and cells and max(cells) > 0:
        per_rank.append(tree/float(max(cells)))
    row["bytesPerFineCellPerRankMax"] = max(per_rank) if per_rank else None
    # Above the baseline (libraries, MPI, the coarse mesh: the peak after
    # stage 1), what each further fine cell costs
    base = row.get("baselineMemoryBytes")
    above = [(m - base)/c for m, c in zip(memory, cells) if c > 0] if base else []
    row["bytesPerFineCellAboveBaseline"] = max(above) if above else None
    return row


def hxt_available(args):
    """Whether this pmshFoam accepts 'volumeMesher hxt;' (a tiny serial run)"""
    case = make_case(args.work, "hxt-probe", "sphere", 0.6, 1, "hxt")
    run = Run([args.pmshFoam, "-case", case], case, "log.pmshFoam")
    if run.rc == 0:
        return True, ""
    text = run.text()
    m = re.search(r"FOAM FATAL ERROR.*?(?:\n\s*\n|\Z)", text, re.S)
    return False, (m.group(0) if m else run.tail(6)).strip()



# ---------------------------------------------------------------------------
# Size search for the peers: a size (larger -> fewer cells) that gives
# pmshFoam's cell count
# ---------------------------------------------------------------------------

def next_size(tries, target):
    """The next size to try, from (size, cells) pairs: cells ~ size^-3,
    log-log interpolation once the target is bracketed"""
    h, n = tries[-1]
    many = [t for t in tries if t[1] > target]     # size too small
    few = [t for t in tries if t[1] < target]      # size too large
    if many and few:
        h1, n1 = max(many)
        h2, n2 = min(few)
        if h1 < h2 and n1 > n2:
            x = (math.log(target) - math.log(n1))/(math.log(n2) - math.log(n1))
            return math.exp(math.log(h1) + x*(math.log(h2) - math.log(h1)))
        return math.sqrt(h1*h2)     # cell counts are not monotonic here
    return h*min(max((n/float(target))**(1/3.0), 0.75), 1.33)


def search_size(run_one, h0, target):
    """run_one(size, attempt) -> row with ok, cells, cellRatio, seconds.
    Returns (rows, the row closest to target)"""
    rows, tries, best = [], [], None
    h = h0
    for attempt in range(MAX_SEARCH_RUNS):
        row = run_one(h, attempt)
        rows.append(row)
        if not row.get("ok"):
            break
        tries.append((h, row["cells"]))
        error = abs(row["cellRatio"] - 1)
        if best is None or error < abs(best["cellRatio"] - 1):
            best = row
        if error <= SEARCH_TOLERANCE or \
           (error <= MATCH_TOLERANCE and row.get("seconds", 0) > SLOW_RUN):
            break
        h = next_size(tries, target)
    if best is not None:
        best["final"] = True
    return rows, best

# ---------------------------------------------------------------------------
# Peer (a): Netgen serial at the fine size
# ---------------------------------------------------------------------------

def run_netgen_serial(args, geom, levels, target, h, tag):
    name = "%s-r%d-netgenSerial-%s" % (geom["name"], levels, tag)
    case = make_case(args.work, name, geom["tutorial"], h, 0, "netgen")
    run = Run([args.pmshFoam, "-case", case], case, "log.pmshFoam",
              stop_pattern=r"^Stage 2")
    text = run.text()
    m_cells = re.search(r"^Stage 1.*?coarse cells: (\d+)", text, re.S | re.M)
    m_time = re.search(r"^Stage 1.*?time: ([0-9.eE+-]+) s", text, re.S | re.M)
    row = {
        "peer": "netgenSerial", "geometry": geom["name"], "r": levels, "forMesher": "netgen",
        "setting": "maxCellSize", "value": h, "targetCells": target,
        "loadBefore": run.load_before, "loadAfter": run.load_after,
        "peakMemoryBytes": run.max_rss, "case": case,
    }
    if not (m_cells and m_time):
        row.update({"ok": False, "error": run.tail()})
        log("    netgen serial FAILED, see %s" % run.log)
        return row
    cells, seconds = int(m_cells.group(1)), float(m_time.group(1))
    row.update({
        "ok": True, "cells": cells, "time": seconds, "seconds": run.wall,
        "cellsPerSecondPerCore": cells/seconds if seconds > 0 else None,
        "bytesPerCell": run.max_rss/cells if run.max_rss and cells else None,
        "cellRatio": cells/target,
    })
    log("      netgen serial maxCellSize %.4g: %d cells (%.2fx target) in %.2f s, "
        "%.0f cells/s, load %.1f"
        % (h, cells, cells/target, seconds, row["cellsPerSecondPerCore"], run.load_before))
    return row


# ---------------------------------------------------------------------------
# Peer (b): gmsh HXT (2 threads) + gmshToFoam + decomposePar
# ---------------------------------------------------------------------------

GMSH_GEO = """// pmshFoam bench: fill pmshFoam's fine boundary surface with gmsh HXT
Merge "surface.stl";
Surface Loop(1) = Surface{{:}};
Volume(1) = {{1}};
{physicals}
Physical Volume("internal") = {{1}};
Mesh.Algorithm3D = 10;                  // HXT
Mesh.MeshSizeExtendFromBoundary = 0;    // interior size from MeshSizeMax
Mesh.MeshSizeMax = {size:.6g};
Mesh.MshFileVersion = 2.2;              // what gmshToFoam reads
Mesh 3;
Coherence Mesh;                         // gmsh 4.8.4 HXT with 2 threads can duplicate nodes
Save "mesh.msh";
"""

DECOMPOSE_PAR_DICT = """FoamFile
{
    version     2.0;
    format      ascii;
    class       dictionary;
    location    "system";
    object      decomposeParDict;
}

numberOfSubdomains 2;
method          simple;
simpleCoeffs
{
    n           (2 1 1);
    delta       0.001;
}
"""


def stl_solids(path):
    names, facets = [], 0
    with open(path) as f:
        for line in f:
            s = line.strip()
            if s.startswith("solid"):
                names.append(s[5:].strip() or "patch%d" % len(names))
            elif s.startswith("facet"):
                facets += 1
    return names, facets


def export_surface(args, pmsh_case, dest):
    """pmshFoam's fine boundary (serial mesh) as an ascii STL, one solid a patch"""
    run = Run(["foamToSurface", "-case", pmsh_case, "-constant", dest], pmsh_case,
              "log.foamToSurface")
    return run.ok and os.path.exists(dest)


def gmsh_case(args, geom, levels, mesher, pmsh_case, surface):
    case = os.path.join(args.work, "%s-r%d-gmsh-for-%s" % (geom["name"], levels, mesher))
    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(os.path.join(case, "system"))
    for f in ("controlDict", "fvSchemes", "fvSolution"):
        shutil.copy(os.path.join(pmsh_case, "system", f), os.path.join(case, "system", f))
    # The same initial fields as pmshFoam writes: decomposePar decomposes them
    shutil.copytree(os.path.join(ROOT, "tutorials", geom["tutorial"], "0"),
                    os.path.join(case, "0"))
    with open(os.path.join(case, "system", "decomposeParDict"), "w") as f:
        f.write(DECOMPOSE_PAR_DICT)
    shutil.copy(surface, os.path.join(case, "surface.stl"))
    return case


def run_gmsh_peer(args, geom, levels, target, pmsh_case, h_fine, start_factor, mesher):
    """Search MeshSizeMax for a matched cell count, then the timed chain"""
    surface = os.path.join(args.work, "%s-r%d-%s-surface.stl" % (geom["name"], levels, mesher))
    if not export_surface(args, pmsh_case, surface):
        log("    gmsh peer: foamToSurface FAILED on %s" % pmsh_case)
        return [{"peer": "gmshHXT", "geometry": geom["name"], "r": levels, "ok": False,
                 "forMesher": mesher,
                 "error": "foamToSurface failed"}], None
    case = gmsh_case(args, geom, levels, mesher, pmsh_case, surface)
    names, n_triangles = stl_solids(surface)
    physicals = "\n".join('Physical Surface("%s") = {%d};' % (n, i + 1)
                          for i, n in enumerate(names))

    def run_one(size, attempt):
        with open(os.path.join(case, "mesh.geo"), "w") as f:
            f.write(GMSH_GEO.format(physicals=physicals, size=size))
        run = Run(["gmsh", "mesh.geo", "-nt", "2", "-"], case, "log.gmsh.%d" % attempt)
        m = re.findall(r"(\d+) nodes (\d+) elements", run.text())
        row = {
            "peer": "gmshHXT", "geometry": geom["name"], "r": levels, "forMesher": mesher,
            "setting": "MeshSizeMax", "value": size, "targetCells": target,
            "loadBefore": run.load_before, "loadAfter": run.load_after, "case": case,
            "gmshTime": round(run.wall, 3), "gmshMemoryBytes": run.max_rss,
            "seconds": run.wall,
        }
        if not run.ok or not m:
            row.update({"ok": False, "error": run.tail()})
            log("    gmsh FAILED, see %s" % run.log)
            return row
        cells = int(m[-1][1]) - n_triangles
        row.update({"ok": True, "cells": cells, "cellRatio": cells/target})
        log("      gmsh HXT MeshSizeMax %.4g: %d cells (%.2fx target) in %.2f s, load %.1f"
            % (size, cells, cells/target, run.wall, run.load_before))
        os.replace(os.path.join(case, "mesh.msh"), os.path.join(case, "mesh.%d.msh" % attempt))
        row["msh"] = "mesh.%d.msh" % attempt
        return row

    rows, best = search_size(run_one, h_fine*start_factor, target)
    if best is None:
        return rows, None
    os.replace(os.path.join(case, best["msh"]), os.path.join(case, "mesh.msh"))
    for row in rows:
        if row is not best and row.get("msh"):
            os.remove(os.path.join(case, row["msh"]))

    g2f = Run(["gmshToFoam", "-case", case, "mesh.msh"], case, "log.gmshToFoam")
    dec = Run(["decomposePar", "-case", case], case, "log.decomposePar") if g2f.ok else None
    total_cells = re.search(r"total:\s*(\d+)", g2f.text())
    best.update({
        "final": True,
        "gmshToFoamTime": round(g2f.wall, 3),
        "gmshToFoamMemoryBytes": g2f.max_rss,
        "decomposeParTime": round(dec.wall, 3) if dec else None,
        "decomposeParMemoryBytes": dec.max_rss if dec else None,
        "ok": bool(g2f.ok and dec and dec.ok),
    })
    if total_cells:
        best["cells"] = int(total_cells.group(1))
        best["cellRatio"] = best["cells"]/target
    if not best["ok"]:
        best["error"] = (dec or g2f).tail()
        log("    gmsh chain FAILED, see %s" % (dec or g2f).log)
        return rows, best
    chain = best["gmshTime"] + best["gmshToFoamTime"] + best["decomposeParTime"]
    best["time"] = round(chain, 3)
    best["peakMemoryBytes"] = max(v for v in (best["gmshMemoryBytes"],
                                              best["gmshToFoamMemoryBytes"],
                                              best["decomposeParMemoryBytes"]) if v)
    best["bytesPerCell"] = best["peakMemoryBytes"]/best["cells"]
    # gmsh uses both cores: per core = cells / time / 2
    best["cellsPerSecondPerCore"] = best["cells"]/chain/2
    best["gmshCellsPerSecondPerCore"] = best["cells"]/best["gmshTime"]/2
    # Untimed: is it a valid OpenFOAM mesh?
    best["checkMesh"] = "Mesh OK" if check_mesh(case)["meshOK"] else "FAILED"
    log("      gmsh chain: gmsh %.2f s + gmshToFoam %.2f s + decomposePar %.2f s = %.2f s "
        "for %d cells (checkMesh: %s)"
        % (best["gmshTime"], best["gmshToFoamTime"], best["decomposeParTime"], chain,
           best["cells"], best["checkMesh"]))
    return rows, best


# ---------------------------------------------------------------------------
# Peer (c): the paper's Table 2
# ---------------------------------------------------------------------------

def read_paper_table():
    path = os.path.join(BENCH_DIR, "paperTable2.csv")
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    table = []
    for r in rows:
        cores = int(r["cores"])
        fine = float(r["fineMcells"])*1e6
        table.append({
            "geometry": r["geometry"], "cores": cores, "r": int(r["refinementLevels"]),
            "coarseMcells": float(r["coarseMcells"]), "fineMcells": float(r["fineMcells"]),
            "coarseTime": float(r["coarseTime"]), "fineTime": float(r["fineTime"]),
            "totalTime": float(r["totalTime"]),
            "fineRatePerCore": fine/float(r["fineTime"])/cores,
            "totalRatePerCore": fine/float(r["totalTime"])/cores,
        })
    return table


def paper_rates(table, paper_geometry):
    rows = [t for t in table if t["geometry"] == paper_geometry]
    if not rows:
        return None
    n = float(len(rows))
    return {
        "rows": len(rows),
        "fineRatePerCore": sum(t["fineRatePerCore"] for t in rows)/n,
        "totalRatePerCore": sum(t["totalRatePerCore"] for t in rows)/n,
        "fineRatePerCoreMax": max(t["fineRatePerCore"] for t in rows),
        "totalRatePerCoreMax": max(t["totalRatePerCore"] for t in rows),
    }


# ---------------------------------------------------------------------------
# The machine
# ---------------------------------------------------------------------------

def dpkg_version(package):
    return command_output(["dpkg-query", "-W", "-f", "${Version}", package]) or "?"


def line_value(path, prefix):
    """The rest of the first line of the text file `path` that starts with
    `prefix`, or None (no such line, or no such file)"""
    try:
        with open(path) as f:
            for line in f:
                if line.startswith(prefix):
                    return line[len(prefix):]
    except OSError:
        pass
    return None


def machine_description(args):
    cpu = line_value("/proc/cpuinfo", "model name")         # "\t: Intel(R) ..."
    cpu = cpu.split(":", 1)[1].strip() if cpu else "?"
    mem = line_value("/proc/meminfo", "MemTotal:")          # "   24576000 kB"
    mem = "%.1f GiB" % (int(mem.split()[0])/1048576.0) if mem else "?"
    os_name = line_value("/etc/os-release", "PRETTY_NAME=")
    os_name = os_name.strip().strip('"') if os_name else "?"
    commit = command_output(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"]) or "?"
    dirty = command_output(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no",
                            "--", "src", "pmshFoam.C", "createFields.H", "Make"])
    try:
        import matplotlib
        mpl = matplotlib.__version__
    except ImportError:
        mpl = "not installed"
    gmsh_version = command_output(["gmsh", "--version"]).splitlines()
    mpi_version = command_output(["mpirun", "--version"]).splitlines()
    gxx = command_output(["g++", "--version"]).splitlines()
    info = {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "memory": mem,
        "os": os_name,
        "kernel": platform.release(),
        "pmshFoam": ("%s%s (%s)" % (commit, " + uncommitted changes" if dirty else "",
                                    args.pmshFoam))
        if os.path.abspath(args.pmshFoam).startswith(ROOT + os.sep) else
        ("%s (the project tree is at %s%s)" % (args.pmshFoam, commit,
                                               " + uncommitted changes" if dirty else "")),
        "netgen (libnglib-dev)": dpkg_version("libnglib-dev"),
        "metis (libmetis-dev)": dpkg_version("libmetis-dev"),
        "openfoam": dpkg_version("openfoam"),
        "open mpi": mpi_version[0] if mpi_version else "?",
        "gmsh": gmsh_version[-1] if gmsh_version else "?",
        "g++": gxx[0] if gxx else "?",
        "python": platform.python_version(),
        "matplotlib": mpl,
        "load at start (1 min)": load1(),
        "uptime at start": command_output(["uptime"]),
    }
    if args.note:
        info["note"] = args.note
    return info


# ---------------------------------------------------------------------------
# Ratios
# ---------------------------------------------------------------------------



# ---------------------------------------------------------------------------
# The benchmark
# ---------------------------------------------------------------------------

def finish(res, out, work):
    """Ratios, targets, notes; then CSV, JSON, Markdown, plots and the console
    summary. Also run alone by --rewrite on a results.json."""
    res["ratios"] = compute_ratios(res["cases"], res["paper"])

    # Targets, at the largest case of each geometry (the Netgen backend; the
    # hxt backend's figures for information)
    targets = []
    for geom in [g for g in GEOMETRIES if g["name"] in res["geometries"]]:
        for mesher in res["meshers"]:
            cs = [c for c in res["cases"]
                  if c["geometry"] == geom["name"] and c["mesher"] == mesher]
            if not cs:
                continue
            c = max(cs, key=lambda x: x["r"])
            q = next(x for x in res["ratios"] if x["geometry"] == c["geometry"]
                     and x["r"] == c["r"] and x["mesher"] == mesher)
            where = "%s r=%d %s" % (c["geometry"], c["r"], mesher)
            for ranks in RANKS:
                v = q.get("fineRatePerCoreVsNetgenSerial_P%d" % ranks)
                targets.append({"target": "fine-stage cells/s/core >= %.1fx Netgen serial (P=%d)"
                                % (TARGET_RATE_VS_NETGEN, ranks), "where": where, "value": v,
                                "verdict": verdict(v, TARGET_RATE_VS_NETGEN)})
            for key, label in (("speedupTotal", "coarse + fine"),
                               ("speedupFine", "fine stages")):
                v = q.get(key)
                targets.append({"target": "speedup 1 -> 2 ranks >= %.1f (%s)"
                                % (TARGET_SPEEDUP_1_TO_2, label), "where": where, "value": v,
                                "verdict": verdict(v, TARGET_SPEEDUP_1_TO_2)})
            for ranks in RANKS:
                run = c["runs"].get(ranks) or {}
                v = run.get("bytesPerFineCellPerRankMax")
                targets.append({"target": "peak memory <= 1 KB per fine cell per rank (P=%d)%s"
                                % (ranks, "" if mesher == "netgen" else " [netgen target]"),
                                "where": where, "value": v,
                                "verdict": verdict(v, TARGET_BYTES_PER_CELL_PER_RANK, False)})
                v = run.get("bytesPerFineCellAboveBaseline")
                targets.append({"target": "(for information) the same above the stage-1 "
                                "baseline (P=%d)" % ranks, "where": where, "value": v,
                                "verdict": verdict(v, TARGET_BYTES_PER_CELL_PER_RANK, False)})
    res["targets"] = targets

    # Anything odd, in words
    res["notes"] = list(res.get("setupNotes", []))
    for c in res["cases"]:
        for key in ("netgenSerial", "gmsh"):
            p = c.get(key)
            if p and p.get("forMesher", c["mesher"]) == c["mesher"] and p.get("cellRatio") \
               and abs(p["cellRatio"] - 1) > MATCH_TOLERANCE:
                res["notes"].append("%s r=%d: the %s peer's cell count %d is %+.0f%% off "
                                    "pmshFoam %s's %d (outside the 20%% match)."
                                    % (c["geometry"], c["r"], key, p["cells"],
                                       100*(p["cellRatio"] - 1), c["mesher"], p["targetCells"]))
    for c in res["cases"]:
        p1, p2 = c["runs"].get(1) or {}, c["runs"].get(2) or {}
        if p1.get("ok") and p2.get("ok") and \
           abs(p2["fineCells"]/float(p1["fineCells"]) - 1) > MATCH_TOLERANCE:
            res["notes"].append("%s r=%d %s: 2 ranks give %d fine cells, 1 rank %d (%+.0f%%): "
                                "the peers are matched to the mean of the two."
                                % (c["geometry"], c["r"], c["mesher"], p2["fineCells"],
                                   p1["fineCells"], 100*(p2["fineCells"]/float(p1["fineCells"]) - 1)))
    for r in res["runs"]:
        if r.get("volumeRetries"):
            res["notes"].append("%s r=%d P=%d %s: volume meshing retried (%s): that run's "
                                "figures include the retries."
                                % (r["geometry"], r["r"], r["ranks"], r["mesher"],
                                   r["volumeRetries"]))
    for r in res["runs"]:
        own, tree = r.get("summaryBytesPerFineCellPerRankMax"), r.get("bytesPerFineCellPerRankMax")
        if own and tree and tree > 1.5*own and r.get("fineCells", 0) > 100000:
            res["notes"].append("%s r=%d P=%d %s: summary.json's peak memory (%.0f B/cell/rank) "
                                "misses most of the run's peak (%.0f B/cell/rank from GNU time "
                                "over the process tree): the volume meshing child's memory is "
                                "not in its VmHWM."
                                % (r["geometry"], r["r"], r["ranks"], r["mesher"], own, tree))
    for q in res["ratios"]:
        if (q.get("speedupTotal") or 0) > 2.0:
            c = next(x for x in res["cases"] if x["geometry"] == q["geometry"]
                     and x["r"] == q["r"] and x["mesher"] == q["mesher"])
            p1, p2 = c["runs"][1], c["runs"][2]
            res["notes"].append(
                "%s r=%d %s: super-linear speedup %.2f. 1 rank: %d cells in %.1f s at load %.1f; "
                "2 ranks: %d cells (largest rank %d) in %.1f s at load %.1f. The volume "
                "mesher's cost per cell grows with the size of what it meshes (the "
                "speedup compares time per cell), and the loads may differ."
                % (q["geometry"], q["r"], q["mesher"], q["speedupTotal"], p1["fineCells"],
                   p1["paperTotal"], p1["loadBefore"], p2["fineCells"],
                   max(p2["fineCellsPerRank"] or [0]), p2["paperTotal"], p2["loadBefore"]))
    failed = [r for r in res["runs"] if not r.get("ok")] + \
             [p for p in res["peers"] if not p.get("ok")]
    for r in failed:
        first = first_error(r.get("error"))
        res["notes"].append("FAILED: %s%s" % (
            ", ".join("%s %s" % (k, r[k]) for k in ("geometry", "r", "ranks", "mesher", "peer",
                                                    "forMesher", "case") if r.get(k) is not None),
            (": `%s`" % first) if first else ""))
    loads = [r["loadBefore"] for r in res["runs"] if r.get("loadBefore") == r.get("loadBefore")]
    if loads and max(loads) > (os.cpu_count() or 1):
        res["notes"].append("The machine was busy: load average up to %.1f on %d cores "
                            "during the runs, so the timings (and above all the 1 -> 2 rank "
                            "speedup) are pessimistic and noisy." % (max(loads), os.cpu_count()))

    res["plots"] = make_plots(out, res)
    write_csv(os.path.join(out, "runs.csv"), res["runs"], RUN_COLUMNS)
    write_csv(os.path.join(out, "peers.csv"), res["peers"], PEER_COLUMNS)
    ratio_columns = ["geometry", "mesher", "r"] + sorted(
        {k for q in res["ratios"] for k in q} - {"geometry", "mesher", "r"})
    write_csv(os.path.join(out, "ratios.csv"), res["ratios"], ratio_columns)
    with open(os.path.join(out, "results.json"), "w") as f:
        json.dump(res, f, indent=1, default=str)
    write_markdown(os.path.join(out, "results.md"), res)

    # The console summary
    log("")
    log("Ratios (pmshFoam / peer time per cell: < 1 is faster; rates: > 1 is faster):")
    for q in res["ratios"]:
        log("  %-10s r=%d %-6s " % (q["geometry"], q["r"], q["mesher"]) + ", ".join(
            "%s %.2f" % (k, v) for k, v in q.items()
            if k not in ("geometry", "r", "mesher") and v is not None))
    log("Targets:")
    for t in res["targets"]:
        log("  %-66s %-20s %8s  %s" % (t["target"], t["where"],
                                      target_value(t["value"]),
                                      t["verdict"].strip("*")))
    for n in res["notes"]:
        log("note: " + n)
    log("")
    log("Results: %s/results.md (work files in %s), %.0f s"
        % (out, work, res["elapsed"]))
    return 0 if not failed else 1


def load_results(path):
    """A results.json back as the benchmark holds it (JSON keys are strings)"""
    with open(path) as f:
        res = json.load(f)
    for r in res["runs"]:
        if r.get("ok") and r.get("peakRssTreeBytes") is None and r.get("case"):
            _, r["peakRssTreeBytes"] = parse_time_v(
                os.path.join(r["case"], "log.pmshFoam.time"))
        if r.get("ok"):
            memory_fields(r)
    for c in res["cases"]:
        c["runs"] = {int(k): next((r for r in res["runs"] if r["geometry"] == c["geometry"]
                                   and r["r"] == c["r"] and r["mesher"] == c["mesher"]
                                   and r["ranks"] == int(k)), v)
                     for k, v in c["runs"].items()}
    res.setdefault("setupNotes", [n for n in res.get("notes", []) if n.startswith("hxt rows")])
    res.setdefault("meshers", sorted({c["mesher"] for c in res["cases"]},
                                     key=["netgen", "hxt"].index))
    res.setdefault("geometries", [g["name"] for g in GEOMETRIES
                                  if any(c["geometry"] == g["name"] for c in res["cases"])])
    return res


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--quick", dest="mode", action="store_const", const="quick",
                       help="r = 1, 2 on coarse sizes: a minute or two (default)")
    group.add_argument("--full", dest="mode", action="store_const", const="full",
                       help="r = 1, 2, 3: ~30 minutes on 2 cores; writes bench/results/")
    parser.add_argument("--out", help="results directory (default: bench/results for "
                        "--full, <work>/results for --quick)")
    parser.add_argument("--work", help="scratch directory for the cases (default: a new "
                        "directory under $TMPDIR, kept)")
    parser.add_argument("--scale", type=float, default=1.0,
                        help="divide every maxCellSize by this (1.26 doubles the cells)")
    parser.add_argument("--geometries", default=",".join(g["name"] for g in GEOMETRIES),
                        help="comma-separated subset of sphere,shaft,sphereSTL")
    parser.add_argument("--no-peers", action="store_true", help="pmshFoam runs only")
    parser.add_argument("--no-hxt", action="store_true",
                        help="skip the hxt backend rows even if pmshFoam has it")
    parser.add_argument("--note", default="",
                        help="a line for the machine table (e.g. which build was measured)")
    parser.add_argument("--no-build", action="store_true",
                        help="(bench/run) use the installed pmshFoam, do not run ./Allwmake")
    parser.add_argument("--pmshFoam", default=shutil.which("pmshFoam") or "pmshFoam",
                        help="the pmshFoam executable (default: from PATH)")
    parser.add_argument("--rewrite", metavar="DIR",
                        help="only rewrite the report (Markdown, CSV, plots) of DIR/results.json")
    args = parser.parse_args()
    if args.rewrite:
        res = load_results(os.path.join(args.rewrite, "results.json"))
        return finish(res, args.rewrite, "(rewritten)")
    args.mode = args.mode or "quick"
    args.pmshFoam = os.path.abspath(args.pmshFoam) if os.path.exists(args.pmshFoam) \
        else args.pmshFoam
    if args.work is None:
        args.work = tempfile.mkdtemp(prefix="pmshFoam-bench-")
    os.makedirs(args.work, exist_ok=True)
    args.work = os.path.abspath(args.work)
    if args.out is None:
        args.out = os.path.join(BENCH_DIR, "results") if args.mode == "full" \
            else os.path.join(args.work, "results")
    os.makedirs(args.out, exist_ok=True)
    mode = MODES[args.mode]
    global MAX_SEARCH_RUNS
    MAX_SEARCH_RUNS = mode["searchRuns"]
    wanted = [g for g in GEOMETRIES if g["name"] in args.geometries.split(",")]

    t0 = time.time()
    res = {
        "mode": args.mode,
        "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        "machine": machine_description(args),
        "runs": [], "peers": [], "cases": [], "notes": [], "setupNotes": [],
        "settings": {"scale": args.scale, "levels": mode["levels"],
                     "hxtOnlyLevels": mode.get("hxtOnlyLevels", []), "ranks": RANKS,
                     "maxCellSize": {g["name"]: mode["maxCellSize"][g["name"]]/args.scale
                                     for g in wanted}},
    }
    log("pmshFoam benchmark, %s mode: work in %s, results to %s"
        % (args.mode, args.work, args.out))
    log("machine: %s, %s cores, %s; load %s"
        % (res["machine"]["cpu"], res["machine"]["cores"], res["machine"]["memory"], load1()))

    meshers = ["netgen"]
    hxt, why = (False, "--no-hxt") if args.no_hxt else hxt_available(args)
    res["hxt"] = {"available": hxt, "reason": why}
    if hxt:
        meshers.append("hxt")
        log("volumeMesher hxt: available, hxt rows included")
    else:
        log("volumeMesher hxt: not available (%s); hxt rows left out"
            % (why.splitlines()[0] if why else "?"))
        res["setupNotes"].append("hxt rows: not measured, this pmshFoam does not accept "
                            "`volumeMesher hxt;` (%s)." % " ".join(why.split())[:300])

    res["meshers"] = meshers
    res["geometries"] = [g["name"] for g in wanted]
    table = read_paper_table()
    res["paper"] = {g["name"]: paper_rates(table, g["paper"]) for g in GEOMETRIES}
    res["paperNetgenSerialRate"] = PAPER_NETGEN_SERIAL_RATE

    for geom in wanted:
        h0 = mode["maxCellSize"][geom["name"]]/args.scale
        netgen_factor = 1.25        # Netgen direct maxh / fine size at equal cells
        # gmsh MeshSizeMax / fine size at equal cells (hxt makes more cells)
        gmsh_factor = {"netgen": 1.2, "hxt": 1.05}
        netgen_peer = {}
        hxt_only = mode.get("hxtOnlyLevels", []) if "hxt" in meshers else []
        for levels in mode["levels"] + hxt_only:
            h_fine = h0/2**levels
            for mesher in (["hxt"] if levels in hxt_only else meshers):
                log("%s r=%d (maxCellSize %.4g, fine size %.4g), %s:"
                    % (geom["name"], levels, h0, h_fine, mesher))
                case = {"geometry": geom["name"], "r": levels, "mesher": mesher, "runs": {}}
                for ranks in RANKS:
                    row = run_pmsh(args, geom, levels, h0, ranks, mesher)
                    res["runs"].append(row)
                    case["runs"][ranks] = row
                res["cases"].append(case)
                good = [r for r in case["runs"].values() if r.get("ok")]
                if args.no_peers or not good:
                    continue
                target = int(round(sum(r["fineCells"] for r in good)/len(good)))

                # (a) Netgen serial, maxCellSize searched; once per (geometry, r),
                # matched to the Netgen backend's cells (hxt rows share it)
                if mesher == "netgen":
                    rows, best = search_size(
                        lambda h, attempt: run_netgen_serial(args, geom, levels, target, h,
                                                             "try%d" % attempt),
                        h_fine*netgen_factor, target)
                    res["peers"].extend(rows)
                    if best:
                        best["forMesher"] = mesher
                        netgen_peer[levels] = best
                        # carry the calibration to the next (larger) size
                        netgen_factor = best["value"]/h_fine*best["cellRatio"]**(1/3.0)
                if netgen_peer.get(levels):
                    case["netgenSerial"] = netgen_peer[levels]

                # (b) gmsh HXT chain, on the serial pmshFoam mesh's boundary,
                # matched to this backend's cells
                p1 = case["runs"].get(1)
                if p1 and p1.get("ok"):
                    rows, gbest = run_gmsh_peer(args, geom, levels, target, p1["case"],
                                                h_fine, gmsh_factor[mesher], mesher)
                    res["peers"].extend(rows)
                    if gbest:
                        case["gmsh"] = gbest
                        if gbest.get("cellRatio"):
                            gmsh_factor[mesher] = \
                                gbest["value"]/h_fine*gbest["cellRatio"]**(1/3.0)

    res["loadAtEnd"] = load1()
    res["elapsed"] = time.time() - t0
    return finish(res, args.out, args.work)


if __name__ == "__main__":
    sys.exit(main())
