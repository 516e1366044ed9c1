"""Parallel pmshFoam end to end: every tutorial at several rank counts and
refinement levels straight into processor*/, judged by OpenFOAM itself:
checkMesh -parallel, a solver run without decomposePar, reconstructParMesh
and reconstructPar; plus determinism, cell totals against the serial run,
and a global mesh assembled from the procAddressing files.

Run one test:  python3 testParallelTutorials.py sphere.test_np2
"""

import filecmp
import os
import re
import shutil
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from foamCase import CaseTest, PolyMeshFiles, cells_in_checkmesh_log, environment  # noqa: E402


def write_list_file(path, cls, obj, items, fmt):
    with open(path, "w") as f:
        f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n"
                "    object %s;\n}\n\n%d\n(\n" % (cls, obj, len(items)))
        for item in items:
            f.write(fmt(item) + "\n")
        f.write(")\n")


class ParallelCaseTest(CaseTest):

    def mesh_parallel(self, name, np, r, precision=None, **entries):
        """pmshFoam -parallel, then checkMesh -parallel must say Mesh OK and
        match coupled points; returns (case, total cells)."""
        c = self.case(name, refinementLevels=r, **entries)
        if precision:
            c.set_entry("system/controlDict", "writePrecision", precision)
        _, log = c.run("pmshFoam", np=np)
        self.assertIn("End", log)
        for p in range(np):
            self.assertTrue(c.exists("processor%d/constant/polyMesh/faceProcAddressing" % p))
            self.assertTrue(c.exists("processor%d/0/U" % p))
        with open(os.path.join(c.dir, "system/decomposeParDict")) as f:
            self.assertRegex(f.read(), r"numberOfSubdomains\s+%d;" % np)
        text = c.check_mesh(np=np)
        self.assertRegex(text, r"Coupled point location match.*OK")
        return c, cells_in_checkmesh_log(text)

    def full_cycle(self, name, np, r, backend="netgen"):
        """Mesh, check, solve, reconstruct mesh and fields."""
        c, cells = self.mesh_parallel(name, np, r, volumeMesher=backend)
        _, log = c.run("simpleFoam", np=np)
        self.assertRegex(log, r"(?m)^End")
        c.run("reconstructParMesh", "-constant")
        merged = c.check_mesh()
        self.assertEqual(cells_in_checkmesh_log(merged), cells)
        _, log = c.run("reconstructPar", "-latestTime")
        self.assertNotIn("FOAM FATAL", log)
        self.assertTrue(c.exists("5/U"), "reconstructPar wrote no 5/U")
        return c


def make_cycle_test(name, np, r, backend, cycle):
    """The mesh and checkMesh -parallel, and with cycle the solver and the
    reconstruction too: they read what the same writer writes whichever
    mesher filled the volume, so the Netgen tests run them and hxt's do
    not (2.5 s a test of CI's time)"""
    def test(self):
        if cycle:
            self.full_cycle(name, np, r, backend)
        else:
            self.mesh_parallel(name, np, r, volumeMesher=backend)
    test.__name__ = "test_np%d_r%d%s" % (np, r, "" if backend == "netgen" else "_" + backend)
    return test


class sphere(ParallelCaseTest):
    pass


class shaft(ParallelCaseTest):
    pass


class sphereSTL(ParallelCaseTest):
    pass


# r = 1 on 2 ranks, r = 2 on 2, 3 and 4 (r = 2 runs every stage r = 1
# does) with hxt, and with Netgen r = 1 on 2 ranks and r = 2 on 4: the
# ranks' count changes nothing in what the mesher fills, only in the
# matching between the ranks, which hxt's tests check at each count
# (8 s a Netgen test of CI's time)
for cls in (sphere, shaft, sphereSTL):
    for np, r in ((2, 1), (2, 2), (3, 2), (4, 2)):
        for backend in ("netgen", "hxt"):
            if backend == "netgen" and (np, r) not in ((2, 1), (4, 2)):
                continue
            cycle = backend == "netgen"
            t = make_cycle_test(cls.__name__, np, r, backend, cycle)
            setattr(cls, t.__name__, t)


