"""Serial pmshFoam end to end: every tutorial meshed at refinement levels
0..2, ascii and binary, judged by OpenFOAM's own checkMesh; the refined
boundary lies on the geometry. (Bad input: testBadInput.py.)

Run one test:  python3 testSerialTutorials.py sphere.test_meshOkAtEachLevelAscii
"""

import math
import os
import re
import sys
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, cells_in_checkmesh_log  # noqa: E402


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
        s = c.summary()
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
            q = c.summary()["quality"]
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
