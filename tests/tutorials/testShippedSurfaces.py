"""The surfaces OpenFOAM ships (Debian's openfoam-examples,
examples/resources/geometry), each as a body in pmshDict's domain box,
meshed on 2 ranks and judged by checkMesh -parallel: clean CAD as it is
(the bullet standing on a side, blob, flange, building_wtc2; the DTC
hull with its coarse surface remeshed), dirty CAD wrapped (wigley's half hull, not
manifold; propellerTip, cyclone and the motorBike's helmet, open); the
motorBike itself is tutorials/motorBike, on its floor (testMotorBike.py).
Sizes from each surface's extent d: maxCellSize d/2, d/20 on the body,
r = 1; the box one d beyond the body on every side.

Run one test:  python3 testShippedSurfaces.py shippedSurfaces.test_flangeNp2
"""

import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import SHIPPED_GEOMETRY as SHIPPED, CaseTest, cells_in_checkmesh_log, extent  # noqa: E402

class shippedSurfaces(CaseTest):

    def mesh_in_a_box(self, surface, wrapped, remeshed=None, entries=(), standing_on=None):
        """Mesh OK on 2 ranks, the box's patch and at least one wall; the
        log says the body was wrapped exactly when it had to be, and its
        coarse surface remeshed (by default: exactly when wrapped); standing
        on a side ("yMin", ...): that side at the body's extreme point, and
        the log says the box was cut by it; returns the log"""
        source = os.path.join(SHIPPED, surface)
        self.assertTrue(os.path.isfile(source), "openfoam-examples is not installed: " + source)
        lo, hi = extent(source)
        d = max(h - l for l, h in zip(lo, hi))
        c = self.case("sphereSTL", maxCellSize=d/2, refinementLevels=1, volumeMesher="hxt")
        shutil.rmtree(os.path.join(c.dir, "0"))
        shutil.copy(source, os.path.join(c.dir, "constant", "geometry", surface))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % surface)
        low = [x - d for x in lo]
        high = [x + d for x in hi]
        if standing_on:
            axis = "xyz".index(standing_on[0])
            (low if standing_on.endswith("Min") else high)[axis] = \
                (lo if standing_on.endswith("Min") else hi)[axis]
        c.set_entry("system/pmshDict", "domain",
                    "{ type box; min (%s); max (%s); patches { default farfield; } }"
                    % (" ".join("%r" % x for x in low), " ".join("%r" % x for x in high)))
        c.substitute("system/pmshDict", r"(?ms)^patches\s*\{.*?^\}",
                     "patches\n{\n    farfield { type patch; }\n"
                     "    \".*\" { type wall; maxCellSize %r; }\n}" % (d/20))
        for key, value in entries:
            c.set_entry("system/pmshDict", key, value)
        _, log = c.run("pmshFoam", np=2)
        self.assertEqual("wrapped the bodies" in log, wrapped, log[-3000:])
        # Every partition at the volume mesher's first attempt: the quality
        # pass and the gradient mending leave nothing a later attempt or
        # Netgen has to redo (a mending move once made a sliver of the
        # building's, and HXT's three attempts all failed on it)
        self.assertNotIn(", attempt 1 (hxt) failed", log)
        self.assertEqual("coarse surface remeshed" in log, wrapped if remeshed is None else remeshed)
        text = c.check_mesh(np=2)
        self.assertGreater(cells_in_checkmesh_log(text), 10000)
        with open(os.path.join(c.dir, "processor0", "constant", "polyMesh", "boundary")) as f:
            boundary = f.read()
        self.assertRegex(boundary, r"(?s)\bfarfield\s*\{\s*type\s+patch;")
        self.assertRegex(boundary, r"(?s)\{\s*type\s+wall;")
        self.assertEqual("bodies cut by the domain box: they reach its side(s) %s;"
                         % standing_on in log, standing_on is not None)
        return log

    def test_blobNp2(self):
        self.mesh_in_a_box("blob.stl.gz", wrapped=False)

    def test_flangeNp2(self):
        self.mesh_in_a_box("flange.stl.gz", wrapped=False)

    def test_buildingNp2(self):
        self.mesh_in_a_box("building_wtc2.obj.gz", wrapped=False)

    def test_bulletStandingOnASideOfTheBoxNp2(self):
        """The bullet's flat base (1477 points at its highest z) in the
        box's zMax side, as a building stands on the ground: the side is
        cut by the base's outline"""
        self.mesh_in_a_box("bullet.stl.gz", wrapped=False, standing_on="zMax")

    def test_wigleysHalfHullIsWrappedNp2(self):
        self.mesh_in_a_box("wigley-scaled-oriented.stl.gz", wrapped=True)

    def test_propellerTipIsWrappedNp2(self):
        self.mesh_in_a_box("propellerTip.obj.gz", wrapped=True)

    def test_motorBikeHelmetIsWrappedNp2(self):
        self.mesh_in_a_box("motorBike-passenger-helmet.obj.gz", wrapped=True)

    def test_cycloneIsWrappedNp2(self):
        self.mesh_in_a_box("cyclone.stl.gz", wrapped=True)

    def test_dtcHullRemeshedNp2(self):
        """The DTC hull at 40 fine cells along its length: Netgen's STL
        mesher sat at "Surface meshing 99%" on it; remeshed it takes 2 s"""
        self.mesh_in_a_box("DTC-scaled.stl.gz", wrapped=False, remeshed=True,
                           entries=[("coarseSurface", "remesh")])


if __name__ == "__main__":
    unittest.main(verbosity=2)
