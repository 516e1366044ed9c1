"""tutorials/sphereDrag end to end, coarser: the tutorial's own Allrun on
a mesh one refinement level coarser (refinementLevels 1: 17.9k cells), so
that it takes about 30 s of CPU on each of 2 ranks; OpenFOAM's checkMesh
-parallel, simpleFoam -parallel and the forceCoeffs function object judge
the case. (The full case, with its Cd within 10 % of the reference, is
./Allrun in the tutorial: not a test.)

Run one test:  python3 testSphereDrag.py sphereDrag.test_coarseAllrunGivesCdNearTheReference
"""

import os
import re
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tutorialCase import openfoam_environment  # noqa: E402
from testSerialTutorials import CaseTest  # noqa: E402

REFERENCE_CD = 1.087     # Johnson & Patel 1999, sphere at Re = 100


class sphereDrag(CaseTest):

    def coefficients(self, case):
        """[(iteration, Cd)] from the forceCoeffs function object's file"""
        path = os.path.join(case.dir, "postProcessing/forceCoeffs/0/coefficient.dat")
        with open(path) as f:
            rows = [line.split() for line in f if not line.startswith("#")]
        return [(int(r[0]), float(r[1])) for r in rows]

    def test_coarseAllrunGivesCdNearTheReference(self):
        """The Allrun meshes the box with its named patches on 2 ranks
        (Mesh OK), simpleFoam converges on it (the runTimeControl on Cd
        stops it before endTime) and the Cd printed is the last one
        forceCoeffs wrote, within the Allrun's 10 % of the reference even
        on this mesh (+8.8 %: 17.9k cells, 65 iterations)."""
        c = self.case("sphereDrag", refinementLevels=1)
        env = openfoam_environment()
        env["PATH"] = os.path.dirname(c.pmshFoam) + ":" + env["PATH"]
        proc = subprocess.run([os.path.join(c.dir, "Allrun")], stdin=subprocess.DEVNULL,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              env=env, timeout=600)
        out = proc.stdout.decode()
        self.assertEqual(proc.returncode, 0, out)
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
        self.assertLess(abs(last - REFERENCE_CD) / REFERENCE_CD, 0.10,
                        "Cd %g on the coarse mesh" % last)


if __name__ == "__main__":
    unittest.main(verbosity=2)