class parallelRun(ParallelCaseTest):

    def test_sixteenRanksPassCheckMeshParallel(self):
        self.mesh_parallel("sphere", 16, 1)

    def test_identicalInputsGiveByteIdenticalProcessorTrees(self):
        a, _ = self.mesh_parallel("shaft", 3, 1)
        b = self.case("shaft", refinementLevels=1)
        b.run("pmshFoam", np=3)
        for p in range(3):
            cmp = filecmp.dircmp(os.path.join(a.dir, "processor%d" % p),
                                 os.path.join(b.dir, "processor%d" % p))
            stack = [cmp]
            while stack:
                d = stack.pop()
                self.assertEqual(d.left_only + d.right_only, [], d.left)
                _, mismatch, errors = filecmp.cmpfiles(d.left, d.right, d.common_files,
                                                       shallow=False)
                self.assertEqual(mismatch + errors, [], d.left)
                stack.extend(d.subdirs.values())

    def total_cells_within_fifteen_percent_of_serial(self, backend):
        serial = self.case("sphere", refinementLevels=2, volumeMesher=backend)
        serial.run("pmshFoam")
        nSerial = cells_in_checkmesh_log(serial.check_mesh())
        # On 4 ranks: more interface than on 2, so further from serial
        _, n = self.mesh_parallel("sphere", 4, 2, volumeMesher=backend)
        self.assertLess(abs(n - nSerial) / nSerial, 0.15,
                        "%s: %d cells on 4 ranks vs %d serial" % (backend, n, nSerial))

    def test_totalCellsWithinFifteenPercentOfSerial(self):
        self.total_cells_within_fifteen_percent_of_serial("netgen")

    def test_hxtTotalCellsWithinFifteenPercentOfSerial(self):
        """The interface's long edges must not coarsen the cells near it
        (hxtVolumeMesher.C: the interior size is capped at the fine size)"""
        self.total_cells_within_fifteen_percent_of_serial("hxt")

    def test_hxtWithQualityPassNoWorseThanNetgenOnTwoRanks(self):
        """volumeMesher hxt with optimisationSteps (the quality pass after
        HXT, tetQualityPass.H): checkMesh -parallel's max non-orthogonality
        and max skewness no worse than Netgen's on the same case and ranks
        (HXT alone: about 80 degrees and 1.1; Netgen: about 70 and 0.75),
        no slivers; and the log's summary.json reports what checkMesh
        says."""
        quality = {}
        for backend in ("netgen", "hxt"):
            c, _ = self.mesh_parallel("sphere", 2, 2, volumeMesher=backend,
                                      optimisationSteps=3)
            text = c.check_mesh(np=2)
            non_orth = re.search(r"non-orthogonality Max:\s*([\d.]+)\s+average:\s*([\d.]+)", text)
            skew = re.search(r"Max skewness =\s*([\d.]+)", text)
            aspect = re.search(r"Max aspect ratio =\s*([\d.]+)", text)
            quality[backend] = (float(non_orth.group(1)), float(skew.group(1)))
            s = c.summary()
            self.assertEqual(s["volumeMesherPerRank"], [backend, backend])
            q = s["quality"]
            self.assertAlmostEqual(q["maxNonOrthogonality"], float(non_orth.group(1)), places=4)
            self.assertAlmostEqual(q["avgNonOrthogonality"], float(non_orth.group(2)), places=4)
            self.assertAlmostEqual(q["maxSkewness"], float(skew.group(1)), places=4)
            self.assertEqual(len(q["maxNonOrthogonalityPerRank"]), 2)
            self.assertLessEqual(q["maxProcessorNonOrthogonality"], q["maxNonOrthogonality"])
            self.assertGreater(q["minVolume"], 0)
            self.assertLess(0, q["minDihedral"])
            self.assertLess(q["minDihedral"], q["maxDihedral"])
            self.assertLess(q["maxDihedral"], 180)
            # From the points before they were written (ascii, 8 digits)
            self.assertAlmostEqual(q["maxAspectRatio"] / float(aspect.group(1)), 1, places=3)
            if backend == "hxt":
                # No crease slivers left (at the pass's former threshold:
                # 0.8 degrees, aspect ratio 32)
                self.assertGreater(q["minDihedral"], 3, q)
        (n_non_orth, n_skew), (h_non_orth, h_skew) = quality["netgen"], quality["hxt"]
        self.assertLessEqual(h_non_orth, n_non_orth, quality)
        self.assertLessEqual(h_skew, n_skew, quality)

    def test_parallelOnOneRankIsAClearError(self):
        c = self.case("sphere")
        code, log = c.run("pmshFoam", "-parallel", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("FOAM FATAL ERROR", log)
        self.assertIn("1 processor", log)
        self.assertFalse(c.exists("processor0"))

    def test_binaryOutputPassesCheckMeshParallel(self):
        c = self.case("sphere", refinementLevels=1)
        c.write_format("binary")
        c.run("pmshFoam", np=3)
        self.assertRegex(c.check_mesh(np=3), r"Coupled point location match.*OK")

    def test_existingDecomposeParDictKeepsItsOtherEntries(self):
        c = self.case("sphere", refinementLevels=0)
        with open(os.path.join(c.dir, "system/decomposeParDict"), "w") as f:
            f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
                    "    object decomposeParDict;\n}\nnumberOfSubdomains 7;\n"
                    "method hierarchical;\ncoeffs { n (2 1 1); }\n")
        c.run("pmshFoam", np=2)
        with open(os.path.join(c.dir, "system/decomposeParDict")) as f:
            text = f.read()
        self.assertRegex(text, r"numberOfSubdomains\s+2;")
        self.assertRegex(text, r"method\s+hierarchical;")
        self.assertRegex(text, r"n\s+\(\s*2 1 1\s*\);")

    def test_decomposeParDictMethodPartitionsTheCoarseMesh(self):
        """The coarse mesh is split by the method system/decomposeParDict
        names (simple cuts along x here: rank 0 holds the cells of x < 0),
        and the result is a valid parallel mesh."""
        for method, coeffs in (("simple", "n (2 1 1);"), ("hierarchical", "n (2 1 1);"),
                               ("metis", "")):
            c = self.case("sphere", refinementLevels=1)
            with open(os.path.join(c.dir, "system/decomposeParDict"), "w") as f:
                f.write("FoamFile { version 2.0; format ascii; class dictionary;"
                        " object decomposeParDict; }\n"
                        "numberOfSubdomains 2;\nmethod %s;\ncoeffs { %s }\n" % (method, coeffs))
            _, log = c.run("pmshFoam", np=2)
            self.assertIn("Selecting decompositionMethod %s" % method, log)
            c.check_mesh(np=2)
            if method != "metis":
                for rank, sign in ((0, -1), (1, 1)):
                    pts = c.polymesh("processor%d/constant/polyMesh" % rank).points()
                    mean_x = sum(p[0] for p in pts) / len(pts)
                    self.assertGreater(sign * mean_x, 0.2,
                                       "%s: rank %d's points centre at x = %g"
                                       % (method, rank, mean_x))

    def test_collatedOutputFromTheControlDictSwitch(self):
        """OptimisationSwitches { fileHandler collated; } in the case's
        controlDict: the run does not hang (v1912's collated handler would
        while Time reads a case with no processors directory) and writes
        processors2/, which checkMesh reads with the same switch."""
        c = self.case("sphere", refinementLevels=1)
        with open(os.path.join(c.dir, "system/controlDict"), "a") as f:
            f.write("\nOptimisationSwitches\n{\n    fileHandler collated;\n}\n")
        _, log = c.run("pmshFoam", np=2, timeout=300)
        self.assertIn("through the collated fileHandler", log)
        self.assertTrue(c.exists("processors2/constant/polyMesh/owner"))
        self.assertFalse(c.exists("processor0"))
        self.assertRegex(c.check_mesh(np=2), r"Coupled point location match.*OK")

    def test_collatedOutputIsReadByCheckMeshAndTheSolver(self):
        """-fileHandler collated: one processors2/ directory that OpenFOAM's
        own tools read back, and a solver runs on it without decomposePar."""
        c = self.case("sphere", refinementLevels=1)
        c.run("pmshFoam", "-fileHandler", "collated", np=2)
        self.assertTrue(c.exists("processors2/constant/polyMesh/faces"))
        self.assertTrue(c.exists("processors2/0/U"))
        self.assertFalse(c.exists("processor0"))
        _, text = c.run("checkMesh", "-fileHandler", "collated", np=2)
        self.assertRegex(text, r"(?m)^Mesh OK")
        self.assertRegex(text, r"Coupled point location match.*OK")
        _, text = c.run("simpleFoam", "-fileHandler", "collated", np=2)
        self.assertRegex(text, r"(?m)^End")
        self.assertTrue(c.exists("processors2/5/U"), "the solver's fields at endTime")

    def test_anInletProfileFromBoundaryDataIsWrittenAndSolvedWithoutDecomposePar(self):
        """0/U's inlet as a mapped profile (timeVaryingMappedFixedValue,
        the profile in constant/boundaryData/inlet), standard OpenFOAM
        practice: stage 7 built the fields in a scratch processor case
        where processorN/../constant/boundaryData did not exist, and
        stopped. Serial and on 2 ranks the field is written with the
        condition, and simpleFoam runs on it."""
        for np in (1, 2):
            c = self.case("shaft", refinementLevels=1)
            data = os.path.join(c.dir, "constant", "boundaryData", "inlet")
            os.makedirs(os.path.join(data, "0"))
            grid = [(0.0, -0.6 + 0.3*i, -0.6 + 0.3*j) for i in range(5) for j in range(5)]
            with open(os.path.join(data, "points"), "w") as f:
                f.write("%d\n(\n%s)\n" % (len(grid), "".join("(%g %g %g)\n" % p for p in grid)))
            with open(os.path.join(data, "0", "U"), "w") as f:
                f.write("%d\n(\n%s)\n" % (len(grid), "(1 0 0)\n"*len(grid)))
            c.substitute("0/U", r"(?s)(inlet\s*\{).*?\}",
                         r"\1\n        type timeVaryingMappedFixedValue;"
                         r"\n        offset (0 0 0);\n        setAverage off;\n    }")
            c.run("pmshFoam", np=np)
            written = [os.path.join(c.dir, d, "0", "U") for d in
                       (["processor0", "processor1"] if np > 1 else [""])]
            texts = []
            for w in written:
                with open(w) as f:
                    texts.append(f.read())
            self.assertTrue(any("timeVaryingMappedFixedValue" in t for t in texts), written)
            _, log = c.run("simpleFoam", np=np)
            self.assertRegex(log, r"(?m)^End")

    def test_openFoamsMotorBikeFieldsAreWrittenAndSolvedWithoutDecomposePar(self):
        """OpenFOAM's own motorBike 0/ (0.orig of its simpleFoam tutorial,
        from the OpenFOAM source the build uses: #include, #includeEtc,
        $macros, k, omega, nut, and the body's conditions on the patch group
        motorBikeGroup), its transport, turbulence (kOmegaSST) and fv
        settings, round a body in a domain box whose sides carry the
        tutorial's patch names: written by pmshFoam -parallel, solved by
        simpleFoam -parallel."""
        motorBike = os.path.join(environment()["WM_PROJECT_DIR"], "tutorials",
                                 "incompressible", "simpleFoam", "motorBike")
        c = self.case("sphereSTL", refinementLevels=1, maxCellSize=0.5)
        shutil.rmtree(os.path.join(c.dir, "0"))
        shutil.copytree(os.path.join(motorBike, "0.orig"), os.path.join(c.dir, "0"))
        for f in ("constant/transportProperties", "constant/turbulenceProperties",
                  "system/fvSchemes", "system/fvSolution"):
            shutil.copy(os.path.join(motorBike, f), os.path.join(c.dir, f))
        c.set_entry("system/pmshDict", "domain",
                    "{ type box; min (-3 -2 -2); max (5 2 2); patches { xMin inlet;"
                    " xMax outlet; zMin lowerWall; zMax upperWall; default frontAndBack; } }")
        c.substitute("system/pmshDict", r"(?ms)^patches\s*\{.*?^\}",
                     "patches\n{\n    \"(inlet|outlet|upperWall|frontAndBack)\" { type patch; }\n"
                     "    lowerWall { type wall; }\n"
                     "    sphere { type wall; inGroups (motorBikeGroup); }\n}")
        c.set_entry("system/controlDict", "endTime", 3)
        c.set_entry("system/controlDict", "writeInterval", 3)
        c.run("pmshFoam", np=2)
        for rank in ("processor0", "processor1"):
            for field in ("U", "p", "k", "omega", "nut"):
                self.assertTrue(os.path.isfile(os.path.join(c.dir, rank, "0", field)), field)
        with open(os.path.join(c.dir, "processor0", "constant", "polyMesh", "boundary")) as f:
            self.assertRegex(f.read(), r"(?s)sphere\s*\{\s*type\s+wall;\s*inGroups\s+"
                                       r"\d*\s*\((wall motorBikeGroup|motorBikeGroup wall)\);")
        with open(os.path.join(c.dir, "processor1", "0", "nut")) as f:
            self.assertRegex(f.read(), r"(?s)sphere\s*\{\s*type\s+nutkWallFunction;")
        _, log = c.run("simpleFoam", np=2)
        self.assertRegex(log, r"(?m)^End")

    def test_expressionAndUnknownConditionsAreWrittenAsGiven(self):
        """An expression condition (exprFixedValue, valueExpr as a string)
        and a condition of a library the solver loads later (unknown here,
        so OpenFOAM's generic one) are written into every processor
        directory with their own entries and a value for the new patch
        (OpenFOAM writes a uniform one as uniform), as decomposePar writes
        them."""
        c = self.case("sphere")
        c.substitute("0/U", "type            noSlip;",
                     "type            exprFixedValue;\n"
                     "        valueExpr       \"vector(0, 0, 0.1*pos().x())\";\n"
                     "        value           uniform (0 0 0);")
        c.substitute("0/p", "type            zeroGradient;",
                     "type            aWallFromALibrary;\n"
                     "        roughness       #{ 1e-5 #};\n"
                     "        value           uniform 0;")
        c.run("pmshFoam", np=2)
        for rank in ("processor0", "processor1"):
            with open(os.path.join(c.dir, rank, "constant", "polyMesh", "boundary")) as f:
                nFaces = int(re.search(r"(?s)walls\s*\{[^}]*?nFaces\s+(\d+);", f.read()).group(1))
            for field, type_, entry in (("U", "exprFixedValue", r'valueExpr\s+"vector\(0, 0, 0.1\*pos\(\).x\(\)\)";'),
                                        ("p", "aWallFromALibrary", r"roughness\s+#\{\s*1e-5\s*#\};")):
                with open(os.path.join(c.dir, rank, "0", field)) as f:
                    text = f.read()
                walls = re.search(r"(?s)\n    walls\s*\{(.*?)\n    \}", text)
                self.assertIsNotNone(walls, text[-2000:])
                self.assertRegex(walls.group(1), r"type\s+%s;" % type_)
                self.assertRegex(walls.group(1), entry)
                self.assertRegex(walls.group(1), r"value\s+(uniform |nonuniform List<\w+>\s*%d\s*\()"
                                 % nFaces)

    def test_procAddressingDescribesAValidGlobalMesh(self):
        """Assemble constant/polyMesh from the processor meshes through
        their procAddressing alone; checkMesh must accept it, and
        reconstructPar must map the parallel cell centres onto it."""
        np = 3
        # Points as computed, so that the cell centres compare to 1e-9
        c, nCells = self.mesh_parallel("shaft", np, 1, precision=17)
        procs = [PolyMeshFiles(os.path.join(c.dir, "processor%d/constant/polyMesh" % p))
                 for p in range(np)]

        points, faces, owner, neighbour = {}, {}, {}, {}
        patch_faces = {}
        for m in procs:
            pts = m.points()
            fcs = m.faces()
            own = m.labels("owner")
            nbr = m.labels("neighbour")
            pAddr = m.labels("pointProcAddressing")
            fAddr = m.labels("faceProcAddressing")
            cAddr = m.labels("cellProcAddressing")
            bAddr = m.labels("boundaryProcAddressing")
            for local, g in enumerate(pAddr):
                points[g] = pts[local]
            patches = m.boundary()
            for local, a in enumerate(fAddr):
                g = abs(a) - 1
                face = [pAddr[v] for v in fcs[local]]
                cell = cAddr[own[local]]
                if a > 0:
                    faces[g] = face
                    owner[g] = cell
                else:
                    neighbour[g] = cell
                if local < len(nbr):
                    self.assertGreater(a, 0)
                    neighbour[g] = cAddr[nbr[local]]
            for pi, (name, entries) in enumerate(patches):
                start, n = int(entries["startFace"]), int(entries["nFaces"])
                if entries["type"] == "processor":
                    self.assertEqual(bAddr[pi], -1)
                    continue
                self.assertEqual(bAddr[pi], pi)
                for local in range(start, start + n):
                    patch_faces.setdefault(pi, (name, entries["type"], []))[2].append(
                        fAddr[local] - 1)

        nFaces = len(faces)
        self.assertEqual(sorted(faces), list(range(nFaces)), "global faces not contiguous")
        self.assertEqual(sorted(points), list(range(len(points))), "points not contiguous")
        nInternal = len(neighbour)
        self.assertEqual(sorted(neighbour), list(range(nInternal)))

        mesh = os.path.join(c.dir, "constant/polyMesh")
        os.makedirs(mesh, exist_ok=True)
        write_list_file(os.path.join(mesh, "points"), "vectorField", "points",
                        [points[i] for i in range(len(points))],
                        lambda p: "(%.17g %.17g %.17g)" % p)
        write_list_file(os.path.join(mesh, "faces"), "faceList", "faces",
                        [faces[i] for i in range(nFaces)],
                        lambda f: "%d(%s)" % (len(f), " ".join(map(str, f))))
        write_list_file(os.path.join(mesh, "owner"), "labelList", "owner",
                        [owner[i] for i in range(nFaces)], str)
        write_list_file(os.path.join(mesh, "neighbour"), "labelList", "neighbour",
                        [neighbour[i] for i in range(nInternal)], str)
        with open(os.path.join(mesh, "boundary"), "w") as f:
            f.write("FoamFile\n{\n    version 2.0;\n    format ascii;\n"
                    "    class polyBoundaryMesh;\n    object boundary;\n}\n\n%d\n(\n"
                    % len(patch_faces))
            for pi in sorted(patch_faces):
                name, ptype, gfaces = patch_faces[pi]
                gfaces.sort()
                self.assertEqual(gfaces, list(range(gfaces[0], gfaces[0] + len(gfaces))))
                f.write("    %s { type %s; nFaces %d; startFace %d; }\n"
                        % (name, ptype, len(gfaces), gfaces[0]))
            f.write(")\n")
        self.assertEqual(cells_in_checkmesh_log(c.check_mesh()), nCells)

        # Cell and face centres computed in parallel and mapped back by
        # reconstructPar through our addressing equal the serial ones
        c.run("postProcess", "-func", "writeCellCentres", np=np)
        c.run("reconstructPar", "-withZero", "-fields", "(C)")
        reconstructed = read_vector_field(os.path.join(c.dir, "0/C"))
        c.run("postProcess", "-func", "writeCellCentres", log="log.serialCentres")
        serial = read_vector_field(os.path.join(c.dir, "0/C"))
        self.assertEqual(sorted(reconstructed), sorted(serial))
        for key in serial:
            self.assertEqual(len(reconstructed[key]), len(serial[key]), key)
            worst = max(max(abs(a - b) for a, b in zip(u, v))
                        for u, v in zip(reconstructed[key], serial[key]))
            self.assertLess(worst, 1e-9, "%s differs by %g" % (key, worst))


def read_vector_field(path):
    """{'internalField' or patch name: [vectors]} of an ascii volVectorField."""
    with open(path) as f:
        text = f.read()
    def vectors(block):
        return [tuple(float(x) for x in v.split()) for v in re.findall(r"\(([^()]+)\)", block)]
    result = {}
    m = re.search(r"internalField\s+nonuniform\s+List<vector>\s*\d+\s*\((.*?)\n\)\s*;", text, re.S)
    result["internalField"] = vectors(m.group(1))
    boundary = text[text.index("boundaryField"):]
    for name, body in re.findall(r"\n    (\w+)\n    \{(.*?)\n    \}", boundary, re.S):
        v = re.search(r"value\s+nonuniform\s+List<vector>\s*\d+\s*\((.*?)\n\)\s*;", body, re.S)
        if v:
            result[name] = vectors(v.group(1))
    return result


if __name__ == "__main__":
    unittest.main(verbosity=2)
