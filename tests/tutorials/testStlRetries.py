"""Stage 1 on STL: when Netgen's STL mesher fails, pmshFoam retries with
smaller sizes (curvatureRefinement 10, 30, then maxCellSize/2), logs each
retry and the attempt that succeeded, and when every attempt fails stops
naming each attempt's reason and the pmshDict entries to change.

The geometry is a slab bent into an arc of radius 1 (tests/data/geometry/
makeGeometry.py curved_wall): at maxCellSize 0.3 the chords of Netgen's
triangles sag below the slab's inner face ("Stop meshing since boundary
mesh is overlapping") when it is thinner than about 0.005.

Each attempt has a time limit (coarseTimeLimit): past it Netgen is
stopped, and the error asks for fewer coarse triangles or more time, never
for the finer attempts that would take longer.

Shells that touch (a desk standing on the floor of its room) stop pmshFoam
before Netgen sees them, with a message that names the solids.

Run one test:  python3 testStlRetries.py stlRetries.test_thinCurvedWallMeshesAtARetry
"""

import math
import os
import shutil
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402
sys.path.insert(0, os.path.join(HERE, "..", "data", "geometry"))
from makeGeometry import curved_wall, volume, write_ascii  # noqa: E402

GEOMETRY = os.path.join(HERE, "..", "data", "geometry")

OVERLAP = "Stop meshing since boundary mesh is overlapping"


class stlRetries(CaseTest):

    def wall_case(self, thickness, angle_degrees, length, n_arc):
        c = self.case("sphereSTL", maxCellSize=0.3, refinementLevels=0)
        v, f = curved_wall(1.0, thickness, math.radians(angle_degrees), length,
                           n_arc, 6)
        self.assertGreater(volume(v, f), 0)
        write_ascii(os.path.join(c.dir, "constant/geometry/wall.stl"),
                    [("wall", v, f)])
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/wall.stl"')
        return c

    def stl_case(self, source, name, **entries):
        """tutorials/sphereSTL meshing tests/data/geometry/<source>, copied
        into the case as constant/geometry/<name>"""
        c = self.case("sphereSTL", refinementLevels=0, **entries)
        shutil.copy(os.path.join(GEOMETRY, source),
                    os.path.join(c.dir, "constant/geometry", name))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % name)
        return c

    def test_thinCurvedWallMeshesAtARetry(self):
        # 0.0015 thick: fails as configured (curvatureRefinement 3). Which
        # retry cures it is not pinned: Netgen's overlap is not monotonic in
        # the thickness (measured: 0.0015 meshes at curvatureRefinement 10,
        # 0.001, 0.002 and 0.0025 at 30)
        c = self.wall_case(0.0015, 120, 1.0, 90)
        _, log = c.run("pmshFoam")
        self.assertIn("    Netgen's STL mesh failed (meshing the volume: %s);"
                      " retrying with curvatureRefinement 10" % OVERLAP, log)
        self.assertRegex(log, r"\n    Netgen's STL mesh succeeded at attempt [2-4]"
                              r" \((curvatureRefinement|maxCellSize) [^\n]*\)\n")
        c.check_mesh()

    def test_tooThinCurvedWallNamesTheEntriesToChange(self):
        # 0.00005 thick: every attempt fails; the message lists them and
        # asks for a maxCellSize below the last one tried (0.15)
        c = self.wall_case(0.00005, 30, 0.15, 15)
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("FOAM FATAL ERROR", log)
        self.assertIn('Netgen could not mesh STL file "%s" in 4 attempts'
                      % os.path.join(c.dir, "constant/geometry/wall.stl"), log)
        for attempt in ["1 (as configured)", "2 (curvatureRefinement 10)",
                        "3 (curvatureRefinement 30)",
                        "4 (maxCellSize 0.15 and curvatureRefinement 30)"]:
            self.assertIn("%s: meshing the volume: %s" % (attempt, OVERLAP), log)
        self.assertRegex(log, r"In system/pmshDict\s+set maxCellSize 0\.075"
                              r" \(or smaller\), or\s+curvatureRefinement 60")
        self.assertFalse(c.exists("constant/polyMesh"))

    def test_timeLimitStopsNetgenAndAsksForFewerTrianglesNotFinerOnes(self):
        # A ball in a box at maxCellSize 0.3: about 300k coarse cells, far
        # more than Netgen makes in half a second anywhere
        c = self.stl_case("sphereInBox.stl", "body.stl", maxCellSize=0.3, coarseTimeLimit=0.5)
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        self.assertLess(code, 128)
        self.assertIn("\n    time limit: 0.5 s an attempt, 1 s for all (coarseTimeLimit)\n", log)
        self.assertIn("FOAM FATAL ERROR", log)
        self.assertIn('Netgen could not mesh STL file "%s" in 1 attempt of 4:'
                      % os.path.join(c.dir, "constant/geometry/body.stl"), log)
        self.assertRegex(log, r"1 \(as configured\): stopped at the time limit of 0\.5 s"
                              r" while (finding edges|meshing the surface|meshing the volume)"
                              r" \(Netgen: [^\n]*\), \d+ surface triangles")
        self.assertIn("raise coarseTimeLimit (now 0.5 s an attempt)", log)
        self.assertRegex(log, r"maxCellSize 0\.6 \(now 0\.3\),\s+minCellSize 0\.075"
                              r" \(now 0\.0375\)\s+or\s+curvatureRefinement 0")
        # Never the finer attempts that would take longer still
        self.assertNotIn("retrying with", log)
        self.assertNotIn("curvatureRefinement 10", log)
        self.assertNotIn("maxCellSize 0.15", log)
        self.assertFalse(c.exists("constant/polyMesh"))

    def test_touchingShellsStopBeforeNetgenNamingTheSolids(self):
        c = self.stl_case("roomWithDesk.stl", "room.stl", maxCellSize=0.5)
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("FOAM FATAL ERROR", log)
        self.assertIn("room.stl\": 8 pair(s) of closed surfaces touch or overlap", log)
        self.assertIn("solid deskLegs", log)
        self.assertIn("solid room (the outer boundary)", log)
        self.assertIn("join the touching solids into one closed surface", log)
        # Stopped before stage 1's Netgen, not by it
        self.assertNotIn("Stage 1", log)
        self.assertNotIn("Netgen did not accept", log)
        self.assertFalse(c.exists("constant/polyMesh"))


if __name__ == "__main__":
    unittest.main()
