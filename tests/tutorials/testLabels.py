"""pmshFoam with the label size of its OpenFOAM build (WM_LABEL_SIZE 32 or
64), end to end: the sphere serial and on 2 ranks, partitioned by metis
(the default) and by hierarchical, written in ascii, judged by Debian's
OpenFOAM binaries (checkMesh, checkMesh -parallel, simpleFoam -parallel).

These are the tests `./Alltest --int64` runs with pmshFoam built against
OpenFOAM's libraries of 64-bit labels: Debian's binaries have 32-bit
labels, and read the Int64 meshes because ascii labels have no width
(binary ones they could not read). pmshFoam's banner says which labels it
ran with.

Run one test:  python3 testLabels.py labels.test_sphereSerialMeshOk
"""

import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, cells_in_checkmesh_log  # noqa: E402

LABEL_SIZE = int(os.environ.get("WM_LABEL_SIZE", "32"))


class labels(CaseTest):

    def expect_label_size(self, c, polyMesh, log):
        """pmshFoam ran with the build's labels (its banner's Arch) and
        wrote ascii."""
        self.assertRegex(log, r"Arch\s*:.*label=%d" % LABEL_SIZE)
        with open(os.path.join(c.dir, polyMesh, "owner")) as f:
            self.assertRegex(f.read(2000), r"format\s+ascii;")

    def sphere_on_two_ranks(self, method):
        c = self.case("sphere", refinementLevels=1)
        c.write_format("ascii")
        if method:
            with open(os.path.join(c.dir, "system/decomposeParDict"), "w") as f:
                f.write("FoamFile { version 2.0; format ascii; class dictionary;"
                        " object decomposeParDict; }\n"
                        "numberOfSubdomains 2;\nmethod %s;\ncoeffs { n (2 1 1); }\n"
                        % method)
        _, log = c.run("pmshFoam", np=2)
        self.assertIn("Selecting decompositionMethod %s" % (method or "metis"), log)
        self.expect_label_size(c, "processor1/constant/polyMesh", log)
        text = c.check_mesh(np=2)
        self.assertRegex(text, r"Coupled point location match.*OK")
        self.assertGreater(cells_in_checkmesh_log(text), 1000)
        _, log = c.run("simpleFoam", np=2)
        self.assertRegex(log, r"(?m)^End")
        return c

    def test_sphereSerialMeshOk(self):
        c = self.case("sphere", refinementLevels=1)
        c.write_format("ascii")
        _, log = c.run("pmshFoam")
        self.expect_label_size(c, "constant/polyMesh", log)
        c.check_mesh()

    def test_sphereOnTwoRanksByMetisSolves(self):
        # METIS's idx_t is 32-bit in Debian: OpenFOAM's metisDecomp converts
        # the coarse graph's labels to it and back
        self.sphere_on_two_ranks(None)

    def test_sphereOnTwoRanksByHierarchicalSolves(self):
        self.sphere_on_two_ranks("hierarchical")


if __name__ == "__main__":
    unittest.main()
