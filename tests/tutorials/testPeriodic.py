"""Periodic pairs: the faces x = 0 and x = 1 of a cube, paired by CSG
'identify periodic', become a pair of cyclic patches whose faces match
(checkMesh's "Coupled point location match ... OK"), at r = 0, 1, 2
serially, on 2 and 4 ranks (faces whose image is on another rank in
processorCyclic patches), after reconstructParMesh, and a solver runs on
them. The same with three pairs that meet at the cube's edges and
corners (fully periodic), and with Netgen's period.geo (two regions,
three pairs). Between two ranks the processorCyclic patches come in
partner order on both (OpenFOAM streams their data one after the other).

Run one test:  python3 testPeriodic.py periodic.test_cyclicMatchSerialAtEachLevel
"""

import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402

MATCH = r"Coupled point location match \(average [0-9.e+-]+\) OK"


class periodic(CaseTest):

    def periodic_case(self, levels, geometry="periodicCube.geo"):
        """tutorials/sphere with a periodic geometry; 0/U and 0/p name the
        periodic cube's wall patch `cube` (the cyclic ones come from
        setConstraintTypes)."""
        return self.geometry_case(geometry, "cube", maxCellSize=0.3, refinementLevels=levels)

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

    def mesh_pairs(self, geometry, levels, np, pairs):
        """Mesh `geometry`; checkMesh must say Mesh OK and match the cyclic
        points; every (first, second, separation) of `pairs` must be a
        pair of cyclic patches; between two ranks the processorCyclic
        patches must be partners in the same order. Returns the case."""
        c = self.periodic_case(levels, geometry)
        c.run("pmshFoam", np=np)
        self.assertRegex(c.check_mesh(np=np), MATCH)
        processors = ["processor%d/constant/polyMesh" % p for p in range(np)] \
            if np > 1 else ["constant/polyMesh"]
        boundaries = [c.polymesh(where).boundary() for where in processors]
        for boundary in boundaries:
            patches = dict(boundary)
            for first, second, separation in pairs:
                self.assertEqual(patches[first]["type"], "cyclic")
                self.assertEqual(patches[first]["neighbourPatch"], second)
                self.assertEqual(patches[second]["neighbourPatch"], first)
                self.assertEqual(
                    [float(x) for x in patches[first]["separationVector"].strip("()").split()],
                    separation)
        self.assertProcessorCyclicPartnersInOrder(boundaries)
        return c

    def assertProcessorCyclicPartnersInOrder(self, boundaries):
        """The k-th processorCyclic patch from rank a to rank b is part of
        the neighbour of the cyclic patch of the k-th from b to a, with as
        many faces."""
        cyclic_neighbour = {name: e["neighbourPatch"] for name, e in boundaries[0]
                            if e["type"] == "cyclic"}
        through = {}
        for rank, boundary in enumerate(boundaries):
            for name, e in boundary:
                if e["type"] == "processorCyclic":
                    through.setdefault((rank, int(e["neighbProcNo"])), []).append(
                        (e["referPatch"], int(e["nFaces"])))
        for (a, b), patches in through.items():
            partners = through.get((b, a), [])
            self.assertEqual(
                [(cyclic_neighbour[refer], n) for refer, n in patches], partners,
                "processorCyclic patches from %d to %d and from %d to %d" % (a, b, b, a))

    FULLY_PERIODIC = [("left", "right", [1, 0, 0]), ("front", "back", [0, 1, 0]),
                      ("bottom", "top", [0, 0, 1])]
    PERIOD = [("p1", "p2", [0, 0, 1]), ("p3", "p4", [0, 1, 0]), ("p5", "p6", [1, 0, 0])]

    def test_fullyPeriodicCubeSerialAtEachLevel(self):
        for levels in (0, 1, 2):
            self.mesh_pairs("fullyPeriodicCube.geo", levels, 1, self.FULLY_PERIODIC)

    def test_fullyPeriodicCubeOnTwoRanksAndASolverRuns(self):
        c = self.mesh_pairs("fullyPeriodicCube.geo", 2, 2, self.FULLY_PERIODIC)
        c.set_entry("system/controlDict", "endTime", 5)
        _, log = c.run("simpleFoam", np=2)
        self.assertRegex(log, r"(?m)^End")

    def test_fullyPeriodicCubeOnThreeAndFourRanksReconstructs(self):
        self.mesh_pairs("fullyPeriodicCube.geo", 1, 3, self.FULLY_PERIODIC)
        c = self.mesh_pairs("fullyPeriodicCube.geo", 1, 4, self.FULLY_PERIODIC)
        # Each side has faces whose image is on another rank
        through = {e["referPatch"] for p in range(4) for _, e in
                   c.polymesh("processor%d/constant/polyMesh" % p).boundary()
                   if e["type"] == "processorCyclic"}
        self.assertEqual(through, {side for pair in self.FULLY_PERIODIC for side in pair[:2]})
        c.run("reconstructParMesh", "-constant")
        self.assertRegex(c.check_mesh(), MATCH)

    def test_netgenPeriodExampleSerialAndOnTwoRanks(self):
        """Two regions: the cylinders cross the periodic sides, so both
        cellZones reach them."""
        for np in (1, 2):
            c = self.mesh_pairs("period.geo", 1, np, self.PERIOD)
            where = "processor0/constant/polyMesh" if np > 1 else "constant/polyMesh"
            with open(os.path.join(c.dir, where, "cellZones")) as f:
                zones = re.findall(r"(?m)^(\w+)\s*\{\s*type\s+cellZone", f.read())
            self.assertEqual(zones, ["matrix", "inner"])

    def test_rotationalPairStopsWithAMessageAndWritesNothing(self):
        c = self.periodic_case(1)
        with open(os.path.join(c.dir, "constant", "geometry", "wedge.geo"), "w") as f:
            f.write("algebraic3d\n"
                    "solid a = plane (0, 0, 0; 0, -1, 0) -bcname=a;\n"
                    "solid b = plane (0, 0, 0; -0.5, 0.8660254037844386, 0) -bcname=b;\n"
                    "solid w = a and b and plane (0, 0, 0; 0, 0, -1)\n"
                    "    and plane (0, 0, 1; 0, 0, 1) and sphere (0, 0, 0; 1);\n"
                    "identify periodic a b;\n"
                    "tlo w;\n")
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/wedge.geo"')
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("FOAM FATAL ERROR", log)
        self.assertRegex(log, r"wedge\.geo\": cannot make cyclic patches of 'identify periodic a b'"
                              r": a and b are not a translation of each other")
        self.assertIn("Only translational periodic pairs are supported, not rotational ones", log)
        self.assertFalse(c.exists("constant/polyMesh"))

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
        boundaries = [c.polymesh("processor%d/constant/polyMesh" % p).boundary()
                      for p in range(4)]
        self.assertProcessorCyclicPartnersInOrder(boundaries)
        through = [n for boundary in boundaries for n, e in boundary
                   if e["type"] == "processorCyclic"]
        self.assertTrue(through, "no face's image is on another rank")
        self.assertTrue(all(re.match(r"procBoundary\dto\dthrough(left|right)$", n)
                            for n in through), through)
        c.run("reconstructParMesh", "-constant")
        self.assertRegex(c.check_mesh(), MATCH)


if __name__ == "__main__":
    unittest.main()
