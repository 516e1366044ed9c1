"""tutorials/sphereDrag end to end, as shipped: the tutorial's own Allrun
(155k cells on 2 ranks, about a minute of CPU on each); OpenFOAM's
checkMesh -parallel, simpleFoam -parallel and the forceCoeffs function
object judge the case: Cd within 3 % of the reference.

Run one test:  python3 testSphereDrag.py sphereDrag.test_allrunGivesCdWithin3PercentOfTheReference
"""

import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, cells_in_checkmesh_log  # noqa: E402

REFERENCE_CD = 1.087     # Johnson & Patel 1999, sphere at Re = 100


class sphereDrag(CaseTest):

    def coefficients(self, case):
        """[(iteration, Cd)] from the forceCoeffs function object's file"""
        path = os.path.join(case.dir, "postProcessing/forceCoeffs/0/coefficient.dat")
        with open(path) as f:
            rows = [line.split() for line in f if not line.startswith("#")]
        return [(int(r[0]), float(r[1])) for r in rows]

    def test_allrunGivesCdWithin3PercentOfTheReference(self):
        """The Allrun meshes the box with its named patches on 2 ranks
        (Mesh OK), simpleFoam converges on it (the runTimeControl on Cd
        stops it before endTime) and the Cd printed is the last one
        forceCoeffs wrote, within 3 % of the reference with no more than
        155k cells (+1.3 % with the shipped schemes; Gauss linear
        gradients gave +7.0 % and fail this test)."""
        c = self.case("sphereDrag")
        code, out = c.run_allrun(timeout=600)
        self.assertEqual(code, 0, out)
        self.assertIn("Mesh OK", out)

        boundary = dict(c.polymesh("processor0/constant/polyMesh").boundary())
        for name, kind in (("inlet", "patch"), ("outlet", "patch"),
                           ("sides", "symmetry"), ("ball", "wall")):
            self.assertIn(name, boundary)
            self.assertEqual(boundary[name]["type"], kind, name)

        with open(os.path.join(c.dir, "log.simpleFoam")) as f:
            log = f.read()
        self.assertRegex(log, r"(?m)^End")
        self.assertIn("CdSettled condition satisfied", log)

        cd = self.coefficients(c)
        iterations, last = cd[-1]
        self.assertLess(iterations, 1000, "stopped at endTime, not when Cd settled")
        printed = re.search(r"Cd = ([\d.]+)\s+reference 1\.087.*difference ([-+][\d.]+) %", out)
        self.assertIsNotNone(printed, out)
        self.assertAlmostEqual(float(printed.group(1)), last, places=4)
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.03, "Cd %g" % last)
        with open(os.path.join(c.dir, "log.checkMesh")) as f:
            cells = cells_in_checkmesh_log(f.read())
        self.assertLessEqual(cells, 155500, "the 3 % must hold at no more than 155k cells")

    def test_hxtMeshConvergesWithTheShippedSchemes(self):
        """The same case with volumeMesher hxt, the fast mesher: simpleFoam
        with the tutorial's own schemes converges on it (Cd settles), and
        Cd is within 5 % of the reference. HXT's mesh of this dictionary
        diverged (Cd -183 at iteration 100, a floating-point exception
        later): its interior sizes jumped away from the ball and left
        interior points a tenth of a cell above the wall
        (bench/results/hxt-divergence.md). It now gives +3.5 % at 194k
        cells; Netgen's +1.3 % (the 3 % of the Allrun is not yet met)."""
        c = self.case("sphereDrag", volumeMesher="hxt")
        c.run("pmshFoam", np=2)
        c.check_mesh(np=2)
        code, log = c.run("simpleFoam", np=2, check=False)
        self.assertEqual(code, 0, "simpleFoam failed (diverged?):\n" + log[-3000:])
        self.assertIn("CdSettled condition satisfied", log)
        iterations, last = self.coefficients(c)[-1]
        self.assertLess(iterations, 1000, "stopped at endTime, not when Cd settled")
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.05, "Cd %g" % last)


if __name__ == "__main__":
    unittest.main(verbosity=2)
