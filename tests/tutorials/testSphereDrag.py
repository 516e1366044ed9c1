"""tutorials/sphereDrag end to end, as shipped: the tutorial's own Allrun
(hxt with 3 prism layers on the ball, 223k cells on 2 ranks); OpenFOAM's
checkMesh -parallel, simpleFoam -parallel and the forceCoeffs function
object judge the case: Cd within 1 % of the reference, and the other
routes (Netgen with layers, hxt without, hxt smoothed by Netgen), at the
ball's size 0.12 and the wake's 1.2, converged within their bounds.

Run one test:  python3 testSphereDrag.py sphereDrag.test_allrunGivesCdWithin1PercentOfTheReference
"""

import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402

REFERENCE_CD = 1.087     # Johnson & Patel 1999, sphere at Re = 100


class sphereDrag(CaseTest):

    def coefficients(self, case):
        """[(iteration, Cd)] from the forceCoeffs function object's file"""
        path = os.path.join(case.dir, "postProcessing/forceCoeffs/0/coefficient.dat")
        with open(path) as f:
            rows = [line.split() for line in f if not line.startswith("#")]
        return [(int(r[0]), float(r[1])) for r in rows]

    def settled_cd(self, case):
        """simpleFoam -parallel on a meshed case (checkMesh Mesh OK first):
        it must converge (Cd settles before endTime); the last Cd"""
        case.check_mesh(np=2)
        code, log = case.run("simpleFoam", np=2, check=False)
        self.assertEqual(code, 0, "simpleFoam failed (diverged?):\n" + log[-3000:])
        self.assertIn("CdSettled condition satisfied", log)
        iterations, last = self.coefficients(case)[-1]
        self.assertLess(iterations, 1000, "stopped at endTime, not when Cd settled")
        return last

    def cd_without_layers(self, **entries):
        """The tutorial without the ball's layers (pmshDict entries as
        given) at fewer cells, meshed on 2 ranks and solved: the settled
        Cd"""
        c = self.case("sphereDrag", **entries)
        self.fewer_cells(c)
        c.substitute("system/pmshDict", r"\n\s*layers\s+3;\n\s*firstLayerThickness\s+0\.004;"
                     r"\n\s*expansionRatio\s+1\.2;", "")
        c.run("pmshFoam", np=2)
        self.assertEqual(c.summary()["prisms"], 0)
        return self.settled_cd(c)

    def fewer_cells(self, case):
        """The ball's size 0.12 and the wake's 1.2 instead of 0.1 and 1"""
        case.substitute("system/pmshDict", r"maxCellSize         0\.1;", "maxCellSize         0.12;")
        case.substitute("system/pmshDict", r"maxCellSize 1; \}", "maxCellSize 1.2; }")

    def test_allrunGivesCdWithin1PercentOfTheReference(self):
        """The Allrun meshes the box with its named patches and the ball's
        prism layers on 2 ranks (Mesh OK), simpleFoam converges on it (the
        runTimeControl on Cd stops it before endTime) and the Cd printed is
        the last one forceCoeffs wrote, within 1 % of the reference
        (-0.3 % with hxt and 3 layers, +0.3 % before Netgen's smoothing
        became hxt's default; hxt without layers gave +3.5 %,
        Gauss linear gradients +7 %: both fail this test)."""
        c, out = self.sphere_in_box_allrun("sphereDrag")
        s = c.summary()
        self.assertEqual(s["volumeMesher"], "hxt")
        self.assertEqual(s["layers"]["ball"]["coverage"], 1)

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
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.01, "Cd %g" % last)

    def test_netgenWithLayersGivesCdWithin2Percent(self):
        """volumeMesher netgen, one word away, at the ball's size 0.12 and
        the wake's 1.2: the tutorial's answer (-0.5 % with 133k cells;
        -1.3 % at the tutorial's sizes; hxt +1.6 % at these sizes with
        143k cells, +0.3 % at the tutorial's)."""
        c = self.case("sphereDrag", volumeMesher="netgen")
        self.fewer_cells(c)
        c.run("pmshFoam", np=2)
        last = self.settled_cd(c)
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.02, "Cd %g" % last)

    def test_hxtMeshWithoutLayersConvergesWithTheShippedSchemes(self):
        """hxt without the layers, 121k cells: simpleFoam with the
        tutorial's own schemes converges on it, and Cd is within 4 % of
        the reference: +2.9 % with Netgen's smoothing of HXT's interior
        points, hxt's default (+2.8 % with optimisationSteps 3). HXT's
        points where it puts them gave +4.4 %, which fails this test; HXT's
        mesh of this dictionary before its sizes were graded diverged (Cd
        -183 at iteration 100, a floating-point exception later): its
        interior sizes jumped away from the ball and left interior points
        a tenth of a cell above the wall (bench/results/hxt-divergence.md)."""
        last = self.cd_without_layers()
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.04, "Cd %g" % last)


if __name__ == "__main__":
    unittest.main(verbosity=2)
