"""Periodic pairs: the faces x = 0 and x = 1 of a cube, paired by CSG
'identify periodic', become a pair of cyclic patches whose faces match
(checkMesh's "Coupled point location match ... OK"), at r = 0, 1, 2
serially, on 2 and 4 ranks (faces whose image is on another rank in
processorCyclic patches), after reconstructParMesh, and a solver runs on
them.

Run one test:  python3 testPeriodic.py periodic.test_cyclicMatchSerialAtEachLevel
"""

import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from tutorialCase import SOURCE_DIR  # noqa: E402
from testSerialTutorials import CaseTest  # noqa: E402

GEOMETRY = os.path.join(SOURCE_DIR, "tests", "data", "geometry")
MATCH = r"Coupled point location match \(average [0-9.e+-]+\) OK"


class periodic(CaseTest):

    def periodic_case(self, levels):
        """tutorials/sphere with the periodic cube; 0/U and 0/p name its
        wall patch `cube` (the cyclic ones come from setConstraintTypes)."""
        c = self.case("sphere", maxCellSize=0.3, refinementLevels=levels)
        shutil.copy(os.path.join(GEOMETRY, "periodicCube.geo"),
                    os.path.join(c.dir, "constant", "geometry", "periodicCube.geo"))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/periodicCube.geo"')
        path = os.path.join(c.dir, "system", "pmshDict")
        with open(path) as f:
            text = re.sub(r"(?ms)^patches\s*\{.*?^\}", "", f.read())
        with open(path, "w") as f:
            f.write(text)
        for field in ("U", "p"):
            path = os.path.join(c.dir, "0", field)
            with open(path) as f:
                text = f.read().replace("walls", "cube")
            with open(path, "w") as f:
                f.write(text)
        return c

    def mesh(self, levels, np):
        """Mesh; checkMesh must say Mesh OK and match the cyclic points.
        Returns the case and the boundary file of processor 0 (or the
        case)."""
        c = self.periodic_case(levels)
        c.run("pmshFoam", np=np)
        self.assertRegex(c.check_mesh(np=np), MATCH)
        where = "processor0/constant/polyMesh" if np > 1 else "constant/polyMesh"
        boundary = dict(c.polymesh(where).boundary())
        self.assertEqual(boundary["left"]["type"], "cyclic")
        self.assertEqual(boundary["left"]["neighbourPatch"], "right")
        self.assertEqual(boundary["right"]["type"], "cyclic")
        self.assertEqual(boundary["left"]["separationVector"].split(), ["(1", "0", "0)"])
        return c, boundary

    def test_cyclicMatchSerialAtEachLevel(self):
        for levels in (0, 1, 2):
            _, boundary = self.mesh(levels, 1)
            self.assertEqual(boundary["left"]["nFaces"], boundary["right"]["nFaces"])
            self.assertGreater(int(boundary["left"]["nFaces"]), 0)

    def test_cyclicMatchOnTwoRanksAtEachLevelAndASolverRuns(self):
        for levels in (0, 1, 2):
            c, _ = self.mesh(levels, 2)
        c.set_entry("system/controlDict", "endTime", 5)
        _, log = c.run("simpleFoam", np=2)
        self.assertRegex(log, r"(?m)^End")

    def test_processorCyclicOnFourRanksReconstructs(self):
        c, _ = self.mesh(1, 4)
        through = [n for p in range(4) for n, e in
                   c.polymesh("processor%d/constant/polyMesh" % p).boundary()
                   if e["type"] == "processorCyclic"]
        self.assertTrue(through, "no face's image is on another rank")
        self.assertTrue(all(re.match(r"procBoundary\dto\dthrough(left|right)$", n)
                            for n in through), through)
        c.run("reconstructParMesh", "-constant")
        self.assertRegex(c.check_mesh(), MATCH)


if __name__ == "__main__":
    unittest.main()
