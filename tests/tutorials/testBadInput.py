"""Bad input end to end: pmshFoam stops before meshing with an OpenFOAM
error block ("--> FOAM FATAL ERROR" or, for a dictionary entry, "--> FOAM
FATAL IO ERROR" with "file: <path> at line N.") that names the file, the
entry (and its line) and what would be valid, exits non-zero, finishes
promptly, and writes or changes nothing in the case.

Every run is checked for all of that (BadInputTest.expect_fatal):

- the exit code is non-zero (and not a signal's). In parallel that is
  mpirun's: a failure every rank agreed on (failTogether) ends, as
  OpenFOAM's own utilities end on a fatal error, in UPstream::exit(1),
  i.e. MPI_Abort on every rank, so Open MPI's "MPI_ABORT was invoked"
  notice is expected and the ranks' own exit codes are not theirs to give;
- the error block is printed once (not once per rank), no rank crashed
  (no signal, no stack trace), and the block holds the given key phrases;
- the run finishes within RUN_TIMEOUT seconds (a hang fails the test);
- the case tree is unchanged byte for byte: no constant/polyMesh, no
  processor*, no hidden temporaries (.processor*, constant/.polyMesh*), no
  system/decomposeParDict, and a previous mesh is left as it was.

Runs are limited to RUN_MEMORY_LIMIT of address space per process, so that
a check that stopped working fails the test quickly instead of meshing for
hours on a shared machine.

badInput runs each case serially; badInputParallel runs a representative
subset, and what only exists in parallel, with mpirun -np 2 or 3.

Run one test:  python3 testBadInput.py badInput.test_missingGeometryFile
"""

import hashlib
import os
import re
import resource
import shutil
import signal
import stat
import struct
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, environment, mpi  # noqa: E402

#- Seconds a failing run may take: bad input is found in about a second.
RUN_TIMEOUT = 90

#- Address space per process of a run that is expected to fail early.
RUN_MEMORY_LIMIT = 4 << 30


# -- the case tree -----------------------------------------------------------

def tree_snapshot(directory):
    """{relative path: sha256 of the content, or 'dir'} of every file and
    directory below directory, hidden ones included."""
    snapshot = {}
    for root, dirs, files in os.walk(directory):
        for d in dirs:
            snapshot[os.path.relpath(os.path.join(root, d), directory)] = "dir"
        for f in files:
            path = os.path.join(root, f)
            with open(path, "rb") as stream:
                digest = hashlib.sha256(stream.read()).hexdigest()
            snapshot[os.path.relpath(path, directory)] = digest
    return snapshot


def line_of(path, keyword):
    """1-based number of the first line of a file that starts with keyword."""
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if re.match(r"\s*%s\b" % re.escape(keyword), line):
                return number
    raise AssertionError("no line starting with %r in %s" % (keyword, path))


# -- STL files ---------------------------------------------------------------

def read_ascii_stl(path):
    """The facets of an ascii STL: [(v0, v1, v2)], each vertex the three
    coordinates as written (so that rewriting keeps them bit for bit)."""
    with open(path) as f:
        vertices = re.findall(r"^\s*vertex\s+(\S+)\s+(\S+)\s+(\S+)", f.read(), re.M)
    assert vertices and len(vertices) % 3 == 0, path
    return [tuple(vertices[i:i + 3]) for i in range(0, len(vertices), 3)]


def write_ascii_stl(path, facets, name="sphere"):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for facet in facets:
            f.write("  facet normal 0 0 0\n    outer loop\n")
            for v in facet:
                f.write("      vertex %s %s %s\n" % tuple(v))
            f.write("    endloop\n  endfacet\n")
        f.write("endsolid %s\n" % name)


def write_binary_stl(path, facets):
    with open(path, "wb") as f:
        f.write(b"binary STL written by testBadInput.py".ljust(80, b" "))
        f.write(struct.pack("<I", len(facets)))
        for facet in facets:
            coordinates = [0.0, 0.0, 0.0] + [float(x) for v in facet for x in v]
            f.write(struct.pack("<12fH", *coordinates, 0))


# -- running -----------------------------------------------------------------

def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (RUN_MEMORY_LIMIT, RUN_MEMORY_LIMIT))


def run_bounded(argv, cwd, env=None):
    """Run argv in its own process group with bounded memory; kill the
    whole group and fail if it takes longer than RUN_TIMEOUT seconds.
    Returns (exit code, output)."""
    proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, cwd=cwd,
                            env=env or environment(),
                            preexec_fn=limit_memory, start_new_session=True)
    try:
        out, _ = proc.communicate(timeout=RUN_TIMEOUT)
    except subprocess.TimeoutExpired:
        # SIGTERM first: mpirun then stops its ranks (which it starts in
        # process groups of their own)
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            out, _ = proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            out, _ = proc.communicate()
        raise AssertionError("%s did not finish within %d s (hang?):\n%s"
                             % (" ".join(argv), RUN_TIMEOUT,
                                out.decode(errors="replace")[-3000:]))
    return proc.returncode, out.decode(errors="replace")


