"""Serial pmshFoam end to end: every tutorial meshed at refinement levels
0..2, ascii and binary, judged by OpenFOAM's own checkMesh; the refined
boundary lies on the geometry. (Bad input: testBadInput.py.)

Run one test:  python3 testSerialTutorials.py sphere.test_meshOkAtEachLevelAscii
"""

import json
import math
import os
import re
import shutil
import sys
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tutorialCase import SOURCE_DIR, TutorialCase, cells_in_checkmesh_log, openfoam_environment  # noqa: E402


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

    def geometry_case(self, geometry, wall_patch=None, **entries):
        """tutorials/sphere meshing tests/data/geometry/<geometry> instead:
        no patches entry (every patch as the geometry names it), and 0/U
        and 0/p with the sphere's `walls` entry renamed wall_patch, or no
        0/ at all without one."""
        c = self.case("sphere", **entries)
        shutil.copy(os.path.join(SOURCE_DIR, "tests", "data", "geometry", geometry),
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


class sphere(CaseTest):

    def test_meshOkAtEachLevelAscii(self):
        self.mesh_levels("sphere", [0, 1, 2], "ascii")

    def test_meshOkAtEachLevelBinary(self):
        self.mesh_levels("sphere", [0, 1, 2], "binary")

    def test_refinedBoundaryLiesOnTheSphere(self):
        # binary: the points as computed (ascii keeps writePrecision digits)
        meshes = self.mesh_levels("sphere", [2], "binary")
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

    def test_summaryJsonAgreesWithCheckMesh(self):
        """postProcessing/pmshFoam/summary.json, what the benchmark reads"""
        c = self.case("sphere", refinementLevels=1)
        started = time.monotonic()
        c.run("pmshFoam")
        wall = time.monotonic() - started
        cells = cells_in_checkmesh_log(c.check_mesh())
        with open(os.path.join(c.dir, "postProcessing/pmshFoam/summary.json")) as f:
            s = json.load(f)
        self.assertEqual(s["fineCells"], cells)
        self.assertEqual(s["fineCellsPerRank"], [cells])
        self.assertEqual(s["volumeMesherPerRank"], ["netgen"])
        self.assertEqual(s["volumeAttemptsPerRank"], [1])
        stages = ["coarse", "partition", "surface", "volume", "numbering", "balance", "write"]
        self.assertEqual(list(s["stages"]), stages)
        memory = [s["stages"][k]["peakMemoryBytes"] for k in stages]
        self.assertEqual(memory, sorted(memory), "a peak so far cannot fall")
        self.assertEqual(memory[-1], max(s["peakMemoryPerRankBytes"]))
        # The paper's split that the benchmark reads: coarse mesh, fine mesh
        # (stages 2-6) and write are disjoint parts of the run, which
        # pmshFoam's total clock and this test's clock each measure whole;
        # between the stages there is only logging
        parts = s["coarseTime"] + s["fineTime"] + s["writeTime"]
        self.assertLessEqual(parts, s["totalTime"] * (1 + 1e-9), "a stage counted twice")
        self.assertLessEqual(s["totalTime"], wall)
        self.assertGreater(parts, 0.9 * s["totalTime"], "a stage left out")
        self.assertAlmostEqual(s["fineCellsPerSecondPerCore"] * s["fineTime"], cells,
                               delta=1e-6 * cells)
        # bench/memoryFigures.py recovers weightedFineCells with the
        # estimate's factor
        self.assertGreater(s["estimatedCellsPerWeighted"], 0)

    def test_faceMetricsAsCheckMesh(self):
        """checkMeshFaceMetrics.H, the kernel of the quality pass and of
        summary.json's quality: max and average non-orthogonality and max
        skewness as OpenFOAM's checkMesh finds them on the written mesh.
        hxt with the pass: the worst skewness on a boundary face; Netgen
        unoptimised at level 0: on an internal face."""
        for mesher, steps, levels in (("hxt", 3, 1), ("netgen", 0, 0)):
            c = self.case("sphere", refinementLevels=levels, volumeMesher=mesher,
                          optimisationSteps=steps)
            c.run("pmshFoam")
            text = c.check_mesh()
            non_orth = re.search(r"non-orthogonality Max:\s*([\d.]+)\s+average:\s*([\d.]+)", text)
            skew = re.search(r"Max skewness =\s*([\d.]+)", text)
            with open(os.path.join(c.dir, "postProcessing/pmshFoam/summary.json")) as f:
                q = json.load(f)["quality"]
            self.assertAlmostEqual(q["maxNonOrthogonality"], float(non_orth.group(1)), places=4, msg=mesher)
            self.assertAlmostEqual(q["avgNonOrthogonality"], float(non_orth.group(2)), places=4, msg=mesher)
            self.assertAlmostEqual(q["maxSkewness"], float(skew.group(1)), places=4, msg=mesher)

    def test_tutorialAllrunEndsWithMeshOK(self):
        c = self.case("sphere")
        code, out = c.run_allrun()
        self.assertEqual(code, 0, out)
        self.assertIn("Mesh OK", out)


class shaft(CaseTest):

    def test_meshOkAtEachLevelWithNamedPatches(self):
        meshes = self.mesh_levels("shaft", [0, 1, 2])
        names = [n for n, _ in meshes[0][0].polymesh().boundary()]
        for expected in ("inlet", "outlet", "walls"):
            self.assertIn(expected, names)
        types = dict((n, e["type"]) for n, e in meshes[0][0].polymesh().boundary())
        self.assertEqual(types["inlet"], "patch")
        self.assertEqual(types["walls"], "wall")


class sphereSTL(CaseTest):

    def test_meshOkAtEachLevel(self):
        self.mesh_levels("sphereSTL", [0, 1, 2])


if __name__ == "__main__":
    unittest.main(verbosity=2)
