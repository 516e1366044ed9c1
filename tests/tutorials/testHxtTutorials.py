"""Serial pmshFoam with the HXT backend (volumeMesher hxt): every tutorial
at refinement levels 0..2 passes OpenFOAM's checkMesh, as with Netgen, and
the cell count per level stays near Netgen's.

Run one test:  python3 testHxtTutorials.py hxt.test_sphereMeshOkAtEachLevel
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402


class hxt(CaseTest):

    def test_sphereMeshOkAtEachLevel(self):
        self.mesh_levels("sphere", [0, 1, 2], volumeMesher="hxt")

    def test_shaftMeshOkAtEachLevel(self):
        self.mesh_levels("shaft", [0, 1, 2], volumeMesher="hxt")

    def test_sphereSTLMeshOkAtEachLevel(self):
        self.mesh_levels("sphereSTL", [0, 1, 2], volumeMesher="hxt")

    def test_binaryMeshOk(self):
        self.mesh_levels("sphere", [1], "binary", volumeMesher="hxt")

    def test_cellCountAtMostSixtyPercentAboveNetgen(self):
        """The interior size is capped at the same fine size as Netgen's;
        HXT has no optimiser that removes cells as Netgen's does, so it
        makes 1.45-1.5x as many (sphere, shaft, sphereSTL at r = 2)."""
        for name in ("sphere", "shaft", "sphereSTL"):
            n = self.mesh_levels(name, [2], volumeMesher="netgen")[2][1]
            h = self.mesh_levels(name, [2], volumeMesher="hxt")[2][1]
            self.assertTrue(n <= h < 1.6 * n, "%s: hxt %d cells, netgen %d" % (name, h, n))


if __name__ == "__main__":
    unittest.main(verbosity=2)