#- The start of an OpenFOAM error block: FatalError or FatalIOError.
ERROR_BLOCK = re.compile(r"--> FOAM FATAL (?:IO )?ERROR")

#- What a crash (not a stop) leaves in the log: a signal, a stack trace.
CRASH = re.compile(r"exited on signal|Segmentation fault|core dumped|printStack|"
                   r"terminate called|Aborted \(")


class BadInputTest(CaseTest):
    """Cases with bad input, and the checks every failing run must pass."""

    def case(self, name, **entries):
        c = super().case(name, **entries)
        # The tutorials ship no decomposeParDict: a leftover from running a
        # tutorial in place must not hide one that pmshFoam creates
        path = os.path.join(c.dir, "system/decomposeParDict")
        if os.path.exists(path):
            os.remove(path)
        return c

    def path(self, case, relative):
        return os.path.join(case.dir, relative)

    def dict_line(self, case, keyword, dict_file="system/pmshDict"):
        """'<dict_file> at line N.' of keyword's entry, as OpenFOAM's
        FatalIOError gives the file and the line ('file: <path> at line N.')."""
        return "%s at line %d." % (dict_file, line_of(self.path(case, dict_file), keyword))

    # -- running pmshFoam -------------------------------------------------

    def pmshFoam_argv(self, case, args):
        return [case.pmshFoam] + list(args) + ["-case", case.dir]

    def run_serial(self, case, args, prefix=(), env=None):
        return run_bounded(list(prefix) + self.pmshFoam_argv(case, args), case.root, env)

    def run_parallel(self, case, np, args):
        """mpirun -np np pmshFoam -parallel. Returns (mpirun's exit code,
        output). A collective failure ends, as OpenFOAM's own utilities
        do, in UPstream::exit(1), i.e. MPI_Abort on every rank: mpirun then
        stops the ranks and exits non-zero, so its exit code stands for the
        ranks'."""
        argv = mpi(np, self.pmshFoam_argv(case, args))
        code, log = run_bounded(argv, case.root)
        self.check_output(log)
        return code, log

    def check_output(self, log):
        """One error block, printed once (not once per rank), and nobody
        crashed (Open MPI's "MPI_ABORT was invoked" notice, which ends a
        failed parallel run, is no crash)."""
        self.assertEqual(len(ERROR_BLOCK.findall(log)), 1,
                         "expected exactly one error block:\n" + log[-4000:])
        self.assertIsNone(CRASH.search(log), "a rank crashed:\n" + log[-4000:])

    def error_of(self, log):
        """The error block (from '--> FOAM FATAL ...' on) of a log."""
        return log[ERROR_BLOCK.search(log).start():]

    # -- the checks -------------------------------------------------------

    def expect_fatal(self, case, phrases, np=1, args=(), prefix=(), env=None):
        """Run pmshFoam on case; it must fail as described at the top and
        leave the case as it was. Returns the log."""
        before = tree_snapshot(case.dir)
        if np > 1:
            code, log = self.run_parallel(case, np, args)
        else:
            code, log = self.run_serial(case, args, prefix, env)
            self.check_output(log)
        self.assertNotEqual(code, 0, log[-3000:])
        self.assertLess(code, 128, "killed by a signal, not stopped:\n" + log[-3000:])
        error = self.error_of(log)
        for phrase in phrases:
            self.assertIn(phrase, error, "%r missing from the error:\n%s"
                          % (phrase, error[:3000]))
        self.expect_unchanged(case, before)
        return log

    def expect_unchanged(self, case, before):
        after = tree_snapshot(case.dir)
        created = sorted(set(after) - set(before))
        removed = sorted(set(before) - set(after))
        changed = sorted(p for p in set(before) & set(after) if before[p] != after[p])
        for p in created:
            self.assertFalse(p.split(os.sep)[0].startswith("processor"),
                             "processor directory written: " + p)
            self.assertFalse(p.startswith(os.path.join("constant", "polyMesh")),
                             "a mesh was written: " + p)
            self.assertFalse(any(part.startswith(".") for part in p.split(os.sep)),
                             "temporary output left behind: " + p)
            self.assertNotEqual(p, os.path.join("system", "decomposeParDict"),
                                "system/decomposeParDict written")
        self.assertEqual((created, removed, changed), ([], [], []),
                         "the case was changed (created, removed, changed)")

    # -- inputs -----------------------------------------------------------

    def stl_case(self, facets=None, binary=False):
        """The sphereSTL tutorial, its STL replaced by facets if given.
        Returns (case, facets of the tutorial's STL, STL path)."""
        c = self.case("sphereSTL")
        stl = self.path(c, "constant/geometry/sphere.stl")
        original = read_ascii_stl(stl)
        if facets is not None:
            (write_binary_stl if binary else write_ascii_stl)(stl, facets(original))
        return c, original, stl

    def parallel_mesh(self, case, np):
        """Mesh case in parallel (it must succeed)."""
        case.run("pmshFoam", np=np)
        for p in range(np):
            self.assertTrue(case.exists("processor%d/constant/polyMesh/points" % p))


