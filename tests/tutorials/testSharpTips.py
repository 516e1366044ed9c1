"""Sharp tips: a cone in a box (tests/data/geometry/
coneInBox.geo, half angle 9.5 degrees, tip radius 0.0005) on 2 ranks with
hxt meshes without falling back to Netgen, and checkMesh -parallel's max
non-orthogonality stays below 80 degrees. HXT alone (optimisationSteps 0)
makes slivers there and falls back to Netgen at 86 degrees: the quality
pass after HXT is what this holds.

Run one test:  python3 testSharpTips.py sharpTips.test_coneInBoxHxtOnTwoRanks
"""

import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402



class sharpTips(CaseTest):

    def cone_case(self, **entries):
        """tutorials/sphere with the cone in a box; its 0/ files cover
        every patch."""
        return self.geometry_case("coneInBox.geo", '".*"', maxCellSize=0.25, **entries)

    def test_coneInBoxHxtOnTwoRanks(self):
        c = self.cone_case(refinementLevels=1, volumeMesher="hxt")
        c.run("pmshFoam", np=2)
        summary = c.summary()
        self.assertEqual(summary["volumeMesherPerRank"], ["hxt", "hxt"])
        text = c.check_mesh(np=2)
        worst = float(re.search(r"non-orthogonality Max:\s*([\d.]+)", text).group(1))
        self.assertLess(worst, 80, "max non-orthogonality at the cone's tip")


if __name__ == "__main__":
    unittest.main()
