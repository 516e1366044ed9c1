"""What the bench scripts share about an OpenFOAM case: the project's
environment, a fresh copy of a tutorial, a dictionary entry set, and
OpenFOAM's checkMesh run and read.

Kept apart from pmshBench.py (the bench/run benchmark) so that the small
scripts (balance, picture, quality.py) get these without the benchmark's
imports and state. pmshBench.py, dragStudy.py, scaleBench.py and
memoryFigures.py use them too.
"""

import os
import re
import shutil
import subprocess

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(BENCH_DIR)
TUTORIALS = os.path.join(ROOT, "tutorials")

# What a tutorial may hold from an earlier run, not to be copied
RUN_LEFTOVERS = ("processor*", "log.*", "postProcessing", "decomposeParDict", "polyMesh")


def environment():
    """The project's environment (tools/environment), as a dict, with
    Open MPI allowed to run as root and on shared memory."""
    out = subprocess.run(
        ["bash", "-c", ". tools/environment >/dev/null 2>&1 && env -0"],
        cwd=ROOT, check=True, stdout=subprocess.PIPE).stdout
    env = dict(item.split("=", 1) for item in out.decode().split("\0") if "=" in item)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.setdefault("OMPI_MCA_btl", "self,vader")
    return env


def copy_case(source, case, ignore=RUN_LEFTOVERS, parts=None):
    """A fresh copy of the case directory source at case (whatever was there
    is removed): the whole of it, or only its directories parts, without
    the files and directories that match the patterns ignore."""
    shutil.rmtree(case, ignore_errors=True)
    ignored = shutil.ignore_patterns(*ignore)
    if parts is None:
        shutil.copytree(source, case, ignore=ignored)
        return case
    os.makedirs(case)
    for part in parts:
        shutil.copytree(os.path.join(source, part), os.path.join(case, part), ignore=ignored)
    return case


def copy_tutorial(tutorial, case, ignore=RUN_LEFTOVERS, parts=None):
    """copy_case of tutorials/<tutorial>"""
    return copy_case(os.path.join(TUTORIALS, tutorial), case, ignore, parts)


def set_entry(path, key, value):
    """Set 'key value;' in an OpenFOAM dictionary file: its first entry
    key, at any indentation, or a new line at the end."""
    with open(path) as f:
        text = f.read()
    pattern = re.compile(r"^(\s*)" + re.escape(key) + r"\s+[^;]*;", re.M)
    line = "%s %s;" % (key, value)
    if pattern.search(text):
        text = pattern.sub(lambda m: m.group(1) + line, text, count=1)
    else:
        text = text.rstrip("\n") + "\n" + line + "\n"
    with open(path, "w") as f:
        f.write(text)


def mpi(ranks, argv):
    """argv on ranks MPI ranks (mpirun ... -parallel), or as it is on one"""
    if ranks > 1:
        return ["mpirun", "-np", str(ranks), "--oversubscribe"] + argv + ["-parallel"]
    return argv


def read_check_mesh(text):
    """checkMesh's figures in its output: meshOK, and where it printed
    them cells, tetrahedra, prisms, hexahedra, polyhedra, maxNonOrtho,
    avgNonOrtho, maxSkewness and volume."""
    out = {"meshOK": re.search(r"^Mesh OK", text, re.M) is not None}
    for key, pattern in (("maxNonOrtho", r"non-orthogonality Max:\s*([0-9.eE+-]+)"),
                         ("avgNonOrtho",
                          r"non-orthogonality Max:\s*[0-9.eE+-]+\s+average:\s*([0-9.eE+-]+)"),
                         ("maxSkewness", r"Max skewness =\s*([0-9.eE+-]+)"),
                         ("volume", r"Total volume = ([0-9.eE+-]+?)\.?\s")):
        found = re.search(pattern, text, re.M)
        if found:
            out[key] = float(found.group(1))
    for count in ("cells", "tetrahedra", "prisms", "hexahedra", "polyhedra"):
        found = re.search(r"^\s*%s:\s+(\d+)" % count, text, re.M)
        if found:
            out[count] = int(found.group(1))
    return out


def check_mesh(case, ranks=1, env=None):
    """OpenFOAM's checkMesh on a case (-parallel on ranks > 1), its output
    in <case>/log.checkMesh: read_check_mesh of it."""
    case = os.path.abspath(case)
    log = os.path.join(case, "log.checkMesh")
    with open(log, "w") as out:
        subprocess.run(mpi(ranks, ["checkMesh", "-case", case]), cwd=case, env=env,
                       stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    with open(log, errors="replace") as f:
        return read_check_mesh(f.read())