class cases:
    """The bad inputs, each a method returning (case, key phrases) for the
    serial and the parallel tests to run."""

    # -- geometry file ----------------------------------------------------

    def missingGeometryFile(self):
        c = self.case("sphere", geometry='"constant/geometry/nothere.geo"')
        return c, ["nothere.geo", "Entry 'geometry'", self.dict_line(c, "geometry"),
                   "does not exist", "relative to the case directory"]

    def unknownGeometryExtension(self):
        c = self.case("sphere", geometry='"constant/geometry/sphere.step"')
        shutil.copy(self.path(c, "constant/geometry/sphere.geo"),
                    self.path(c, "constant/geometry/sphere.step"))
        return c, ["sphere.step", "Entry 'geometry'", self.dict_line(c, "geometry"),
                   "'.step' is not supported", ".geo (Netgen CSG)", ".stl", ".obj"]

    def geoSyntaxError(self):
        c = self.case("sphere")
        geo = self.path(c, "constant/geometry/sphere.geo")
        line = line_of(geo, "solid")
        with open(geo) as f:
            text = f.read()
        with open(geo, "w") as f:
            f.write(text.replace("sphere (0, 0, 0; 1)", "sphere (0, 0, 0; 1"))
        return c, ["sphere.geo", "line %d" % line, "')' expected"]

    # -- surface files of OpenFOAM's formats, and the domain box -----------

    def objWithoutTriangles(self):
        c = self.case("sphereSTL", geometry='"constant/geometry/body.obj"')
        with open(self.path(c, "constant/geometry/body.obj"), "w") as f:
            f.write("# a CAD export that lost its faces\nv 0 0 0\nv 1 0 0\nv 0 1 0\n")
        return c, ["body.obj", "is empty: it contains no triangles"]

    def bodyOutsideTheDomainBox(self):
        # The tutorial's sphere has radius 1: a body through a side is cut
        # by it, one wholly outside is a mistake
        c = self.case("sphereSTL", domain="{ type box; min (2 -5 -5); max (5 5 5); }")
        return c, ["Solid sphere of STL file", "sphere.stl", "lies outside the domain box from"
                   " (2 -5 -5) to (5 5 5)", "enlarge the box"]

    def domainWithAZeroSide(self):
        c = self.case("sphereSTL", domain="{ type box; min (-5 -5 -5); max (5 -5 5); }")
        return c, ["Entry 'max' of 'domain' is ( 5 -5 5 ) (not above min)",
                   "Every component of 'max' of 'domain' must be larger than that of 'min'",
                   self.dict_line(c, "domain")]

    # -- STL --------------------------------------------------------------

    def emptyStl(self):
        c, _, stl = self.stl_case()
        open(stl, "w").close()
        return c, ["sphere.stl", "is empty", "Entry 'geometry'"]

    def truncatedBinaryStl(self):
        c, original, stl = self.stl_case(lambda facets: facets, binary=True)
        size = os.path.getsize(stl)
        with open(stl, "r+b") as f:
            f.truncate(size - 30)
        return c, ["sphere.stl", "truncated",
                   "announces %d triangles (%d bytes)" % (len(original), size),
                   "has %d bytes" % (size - 30)]

    def stlThatIsNotClosed(self):
        c, _, _ = self.stl_case(lambda facets: facets[1:])
        return c, ["sphere.stl", "not closed", "used by only one triangle"]

    def inconsistentlyOrientedStl(self):
        def flip_one(facets):
            a, b, c = facets[7]
            return facets[:7] + [(a, c, b)] + facets[8:]
        c, _, _ = self.stl_case(flip_one)
        return c, ["sphere.stl", "inconsistently oriented", "normals outward"]

    # -- pmshDict ---------------------------------------------------------

    def missingMaxCellSize(self):
        c = self.case("sphere")
        pmshDict = self.path(c, "system/pmshDict")
        with open(pmshDict) as f:
            lines = f.readlines()
        with open(pmshDict, "w") as f:
            f.writelines(l for l in lines if not l.startswith("maxCellSize"))
        return c, ["Entry 'maxCellSize' not found", "file: %s" % pmshDict,
                   "maxCellSize must be a number > 0"]

    def maxCellSizeOfTheWrongType(self):
        c = self.case("sphere", maxCellSize="fine")
        return c, ["Entry 'maxCellSize' is fine (not a number)",
                   self.dict_line(c, "maxCellSize"), "maxCellSize must be a number > 0"]

    def nonPositiveMaxCellSize(self):
        c = self.case("sphere", maxCellSize=0)
        return c, ["Entry 'maxCellSize' is 0\n", self.dict_line(c, "maxCellSize"),
                   "maxCellSize must be a number > 0"]

    def unknownVolumeMesher(self):
        c = self.case("sphere", volumeMesher="tetgen")
        return c, ["Entry 'volumeMesher' is tetgen", self.dict_line(c, "volumeMesher"),
                   "Valid values are: netgen"]

    # 7 levels of the sphere at maxCellSize 0.36: some 600 million cells,
    # within 32-bit labels, far beyond the memory of a 24 GiB machine
    beyondTheMemory = {"refinementLevels": 7, "maxCellSize": 0.36}

    def refinementLevelsBeyondTheMemory(self):
        c = self.case("sphere", **self.beyondTheMemory)
        # pmsh::FatalError (not an IOerror): the file and line in the text
        pmshDict = self.path(c, "system/pmshDict")
        return c, ["Entry 'refinementLevels' in dictionary \"%s\" (line %d) is 7"
                   % (pmshDict, line_of(pmshDict, "refinementLevels")),
                   "cannot fit in the memory", "of memory", "fewer refinementLevels",
                   "-noMemoryCheck",
                   "more ranks", "larger maxCellSize"]

    # -- case files -------------------------------------------------------

    def missingControlDict(self):
        c = self.case("sphere")
        os.remove(self.path(c, "system/controlDict"))
        # OpenFOAM's words, the case's own file (also in parallel)
        return c, ["cannot find file", "A case needs system/controlDict"]


