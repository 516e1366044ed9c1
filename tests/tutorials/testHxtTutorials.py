"""Serial pmshFoam with the HXT backend (volumeMesher hxt): every tutorial
at refinement levels 0..2 passes OpenFOAM's checkMesh, as with Netgen, and
the cell count per level stays near Netgen's.

Run one test:  python3 testHxtTutorials.py hxt.test_sphereMeshOkAtEachLevel
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from testSerialTutorials import CaseTest  # noqa: E402


class hxt(CaseTest):

    def test_sphereMeshOkAtEachLevel(self):
        self.mesh_levels("sphere", [0, 1, 2], volumeMesher="hxt")

    def test_shaftMeshOkAtEachLevel(self):
        self.mesh_levels("shaft", [0, 1, 2], volumeMesher="hxt")

    def test_sphereSTLMeshOkAtEachLevel(self):
        self.mesh_levels("sphereSTL", [0, 1, 2], volumeMesher="hxt")

    def test_binaryMeshOk(self):
        self.mesh_levels("sphere", [1], "binary", volumeMesher="hxt")

    def test_cellCountWithinFiftyPercentOfNetgen(self):
        """The interior size follows the same surface; HXT has no optimiser
        that removes cells as Netgen's does, so it makes 1.3-1.45x as many
        (measured: sphere 1.33, shaft 1.42 at r = 2)."""
        for name in ("sphere", "shaft", "sphereSTL"):
            n = self.mesh_levels(name, [2], volumeMesher="netgen")[2][1]
            h = self.mesh_levels(name, [2], volumeMesher="hxt")[2][1]
            self.assertLess(abs(h - n) / n, 0.5, "%s: hxt %d cells, netgen %d" % (name, h, n))


if __name__ == "__main__":
    unittest.main(verbosity=2)
