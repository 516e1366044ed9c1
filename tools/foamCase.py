"""pmshFoam's one OpenFOAM case harness, for the tests and the bench.

A case is a copy of a tutorial (or any case directory) in scratch space;
commands run on it through pmshFoam and the real OpenFOAM binaries, in
parallel through mpirun, with the project's environment; what they wrote
is read back: checkMesh's verdict and figures, postProcessing/pmshFoam/
summary.json, the polyMesh files. The functions serve the bench scripts;
TutorialCase and CaseTest (a unittest.TestCase that removes the cases of a
passing test) are the same on top of them for the tests.

    sys.path.insert(0, os.path.join(ROOT, "tools")); import foamCase
"""

import gzip
import json
import glob
import os
import re
import shutil
import struct
import subprocess
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TUTORIALS = os.path.join(ROOT, "tutorials")
BENCH_DIR = os.path.join(ROOT, "bench")
TEST_GEOMETRY = os.path.join(ROOT, "tests", "data", "geometry")

# What a tutorial may hold from an earlier run, not to be copied
RUN_LEFTOVERS = ("processor*", "log.*", "postProcessing", "decomposeParDict", "polyMesh",
                 "[1-9]*", ".*")

_sourced = None


def environment():
    """The project's environment as a dict: the caller's when it has
    sourced tools/environment (Alltest, bench/run), else tools/environment
    sourced once; with Open MPI allowed to run as root and on shared
    memory."""
    global _sourced
    if os.environ.get("PMSH_PROJECT_DIR") and os.environ.get("WM_PROJECT_DIR"):
        env = dict(os.environ)
    else:
        if _sourced is None:
            out = subprocess.run(
                ["bash", "-c", ". tools/environment >/dev/null 2>&1 && env -0"],
                cwd=ROOT, check=True, stdout=subprocess.PIPE).stdout
            _sourced = dict(item.split("=", 1)
                            for item in out.decode().split("\0") if "=" in item)
        env = dict(_sourced)
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    env.setdefault("OMPI_MCA_btl", "self,vader")
    env["PMSH_PROJECT_DIR"] = ROOT
    return env


def pmsh_binary():
    """The pmshFoam under test: PMSH_BINARY, else the one on the PATH."""
    found = os.environ.get("PMSH_BINARY") or shutil.which("pmshFoam")
    if not found:
        raise RuntimeError("pmshFoam binary not found (PMSH_BINARY or PATH)")
    return found


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
    """Set the top-level entry 'key value;' of an OpenFOAM dictionary file
    (its first line starting with key), or add it at the end."""
    with open(path) as f:
        text = f.read()
    pattern = re.compile(r"^" + re.escape(key) + r"\s+[^;]*;", re.M)
    line = "%s %s;" % (key, value)
    if pattern.search(text):
        text = pattern.sub(lambda m: line, text, count=1)
    else:
        text = text.rstrip("\n") + "\n" + line + "\n"
    with open(path, "w") as f:
        f.write(text)


def substitute(path, pattern, replacement, count=1):
    """re.sub in a file; the pattern must match `count` times (a tutorial
    whose text moved on fails here, not silently)."""
    with open(path) as f:
        text, n = re.subn(pattern, replacement, f.read())
    if n != count:
        raise AssertionError("%r matched %d times in %s, not %d" % (pattern, n, path, count))
    with open(path, "w") as f:
        f.write(text)


def motorbike_box(max_cell_size):
    """tutorials/motorBike's refinementBox at maxCellSize max_cell_size
    instead of 0.25 (substitute() in its pmshDict; r = 1 halves it)"""
    return (r"(refinementBox\s*\{[^}]*maxCellSize\s+)0\.25\b", r"\g<1>%g" % max_cell_size)


# tutorials/motorBike's refinementBox at its OpenFOAM tutorial's level 4:
# fine cells of 0.0625 instead of 0.125
MOTORBIKE_LEVEL4_BOX = motorbike_box(0.125)


def mpi(ranks, argv):
    """argv on ranks MPI ranks (mpirun ... -parallel), or as it is on one"""
    if ranks > 1:
        return ["mpirun", "--oversubscribe", "-np", str(ranks)] + argv + ["-parallel"]
    return argv


