"""optimisationSteps 0, the fast mode: HXT without Gmsh's optimiser or the
quality pass's general steps, only its sliver removal. The three tutorials
the issue names (sphere, shaft, sphereSTL) at r = 2 on 2 ranks: checkMesh
-parallel says Mesh OK, and every partition was meshed by its first
attempt (the retries have optimisation steps, so a fast mode that only
passes by retrying is no fast mode).

Run one test:  python3 testFastMode.py fastMode.test_sphere
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from testParallelTutorials import ParallelCaseTest  # noqa: E402


class fastMode(ParallelCaseTest):

    def mesh_fast(self, name):
        c, cells = self.mesh_parallel(name, 2, 2, volumeMesher="hxt", optimisationSteps=0)
        self.assertGreater(cells, 0)
        with open(os.path.join(c.dir, "log.pmshFoam")) as f:
            retried = [line for line in f if "at attempt" in line]
        self.assertEqual(retried, [], "partitions meshed by a retry")
        summary = c.summary()
        self.assertEqual(summary["volumeAttemptsPerRank"], [1, 1])
        self.assertEqual(summary["volumeMesherPerRank"], ["hxt", "hxt"])

    def test_sphere(self):
        self.mesh_fast("sphere")

    def test_shaft(self):
        self.mesh_fast("shaft")

    def test_sphereSTL(self):
        self.mesh_fast("sphereSTL")


if __name__ == "__main__":
    unittest.main(verbosity=2)