class badInput(BadInputTest, cases):
    """Serial runs: each bad input stops before meshing, names the problem
    and writes nothing."""

    # -- geometry file ----------------------------------------------------

    def test_missingGeometryFile(self):
        self.expect_fatal(*self.missingGeometryFile())

    def test_unreadableGeometryFile(self):
        c = self.case("sphere")
        geo = self.path(c, "constant/geometry/sphere.geo")
        os.chmod(geo, 0)
        prefix = ()
        env = None
        if os.geteuid() == 0:
            # root reads anything: run as nobody, who may read the rest, and
            # a copy of OpenFOAM's etc/ (its controlDict is read at start;
            # the installation may be where nobody cannot read, below /root)
            env = environment()
            project = os.path.join(c.root, "OpenFOAM")
            shutil.copytree(os.path.join(env["WM_PROJECT_DIR"], "etc"),
                            os.path.join(project, "etc"))
            env["WM_PROJECT_DIR"] = project
            for root, dirs, files in os.walk(c.root):
                os.chmod(root, os.stat(root).st_mode | stat.S_IROTH | stat.S_IXOTH)
                for f in files:
                    p = os.path.join(root, f)
                    if p != geo:
                        os.chmod(p, os.stat(p).st_mode | stat.S_IROTH)
            prefix = ("setpriv", "--reuid=65534", "--regid=65534", "--clear-groups")
        self.expect_fatal(c, ["sphere.geo", "Entry 'geometry'", self.dict_line(c, "geometry"),
                              "cannot be read", "permissions"], prefix=prefix, env=env)

    def test_geometryThatIsADirectory(self):
        c = self.case("sphere", geometry='"constant/geometry/body.stl"')
        os.mkdir(self.path(c, "constant/geometry/body.stl"))
        self.expect_fatal(c, ["body.stl", "Entry 'geometry'", self.dict_line(c, "geometry"),
                              "is not a regular file"])

    def test_unknownGeometryExtension(self):
        self.expect_fatal(*self.unknownGeometryExtension())

    def test_geometryWithoutExtension(self):
        c = self.case("sphere", geometry='"constant/geometry/sphere"')
        shutil.copy(self.path(c, "constant/geometry/sphere.geo"),
                    self.path(c, "constant/geometry/sphere"))
        self.expect_fatal(c, ["constant/geometry/sphere", "Entry 'geometry'",
                              self.dict_line(c, "geometry"), "has no extension",
                              "Valid geometry files are: .geo"])

    def test_geoSyntaxErrorNamesItsLine(self):
        self.expect_fatal(*self.geoSyntaxError())

    def test_geoUndefinedTopLevelObjectNamesItsLine(self):
        c = self.case("sphere")
        geo = self.path(c, "constant/geometry/sphere.geo")
        with open(geo) as f:
            text = f.read()
        with open(geo, "w") as f:
            f.write(text.replace("tlo ball;", "tlo bal;"))
        self.expect_fatal(c, ["sphere.geo", "line %d" % line_of(geo, "tlo"),
                              "tlo) bal is not a solid", "Defined solids: ball"])

    def test_geoWithoutAlgebraic3d(self):
        c = self.case("sphere")
        geo = self.path(c, "constant/geometry/sphere.geo")
        with open(geo) as f:
            text = f.read()
        with open(geo, "w") as f:
            f.write(text.replace("algebraic3d", "", 1))
        self.expect_fatal(c, ["sphere.geo", "algebraic3d", "tlo"])

    # -- STL --------------------------------------------------------------

    def test_emptyStl(self):
        self.expect_fatal(*self.emptyStl())

    def test_objWithoutTriangles(self):
        self.expect_fatal(*self.objWithoutTriangles())

    def test_bodyOutsideTheDomainBox(self):
        self.expect_fatal(*self.bodyOutsideTheDomainBox())

    def test_domainWithAZeroSide(self):
        self.expect_fatal(*self.domainWithAZeroSide())

    def test_stlWithoutTriangles(self):
        c, _, _ = self.stl_case(lambda facets: [])
        self.expect_fatal(c, ["sphere.stl", "no triangles"])

    def test_truncatedBinaryStl(self):
        self.expect_fatal(*self.truncatedBinaryStl())

    def test_truncatedAsciiStlNamesItsLine(self):
        c, _, stl = self.stl_case()
        with open(stl) as f:
            lines = f.readlines()
        # Cut inside the third vertex of the tenth facet
        cut = [i for i, l in enumerate(lines) if l.strip().startswith("vertex")][29]
        with open(stl, "w") as f:
            f.writelines(lines[:cut])
            f.write("      vertex 0.1 0.2\n")
        self.expect_fatal(c, ["sphere.stl", "line %d" % (cut + 2), "expected a number",
                              "end of file"])

    def test_stlThatIsNotClosed(self):
        self.expect_fatal(*self.stlThatIsNotClosed())

    def test_nonManifoldStl(self):
        # A third triangle on the first facet's first edge
        c, _, _ = self.stl_case(
            lambda facets: facets + [(facets[0][0], facets[0][1], ("0", "0", "0"))])
        self.expect_fatal(c, ["sphere.stl", "not manifold", "more than two triangles"])

    def test_inconsistentlyOrientedStl(self):
        self.expect_fatal(*self.inconsistentlyOrientedStl())

    def test_inwardOrientedStl(self):
        c, _, _ = self.stl_case(lambda facets: [(a, c_, b) for a, b, c_ in facets])
        self.expect_fatal(c, ["sphere.stl", "oriented inward", "flip the normals"])

    def test_stlWithDegenerateTriangles(self):
        # A zero-area triangle: two of its corners are the same point
        c, _, _ = self.stl_case(
            lambda facets: facets + [(facets[0][0], facets[0][1], facets[0][0])])
        self.expect_fatal(c, ["sphere.stl", "1 degenerate (zero-area) triangle"])

    # -- pmshDict ---------------------------------------------------------

    def test_missingMaxCellSize(self):
        self.expect_fatal(*self.missingMaxCellSize())

    def test_missingGeometryEntry(self):
        c = self.case("sphere")
        pmshDict = self.path(c, "system/pmshDict")
        with open(pmshDict) as f:
            lines = f.readlines()
        with open(pmshDict, "w") as f:
            f.writelines(l for l in lines if not l.startswith("geometry"))
        self.expect_fatal(c, ["Entry 'geometry' not found", "system/pmshDict",
                              ".geo (Netgen CSG)", ".stl"])

    def test_missingPmshDict(self):
        c = self.case("sphere")
        os.remove(self.path(c, "system/pmshDict"))
        # Names the file and both cures
        self.expect_fatal(c, ['"%s" does not exist' % self.path(c, "system/pmshDict"),
                              "Create system/pmshDict", "-dict <file>"])
        # ... and so for the file given with -dict
        c = self.case("sphere")
        self.expect_fatal(c, ['"%s" does not exist' % self.path(c, "system/nothere")],
                          args=["-dict", "system/nothere"])

    def test_missingPmshDictStopsEveryRank(self):
        """A missing dictionary is seen by every rank: none waits for the
        master's copy of a file that is not there"""
        c = self.case("sphere")
        os.remove(self.path(c, "system/pmshDict"))
        self.expect_fatal(c, ['"%s" does not exist' % self.path(c, "system/pmshDict")],
                          np=2)

    def test_maxCellSizeOfTheWrongType(self):
        self.expect_fatal(*self.maxCellSizeOfTheWrongType())

    def test_refinementLevelsOfTheWrongType(self):
        c = self.case("sphere", refinementLevels=1.5)
        self.expect_fatal(c, ["Entry 'refinementLevels' is 1.5 (not an integer)",
                              self.dict_line(c, "refinementLevels"),
                              "Valid values are integers 0 <= refinementLevels <= 10"])

    def test_nonPositiveMaxCellSize(self):
        self.expect_fatal(*self.nonPositiveMaxCellSize())
        c = self.case("sphere", maxCellSize=-0.1)
        self.expect_fatal(c, ["Entry 'maxCellSize' is -0.1\n", self.dict_line(c, "maxCellSize"),
                              "maxCellSize must be a number > 0"])

    def test_gradingOutsideZeroToOne(self):
        for value in (1.5, -0.1):
            c = self.case("sphere", grading=value)
            self.expect_fatal(c, ["Entry 'grading' is %s\n" % value,
                                  self.dict_line(c, "grading"),
                                  "Valid values are numbers 0 <= grading <= 1"])

    def test_maxPieceCellsBelowAThousand(self):
        c = self.case("sphere", maxPieceCells=10)
        self.expect_fatal(c, ["Entry 'maxPieceCells' is 10\n",
                              self.dict_line(c, "maxPieceCells"),
                              "Valid values are integers 1000 <= maxPieceCells <= 1e9"])

    def test_refinementLevelsOutsideTheirRange(self):
        for value in (11, -1):
            c = self.case("sphere", refinementLevels=value)
            self.expect_fatal(c, ["Entry 'refinementLevels' is %d\n" % value,
                                  self.dict_line(c, "refinementLevels"),
                                  "Valid values are integers 0 <= refinementLevels <= 10"])

    def test_unknownVolumeMesher(self):
        self.expect_fatal(*self.unknownVolumeMesher())

    def test_unknownEntryNamesTheValidOnes(self):
        c = self.case("sphere", refinementLevel=2)
        self.expect_fatal(c, ["Unknown entry 'refinementLevel'. Did you mean 'refinementLevels'?",
                              self.dict_line(c, "refinementLevel "),
                              "Valid entries are: geometry, maxCellSize, grading,"
                              " refinementLevels,"])

    def test_labelSizeIsNoLongerAnEntry(self):
        # Labels follow the OpenFOAM build (WM_LABEL_SIZE) now
        c = self.case("sphere", labelSize=64)
        self.expect_fatal(c, ["Entry 'labelSize' is no longer supported",
                              self.dict_line(c, "labelSize"), "WM_LABEL_SIZE",
                              "Remove the entry"])

    def test_refinementLevelsBeyondTheMachineMemoryStopAfterTheCoarseMesh(self):
        log = self.expect_fatal(*self.refinementLevelsBeyondTheMemory())
        self.assertNotIn("Stage 3", log, "the memory check came too late")

    def test_threeBillionCellsStopAtTheLabelsOrTheMemoryAfterTheCoarseMesh(self):
        # 7 levels of the sphere at maxCellSize 0.21: some 3 billion cells
        # (expected 3.4), 6 billion faces. 32-bit labels cannot hold them: the label stop,
        # before the partition. 64-bit labels can: on to the memory check,
        # which refuses them on this machine
        c = self.case("sphere", refinementLevels=7, maxCellSize=0.21)
        if os.environ.get("WM_LABEL_SIZE", "32") == "32":
            log = self.expect_fatal(c, ["Entry 'refinementLevels'",
                                        "too large for this OpenFOAM's 32-bit labels",
                                        "WM_LABEL_SIZE=64",
                                        "at most 6 refinementLevels"])
        else:
            log = self.expect_fatal(c, ["Entry 'refinementLevels'",
                                        "cannot fit in the memory"])
            self.assertNotIn("-bit labels", log)
        self.assertIn("expected fine cells: 3.4e+09", log)
        self.assertNotIn("Stage 2", log, "the label or memory check came too late")

    # -- case files -------------------------------------------------------

    def test_missingControlDict(self):
        c, phrases = self.missingControlDict()
        self.expect_fatal(c, phrases + ['"%s"' % self.path(c, "system/controlDict")])

    # -- an existing mesh -------------------------------------------------

    def test_existingMeshIsKeptWithoutOverwrite(self):
        c = self.case("sphere", refinementLevels=0)
        c.run("pmshFoam")
        c.set_entry("system/pmshDict", "maxCellSize", 0.2)
        self.expect_fatal(c, ["A mesh already exists", "constant/polyMesh", "-overwrite"])
        with open(self.path(c, "constant/polyMesh/points"), "rb") as f:
            before = f.read()
        c.run("pmshFoam", "-overwrite")
        with open(self.path(c, "constant/polyMesh/points"), "rb") as f:
            self.assertNotEqual(f.read(), before)
        c.check_mesh()

    def test_badInputWithOverwriteKeepsTheExistingMesh(self):
        c = self.case("sphere", refinementLevels=0)
        c.run("pmshFoam")
        # Before meshing (settings) and after the coarse mesh (memory)
        c.set_entry("system/pmshDict", "grading", 2)
        self.expect_fatal(c, ["Entry 'grading'"], args=["-overwrite"])
        c.set_entry("system/pmshDict", "grading", 0.3)
        for key, value in self.beyondTheMemory.items():
            c.set_entry("system/pmshDict", key, value)
        self.expect_fatal(c, ["Entry 'refinementLevels'", "memory"], args=["-overwrite"])
        c.check_mesh()