def summary(case):
    """pmshFoam's postProcessing/pmshFoam/summary.json of a case, None
    where there is none (a run that failed writes none)"""
    path = os.path.join(case, "postProcessing", "pmshFoam", "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)


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


def cells_in_checkmesh_log(text):
    """The cell count checkMesh printed; AssertionError without one"""
    cells = read_check_mesh(text).get("cells")
    if cells is None:
        raise AssertionError("no cell count in checkMesh output")
    return cells


def check_mesh(case, ranks=1, env=None):
    """OpenFOAM's checkMesh on a case (-parallel on ranks > 1), its output
    in <case>/log.checkMesh: read_check_mesh of it."""
    case = os.path.abspath(case)
    log = os.path.join(case, "log.checkMesh")
    with open(log, "w") as out:
        subprocess.run(mpi(ranks, ["checkMesh", "-case", case]), cwd=case,
                       env=env or environment(),
                       stdout=out, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL)
    with open(log, errors="replace") as f:
        return read_check_mesh(f.read())


def last_force_coefficients(case, names=("Cd", "Cl")):
    """(iteration, {name: value}) of the last row the forceCoeffs function
    objects of a case wrote (postProcessing/forceCoeffs*/0/coefficient*.dat,
    columns by the file's header), or (None, {}) where there is none"""
    header, last = None, None
    for path in sorted(glob.glob(os.path.join(case, "postProcessing", "forceCoeffs*", "0",
                                              "coefficient*.dat"))):
        with open(path) as f:
            for line in f:
                if line.startswith("# Time"):
                    header = line[1:].split()
                elif line.strip() and not line.startswith("#"):
                    last = line.split()
    if not header or not last:
        return None, {}
    return int(float(last[0])), {n: float(last[header.index(n)]) for n in names}


# The surfaces OpenFOAM ships (Debian's openfoam-examples)
SHIPPED_GEOMETRY = "/usr/share/doc/openfoam-examples/examples/resources/geometry"


def extent(path):
    """The bounding box of an (optionally gzipped) STL or OBJ file"""
    lo, hi = [1e300]*3, [-1e300]*3
    with (gzip.open if path.endswith(".gz") else open)(path, "rt", errors="replace") as f:
        for line in f:
            t = line.split()
            if t and t[0] in ("v", "vertex"):
                x = [float(a) for a in t[1:4]]
                lo = [min(a, b) for a, b in zip(lo, x)]
                hi = [max(a, b) for a, b in zip(hi, x)]
    return lo, hi


def write_bullet_in_box(path):
    """OpenFOAM's bullet (tutorials/resources/geometry/bullet.stl.gz of
    the OpenFOAM source the build uses), its triangles flipped to point out
    of the fluid, in a box with 1.5 body lengths of padding and 3
    downstream along its axis (z): solids inlet, outlet, sides, body."""
    source = os.path.join(environment()["WM_PROJECT_DIR"], "tutorials", "resources",
                          "geometry", "bullet.stl.gz")
    with gzip.open(source, "rt") as f:
        v = [tuple(map(float, m)) for m in
             re.findall(r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", f.read())]
    body = [(v[i], v[i + 2], v[i + 1]) for i in range(0, len(v), 3)]
    lo = [min(p[k] for p in v) for k in range(3)]
    hi = [max(p[k] for p in v) for k in range(3)]
    length = max(hi[k] - lo[k] for k in range(3))
    x0, y0, z0 = (lo[k] - 1.5 * length for k in range(3))
    x1, y1 = (hi[k] + 1.5 * length for k in range(2))
    z1 = hi[2] + 3 * length

    def corner(i, j, k):
        return ((x0, x1)[i], (y0, y1)[j], (z0, z1)[k])

    def quad(a, b, c, d):       # outward by the right-hand rule
        return [(corner(*a), corner(*b), corner(*c)), (corner(*a), corner(*c), corner(*d))]
    solids = [
        ("inlet", quad((0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0))),
        ("outlet", quad((0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1))),
        ("sides", quad((0, 0, 0), (0, 0, 1), (0, 1, 1), (0, 1, 0))
         + quad((1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1))
         + quad((0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1))
         + quad((0, 1, 0), (0, 1, 1), (1, 1, 1), (1, 1, 0))),
        ("body", body)]
    with open(path, "w") as out:
        for name, triangles in solids:
            out.write("solid %s\n" % name)
            for t in triangles:
                out.write("  facet normal 0 0 0\n    outer loop\n")
                out.write("".join("      vertex %.9g %.9g %.9g\n" % p for p in t))
                out.write("    endloop\n  endfacet\n")
            out.write("endsolid %s\n" % name)


class TutorialCase:
    """A fresh copy of tutorials/<name> in a temporary directory, its
    pmshDict entries set as given."""

    def __init__(self, name, **entries):
        self.name = name
        self.root = tempfile.mkdtemp(prefix="pmshFoam-%s-" % name)
        self.dir = copy_tutorial(name, os.path.join(self.root, name))
        self.pmshFoam = pmsh_binary()
        for key, value in entries.items():
            self.set_entry("system/pmshDict", key, value)

    def cleanup(self):
        shutil.rmtree(self.root, ignore_errors=True)

    # -- dictionaries -----------------------------------------------------

    def set_entry(self, dict_file, key, value):
        """Set (or add) a top-level 'key value;' entry of a dictionary."""
        set_entry(os.path.join(self.dir, dict_file), key, value)

    def write_format(self, fmt):
        self.set_entry("system/controlDict", "writeFormat", fmt)

    def substitute(self, relative, pattern, replacement, count=1):
        """substitute() in a file of the case"""
        substitute(os.path.join(self.dir, relative), pattern, replacement, count)

    # -- running ----------------------------------------------------------

    def run(self, *command, np=1, log=None, check=True, env=None, timeout=1800):
        """Run an OpenFOAM-style application on the case (in parallel when
        np > 1) with its output in log.<app>; returns (exit code, log)."""
        app = command[0]
        argv = [self.pmshFoam if app == "pmshFoam" else app] + list(command[1:])
        argv = mpi(np, argv + ["-case", self.dir])
        environment_ = environment()
        environment_.update(env or {})
        proc = subprocess.run(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, env=environment_,
                              cwd=self.dir, timeout=timeout)
        text = proc.stdout.decode(errors="replace")
        with open(os.path.join(self.dir, log or "log." + app), "w") as f:
            f.write(text)
        if check and proc.returncode != 0:
            raise AssertionError("%s failed with exit code %d:\n%s"
                                 % (" ".join(argv), proc.returncode, text[-4000:]))
        return proc.returncode, text

    def run_allrun(self, *args, timeout=1100):
        """The tutorial's own Allrun (with its arguments), this pmshFoam
        first on the PATH; returns (exit code, output)."""
        env = environment()
        env["PATH"] = os.path.dirname(self.pmshFoam) + ":" + env["PATH"]
        proc = subprocess.run([os.path.join(self.dir, "Allrun")] + list(args),
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, env=env, timeout=timeout)
        return proc.returncode, proc.stdout.decode(errors="replace")

    def check_mesh(self, np=1):
        """Run checkMesh; fail unless it says 'Mesh OK'. Returns the log."""
        _, text = self.run("checkMesh", np=np)
        if not read_check_mesh(text)["meshOK"]:
            problems = "\n".join(l for l in text.splitlines()
                                 if "***" in l or "FATAL" in l or "Failed" in l)
            raise AssertionError("checkMesh did not say 'Mesh OK' for %s:\n%s"
                                 % (self.dir, problems or text[-3000:]))
        return text

    # -- reading results --------------------------------------------------

    def exists(self, relative):
        return os.path.exists(os.path.join(self.dir, relative))

    def summary(self):
        """summary.json; AssertionError where pmshFoam wrote none"""
        found = summary(self.dir)
        if found is None:
            raise AssertionError("no postProcessing/pmshFoam/summary.json in " + self.dir)
        return found

    def polymesh(self, location="constant/polyMesh"):
        return PolyMeshFiles(os.path.join(self.dir, location))


class CaseTest(unittest.TestCase):
    """Creates cases that are removed after a passing test (kept on failure
    for inspection)."""

    def setUp(self):
        self.cases = []

    def tearDown(self):
        failed = not self._outcome.success
        for case in self.cases:
            if failed:
                print("kept for inspection: " + case.dir)
            else:
                case.cleanup()

    def case(self, name, **entries):
        c = TutorialCase(name, **entries)
        self.cases.append(c)
        return c

    def sphere_in_box_allrun(self, tutorial):
        """A tutorial of flow round the D = 1 ball (sphereDrag, bodyInBox)
        run by its Allrun: it must succeed with Mesh OK and the box's and
        ball's patches of their types. Returns (case, Allrun's output)."""
        c = self.case(tutorial)
        code, out = c.run_allrun(timeout=600)
        self.assertEqual(code, 0, out)
        self.assertIn("Mesh OK", out)
        boundary = dict(c.polymesh("processor0/constant/polyMesh").boundary())
        for name, kind in (("inlet", "patch"), ("outlet", "patch"),
                           ("sides", "symmetry"), ("ball", "wall")):
            self.assertIn(name, boundary)
            self.assertEqual(boundary[name]["type"], kind, name)
        return c, out

    def geometry_case(self, geometry, wall_patch=None, **entries):
        """tutorials/sphere meshing tests/data/geometry/<geometry> instead:
        no patches entry (every patch as the geometry names it), and 0/U
        and 0/p with the sphere's `walls` entry renamed wall_patch, or no
        0/ at all without one."""
        c = self.case("sphere", **entries)
        shutil.copy(os.path.join(TEST_GEOMETRY, geometry),
                    os.path.join(c.dir, "constant", "geometry", geometry))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % geometry)
        path = os.path.join(c.dir, "system", "pmshDict")
        with open(path) as f:
            text = re.sub(r"(?ms)^patches\s*\{.*?^\}", "", f.read())
        with open(path, "w") as f:
            f.write(text)
        if wall_patch is None:
            shutil.rmtree(os.path.join(c.dir, "0"), ignore_errors=True)
            return c
        for field in ("U", "p"):
            path = os.path.join(c.dir, "0", field)
            with open(path) as f:
                text = f.read().replace("    walls\n", "    %s\n" % wall_patch)
            with open(path, "w") as f:
                f.write(text)
        return c

    def mesh_levels(self, name, levels, fmt="ascii", **entries):
        """Mesh tutorial `name` at each level; checkMesh must pass. Returns
        {level: (case, cells)}."""
        result = {}
        for r in levels:
            c = self.case(name, refinementLevels=r, **entries)
            c.write_format(fmt)
            c.run("pmshFoam")
            log = c.check_mesh()
            result[r] = (c, cells_in_checkmesh_log(log))
        return result


class PolyMeshFiles:
    """Reads points, faces, owner and boundary of a polyMesh (ascii or binary)."""

    def __init__(self, directory):
        self.directory = directory

    def _read(self, name):
        with open(os.path.join(self.directory, name), "rb") as f:
            data = f.read()
        header_end = data.index(b"}", data.index(b"FoamFile")) + 1
        header = data[:header_end].decode()
        binary = re.search(r"format\s+binary", header) is not None
        arch = re.search(r"label=(\d+)", header)
        label_bytes = int(arch.group(1)) // 8 if arch else 4
        cls = re.search(r"class\s+(\w+)", header).group(1)
        return data[header_end:], binary, label_bytes, cls

    @staticmethod
    def _strip_comments(body):
        body = re.sub(rb"/\*.*?\*/", b"", body, flags=re.S)
        return re.sub(rb"//[^\n]*", b"", body)

    def _list(self, body, binary, item_bytes, fmt, parse_ascii, offset=0):
        """Read one list at byte offset; returns (items, end offset)."""
        # OpenFOAM's writers put a "// * * *" line between header and data
        m = re.compile(rb"(?:\s*//[^\n]*\n)*\s*(\d+)\s*").match(body, offset)
        n = int(m.group(1))
        pos = m.end()
        if binary:
            if n == 0:
                return [], pos
            assert body[pos:pos + 1] == b"("
            raw = body[pos + 1:pos + 1 + n * item_bytes]
            items = [struct.unpack_from(fmt, raw, i * item_bytes) for i in range(n)]
            return items, pos + 1 + n * item_bytes + 1
        depth, i = 0, pos
        while True:
            c = body[i:i + 1]
            if c == b"(":
                depth += 1
            elif c == b")":
                depth -= 1
                if depth == 0:
                    break
            i += 1
        return parse_ascii(body[pos:i + 1].decode(), n), i + 1

    def points(self):
        body, binary, _, _ = self._read("points")
        if not binary:
            body = self._strip_comments(body)
        def parse(text, n):
            return [tuple(float(x) for x in t.split())
                    for t in re.findall(r"\(([^()]+)\)", text[1:-1])]
        return self._list(body, binary, 24, "<3d", parse)[0]

    def faces(self):
        body, binary, lb, cls = self._read("faces")
        lfmt = "<q" if lb == 8 else "<i"
        if binary and cls == "faceCompactList":
            offsets, end = self._list(body, True, lb, lfmt, None)
            labels, _ = self._list(body, True, lb, lfmt, None, end)
            offsets = [o[0] for o in offsets]
            labels = [l[0] for l in labels]
            return [labels[offsets[i]:offsets[i + 1]] for i in range(len(offsets) - 1)]
        body = self._strip_comments(body)
        def parse(text, n):
            return [[int(x) for x in t.split()]
                    for t in re.findall(r"\d+\(([^()]*)\)", text[1:-1])]
        return self._list(body, False, 0, None, parse)[0]

    def labels(self, name):
        """A labelList file (owner, neighbour, *ProcAddressing)."""
        body, binary, lb, _ = self._read(name)
        if not binary:
            body = self._strip_comments(body)
        def parse(text, n):
            return [int(x) for x in text[1:-1].split()]
        items, _ = self._list(body, binary, lb, "<q" if lb == 8 else "<i", parse)
        return [i[0] if isinstance(i, tuple) else i for i in items]

    def boundary(self):
        """[(name, dict of entries)] from the (always ascii) boundary file."""
        body, _, _, _ = self._read("boundary")
        body = self._strip_comments(body).decode()
        patches = []
        for name, content in re.findall(r"(\w+)\s*\{([^}]*)\}", body):
            entries = dict(re.findall(r"(\w+)\s+([^;]+);", content))
            patches.append((name, entries))
        return patches

    def boundary_points(self):
        """Indices of the points used by boundary faces."""
        faces = self.faces()
        used = set()
        for name, entries in self.boundary():
            start, n = int(entries["startFace"]), int(entries["nFaces"])
            for f in faces[start:start + n]:
                used.update(f)
        return used
