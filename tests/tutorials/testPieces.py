"""Meshing in pieces (src/partition/meshPieces.H): no volume-mesher call
meshes more than maxPieceCells expected fine cells. A rank meshes its
pieces one after another, joined on the faces between them; and as the
pieces do not depend on the number of ranks, neither does the mesh.

Run one test:  python3 testPieces.py pieces.test_sameGlobalMeshAtOneTwoAndFourRanksWhenMeshedInPieces
"""

import glob
import os
import re
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, PolyMeshFiles, read_check_mesh  # noqa: E402
from testLayers import bullet_with_thick_layers_case, set_patches  # noqa: E402

# The sphere at r = 2 expects about 82k fine cells: 5 pieces of 20k
PIECE_CELLS = 20000
# With 3 layers the tets are fewer (the prisms are not the mesher's)
LAYERED_PIECE_CELLS = 16000
# The bullet with 5 layers expects about 380k tets: 7 pieces
BULLET_PIECE_CELLS = 60000
# The pipe as shipped (8 layers) expects about 60k tets: 4 pieces
PIPE_PIECE_CELLS = 15000


def global_cells(case_dir):
    """Every cell of the case's mesh (all processor directories, or
    constant/), as the sorted coordinates of its points: a set that does
    not depend on how the cells are numbered or split between ranks."""
    dirs = sorted(glob.glob(os.path.join(case_dir, "processor*", "constant", "polyMesh"))) \
        or [os.path.join(case_dir, "constant", "polyMesh")]
    cells = set()
    for d in dirs:
        mesh = PolyMeshFiles(d)
        points = mesh.points()
        owner, neighbour = mesh.labels("owner"), mesh.labels("neighbour")
        cell_points = {}
        for f, face in enumerate(mesh.faces()):
            for c in [owner[f]] + ([neighbour[f]] if f < len(neighbour) else []):
                cell_points.setdefault(c, set()).update(face)
        for vertices in cell_points.values():
            cells.add(tuple(sorted(tuple(points[v]) for v in vertices)))
    return cells


