"""Reproducible meshes: the same case on the same number of ranks gives
byte-identical processor directories run after run, with hxt too.

Gmsh's HXT gives another mesh of the same surface depending on how the
heap of its process was used before (one thread; it orders by address
somewhere), and a rank's heap depends on MPI's timing; multithreaded HXT
differs from run to run anyway. So the meshers run in fresh processes of
pmshFoam (src/process/childProcess.H) and the coarse surface is filled
with one thread (src/coarse/coarseMesh.C). Without either, the shaft at
r = 2 on 2 ranks with hxt gave another mesh in most runs.

Run one test:  python3 testReproducible.py reproducible.test_hxtOnTwoRanksTwice
"""

import filecmp
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest  # noqa: E402


class reproducible(CaseTest):

    def assert_same_trees(self, a, b):
        """The directories a and b hold the same files, byte for byte."""
        stack = [filecmp.dircmp(a, b)]
        while stack:
            d = stack.pop()
            self.assertEqual(d.left_only + d.right_only, [], d.left)
            _, mismatch, errors = filecmp.cmpfiles(d.left, d.right, d.common_files,
                                                   shallow=False)
            self.assertEqual(mismatch + errors, [], "differ in " + d.left)
            stack.extend(d.subdirs.values())

    def mesh_twice(self, np, **entries):
        cases = []
        for _ in range(2):
            c = self.case("shaft", **entries)
            c.run("pmshFoam", np=np)
            cases.append(c)
        # The logs and postProcessing/ (timings) are left out: only the mesh
        # and fields a solver reads
        for p in range(np):
            where = "processor%d" % p if np > 1 else "constant"
            self.assertTrue(cases[0].exists(where))
            self.assert_same_trees(os.path.join(cases[0].dir, where),
                                   os.path.join(cases[1].dir, where))

    def test_hxtOnTwoRanksTwice(self):
        """The issue's case: the shaft at r = 2 on 2 ranks with hxt (the
        coarse mesh by hxt too)."""
        self.mesh_twice(2, refinementLevels=2, volumeMesher="hxt")

    def test_hxtSerialTwice(self):
        self.mesh_twice(1, refinementLevels=2, volumeMesher="hxt")


if __name__ == "__main__":
    unittest.main()
