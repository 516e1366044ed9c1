"""Serial pmshFoam end to end: every tutorial meshed at refinement levels
0..2, ascii and binary, judged by OpenFOAM's own checkMesh; the refined
boundary lies on the geometry; bad input stops cleanly and writes nothing.

Run one test:  python3 testSerialTutorials.py sphere.test_meshOkAtEachLevelAscii
"""

import math
import os
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tutorialCase import TutorialCase, cells_in_checkmesh_log, openfoam_environment  # noqa: E402


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


class sphere(CaseTest):

    def test_meshOkAtEachLevelAscii(self):
        self.mesh_levels("sphere", [0, 1, 2], "ascii")

    def test_meshOkAtEachLevelBinary(self):
        self.mesh_levels("sphere", [0, 1, 2], "binary")

    def test_meshOkWith64BitLabels(self):
        for fmt in ("ascii", "binary"):
            c = self.case("sphere", refinementLevels=1, labelSize=64)
            c.write_format(fmt)
            c.run("pmshFoam")
            c.check_mesh()
            with open(os.path.join(c.dir, "constant/polyMesh/owner"), "rb") as f:
                self.assertIn(b"label=64", f.read(2000))

    def test_refinedBoundaryLiesOnTheSphere(self):
        meshes = self.mesh_levels("sphere", [2])
        points = meshes[2][0].polymesh().points()
        boundary = meshes[2][0].polymesh().boundary_points()
        worst = max(abs(math.sqrt(sum(x * x for x in points[p])) - 1.0) for p in boundary)
        self.assertLess(worst, 1e-9, "boundary point off the unit sphere by %g" % worst)

    def test_cellCountGrowsAboutEightfoldPerLevel(self):
        meshes = self.mesh_levels("sphere", [0, 1, 2])
        for r in (1, 2):
            ratio = meshes[r][1] / meshes[r - 1][1]
            self.assertTrue(8 * 0.7 <= ratio <= 8 * 1.3,
                            "cells grew %.2fx from level %d to %d" % (ratio, r - 1, r))

    def test_tutorialAllrunEndsWithMeshOK(self):
        c = self.case("sphere")
        env = openfoam_environment()
        env["PATH"] = os.path.dirname(c.pmshFoam) + ":" + env["PATH"]
        proc = subprocess.run([os.path.join(c.dir, "Allrun")], stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, env=env)
        out = proc.stdout.decode()
        self.assertEqual(proc.returncode, 0, out)
        self.assertIn("Mesh OK", out)


class shaft(CaseTest):

    def test_meshOkAtEachLevelWithNamedPatches(self):
        meshes = self.mesh_levels("shaft", [0, 1, 2])
        names = [n for n, _ in meshes[0][0].polymesh().boundary()]
        for expected in ("inlet", "outlet", "wall"):
            self.assertIn(expected, names)
        types = dict((n, e["type"]) for n, e in meshes[0][0].polymesh().boundary())
        self.assertEqual(types["inlet"], "patch")
        self.assertEqual(types["wall"], "wall")


class sphereSTL(CaseTest):

    def test_meshOkAtEachLevel(self):
        self.mesh_levels("sphereSTL", [0, 1, 2])


class badInput(CaseTest):
    """Each must stop with FOAM FATAL ERROR naming the problem, exit
    non-zero and write nothing."""

    def expect_fatal(self, case, *phrases):
        code, log = case.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0, log)
        self.assertIn("FOAM FATAL ERROR", log)
        for phrase in phrases:
            self.assertIn(phrase, log)
        self.assertFalse(case.exists("constant/polyMesh"), "a mesh was written")
        leftovers = [f for f in os.listdir(os.path.join(case.dir, "constant"))
                     if f.startswith(".")]
        self.assertEqual(leftovers, [], "temporary output left behind")

    def test_missingGeometryFile(self):
        c = self.case("sphere", geometry='"constant/geometry/nothere.geo"')
        self.expect_fatal(c, "nothere.geo")

    def test_unknownVolumeMesher(self):
        c = self.case("sphere", volumeMesher="tetgen")
        self.expect_fatal(c, "tetgen", "netgen")

    def test_nonPositiveMaxCellSize(self):
        c = self.case("sphere", maxCellSize=0)
        self.expect_fatal(c, "maxCellSize")

    def test_stlThatIsNotClosed(self):
        c = self.case("sphereSTL")
        stl = os.path.join(c.dir, "constant/geometry/sphere.stl")
        with open(stl) as f:
            text = f.read()
        # Drop the first facet
        start = text.index("facet")
        end = text.index("endfacet", start) + len("endfacet")
        with open(stl, "w") as f:
            f.write(text[:start] + text[end:])
        self.expect_fatal(c, "sphere.stl", "not closed")

    def test_existingMeshIsKeptWithoutOverwrite(self):
        c = self.case("sphere", refinementLevels=0)
        c.run("pmshFoam")
        with open(os.path.join(c.dir, "constant/polyMesh/points"), "rb") as f:
            before = f.read()
        c.set_entry("system/pmshDict", "maxCellSize", 0.2)
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("-overwrite", log)
        with open(os.path.join(c.dir, "constant/polyMesh/points"), "rb") as f:
            self.assertEqual(f.read(), before)
        c.run("pmshFoam", "-overwrite")
        with open(os.path.join(c.dir, "constant/polyMesh/points"), "rb") as f:
            self.assertNotEqual(f.read(), before)
        c.check_mesh()


if __name__ == "__main__":
    unittest.main(verbosity=2)
