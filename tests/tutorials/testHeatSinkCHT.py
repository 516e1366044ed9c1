"""tutorials/heatSinkCHT end to end: the tutorial's own Allrun on 2 ranks
(24k cells, about 30 s): pmshFoam writes two cellZones from the CSG file's
two solids, splitMeshRegions -cellZones -parallel makes regions of them
with coupled mappedWall patches, each region passes checkMesh, and
chtMultiRegionFoam -parallel runs to End, heat flowing from the heated
block into the air.

Run one test:  python3 testHeatSinkCHT.py heatSinkCHT.test_allrunMeshesSplitsAndRunsChtToEnd
"""

import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402


class heatSinkCHT(CaseTest):

    def test_allrunMeshesSplitsAndRunsChtToEnd(self):
        c = self.case("heatSinkCHT")
        code, out = c.run_allrun("2", timeout=900)
        self.assertEqual(code, 0, out)
        self.assertEqual(out.count("Mesh OK"), 3, out)   # whole mesh, air, heatSink

        with open(os.path.join(c.dir, "processor0/constant/polyMesh/cellZones")) as f:
            self.assertEqual(re.findall(r"(?m)^(\w+)\s*\n\{\s*type\s+cellZone;", f.read()),
                             ["air", "heatSink"])
        for region, other in (("air", "heatSink"), ("heatSink", "air")):
            boundary = dict(c.polymesh("processor0/constant/%s/polyMesh" % region).boundary())
            name = "%s_to_%s" % (region, other)
            self.assertEqual(boundary[name]["type"], "mappedWall", region)

        with open(os.path.join(c.dir, "log.chtMultiRegionFoam")) as f:
            self.assertRegex(f.read(), r"(?m)^End")
        tmax = float(re.search(r"highest cell\s+(\S+) K", out).group(1))
        qair = float(re.search(r"into the air\s+(\S+) W", out).group(1))
        self.assertTrue(300 < tmax < 350, tmax)
        self.assertGreater(qair, 0)


if __name__ == "__main__":
    unittest.main(verbosity=2)
