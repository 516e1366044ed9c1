"""External flow: a body inside a box, from one STL with several closed
shells (the body's triangles pointing into it, out of the fluid), from
several surface files of OpenFOAM's formats, from CAD bodies of either
orientation in pmshDict's domain box, and from CSG (box and not body),
meshed serially and on 2 and 4 ranks, judged by
checkMesh; the patches are the STL solids / CSG bcnames, and summary.json
reports the points the fold repair left off the geometry.

Run one test:  python3 testBodyInBox.py bodyInBox.test_stlNp2
"""

import gzip
import math
import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, ROOT, cells_in_checkmesh_log, write_bullet_in_box  # noqa: E402

GEOMETRY = os.path.join(ROOT, "tests", "data", "geometry")
PATCHES = {"inlet": "patch", "outlet": "patch", "sides": "patch", "body": "wall"}

FIELD = """FoamFile
{
    version 2.0;
    format ascii;
    class %s;
    object %s;
}
dimensions %s;
internalField uniform %s;
boundaryField
{
    #includeEtc "caseDicts/setConstraintTypes"
%s
}
"""


def write_obj(path, stl_facets, flip=False):
    """The facets of an ascii STL solid as a gzipped OBJ group 'body', the
    same coordinates to the bit (repr round-trips), flipped if asked"""
    points, faces = {}, []
    for t in re.findall(r"outer loop\s+(.*?)endloop", stl_facets, re.S):
        corners = [tuple(float(x) for x in v) for v in re.findall(
            r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", t)]
        faces.append([points.setdefault(p, len(points) + 1) for p in corners])
    with gzip.open(path, "wt") as f:
        f.write("".join("v %r %r %r\n" % p for p in points))
        f.write("g body\n" + "".join("f %d %d %d\n" % ((t[0], t[2], t[1]) if flip else tuple(t))
                                     for t in faces))


class bodyInBox(CaseTest):

    def body_case(self, geometry, **entries):
        """tutorials/sphereSTL with the body-in-box geometry, its patches in
        system/pmshDict and 0/U, 0/p with a condition for each."""
        c = self.case("sphereSTL", maxCellSize=2.5, refinementLevels=1, **entries)
        shutil.copy(os.path.join(GEOMETRY, geometry),
                    os.path.join(c.dir, "constant", "geometry", geometry))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/%s"' % geometry)
        path = os.path.join(c.dir, "system", "pmshDict")
        with open(path) as f:
            text = f.read()
        patches = "".join("    %s { type %s; }\n" % p for p in PATCHES.items())
        text = re.sub(r"(?ms)^patches\s*\{.*?^\}", "patches\n{\n%s}" % patches, text)
        with open(path, "w") as f:
            f.write(text)
        u = {"inlet": "type fixedValue; value uniform (1 0 0);",
             "outlet": "type zeroGradient;", "sides": "type slip;", "body": "type noSlip;"}
        p = {"inlet": "type zeroGradient;", "outlet": "type fixedValue; value uniform 0;",
             "sides": "type slip;", "body": "type zeroGradient;"}
        for name, cls, dims, value, bcs in (
                ("U", "volVectorField", "[0 1 -1 0 0 0 0]", "(1 0 0)", u),
                ("p", "volScalarField", "[0 2 -2 0 0 0 0]", "0", p)):
            with open(os.path.join(c.dir, "0", name), "w") as f:
                f.write(FIELD % (cls, name, dims, value, "".join(
                    "    %s { %s }\n" % (patch, bc) for patch, bc in bcs.items())))
        return c

    def mesh(self, geometry, np, estimate_within_band=True, **entries):
        """Mesh, checkMesh must say Mesh OK, the patches are the solids /
        bcnames with their types, the estimate after stage 1 within
        0.67-1.5 of the fine cells unless told otherwise; returns (case,
        summary.json)."""
        return self.mesh_case(self.body_case(geometry, **entries), np, estimate_within_band)

    def mesh_case(self, c, np, estimate_within_band=True):
        """mesh() on a case made already"""
        _, log = c.run("pmshFoam", np=np)
        self.assertIn("End", log)
        text = c.check_mesh(np=np)
        if np > 1:
            self.assertRegex(text, r"Coupled point location match.*OK")
        self.assertGreater(cells_in_checkmesh_log(text), 1000)
        boundary = os.path.join(c.dir, "processor0" if np > 1 else "", "constant",
                                "polyMesh", "boundary")
        with open(boundary) as f:
            text = f.read()
        for name, kind in PATCHES.items():
            self.assertRegex(text, r"(?s)\b%s\s*\{\s*type\s+%s;" % (name, kind))
        summary = c.summary()
        # The estimate after stage 1 within its band (bench/run --estimates),
        # with the shares of its terms
        ratio = summary["estimatedFineCells"] / summary["fineCells"]
        if estimate_within_band:
            self.assertGreaterEqual(ratio, 0.67)
            self.assertLessEqual(ratio, 1.5)
        shares = summary["estimateShares"]
        self.assertAlmostEqual(shares["sizeField"] + shares["interfaces"], 1, 6)
        self.assertGreater(shares["sizeField"], 0)
        self.assertGreater(shares["interfaces"], 0)
        self.assertIn("pointsOffGeometry", summary)
        self.assertIn("maxDistanceOffGeometry", summary)
        # Far below the body's radius (0.5) and the fine cells (~0.3 here)
        self.assertLess(summary["maxDistanceOffGeometry"], 0.05)
        return c, summary

    def test_stlSerial(self):
        self.mesh("sphereInBox.stl", 1)

    def test_stlNp2(self):
        self.mesh("sphereInBox.stl", 2)

    def test_stlNp4(self):
        self.mesh("sphereInBox.stl", 4)

    def test_aBoxInStlAndABodyInGzippedObjMeshAsTheirOneStlFileNp2(self):
        """geometry ("box.stl" "body.obj.gz"): sphereInBox.stl's box solids
        in one STL, its body as an OBJ group read by OpenFOAM's triSurface
        from a .gz; the same coordinates, so the same mesh to the bit."""
        one, _ = self.mesh("sphereInBox.stl", 2)
        c = self.body_case("sphereInBox.stl")
        geometry = os.path.join(c.dir, "constant", "geometry")
        with open(os.path.join(geometry, "sphereInBox.stl")) as f:
            solids = re.findall(r"(?ms)^solid (\w+)\n(.*?)endsolid \1", f.read())
        self.assertEqual([name for name, _ in solids], ["inlet", "outlet", "sides", "body"])
        os.remove(os.path.join(geometry, "sphereInBox.stl"))
        with open(os.path.join(geometry, "box.stl"), "w") as f:
            for name, text in solids[:3]:
                f.write("solid %s\n%sendsolid %s\n" % (name, text, name))
        points, faces = {}, []
        for t in re.findall(r"outer loop\s+(.*?)endloop", solids[3][1], re.S):
            corners = [tuple(float(x) for x in v) for v in re.findall(
                r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", t)]
            faces.append([points.setdefault(p, len(points) + 1) for p in corners])
        with gzip.open(os.path.join(geometry, "body.obj.gz"), "wt") as f:
            f.write("".join("v %r %r %r\n" % p for p in points))
            f.write("g body\n" + "".join("f %d %d %d\n" % tuple(t) for t in faces))
        c.set_entry("system/pmshDict", "geometry",
                    '("constant/geometry/box.stl" "constant/geometry/body.obj.gz")')
        two, summary = self.mesh_case(c, 2)
        self.assertEqual(summary["geometryFiles"], [os.path.join(geometry, "box.stl"),
                                                    os.path.join(geometry, "body.obj.gz")])
        for rank in ("processor0", "processor1"):
            a = two.polymesh("%s/constant/polyMesh" % rank)
            b = one.polymesh("%s/constant/polyMesh" % rank)
            self.assertEqual(a.points(), b.points(), rank)
            self.assertEqual(a.faces(), b.faces(), rank)

    def split_case(self):
        """body_case of sphereInBox.stl without it, and its solids
        (name, STL text of the facets) for a test to write as it likes"""
        c = self.body_case("sphereInBox.stl")
        path = os.path.join(c.dir, "constant", "geometry", "sphereInBox.stl")
        with open(path) as f:
            solids = re.findall(r"(?ms)^solid (\w+)\n(.*?)endsolid \1", f.read())
        self.assertEqual([name for name, _ in solids], ["inlet", "outlet", "sides", "body"])
        os.remove(path)
        return c, solids

    def cad_body_in_domain(self, box_min, flip):
        """split_case with the sphere as a CAD body (body.obj.gz, flipped
        or not) in a domain box from box_min to (5 5 5); returns (case,
        solids)"""
        c, solids = self.split_case()
        write_obj(os.path.join(c.dir, "constant", "geometry", "body.obj.gz"),
                  solids[3][1], flip=flip)
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/body.obj.gz"')
        c.set_entry("system/pmshDict", "domain",
                    "{ type box; min %s; max (5 5 5);"
                    " patches { xMin inlet; xMax outlet; default sides; } }" % box_min)
        return c, solids

    def test_aCadBodyOfEitherOrientationInTheDictionarysDomainBoxNp2(self):
        """geometry "body.obj.gz" and domain { type box; ... }: the body as
        CAD exports it (normals out of the body, into the fluid), no box
        surface; the mesh of sphereInBox.stl, within 10 % of its cells"""
        one, reference = self.mesh("sphereInBox.stl", 2)
        for flip in (True, False):
            c, _ = self.cad_body_in_domain("(-5 -5 -5)", flip)
            _, summary = self.mesh_case(c, 2)
            ratio = summary["fineCells"] / reference["fineCells"]
            self.assertGreater(ratio, 0.9, "flip %s" % flip)
            self.assertLess(ratio, 1.1, "flip %s" % flip)

    def two_bodies_in_the_domain(self, np):
        """geometry ("body.obj.gz" "cube.stl") in a domain box: the sphere
        as CAD exports it and a cube beside it, solid 'cube', each file a
        body; Mesh OK, the sides' and bodies' patches with their types"""
        c, solids = self.split_case()
        geometry = os.path.join(c.dir, "constant", "geometry")
        write_obj(os.path.join(geometry, "body.obj.gz"), solids[3][1], flip=True)
        lo, hi = (2.0, 1.0, -0.5), (3.0, 2.0, 0.5)
        corner = [(lo[0] if i & 1 == 0 else hi[0], lo[1] if i & 2 == 0 else hi[1],
                   lo[2] if i & 4 == 0 else hi[2]) for i in range(8)]
        quads = [(0, 2, 6, 4), (1, 5, 7, 3), (0, 4, 5, 1), (2, 3, 7, 6), (0, 1, 3, 2), (4, 6, 7, 5)]
        with open(os.path.join(geometry, "cube.stl"), "w") as f:
            f.write("solid cube\n")
            for a, b, cc, d in quads:      # outward, as CAD exports a solid
                for t in ((a, b, cc), (a, cc, d)):
                    f.write("facet normal 0 0 0\nouter loop\n%sendloop\nendfacet\n" % "".join(
                        "vertex %r %r %r\n" % corner[v] for v in t))
            f.write("endsolid cube\n")
        c.set_entry("system/pmshDict", "geometry",
                    '("constant/geometry/body.obj.gz" "constant/geometry/cube.stl")')
        c.set_entry("system/pmshDict", "domain",
                    "{ type box; min (-5 -5 -5); max (5 5 5);"
                    " patches { xMin inlet; xMax outlet; default sides; } }")
        c.substitute("system/pmshDict", r"body \{ type wall; \}",
                     "body { type wall; }\n    cube { type wall; }")
        for field in ("0/U", "0/p"):
            c.substitute(field, r"(?m)^(\s*)body(\s*\{[^}]*\})", r"\1body\2\n\1cube\2")
        self.mesh_case(c, np)
        boundary = os.path.join(c.dir, "processor0" if np > 1 else "", "constant",
                                "polyMesh", "boundary")
        with open(boundary) as f:
            self.assertRegex(f.read(), r"(?s)\bcube\s*\{\s*type\s+wall;")

    def body_through_the_floor(self, np):
        """The sphere (radius 0.5) through the domain box's floor at its
        equator, as a car's tyres stand in the road: the box is cut by it
        and the log says so; Mesh OK with the patches, the fluid the box
        less the upper half of the sphere, no point below the floor"""
        c, solids = self.cad_body_in_domain("(-5 -5 0)", flip=True)
        self.mesh_case(c, np)
        with open(os.path.join(c.dir, "log.pmshFoam")) as f:
            self.assertIn("bodies cut by the domain box: they reach its side(s) zMin;", f.read())
        # The sphere's facets are symmetric about z = 0 (an icosphere)
        facets = [[tuple(float(x) for x in v) for v in re.findall(
            r"vertex\s+(\S+)\s+(\S+)\s+(\S+)", f)]
            for f in re.findall(r"outer loop\s+(.*?)endloop", solids[3][1], re.S)]
        sphere = abs(sum(a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0])
                         + a[2] * (b[0] * d[1] - b[1] * d[0]) for a, b, d in facets)) / 6
        text = c.check_mesh(np=np)
        volume = float(re.search(r"Total volume = ([0-9.eE+-]+?)\.?\s", text).group(1))
        # The whole sphere left in or taken out is 0.13 away
        self.assertAlmostEqual(volume, 500 - sphere / 2, delta=0.02)
        for rank in (["processor%d" % r for r in range(np)] if np > 1 else [""]):
            points = c.polymesh(os.path.join(rank, "constant", "polyMesh")).points()
            self.assertGreaterEqual(min(p[2] for p in points), 0, rank)

    def test_aBodyThroughTheBoxsFloorIsCutByItSerial(self):
        self.body_through_the_floor(1)

    def test_aBodyThroughTheBoxsFloorIsCutByItNp2(self):
        self.body_through_the_floor(2)

    def test_aBodyRestingOnTheFloorStandsOnAPlinthNp2(self):
        """The sphere resting on the box's floor at its lowest point: the
        fluid would end there in a wedge of zero angle, and pmshFoam stops
        saying so and naming plinthHeight. With plinthHeight 0.05 its part
        within 0.05 of the floor is replaced by its section there drawn
        down through the floor: Mesh OK, the log says so, the sphere's
        patch meets the floor on a ring, no point below the floor"""
        c, _ = self.cad_body_in_domain("(-5 -5 -0.5)", flip=True)
        code, log = c.run("pmshFoam", np=2, check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("touch the domain box", log)
        self.assertIn("stand them on plinths (plinthHeight in 'domain')", log)
        self.assertFalse(c.exists("processor0"))
        c.substitute("system/pmshDict", r"max \(5 5 5\);", "max (5 5 5); plinthHeight 0.05;")
        self.mesh_case(c, 2)
        with open(os.path.join(c.dir, "log.pmshFoam")) as f:
            self.assertIn("bodies standing on plinths: 1, their parts within"
                          " plinthHeight 0.05", f.read())
        # The footprint: the sphere's patch meets the floor on a ring of
        # the section's radius at 0.05, sqrt(0.5^2 - 0.45^2) = 0.218, not
        # at a point
        ring = []
        for rank in ("processor0", "processor1"):
            mesh = c.polymesh(os.path.join(rank, "constant", "polyMesh"))
            points, faces = mesh.points(), mesh.faces()
            for name, entries in mesh.boundary():
                if name == "body":
                    start, n = int(entries["startFace"]), int(entries["nFaces"])
                    ring += [points[v] for f in faces[start:start + n] for v in f
                             if points[v][2] == -0.5]
        self.assertGreaterEqual(len(ring), 16)
        radii = [math.hypot(x, y) for x, y, _ in ring]
        self.assertGreater(min(radii), 0.19)
        self.assertLess(max(radii), 0.22)
        for rank in ("processor0", "processor1"):
            points = c.polymesh(os.path.join(rank, "constant", "polyMesh")).points()
            self.assertGreaterEqual(min(p[2] for p in points), -0.5, rank)

    def dirty_body(self, boxes, np):
        """A body of unit-ish boxes (lo, hi, solid, open sides 0..5 =
        xMin..zMax) in one STL, as a CAD export may have it (open, parts
        overlapping or sharing an edge), in a domain box with wrap auto:
        the log says why it was wrapped, Mesh OK, each solid a wall patch
        and the sides their names; returns (log, summary)."""
        c, _ = self.split_case()
        quads = [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]
        solids = []
        with open(os.path.join(c.dir, "constant", "geometry", "dirty.stl"), "w") as f:
            for lo, hi, solid, open_sides in boxes:
                corner = [(lo[0] if i & 1 == 0 else hi[0], lo[1] if i & 2 == 0 else hi[1],
                           lo[2] if i & 4 == 0 else hi[2]) for i in range(8)]
                f.write("solid %s\n" % solid)
                for side, (a, b, cc, d) in enumerate(quads):
                    if side in open_sides:
                        continue
                    for t in ((a, b, cc), (a, cc, d)):
                        f.write("facet normal 0 0 0\nouter loop\n%sendloop\nendfacet\n" % "".join(
                            "vertex %r %r %r\n" % corner[v] for v in t))
                f.write("endsolid %s\n" % solid)
                solids.append(solid)
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/dirty.stl"')
        c.set_entry("system/pmshDict", "domain",
                    "{ type box; min (-5 -5 -5); max (5 5 5);"
                    " patches { xMin inlet; xMax outlet; default sides; } }")
        walls = sorted(set(solids))
        c.substitute("system/pmshDict", r"body \{ type wall; \}",
                     "\n    ".join("%s { type wall; maxCellSize 0.4; }" % w for w in walls))
        for field in ("0/U", "0/p"):
            c.substitute(field, r"(?m)^(\s*)body(\s*\{[^}]*\})",
                         "\n".join(r"\g<1>%s\g<2>" % w for w in walls))
        _, log = c.run("pmshFoam", np=np)
        text = c.check_mesh(np=np)
        self.assertGreater(cells_in_checkmesh_log(text), 1000)
        with open(os.path.join(c.dir, "processor0", "constant", "polyMesh", "boundary")) as f:
            boundary = f.read()
        for name, kind in [("inlet", "patch"), ("outlet", "patch"), ("sides", "patch")] + \
                [(w, "wall") for w in walls]:
            self.assertRegex(boundary, r"(?s)\b%s\s*\{\s*type\s+%s;" % (name, kind))
        return log, c.summary()

    def test_anOpenBoxIsWrappedAndMeshedNp2(self):
        log, summary = self.dirty_body([((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), "body", {5})], 2)
        self.assertRegex(log, r"wrapped the bodies: STL file \".*dirty.stl\" is not closed")
        self.assertTrue(summary["wrap"]["wrapped"])
        # The offset, more at the cup's inner corners, which it bridges
        wrap = summary["wrap"]
        self.assertGreaterEqual(wrap["maxDistance"], 0.99*wrap["offset"])
        self.assertLess(wrap["maxDistance"], wrap["size"] + wrap["offset"])
        # The cup's 8 closed edges are its feature edges (the 4 of its open
        # side have one triangle: no angle). Its outer corners are rounded
        # at about the offset, its inner ones bridged: never a cell away.
        self.assertEqual(wrap["featureEdges"], 8)
        self.assertGreaterEqual(wrap["featureDistance"], 0.5*wrap["offset"])
        self.assertLess(wrap["featureDistance"], wrap["size"])
        self.assertEqual(wrap["featureShareWithinSize"], 1)
        self.assertRegex(log, r"the bodies' 8 feature edges \(sharper than 30 degrees\): "
                              r"the wrap at most \S+ from them")

    def test_twoOverlappingCubesAreWrappedIntoOneBodyNp2(self):
        log, summary = self.dirty_body([((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), "body", ()),
                                        ((0, 0, 0), (1, 1, 1), "cube", ())], 2)
        self.assertIn("wrapped the bodies", log)
        self.assertTrue(summary["wrap"]["wrapped"])

    def test_cubesSharingAnEdgeAreWrappedNp2(self):
        log, summary = self.dirty_body([((-0.5, -0.5, -0.5), (0.5, 0.5, 0.5), "body", ()),
                                        ((0.5, 0.5, -0.5), (1.5, 1.5, 0.5), "cube", ())], 2)
        self.assertRegex(log, r"wrapped the bodies: .* is not manifold")
        self.assertTrue(summary["wrap"]["wrapped"])

    def test_twoCadBodiesOfTwoFormatsInTheDomainBoxSerial(self):
        self.two_bodies_in_the_domain(1)

    def test_twoCadBodiesOfTwoFormatsInTheDomainBoxNp2(self):
        self.two_bodies_in_the_domain(2)

    def test_cadLikeStlWithSharpEdgesAndThinTrianglesNp2(self):
        self.mesh("cylinderInBox.stl", 2)

    def test_tutorialGivesTheSpheresCdFromAnObjBodyInTheDomainBox(self):
        """tutorials/bodyInBox as shipped: a gzipped OBJ ball in pmshDict's
        domain box (sides named there), sphereDrag's flow. Its Allrun meshes
        on 2 ranks (Mesh OK), the box's sides get their names and types,
        the OBJ group names the wall, and simpleFoam's Cd is within 2 % of
        the sphere's (+1.0 %)."""
        c, out = self.sphere_in_box_allrun("bodyInBox")
        s = c.summary()
        self.assertEqual(s["layers"]["ball"]["coverage"], 1)
        printed = re.search(r"Cd = ([\d.]+)\s+reference 1\.087", out)
        self.assertIsNotNone(printed, out)
        self.assertLess(abs(float(printed.group(1)) - 1.087) / 1.087, 0.02, out)

    def test_csgSerial(self):
        self.mesh("sphereInBox.geo", 1)

    def test_csgNp2(self):
        self.mesh("sphereInBox.geo", 2)

    def test_csgNp4(self):
        self.mesh("sphereInBox.geo", 4)

    # A needle thinner than the coarse cells: the coarse faces wrap round
    # it and projection folds the refined surface onto itself, which
    # stopped the volume mesher ("boundary mesh is overlapping") before
    # the fold repair. Without curvature sizing, which would otherwise
    # give the needle coarse faces small enough not to fold.
    def needle(self, np):
        # The estimate's known miss: Netgen fills round a body thinner
        # than the coarse cells 2.5x more densely than estimated (README,
        # Memory)
        c, summary = self.mesh("needleInBox.stl", np, estimate_within_band=False,
                               curvatureRefinement=0)
        self.assertGreater(summary["pointsOffGeometry"], 0)
        # Off by less than the needle's radius (0.03)
        self.assertLess(summary["maxDistanceOffGeometry"], 0.03)
        self.assertLessEqual(summary["meanDistanceOffGeometry"], summary["maxDistanceOffGeometry"])
        with open(os.path.join(c.dir, "log.pmshFoam")) as f:
            self.assertRegex(f.read(), r"refined points left off the geometry .*: %d,"
                             % summary["pointsOffGeometry"])

    def test_needleNeedsTheFoldRepairSerial(self):
        self.needle(1)

    def test_needleNeedsTheFoldRepairNp2(self):
        self.needle(2)

    def test_bulletAtTwoRefinementLevelsMeshesWithHxtAtTheFirstAttemptNp2(self):
        """OpenFOAM's bullet in a box (write_bullet_in_box), maxCellSize
        0.01, r = 2, hxt, 2 ranks (#37 case 1): partition 1's refined
        surface overlapped itself and every volume mesher refused it
        (four attempts, 49 s, then the run stopped). Now 4.0M cells in
        about 35 s, every partition meshed by hxt at its first attempt
        (each rank's volume mesh checked by pmshFoam's volume contract;
        checkMesh -parallel, Mesh OK when this test was written, is left
        out for 10 s of CI's time)."""
        c = self.body_case("sphereInBox.stl")
        write_bullet_in_box(os.path.join(c.dir, "constant", "geometry", "bulletInBox.stl"))
        c.set_entry("system/pmshDict", "geometry", '"constant/geometry/bulletInBox.stl"')
        c.set_entry("system/pmshDict", "maxCellSize", 0.01)
        c.set_entry("system/pmshDict", "refinementLevels", 2)
        c.set_entry("system/pmshDict", "volumeMesher", "hxt")
        _, log = c.run("pmshFoam", np=2)
        self.assertNotIn("earlier attempts", log)
        s = c.summary()
        self.assertEqual(s["volumeMesherPerRank"], ["hxt", "hxt"])
        self.assertEqual(s["volumeAttemptsPerRank"], [1, 1])
        self.assertGreater(s["fineCells"], 3000000)

    def coarse(self, geometry, **entries):
        """Stage 1 alone (r = 0) on geometry: (coarse cells, log)."""
        c = self.body_case(geometry, **entries)
        c.set_entry("system/pmshDict", "refinementLevels", 0)
        _, log = c.run("pmshFoam")
        return int(re.search(r"\n    coarse cells: (\d+),", log).group(1)), log

    def test_curvatureSizingKeepsItsFloorAndSaysWhereItActs(self):
        # The CAD cylinder (radius 0.5, 48 facets) at maxCellSize 2.5: its
        # curvature asks for 0.17, below the default floor 2.5/8
        off, _ = self.coarse("cylinderInBox.stl", curvatureRefinement=0)
        floored, log = self.coarse("cylinderInBox.stl")
        unbounded, _ = self.coarse("cylinderInBox.stl", minCellSize=0.0025)
        m = re.search(r"\n    curvature sizing \(curvatureRefinement 3, minCellSize 0\.3125\):"
                      r" (\d+) STL points below maxCellSize, (\d+) held at minCellSize\n"
                      r"        body: (\d+) points, smallest size ([0-9.e-]+), about (\d+)"
                      r" boundary faces at these sizes, (\d+) at maxCellSize\n", log)
        self.assertIsNotNone(m, log)
        self.assertGreater(int(m.group(2)), 0)
        self.assertEqual(m.group(1), m.group(3))     # the box's solids: flat
        self.assertEqual(float(m.group(4)), 0.3125)
        self.assertGreater(int(m.group(5)), int(m.group(6)))
        faces = re.search(r"\n    patches \(coarse boundary faces\): inlet \((\d+)\)"
                          r" outlet \((\d+)\) sides \((\d+)\) body \((\d+)\)\n", log)
        self.assertIsNotNone(faces, log)
        # The default time limit, from the surface's size: the least here
        self.assertIn("\n    time limit: 120 s an attempt, 240 s for all"
                      " (coarseTimeLimit, from the surface's size)\n", log)
        self.assertGreater(int(faces.group(4)), 0)
        # Measured 3119, 3228 and 10051 coarse cells (bench/results/curvature.md)
        self.assertLess(floored, 1.3 * off)
        self.assertGreater(unbounded, 2 * off)

    def test_bodyOrientedIntoTheFluidIsAnErrorNamingItsSolid(self):
        c = self.body_case("sphereInBox.stl")
        path = os.path.join(c.dir, "constant", "geometry", "sphereInBox.stl")
        with open(path) as f:
            text = f.read()
        start = text.index("\nsolid body\n")
        head, body = text[:start], text[start:]
        # Reverse the vertex order of every facet of the body
        body = re.sub(r"(      vertex [^\n]*\n)(      vertex [^\n]*\n)(      vertex [^\n]*\n)",
                      lambda m: m.group(1) + m.group(3) + m.group(2), body)
        with open(path, "w") as f:
            f.write(head + body)
        code, log = c.run("pmshFoam", check=False)
        self.assertNotEqual(code, 0)
        for words in ("sphereInBox.stl", "solid body", "inside",
                      "Flip the normals of solid body"):
            self.assertIn(words, log)
        self.assertFalse(c.exists("constant/polyMesh/owner"))


if __name__ == "__main__":
    unittest.main()
