"""Several solids, one mesh: every CSG top-level solid becomes a cellZone,
the surface between two solids internal faces in a faceZone, serially and
on 2 and 4 ranks, judged by checkMesh (-parallel); splitMeshRegions
-cellZones then gives one mesh per region, each passing checkMesh.

The zones' volumes come from checkMesh's cellZone table. Solids bounded by
planes must come out exactly (1e-6 relative); curved ones within the
discretisation error; and the surface between two solids does not depend
on the partition, so every volume is the same on any number of ranks.

Run one test:  python3 testZones.py zones.test_twoCubesNp2
"""

import math
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402


BALL = 4 / 3 * math.pi * 0.5 ** 3
COIL = math.pi * (0.6 ** 2 - 0.48 ** 2) * 0.8
SENSOR = 4 / 3 * math.pi * 0.2 ** 3


def zone_table(log, kind):
    """{name: (count, volume or points)} from checkMesh's CellZone or
    FaceZone table."""
    m = re.search(r"^\s*%sZone\s+\S+.*\n((?:\s+\S+\s+\d+.*\n)+)" % kind, log, re.M)
    if not m:
        raise AssertionError("no %sZone table in the checkMesh log" % kind)
    rows = {}
    for line in m.group(1).splitlines():
        words = line.split()
        rows[words[0]] = (int(words[1]), float(words[3]) if kind == "Cell" else int(words[2]))
    return rows


def face_zones(case_dir):
    """{name: (faceLabels, flipMap)} of an ascii constant/polyMesh/faceZones."""
    with open(os.path.join(case_dir, "constant", "polyMesh", "faceZones")) as f:
        text = re.sub(r"//[^\n]*", "", f.read())
    zones = {}
    for name, body in re.findall(r"(\w+)\s*\{\s*type\s+faceZone;(.*?)\n\}", text, re.S):
        labels = re.search(r"faceLabels\s+List<label>\s*(?:\d+\s*\(([^)]*)\)|(\d+)\{(\d+)\})", body)
        flips = re.search(r"flipMap\s+List<bool>\s*(?:\d+\s*\(([^)]*)\)|(\d+)\{(\d+)\})", body)
        def expand(m, cast):
            if m.group(1) is not None:
                return [cast(x) for x in m.group(1).split()]
            return [cast(m.group(3))] * int(m.group(2))
        zones[name] = (expand(labels, int), expand(flips, lambda x: x == "1"))
    return zones