class badInputParallel(BadInputTest, cases):
    """mpirun -np 2 (or 3) pmshFoam -parallel: every rank stops together,
    mpirun exits non-zero, one error is printed, no processor* is written.
    Also what only a parallel run meets: more ranks than coarse cells, the
    decomposition dictionary, and the 0/ field templates (a serial run
    writes no fields, so it does not read them)."""

    def test_missingGeometryFile(self):
        self.expect_fatal(*self.missingGeometryFile(), np=2)

    def test_unknownGeometryExtension(self):
        self.expect_fatal(*self.unknownGeometryExtension(), np=2)

    def test_geoSyntaxErrorNamesItsLine(self):
        self.expect_fatal(*self.geoSyntaxError(), np=2)

    def test_emptyStl(self):
        self.expect_fatal(*self.emptyStl(), np=2)

    def test_objWithoutTriangles(self):
        self.expect_fatal(*self.objWithoutTriangles(), np=2)

    def test_bodyOutsideTheDomainBox(self):
        self.expect_fatal(*self.bodyOutsideTheDomainBox(), np=2)

    def test_truncatedBinaryStl(self):
        self.expect_fatal(*self.truncatedBinaryStl(), np=2)

    def test_stlThatIsNotClosed(self):
        self.expect_fatal(*self.stlThatIsNotClosed(), np=2)

    def test_inconsistentlyOrientedStl(self):
        self.expect_fatal(*self.inconsistentlyOrientedStl(), np=2)

    def test_missingMaxCellSize(self):
        self.expect_fatal(*self.missingMaxCellSize(), np=2)

    def test_maxCellSizeOfTheWrongType(self):
        self.expect_fatal(*self.maxCellSizeOfTheWrongType(), np=2)

    def test_nonPositiveMaxCellSize(self):
        self.expect_fatal(*self.nonPositiveMaxCellSize(), np=2)

    def test_unknownVolumeMesher(self):
        self.expect_fatal(*self.unknownVolumeMesher(), np=2)

    def test_missingControlDict(self):
        self.expect_fatal(*self.missingControlDict(), np=2)

    def test_refinementLevelsBeyondTheMachineMemoryStopAfterTheCoarseMesh(self):
        log = self.expect_fatal(*self.refinementLevelsBeyondTheMemory(), np=2)
        self.assertNotIn("Stage 3", log, "the memory check came too late")

    def test_moreRanksThanCoarseCells(self):
        # A tetrahedron meshed coarsely is one coarse cell
        c = self.case("sphere", geometry='"constant/geometry/tet.geo"', maxCellSize=10)
        with open(self.path(c, "constant/geometry/tet.geo"), "w") as f:
            f.write("algebraic3d\n"
                    "solid tet = plane (0, 0, 0; 0, 0, -1) and plane (0, 0, 0; 0, -1, 0)\n"
                    "    and plane (0, 0, 0; -1, 0, 0) and plane (1, 0, 0; 1, 1, 1)"
                    " -bcname=walls;\n"
                    "tlo tet;\n")
        self.expect_fatal(c, ["Cannot split a coarse mesh of 1 cells into 3 parts",
                              "maxCellSize"], np=3)

    def test_nonuniformInternalField(self):
        c = self.case("sphere")
        field = self.path(c, "0/U")
        with open(field) as f:
            text = f.read()
        with open(field, "w") as f:
            f.write(text.replace("internalField   uniform (0 0 0);",
                                 "internalField   nonuniform List<vector> 2((0 0 0) (1 0 0));"))
        self.expect_fatal(c, ["Entry 'internalField' is nonuniform",
                              "'internalField uniform <value>;'", "(mapFieldsPar)",
                              "file: %s at line %d." % (field, line_of(field, "internalField"))],
                          np=2)

    def test_nonuniformBoundaryValue(self):
        c = self.case("sphere")
        field = self.path(c, "0/U")
        with open(field) as f:
            text = f.read()
        with open(field, "w") as f:
            f.write(text.replace("type            noSlip;",
                                 "type            fixedValue;\n"
                                 "        value           nonuniform List<vector> 1((1 0 0));"))
        self.expect_fatal(c, ["Entry 'value' of boundaryField/walls is nonuniform",
                              "'value uniform <value>;'",
                              "file: %s at line %d." % (field, line_of(field, "value"))],
                          np=2)

    def test_fieldWithoutAConditionForAPatch(self):
        # Found once the coarse mesh gives the patches (Stage 1)
        c = self.case("sphere")
        field = self.path(c, "0/U")
        with open(field) as f:
            text = f.read()
        with open(field, "w") as f:
            f.write(re.sub(r"^    walls$", "    sides", text, flags=re.M))
        self.expect_fatal(c, ["Field U has no boundary condition for patch 'walls' (type wall)",
                              "Add an entry 'walls { type ...; }'",
                              "file: %s\n" % field], np=2)

    def test_conditionOpenFoamRefusesOnItsPatchStopsBeforeTheFineMesh(self):
        # slip on sphereDrag's symmetry sides: OpenFOAM refuses it when the
        # field is built on the mesh. That was stage 7, after all the
        # meshing; now it is the coarse mesh's patches, before stage 2
        c = self.case("sphereDrag")
        field = self.path(c, "0/U")
        c.substitute("0/U", r"(?m)^    outlet$", "    sides\n    {\n        type slip;\n    }\n    outlet")
        log = self.expect_fatal(c, ["inconsistent patch and patchField types",
                                    "patch type symmetry and patchField type slip",
                                    "file: %s.boundaryField.sides" % field], np=2)
        self.assertNotIn("Stage 2", log, "found only after the coarse mesh's stage")

    def test_fixedValueWithoutValueStopsBeforeTheFineMesh(self):
        c = self.case("sphere")
        field = self.path(c, "0/U")
        c.substitute("0/U", "type            noSlip;", "type            fixedValue;")
        log = self.expect_fatal(c, ["Essential entry 'value' missing on patch walls",
                                    "file: %s.boundaryField.walls" % field], np=2)
        self.assertNotIn("Stage 2", log, "found only after the coarse mesh's stage")

    # -- the decomposition --------------------------------------------------

    def test_missingDecomposeParDict(self):
        c = self.case("sphere")
        log = self.expect_fatal(c, ["The decomposition dictionary %s"
                                    % self.path(c, "system/nothere"),
                                    "(-decomposeParDict) does not exist"],
                                np=2, args=["-decomposeParDict", "system/nothere"])
        self.assertNotIn("Stage 1", log, "not found before meshing")

    def test_unknownDecompositionMethod(self):
        c = self.case("sphere")
        with open(self.path(c, "system/decomposeParDict"), "w") as f:
            f.write("FoamFile { version 2.0; format ascii; class dictionary;"
                    " object decomposeParDict; }\n"
                    "numberOfSubdomains 2;\n"
                    "method metiss;\n")
        log = self.expect_fatal(c, ["Unknown decomposition method 'metiss'",
                                    self.path(c, "system/decomposeParDict"),
                                    "Valid decomposition methods: (", " metis ", "simple"],
                                np=2)
        self.assertNotIn("Stage 1", log, "not found before meshing")

    def test_existingProcessorMeshIsKeptWithoutOverwrite(self):
        c = self.case("sphere", refinementLevels=0)
        self.parallel_mesh(c, 2)
        c.set_entry("system/pmshDict", "maxCellSize", 0.2)
        self.expect_fatal(c, ["A mesh already exists", "processor", "-overwrite"], np=2)

    def test_badInputWithOverwriteKeepsTheExistingProcessorMeshes(self):
        c = self.case("sphere", refinementLevels=0)
        self.parallel_mesh(c, 2)
        # Before meshing (settings) and after the coarse mesh (memory):
        # processor*, their fields and decomposeParDict stay as they were
        c.set_entry("system/pmshDict", "volumeMesher", "tetgen")
        self.expect_fatal(c, ["Entry 'volumeMesher'"], np=2, args=["-overwrite"])
        c.set_entry("system/pmshDict", "volumeMesher", "netgen")
        for key, value in self.beyondTheMemory.items():
            c.set_entry("system/pmshDict", key, value)
        self.expect_fatal(c, ["Entry 'refinementLevels'", "memory"], np=2,
                          args=["-overwrite"])
        self.assertRegex(c.check_mesh(np=2), r"Coupled point location match.*OK")


if __name__ == "__main__":
    unittest.main(verbosity=2)