class pieces(CaseTest):

    def mesh(self, np, **entries):
        entries.setdefault("volumeMesher", "hxt")
        c = self.case("sphere", refinementLevels=2, **entries)
        c.run("pmshFoam", np=np)
        return c

    def assert_meshed_in_pieces(self, c, np, piece_cells=PIECE_CELLS):
        """The log's pieces, each meshed by one call of at most about
        maxPieceCells (the expected cells are an estimate: 1.5x)"""
        with open(os.path.join(c.dir, "log.pmshFoam")) as f:
            log = f.read()
        found = re.search(r"(\d+) pieces, meshed one volume-mesher call each", log)
        self.assertIsNotNone(found, log[-3000:])
        n_pieces = int(found.group(1))
        self.assertGreaterEqual(n_pieces, np)
        s = c.summary()
        self.assertEqual(sum(s["volumeMesherCallsPerRank"]), n_pieces)
        self.assertTrue(all(calls >= 1 for calls in s["volumeMesherCallsPerRank"]))
        self.assertLessEqual(max(s["largestVolumeMesherCallPerRank"]), 1.5*piece_cells)
        return n_pieces

    def test_sameGlobalMeshAtOneTwoAndFourRanksWhenMeshedInPieces(self):
        meshes = {}
        for np in (1, 2, 4):
            c = self.mesh(np, maxPieceCells=PIECE_CELLS)
            self.assertEqual(self.assert_meshed_in_pieces(c, np), 5)
            meshes[np] = global_cells(c.dir)
            if np == 4:
                c.check_mesh(np)
        self.assertGreater(len(meshes[1]), 50000)
        self.assertEqual(meshes[2], meshes[1], "2 ranks gave another mesh than 1")
        self.assertEqual(meshes[4], meshes[1], "4 ranks gave another mesh than 1")

        # Without pieces, one call a rank: the mesh depends on the ranks
        # (so the comparison above can fail)
        whole = [global_cells(self.mesh(np).dir) for np in (1, 2)]
        self.assertNotEqual(whole[0], whole[1])

    def test_layeredMeshInPiecesIsTheSameAtOneTwoAndFourRanks(self):
        """3 prism layers on the sphere's wall, 5 pieces: the faces between
        pieces rise over the stacks as the interfaces between ranks do, so
        the global mesh, prisms and tets, is the same at 1, 2 and 4 ranks,
        with every wall face layered"""
        meshes = {}
        for np in (1, 2, 4):
            c = self.case("sphere", refinementLevels=2, volumeMesher="hxt",
                          maxPieceCells=LAYERED_PIECE_CELLS)
            set_patches(c, {"walls": "type wall; layers 3; firstLayerThickness 0.004;"})
            c.write_format("binary")
            c.run("pmshFoam", np=np)
            self.assertEqual(self.assert_meshed_in_pieces(c, np, LAYERED_PIECE_CELLS), 5)
            s = c.summary()
            self.assertEqual(s["layers"]["walls"]["coverage"], 1.0, s["layers"])
            meshes[np] = global_cells(c.dir)
            result = read_check_mesh(c.check_mesh(np))
            self.assertEqual(result["prisms"], s["prisms"])
        self.assertEqual(meshes[2], meshes[1], "2 ranks gave another mesh than 1")
        self.assertEqual(meshes[4], meshes[1], "4 ranks gave another mesh than 1")

    def test_pipesThickStacksInPiecesAreTheSameAtOneTwoAndFourRanks(self):
        """The pipe as shipped, 8 layers 0.2 thick in a pipe of radius 0.5,
        whose interfaces cannot rise as far as the stacks: one piece a rank,
        8,592 of its 210,944 prisms differ between 1 and 2 ranks; in 4
        pieces the global mesh, prisms and tets, is the same at 1, 2 and 4
        ranks, every wall face layered. At 4 ranks, as many as the pieces,
        a piece a rank: before, that took the one-a-rank split, and gave
        another mesh (278,775 cells against 278,927)."""
        meshes = {}
        for np in (1, 2, 4):
            c = self.case("pipe", maxPieceCells=PIPE_PIECE_CELLS)
            c.write_format("binary")
            c.run("pmshFoam", np=np)
            self.assertEqual(self.assert_meshed_in_pieces(c, np, PIPE_PIECE_CELLS), 4)
            s = c.summary()
            self.assertEqual(s["layers"]["walls"]["coverage"], 1.0, s["layers"])
            self.assertGreater(s["prisms"], 200000)
            meshes[np] = global_cells(c.dir)
            if np == 4:
                c.check_mesh(np)
        self.assertEqual(meshes[2], meshes[1], "2 ranks gave another mesh than 1")
        self.assertEqual(meshes[4], meshes[1], "4 ranks gave another mesh than 1")

    def test_bulletsThickStacksInPiecesAreTheSameAtOneTwoAndFourRanks(self):
        """OpenFOAM's bullet with 5 layers thick against its surface, in 7
        pieces: the faces between pieces rise over the stacks as the
        interfaces between ranks do, and the stacks are thinned for the
        crossings of their own piece only, so the global mesh, prisms and
        tets, is the same at 1, 2 and 4 ranks, with at least 99 % of the
        body's faces layered. It was not while the lifted surface was
        checked over the whole rank: 82,449 cells of 1 rank's mesh were not
        in 2 ranks'. One piece a rank, 67,110 of its prisms differ between
        1 and 2 ranks, 152,030 between 1 and 4."""
        meshes = {}
        for np in (1, 2, 4):
            c = bullet_with_thick_layers_case(self)
            c.set_entry("system/pmshDict", "maxPieceCells", BULLET_PIECE_CELLS)
            c.write_format("binary")
            c.run("pmshFoam", np=np)
            self.assert_meshed_in_pieces(c, np, BULLET_PIECE_CELLS)
            s = c.summary()
            self.assertGreaterEqual(s["layers"]["body"]["coverage"], 0.99, s["layers"])
            meshes[np] = global_cells(c.dir)
        self.assertEqual(meshes[2], meshes[1], "2 ranks gave another mesh than 1")
        self.assertEqual(meshes[4], meshes[1], "4 ranks gave another mesh than 1")
        result = read_check_mesh(c.check_mesh(4))
        self.assertEqual(result["prisms"], s["prisms"])

    def test_netgenPiecesJoinIntoOneValidMeshOnTwoRanks(self):
        c = self.mesh(2, volumeMesher="netgen", maxPieceCells=PIECE_CELLS)
        self.assert_meshed_in_pieces(c, 2)
        result = read_check_mesh(c.check_mesh(2))
        self.assertEqual(result["cells"], c.summary()["fineCells"])

    def test_piecesKeepTheWholeMeshesQuality(self):
        """The faces between pieces are a flat lattice like the interfaces
        between ranks: the mesh in 5 pieces is as good as in one a rank"""
        split = read_check_mesh(self.mesh(2, maxPieceCells=PIECE_CELLS).check_mesh(2))
        whole = read_check_mesh(self.mesh(2).check_mesh(2))
        self.assertLessEqual(split["maxNonOrtho"], whole["maxNonOrtho"] + 5)
        self.assertLessEqual(split["maxSkewness"], whole["maxSkewness"] + 0.2)


if __name__ == "__main__":
    unittest.main()