class zones(CaseTest):

    def zone_case(self, geometry, maxCellSize, levels=1, mesher="netgen"):
        return self.geometry_case(geometry, maxCellSize=maxCellSize, refinementLevels=levels,
                                  volumeMesher=mesher)

    def mesh(self, geometry, np, maxCellSize, levels=1, mesher="netgen"):
        """Mesh; checkMesh (-parallel) must say Mesh OK. Returns the case,
        {zone: (cells, volume)} and {faceZone: (faces, points)}."""
        c = self.zone_case(geometry, maxCellSize, levels, mesher)
        _, log = c.run("pmshFoam", np=np)
        self.assertIn("End", log)
        text = c.check_mesh(np=np)
        return c, zone_table(text, "Cell"), zone_table(text, "Face")

    def assertVolume(self, measured, expected, tolerance, what):
        self.assertLess(abs(measured / expected - 1), tolerance,
                        "%s: volume %.9g, expected %.9g" % (what, measured, expected))

    # -- two cubes: flat, so exact --------------------------------------

    def two_cubes(self, np):
        c, cells, faces = self.mesh("twoCubes.geo", np, 0.3)
        self.assertEqual(sorted(cells), ["left", "right"])
        for name in ("left", "right"):
            self.assertVolume(cells[name][1], 1.0, 1e-6, name)
        self.assertEqual(list(faces), ["left_to_right"])
        return c

    def test_twoCubesSerialFaceZoneCoversTheSharedFaceOrientedLeftToRight(self):
        c = self.two_cubes(1)
        # The faceZone's faces, flipped by flipMap, add up to the unit face
        # x = 1 pointing from left to right
        mesh = c.polymesh()
        points, faces = mesh.points(), mesh.faces()
        labels, flips = face_zones(c.dir)["left_to_right"]
        self.assertEqual(len(labels), len(flips))
        area = [0.0, 0.0, 0.0]
        for f, flip in zip(labels, flips):
            a, b, d = (points[i] for i in faces[f])
            n = [0.5 * ((b[1] - a[1]) * (d[2] - a[2]) - (b[2] - a[2]) * (d[1] - a[1])),
                 0.5 * ((b[2] - a[2]) * (d[0] - a[0]) - (b[0] - a[0]) * (d[2] - a[2])),
                 0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]))]
            self.assertTrue(all(abs(p[0] - 1) < 1e-12 for p in (a, b, d)))
            s = -1 if flip else 1
            area = [x + s * y for x, y in zip(area, n)]
        self.assertAlmostEqual(area[0], 1.0, places=9)
        self.assertAlmostEqual(area[1], 0.0, places=9)
        self.assertAlmostEqual(area[2], 0.0, places=9)

    def test_twoCubesNp2(self):
        self.two_cubes(2)

    def test_twoCubesNp4ReconstructsWithItsZones(self):
        c = self.two_cubes(4)
        c.run("reconstructParMesh", "-constant")
        text = c.check_mesh()
        self.assertEqual(sorted(zone_table(text, "Cell")), ["left", "right"])
        labels, flips = face_zones(c.dir)["left_to_right"]
        self.assertGreater(len(labels), 0)

    # -- a ball in a cube: curved, the same on any number of ranks -------

    def sphere_in_cube(self, np, mesher="netgen", levels=1):
        c, cells, _ = self.mesh("sphereInCube.geo", np, 0.3, levels, mesher)
        self.assertEqual(sorted(cells), ["ball", "box"])
        total = cells["box"][1] + cells["ball"][1]
        self.assertVolume(total, 8.0, 1e-6, "box + ball")
        self.assertVolume(cells["ball"][1], BALL, 0.03, "ball")
        return c, cells

    def test_sphereInCubeSameZoneVolumesSerialAndOnTwoAndFourRanks(self):
        volumes = []
        for np in (1, 2, 4):
            _, cells = self.sphere_in_cube(np)
            volumes.append(cells["ball"][1])
        for v in volumes[1:]:
            self.assertVolume(v, volumes[0], 1e-7, "ball on more ranks")

    def test_sphereInCubeHxtNp2(self):
        self.sphere_in_cube(2, "hxt", 2)

    def test_sphereInCubeSplitsIntoRegionsSerial(self):
        c, _ = self.sphere_in_cube(1)
        c.run("splitMeshRegions", "-cellZones", "-overwrite")
        self.split_regions_mesh_ok(c, 1)

    def test_sphereInCubeSplitsIntoRegionsNp2(self):
        c, _ = self.sphere_in_cube(2)
        c.run("splitMeshRegions", "-cellZones", "-overwrite", np=2)
        self.split_regions_mesh_ok(c, 2)

    def split_regions_mesh_ok(self, c, np):
        for region, other in (("box", "ball"), ("ball", "box")):
            _, text = c.run("checkMesh", "-region", region, np=np,
                            log="log.checkMesh." + region)
            self.assertRegex(text, r"(?m)^Mesh OK")
            boundary = os.path.join(c.dir, "processor0" if np > 1 else "",
                                    "constant", region, "polyMesh", "boundary")
            with open(boundary) as f:
                text = f.read()
            self.assertRegex(text, r"%s_to_%s\s*\{\s*type\s+mappedWall;" % (region, other))

    # -- five solids: flat and curved, meeting the boundary --------------

    def transformer(self, np):
        _, cells, faces = self.mesh("transformer.geo", np, 0.25)
        self.assertEqual(sorted(cells), ["coilA", "coilB", "core", "oil", "sensor"])
        self.assertVolume(sum(v for _, v in cells.values()), 16.0, 1e-6, "all zones")
        self.assertVolume(cells["core"][1], 1.44, 1e-6, "core")
        self.assertVolume(cells["coilA"][1], COIL, 0.01, "coilA")
        self.assertVolume(cells["coilB"][1], COIL, 0.01, "coilB")
        self.assertVolume(cells["sensor"][1], SENSOR, 0.03, "sensor")
        self.assertEqual(sorted(faces), ["oil_to_coilA", "oil_to_coilB", "oil_to_core",
                                         "oil_to_sensor"])
        return cells

    def test_fiveSolidsSerial(self):
        self.transformer(1)

    def test_fiveSolidsNp2(self):
        self.transformer(2)

    def test_fiveSolidsNp4(self):
        self.transformer(4)


if __name__ == "__main__":
    unittest.main()
