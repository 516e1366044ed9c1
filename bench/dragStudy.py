#!/usr/bin/env python3
"""Drag and pressure drop on every kind of mesh: why tetrahedra overpredicted them.

bench/run --drag (bench/README.md, "The drag study") solves two steady
laminar flows with simpleFoam -parallel, each on every kind of mesh:

- the sphere (tutorials/sphereDrag, Re = 100): Cd against 1.087 (Johnson &
  Patel 1999);
- the pipe (tutorials/pipe, Re = 100): the pressure drop in the developed
  part against Hagen-Poiseuille's, and the wall shear stress there;

on pmshFoam's tetrahedra (netgen and hxt) at three to five sizes, the
polyhedral duals of them (OpenFOAM's polyDualMesh, sphere only),
snappyHexMesh with and without 5 layers (bench/cases/*Snappy), and, for the
sphere, variants that isolate a cause (the wake refined alone, the ball's
surface refined alone, a refinement region round the ball). Every mesh is
solved with each scheme set of SCHEMES, which differ only in their
gradients (and the non-orthogonal limiting of the former tutorial); the
reference mesh of each flow also with one scheme change at a time
(SCHEME_VARIANTS), and for the sphere the forces of a converged solution
are evaluated with the other gradient scheme too (how much of a difference
is the solution, how much the force's evaluation).

For every mesh it also measures how consistent OpenFOAM's gradient schemes
are there: the gradient of the cell-centre field C is exactly the identity,
so |grad(C) - I| over the cells away from the boundaries is the scheme's
error on a linear field, which does not shrink with the cells where it
comes from their shape (skewness).

Everything goes into bench/results/drag-study.json, merged with what is
there, so an interrupted run resumes (--redo NAME measures one again); the
report is bench/results/drag-study.md with the plots drag-study-cd.png and
drag-study-gradient.png. The findings paragraph at its top is kept in the
json ("findings"), written by hand from the tables.
"""

import argparse
import glob
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

BENCH_DIR = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(BENCH_DIR)
sys.path.insert(0, BENCH_DIR)
sys.path.insert(0, os.path.join(ROOT, "tools"))
import pmshBench as pb  # noqa: E402
import foamCase as fc  # noqa: E402
from foamCase import PolyMeshFiles  # noqa: E402

REFERENCE_CD = 1.087            # Johnson & Patel (1999), Re = 100
AREF = math.pi/4                # D = 1
BALL_RADIUS = 0.5
DOMAIN_VOLUME = 20*10*10 - math.pi/6

# ---------------------------------------------------------------------------
# Schemes: the same controlDict, fvSolution and fields for every run
# ---------------------------------------------------------------------------

def fv_schemes(grad, laplacian="corrected", convection="bounded Gauss linearUpwind grad(U)",
               extra_grad=""):
    """fvSchemes that differ from the tutorials' only in what is given"""
    return """FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default steadyState; }
gradSchemes { default %s; %s }
divSchemes
{
    default none;
    div(phi,U) %s;
    div((nuEff*dev2(T(grad(U))))) Gauss linear;
}
laplacianSchemes { default Gauss linear %s; }
interpolationSchemes { default linear; }
snGradSchemes { default %s; }
wallDist { method meshWave; }
""" % (grad, extra_grad, convection, laplacian, laplacian)


# The sets every mesh is solved with
SCHEMES = {
    "gauss": ("cellLimited Gauss linear 1 (the former sphereDrag tutorial)",
              fv_schemes("cellLimited Gauss linear 1", "limited corrected 0.5")),
    "leastSquares": ("leastSquares, unlimited",
                     fv_schemes("leastSquares", "corrected")),
    # leastSquares everywhere but in linearUpwind's reconstruction, which
    # is limited: unlimited, it diverged on the pipe (253k cells)
    "leastSquaresLimitedConvection": (
        "leastSquares; linearUpwind's gradient cellLimited leastSquares 1 (the tutorials now)",
        fv_schemes("leastSquares", "corrected",
                   convection="bounded Gauss linearUpwind limitedGrad",
                   extra_grad="limitedGrad cellLimited leastSquares 1;")),
    # The same with a conservative pressure gradient: the pressure force
    # balances the wall shear, as leastSquares' does not (the pipe)
    "conservativePressure": (
        "as the tutorials, but grad(p) Gauss linear (the pipe tutorial now)",
        fv_schemes("leastSquares", "corrected",
                   convection="bounded Gauss linearUpwind limitedGrad",
                   extra_grad="limitedGrad cellLimited leastSquares 1; grad(p) Gauss linear;")),
}

# One change at a time, on the reference mesh only
SCHEME_VARIANTS = {
    "gaussUnlimited": ("Gauss linear, corrected",
                       fv_schemes("Gauss linear")),
    "gaussLinearConvection": ("Gauss linear, corrected, central convection (Gauss linear)",
                              fv_schemes("Gauss linear", convection="bounded Gauss linear")),
    "gaussUpwind": ("Gauss linear, corrected, first-order upwind convection",
                    fv_schemes("Gauss linear", convection="bounded Gauss upwind")),
    "leastSquaresGradPOnly": ("Gauss linear, grad(p) leastSquares",
                              fv_schemes("Gauss linear", extra_grad="grad(p) leastSquares;")),
    "leastSquaresGradUOnly": ("Gauss linear, grad(U) leastSquares",
                              fv_schemes("Gauss linear", extra_grad="grad(U) leastSquares;")),
    "leastSquaresLimitedCorrected": ("leastSquares, limited corrected 0.5",
                                     fv_schemes("leastSquares", "limited corrected 0.5")),
    "leastSquaresLimitedU": ("leastSquares, grad(U) cellLimited leastSquares 1",
                             fv_schemes("leastSquares",
                                        extra_grad="grad(U) cellLimited leastSquares 1;")),
    "leastSquaresAllLimited": ("cellLimited leastSquares 1 for every gradient",
                               fv_schemes("cellLimited leastSquares 1")),
    "leastSquaresLinearConvection": ("leastSquares, central convection (Gauss linear)",
                                     fv_schemes("leastSquares", convection="bounded Gauss linear")),
    "pointCellsLeastSquares": ("pointCellsLeastSquares",
                               fv_schemes("pointCellsLeastSquares")),
    # Gauss with face values corrected for skewness: conservative, as
    # leastSquares is not, and nearly consistent
    "gaussSkewCorrected": ("Gauss skewCorrected linear; linearUpwind's gradient as shipped",
                           fv_schemes("Gauss skewCorrected linear", "corrected",
                                      convection="bounded Gauss linearUpwind limitedGrad",
                                      extra_grad="limitedGrad cellLimited leastSquares 1;")),
}

FORCES_FUNCTION = """
    // Pressure and viscous parts of the force on the ball (drag study)
    forcesBall
    {
        type            forces;
        libs            ("libforces.so");
        writeControl    timeStep;
        writeInterval   1;
        log             false;
        patches         (ball);
        rho             rhoInf;
        rhoInf          1;
        CofR            (0 0 0);
    }
"""

# ---------------------------------------------------------------------------
# The two studies: what is meshed, how the answer is read
# ---------------------------------------------------------------------------

def pmsh_dict(geometry, patches, regions=""):
    """A study's pmshDict template: the tutorials' settings but for the
    sizes, the mesher and the layers, filled in per mesh"""
    return """FoamFile { version 2.0; format ascii; class dictionary; object pmshDict; }
geometry          "constant/geometry/%s";
maxCellSize       %%(far)g;
grading           0.3;
refinementLevels  2;
volumeMesher      %%(mesher)s;
optimisationSteps 3;
patches
{
%s}
%s""" % (geometry, patches, regions)


SPHERE_PMSH_DICT = pmsh_dict("sphereDrag.geo", """\
    "(inlet|outlet)" { type patch; }
    sides            { type symmetry; }
    ball             { type wall; maxCellSize %(ball)g; %(layers)s}
""", """refinementRegions
{
    wake { type box; min (-1 -1.5 -1.5); max (6 1.5 1.5); maxCellSize %(wake)g; }
    %(regions)s
}
""")

PIPE_PMSH_DICT = pmsh_dict("pipe.geo", """\
    "(inlet|outlet)" { type patch; }
    walls            { type wall; %(layers)s}
""")

# pmshFoam's prism layers: the sphereDrag tutorial's 3 on the ball (0.0146
# thick); on the pipe's wall the 5 of snappyHexMesh's case and the
# tutorial's 12 (0.29 of the radius)
SPHERE_LAYERS = "layers 3; firstLayerThickness 0.004; expansionRatio 1.2; "
PIPE_LAYERS_5 = "layers 5; firstLayerThickness 0.01; expansionRatio 1.2; "
PIPE_LAYERS_12 = "layers 12; firstLayerThickness 0.01; expansionRatio 1.15; "


class Study:
    """One flow of the study: its tutorial, its peer's case, its meshes and
    how a solution's answer is read"""

    layered_sizes = None            # of the matrix, with layers too (None: all)

    # Scheme sets solved on every mesh, and variants on the reference mesh
    scheme_sets = tuple(SCHEMES)
    variants = tuple(SCHEME_VARIANTS)

    def __init__(self, name, tutorial, snappy_case, pmsh_dict, reference, quantity):
        self.name = name
        self.tutorial = tutorial
        self.snappy_case = snappy_case
        self.pmsh_dict = pmsh_dict
        self.reference = reference
        self.quantity = quantity

    def pmsh_mesh(self, name, family, mesher, factor=1.0, regions="", layers="", **sizes):
        full = dict((k, v*factor) for k, v in self.sizes.items())
        full.update(sizes)
        return {"name": name, "family": family, "builder": "pmsh", "mesher": mesher,
                "factor": factor, "sizes": full, "regions": regions, "layers": layers}

    def mesher_matrix(self):
        """pmshFoam's meshes of the tutorial's dictionary: both meshers at
        each of matrix_sizes, with and without the tutorial's layers, the
        smallest first, then the finest meshes"""
        out = []
        for size in self.matrix_sizes:
            for layered in (False, True):
                if layered and size not in (self.layered_sizes or self.matrix_sizes):
                    continue
                for mesher in ("netgen", "hxt"):
                    out.append(self.sized(mesher, size, layered))
        return out + [self.sized(*m) for m in self.finest]


class SphereStudy(Study):
    sizes = {"far": 4.0, "ball": 0.1, "wake": 1.0}      # the tutorial's
    reference_mesh = "netgen-1"
    scheme_sets = ("gauss", "leastSquares", "leastSquaresLimitedConvection")
    shipped = "leastSquaresLimitedConvection"       # tutorials/sphereDrag's fvSchemes

    def __init__(self):
        Study.__init__(self, "sphere", os.path.join(ROOT, "tutorials", "sphereDrag"),
                       os.path.join(BENCH_DIR, "cases", "sphereDragSnappy"),
                       SPHERE_PMSH_DICT, REFERENCE_CD, "Cd")

    # The mesher matrix (--shipped): size factors (cells ~ factor^-3, less
    # where the ball's size rules), and the finest meshes beyond it
    matrix_sizes = (2.0, 1.41, 1.0, 0.71)
    finest = (("hxt", 0.5, True), ("hxt", 0.5, False), ("netgen", 0.5, False))

    def sized(self, mesher, f, layered):
        return self.pmsh_mesh("%s-%g%s" % (mesher, f, "-layers" if layered else ""),
                              "pmshFoam %s%s" % (mesher, ", 3 layers" if layered else ""),
                              mesher, f, layers=SPHERE_LAYERS if layered else "")

    def meshes(self):
        out = self.mesher_matrix()
        for f in (1.41, 1.0, 0.71, 0.5):
            m = self.pmsh_mesh("dual-%g" % f, "polyDualMesh of pmshFoam netgen", "netgen", f)
            m["builder"] = "dual"
            out.append(m)
        for layers in (0, 5):
            for level in (3, 4, 5):
                out.append({"name": "snappy-L%d%s" % (level, "-layers" if layers else ""),
                            "family": "snappyHexMesh%s" % (", 5 layers" if layers else ""),
                            "builder": "snappy",
                            "entries": {"ballLevel": level, "wakeLevel": level - 2,
                                        "nLayers": layers}})
        # Isolating the cause: the reference mesh with one size changed
        out.append(self.pmsh_mesh("netgen-wake0.5", "isolation", "netgen", wake=0.5))
        out.append(self.pmsh_mesh("netgen-ball0.05", "isolation", "netgen", ball=0.05))
        out.append(self.pmsh_mesh("netgen-roundBall", "isolation", "netgen", regions=(
            "round { type sphere; centre (0 0 0); radius 0.9; maxCellSize 0.15; }")))
        return out

    functions = FORCES_FUNCTION

    def interior(self, c):
        r = math.sqrt(sum(x*x for x in c))
        return (r > BALL_RADIUS + 0.1 and abs(c[1]) < 4.5 and abs(c[2]) < 4.5
                and -4.5 < c[0] < 14.5)

    def answer(self, case):
        """(iterations, {Cd, CdPressure, CdViscous})"""
        coeff = last_row(os.path.join(case, "postProcessing", "forceCoeffs", "0",
                                      "coefficient.dat"))
        force_files = glob.glob(os.path.join(case, "postProcessing", "forcesBall", "*",
                                             "force.dat"))
        force = last_row(sorted(force_files)[-1]) if force_files else None
        out = {"Cd": float(coeff.split()[1])}
        if force:
            values = [float(x) for x in re.sub(r"[()]", " ", force).split()]
            out["CdPressure"], out["CdViscous"] = values[4]/(0.5*AREF), values[7]/(0.5*AREF)
        return int(float(coeff.split()[0])), out

    settled_text = "CdSettled condition satisfied"

    def surface_fidelity(self, case):
        return ball_surface(case)


PIPE_RADIUS = 0.5
PIPE_NU = 0.01
PIPE_LENGTH = 14.0
# The tutorial's cross-sections (its planes x7, x12), in the developed flow
PIPE_PLANES = (7, 12)
# Hagen-Poiseuille between them: 32 nu U L / D^2 (kinematic)
PIPE_REFERENCE_DP = 32*PIPE_NU*1.0*(PIPE_PLANES[1] - PIPE_PLANES[0])/(2*PIPE_RADIUS)**2


class PipeStudy(Study):
    sizes = {"far": 0.4}            # the tutorial's: D/10 at r = 2
    reference_mesh = "netgen-0.4"
    # The pipe repeats the sphere's findings at a smaller cost: unlimited
    # leastSquares diverged on its finer tets, and of the variants only
    # those that split the cause (which gradient, limiting, stencil)
    scheme_sets = ("gauss", "leastSquaresLimitedConvection", "conservativePressure")
    variants = ("gaussUnlimited", "leastSquares", "leastSquaresGradPOnly",
                "leastSquaresGradUOnly", "leastSquaresAllLimited", "pointCellsLeastSquares",
                "gaussSkewCorrected")
    shipped = "conservativePressure"                # tutorials/pipe's fvSchemes

    def __init__(self):
        Study.__init__(self, "pipe", os.path.join(ROOT, "tutorials", "pipe"),
                       os.path.join(BENCH_DIR, "cases", "pipeSnappy"),
                       PIPE_PMSH_DICT, PIPE_REFERENCE_DP, "dp")

    matrix_sizes = (0.8, 0.57, 0.4, 0.28)
    layered_sizes = (0.8, 0.57, 0.4)                # 0.28 with layers is among the finest
    finest = (("netgen", 0.28, True), ("hxt", 0.28, True))

    def sized(self, mesher, h, layered):
        return self.pmsh_mesh("%s-%g%s" % (mesher, h, "-layers12" if layered else ""),
                              "pmshFoam %s%s" % (mesher, ", 12 layers" if layered else ""),
                              mesher, far=h, layers=PIPE_LAYERS_12 if layered else "")

    def meshes(self):
        out = self.mesher_matrix()
        out.append(self.pmsh_mesh("netgen-0.4-layers5", "pmshFoam netgen, 5 layers", "netgen",
                                  far=0.4, layers=PIPE_LAYERS_5))
        for layers in (0, 5):
            for level in ((1, 2) if not layers else (1,)):
                out.append({"name": "snappy-L%d%s" % (level, "-layers" if layers else ""),
                            "family": "snappyHexMesh%s" % (", 5 layers" if layers else ""),
                            "builder": "snappy",
                            "entries": {"wallLevel": level, "nLayers": layers}})
        return out

    functions = ""                  # the tutorial's own planes x7, x12

    def interior(self, c):
        return 1 < c[0] < PIPE_LENGTH - 1 and math.hypot(c[1], c[2]) < PIPE_RADIUS - 0.1

    def answer(self, case):
        """(iterations, {dp, wallShear}): the pressure drop between the
        planes, and the mean axial wall shear stress there (against 8 nu U/D)"""
        rows = []
        for plane in ("x%d" % x for x in PIPE_PLANES):
            row = last_row(os.path.join(case, "postProcessing", plane, "0",
                                        "surfaceFieldValue.dat"))
            rows.append([float(x) for x in row.split()])
        out = {"dp": rows[0][1] - rows[1][1]}
        ok, _, _ = run(["simpleFoam", "-postProcess", "-latestTime", "-func",
                        "wallShearStress"], case, "log.wallShearStress", np=len(mesh_dirs(case)))
        if ok:
            out["wallShear"] = mean_wall_shear(case)
        return int(rows[0][0]), out

    settled_text = "upstreamSettled condition satisfied"

    def surface_fidelity(self, case):
        return {}


STUDIES = [SphereStudy(), PipeStudy()]
SNAPPY_WALLS = {"sphere": "ball", "pipe": "walls"}


# ---------------------------------------------------------------------------
# Meshing
# ---------------------------------------------------------------------------

def run(cmd, cwd, logname, np=1, timeout=None):
    """Run an OpenFOAM command (with mpirun -parallel for np > 1); returns
    (ok, wall seconds, log text)"""
    cmd = fc.mpi(np, cmd)
    start = time.perf_counter()
    with open(os.path.join(cwd, logname), "w") as out:
        proc = subprocess.run(cmd, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL, timeout=timeout)
    wall = time.perf_counter() - start
    with open(os.path.join(cwd, logname), errors="replace") as f:
        text = f.read()
    return proc.returncode == 0, wall, text


def run_in_turn(steps):
    """Each step (a function returning (ok, wall seconds, log text) as run
    does) until one fails: (ok, the steps' wall seconds, the last log)"""
    wall = 0.0
    for step in steps:
        ok, w, text = step()
        wall += w
        if not ok:
            break
    return ok, wall, text


def new_case(study, path):
    pb.copy_case(study.tutorial, path, ignore=(), parts=("0", "constant", "system"))


def decompose(case, np):
    with open(os.path.join(case, "system", "decomposeParDict"), "w") as f:
        f.write("FoamFile { version 2.0; format ascii; class dictionary;"
                " object decomposeParDict; }\nnumberOfSubdomains %d;\nmethod metis;\n" % np)
    return run(["decomposePar", "-force"], case, "log.decomposePar")


def build_pmsh(study, m, case, np):
    new_case(study, case)
    with open(os.path.join(case, "system", "pmshDict"), "w") as f:
        f.write(study.pmsh_dict % dict(m["sizes"], mesher=m["mesher"], regions=m["regions"],
                                       layers=m["layers"]))
    if m["builder"] == "pmsh":
        return run(["pmshFoam"], case, "log.pmshFoam", np=np)
    # The dual: pmshFoam serially, polyDualMesh, decomposePar
    return run_in_turn((lambda: run(["pmshFoam"], case, "log.pmshFoam"),
                        lambda: run(["polyDualMesh", "60", "-overwrite"], case,
                                    "log.polyDualMesh"),
                        lambda: decompose(case, np)))


def build_snappy(study, m, case, np):
    new_case(study, case)
    shutil.rmtree(os.path.join(case, "constant", "geometry"))
    os.remove(os.path.join(case, "system", "pmshDict"))
    for f in glob.glob(os.path.join(study.snappy_case, "system", "*")):
        shutil.copy(f, os.path.join(case, "system"))
    snappy_dict = os.path.join(case, "system", "snappyHexMeshDict")
    for key, value in m["entries"].items():
        pb.set_entry(snappy_dict, key, value)
    block_mesh = lambda: run(["blockMesh"], case, "log.blockMesh")  # noqa: E731
    if not m.get("parallel"):
        return run_in_turn((block_mesh,
                            lambda: run(["snappyHexMesh", "-overwrite"], case,
                                        "log.snappyHexMesh"),
                            lambda: decompose(case, np)))
    # On np ranks: decomposed first, then the case's 0/ in every processor
    # directory (as OpenFOAM's motorBike tutorial does: the fields are
    # uniform, and their constraint types come from setConstraintTypes)
    done = run_in_turn((block_mesh,
                        lambda: decompose(case, np),
                        lambda: run(["snappyHexMesh", "-overwrite"], case,
                                    "log.snappyHexMesh", np=np)))
    if done[0]:
        fields_into_processors(case, "0")
    return done


def fields_into_processors(case, fields):
    """The case's uniform initial fields (directory `fields`) as every
    processor directory's 0/, as OpenFOAM's motorBike Allrun restores them
    (restore0Dir -processor): their constraint types come from
    setConstraintTypes"""
    for d in glob.glob(os.path.join(case, "processor*")):
        shutil.rmtree(os.path.join(d, "0"), ignore_errors=True)
        shutil.copytree(os.path.join(case, fields), os.path.join(d, "0"))


def snappy_layer_coverage(case, patch):
    """(mean layers, thickness, thickness %) of a patch from snappyHexMesh's
    final layer table, or None"""
    try:
        with open(os.path.join(case, "log.snappyHexMesh"), errors="replace") as f:
            text = f.read()
    except OSError:
        return None
    rows = re.findall(r"^%s\s+(\d+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)\s+([0-9.eE+-]+)" % patch,
                      text, re.M)
    if not rows:
        return None
    faces, layers, thickness, percent = rows[-1]
    return {"meanLayers": float(layers), "thickness": float(thickness),
            "thicknessPercent": float(percent)}


def pmsh_layer_coverage(case, patch):
    """pmshFoam's report of a patch's layers (summary.json): layers,
    coverage (the share of faces with all their layers), thickness"""
    return fc.summary(case)["layers"][patch]


def mesh_dirs(case):
    dirs = sorted(glob.glob(os.path.join(case, "processor*")),
                  key=lambda d: int(re.sub(r"\D", "", os.path.basename(d))))
    return [os.path.join(d, "constant", "polyMesh") for d in dirs] or \
        [os.path.join(case, "constant", "polyMesh")]


def triangle_fan_area(xs, face):
    area = 0.0
    p0 = xs[face[0]]
    for a, b in zip(face[1:-1], face[2:]):
        u = [xs[a][i] - p0[i] for i in range(3)]
        v = [xs[b][i] - p0[i] for i in range(3)]
        c = (u[1]*v[2] - u[2]*v[1], u[2]*v[0] - u[0]*v[2], u[0]*v[1] - u[1]*v[0])
        area += 0.5*math.sqrt(sum(x*x for x in c))
    return area


def ball_surface(case):
    """Area of the ball patch against pi, and how far its points are from
    the sphere: the projected surface's fidelity"""
    area, deviation = 0.0, 0.0
    for d in mesh_dirs(case):
        mesh = PolyMeshFiles(d)
        patch = [entries for name, entries in mesh.boundary() if name == "ball"]
        if not patch:
            continue
        xs = mesh.points()
        start, n = int(patch[0]["startFace"]), int(patch[0]["nFaces"])
        used = set()
        for face in mesh.faces()[start:start + n]:
            area += triangle_fan_area(xs, face)
            used.update(face)
        for i in used:
            deviation = max(deviation, abs(math.sqrt(sum(x*x for x in xs[i])) - BALL_RADIUS))
    return {"ballAreaError": area/math.pi - 1.0, "ballMaxRadiusError": deviation/BALL_RADIUS}


def field_values(path):
    """A volField's internal values (nonuniform List<scalar|vector|tensor>)"""
    with open(path) as f:
        text = f.read()
    m = re.search(r"internalField\s+nonuniform\s+List<\w+>\s*(\d+)\s*\(", text)
    n = int(m.group(1))
    body = text[m.end():text.find("boundaryField")]
    if "List<scalar>" in m.group(0):
        return [[float(x)] for x in body.split()[:n]]
    return [[float(x) for x in item.split()] for item in re.findall(r"\(([^()]*)\)", body)[:n]]


def patch_values(path, patch):
    """A volVectorField's values on one patch"""
    with open(path) as f:
        text = f.read()
    text = text[text.find("boundaryField"):]
    text = text[re.search(r"\b%s\b" % patch, text).end():]
    m = re.search(r"value\s+nonuniform\s+List<vector>\s*(\d+)\s*\(", text)
    n = int(m.group(1))
    return [[float(x) for x in v.split()] for v in re.findall(r"\(([^()]*)\)", text[m.end():])[:n]]


def mean_wall_shear(case):
    """Mean axial wall shear stress on the pipe's walls between its planes
    (Hagen-Poiseuille: 8 nu U / D)"""
    force, area = 0.0, 0.0
    for d in mesh_dirs(case):
        mesh = PolyMeshFiles(d)
        entries = dict(mesh.boundary())["walls"]
        start, n = int(entries["startFace"]), int(entries["nFaces"])
        processor = os.path.dirname(os.path.dirname(d))
        latest = sorted(glob.glob(os.path.join(processor, "[1-9]*")),
                        key=lambda t: float(os.path.basename(t)))[-1]
        xs = mesh.points()
        stress = patch_values(os.path.join(latest, "wallShearStress"), "walls")
        for face, tau in zip(mesh.faces()[start:start + n], stress):
            x = sum(xs[i][0] for i in face)/len(face)
            if PIPE_PLANES[0] < x < PIPE_PLANES[1]:
                a = triangle_fan_area(xs, face)
                force -= tau[0]*a
                area += a
    return force/area


def gradient_error(study, case, np, grad):
    """|grad(C) - I| of the gradient scheme grad on the cells away from the
    boundaries: (mean, 99th percentile)"""
    work = case + "-grad"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copytree(os.path.join(case, "system"), os.path.join(work, "system"))
    shutil.copytree(os.path.join(case, "constant"), os.path.join(work, "constant"),
                    ignore=shutil.ignore_patterns("geometry"))
    os.makedirs(os.path.join(work, "0"))
    for d in glob.glob(os.path.join(case, "processor*")):
        shutil.copytree(os.path.join(d, "constant"),
                        os.path.join(work, os.path.basename(d), "constant"))
        # postProcess -time 0 needs the time directory
        os.makedirs(os.path.join(work, os.path.basename(d), "0"))
    with open(os.path.join(work, "system", "fvSchemes"), "w") as f:
        f.write(fv_schemes(grad))
    for func, logname in (("writeCellCentres", "log.writeCellCentres"),
                          ("grad(C)", "log.gradC")):
        ok, _, text = run(["postProcess", "-time", "0", "-func", func], work, logname, np=np)
        if not ok:
            raise RuntimeError("postProcess -func %s failed: %s" % (func, pb.first_error(text)))
    errors = []
    times = glob.glob(os.path.join(work, "processor*", "0")) or [os.path.join(work, "0")]
    identity = (1, 0, 0, 0, 1, 0, 0, 0, 1)
    for t in times:
        centres = field_values(os.path.join(t, "C"))
        grads = field_values(os.path.join(t, "grad(C)"))
        for c, g in zip(centres, grads):
            if study.interior(c):
                errors.append(math.sqrt(sum((a - b)**2 for a, b in zip(g, identity))))
    shutil.rmtree(work, ignore_errors=True)
    errors.sort()
    return {"mean": sum(errors)/len(errors), "p99": errors[int(0.99*(len(errors) - 1))]}


def redo(args, name):
    return "all" in args.redo or name in args.redo


def build_mesh(args, study, m, res):
    """Mesh m (unless measured already), check it, store what it is. The
    solutions of a mesh made again are dropped: they were of the old one."""
    case = os.path.join(args.work, study.name, m["name"])
    record = res["meshes"].get(m["name"])
    if record and record.get("ok") and os.path.isdir(case) and not redo(args, m["name"]):
        return case
    for key in [k for k in res["solutions"] if k.split("/", 1)[0] == m["name"]]:
        del res["solutions"][key]
    pb.log("Meshing %s %s (%s)" % (study.name, m["name"], m["family"]))
    builder = build_snappy if m["builder"] == "snappy" else build_pmsh
    ok, wall, text = builder(study, m, case, args.np)
    record = dict((k, v) for k, v in m.items() if k != "regions")
    record.update({"ok": ok, "meshTime": wall, "pmshFoam": pb.command_output(
        ["git", "-C", ROOT, "rev-parse", "--short", "HEAD"])})
    if not ok:
        record["error"] = pb.first_error(text)
        pb.log("    failed: %s" % record["error"])
        res["meshes"][m["name"]] = record
        return None
    record.update(pb.check_mesh(case, args.np))
    record.update(study.surface_fidelity(case))
    if m["builder"] == "snappy" and m["entries"].get("nLayers"):
        record["layers"] = snappy_layer_coverage(case, SNAPPY_WALLS[study.name])
    if m["builder"] == "pmsh" and m.get("layers"):
        record["pmshLayers"] = pmsh_layer_coverage(case, SNAPPY_WALLS[study.name])
    res["meshes"][m["name"]] = record
    pb.log("    %d cells in %.1f s, checkMesh %s, max non-orth %.1f" % (
        record.get("cells", 0), wall, "OK" if record["meshOK"] else "FAILED",
        record.get("maxNonOrtho", float("nan"))))
    if args.gradients:
        record["gradientError"] = {}
        for grad in ("Gauss linear", "leastSquares"):
            record["gradientError"][grad] = gradient_error(study, case, args.np, grad)
        pb.log("    |grad C - I| Gauss %.3f, leastSquares %.3f" % (
            record["gradientError"]["Gauss linear"]["mean"],
            record["gradientError"]["leastSquares"]["mean"]))
    return case


# ---------------------------------------------------------------------------
# Solutions
# ---------------------------------------------------------------------------

def solver_case(mesh_case, dest, schemes_text, functions):
    """A copy of a meshed case (processor meshes and fields) with its own
    fvSchemes and the study's function objects"""
    shutil.rmtree(dest, ignore_errors=True)
    os.makedirs(dest)
    for d in ("0", "system"):
        shutil.copytree(os.path.join(mesh_case, d), os.path.join(dest, d))
    shutil.copytree(os.path.join(mesh_case, "constant"), os.path.join(dest, "constant"),
                    ignore=shutil.ignore_patterns("geometry"))
    for d in glob.glob(os.path.join(mesh_case, "processor*")):
        for sub in ("constant", "0"):
            shutil.copytree(os.path.join(d, sub), os.path.join(dest, os.path.basename(d), sub))
    with open(os.path.join(dest, "system", "fvSchemes"), "w") as f:
        f.write(schemes_text)
    if functions:
        control = os.path.join(dest, "system", "controlDict")
        with open(control) as f:
            text = f.read()
        text = re.sub(r"^functions\s*\n\{", "functions\n{" + functions, text, count=1,
                      flags=re.M)
        with open(control, "w") as f:
            f.write(text)


def last_row(path):
    rows = []
    with open(path) as f:
        for line in f:
            if not line.startswith("#") and line.strip():
                rows.append(line)
    return rows[-1] if rows else None


def error_of(study, value):
    return value/study.reference - 1.0


def solve(args, study, res, mesh_name, mesh_case, schemes_name, schemes_text):
    key = "%s/%s" % (mesh_name, schemes_name)
    if key in res["solutions"] and res["solutions"][key].get("ok") \
            and not redo(args, key) and not redo(args, mesh_name):
        return res["solutions"][key]
    case = os.path.join(args.work, study.name, "%s-%s" % (mesh_name, schemes_name))
    solver_case(mesh_case, case, schemes_text, study.functions)
    ok, wall, text = run(["simpleFoam"], case, "log.simpleFoam", np=args.np)
    record = {"mesh": mesh_name, "schemes": schemes_name, "ok": ok, "solveTime": wall}
    if ok:
        try:
            iterations, answer = study.answer(case)
        except (OSError, AttributeError, IndexError, ValueError) as e:
            ok = False
            record["ok"] = False
            record["error"] = "no answer (%s): %s" % (e, pb.first_error(text))
        else:
            record.update(answer)
            value = answer[study.quantity]
            record.update({"iterations": iterations,
                           "settled": study.settled_text in text,
                           # a diverged run may still stop "settled" on NaN/huge values
                           "diverged": not (abs(value) < 1e3)})
            pb.log("    %-6s %-18s %-30s %s %.4f (%+.1f %%)%s, %d iterations%s" % (
                study.name, mesh_name, schemes_name, study.quantity, value,
                100*error_of(study, value),
                "".join(", %s %.4f" % (k, v) for k, v in answer.items()
                        if k != study.quantity and v is not None),
                iterations, " (diverged)" if record["diverged"] else
                "" if record["settled"] else " (not settled)"))
    else:
        record["error"] = pb.first_error(text)
        pb.log("    %s %s: simpleFoam failed: %s" % (mesh_name, schemes_name, record["error"]))
    res["solutions"][key] = record
    if not args.keep:
        for d in glob.glob(os.path.join(case, "processor*")):
            shutil.rmtree(os.path.join(d, "constant"), ignore_errors=True)
    return record


def reevaluate_forces(args, study, res, mesh_name, solved_with, evaluate_with):
    """The forces of the solution of one scheme set, evaluated with the
    other's gradient (the viscous force is -nu dev(twoSymm(grad U)) at the
    wall, so the gradient scheme is in the force's evaluation as well)"""
    key = "%s/%s-evaluatedWith-%s" % (mesh_name, solved_with, evaluate_with)
    if key in res["solutions"] and res["solutions"][key].get("ok"):
        return
    source = os.path.join(args.work, study.name, "%s-%s" % (mesh_name, solved_with))
    if not os.path.isdir(os.path.join(source, "processor0", "constant")):
        # its mesh was removed after solving: solve again, keeping it
        keep, args.keep = args.keep, True
        args.redo.add("%s/%s" % (mesh_name, solved_with))
        solve(args, study, res, mesh_name, os.path.join(args.work, study.name, mesh_name),
              solved_with, SCHEMES[solved_with][1])
        args.keep = keep
    case = source + "-reevaluated"
    shutil.rmtree(case, ignore_errors=True)
    shutil.copytree(source, case)
    with open(os.path.join(case, "system", "fvSchemes"), "w") as f:
        f.write(SCHEMES[evaluate_with][1])
    shutil.rmtree(os.path.join(case, "postProcessing"), ignore_errors=True)
    control = os.path.join(case, "system", "controlDict")
    with open(control) as f:
        text = f.read()
    # Only the two force function objects
    text = text[:text.index("functions")] + "functions\n{" + FORCES_FUNCTION + """
    forceCoeffs
    {
        type forceCoeffs; libs ("libforces.so"); patches (ball); rho rhoInf; rhoInf 1;
        CofR (0 0 0); dragDir (1 0 0); liftDir (0 0 1); pitchAxis (0 1 0);
        magUInf 1; lRef 1; Aref 0.785398163;
    }
}
"""
    with open(control, "w") as f:
        f.write(text)
    ok, _, text = run(["simpleFoam", "-postProcess", "-latestTime"], case, "log.postProcess",
                      np=args.np)
    record = {"mesh": mesh_name, "schemes": "%s, forces evaluated with %s" % (
        solved_with, evaluate_with), "ok": ok}
    if ok:
        _, answer = study.answer(case)
        record.update(answer)
        pb.log("    %s solved with %s, forces with %s gradients: Cd %.4f (pressure %.4f,"
               " viscous %.4f)" % (mesh_name, solved_with, evaluate_with, answer["Cd"],
                                   answer["CdPressure"], answer["CdViscous"]))
    res["solutions"][key] = record
    shutil.rmtree(case, ignore_errors=True)


# ---------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------

def fmt(v, digits=3):
    return pb.fmt(v, digits)


def pct(study, value):
    return "%+.1f %%" % (100*error_of(study, value)) if value is not None else "-"


FAMILY_ORDER = ["pmshFoam netgen", "pmshFoam hxt", "pmshFoam netgen, 3 layers",
                "pmshFoam hxt, 3 layers", "pmshFoam netgen, 12 layers",
                "pmshFoam hxt, 12 layers", "pmshFoam netgen, 5 layers",
                "polyDualMesh of pmshFoam netgen", "snappyHexMesh", "snappyHexMesh, 5 layers"]
# One colour a family in every panel, whichever families a panel has
FAMILY_COLOURS = dict(zip(FAMILY_ORDER, ["C%d" % i for i in range(len(FAMILY_ORDER))]))


def diverged(study, s):
    """Marked so by the solver's run, or settled on a value no flow has
    (hxt-0.71 with limited convection ends at Cd = -5.7; the worst real
    answer is the pipe's +65 %)"""
    return bool(s.get("diverged")) or abs(error_of(study, s[study.quantity])) > 1.0


def family_rows(study, res, family, schemes):
    rows = []
    for name, m in res["meshes"].items():
        if m.get("family") != family or not m.get("ok"):
            continue
        s = res["solutions"].get("%s/%s" % (name, schemes))
        # A run that never settled is not an answer to plot (the tables
        # show it, marked)
        if s and s.get("ok") and not diverged(study, s) and s.get("settled"):
            rows.append((m.get("cells"), s[study.quantity], name))
    return sorted(rows)


def make_plots(results, out):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        pb.log("No matplotlib: no plots")
        return
    labels = {"sphere": ("Cd of the sphere, Re = 100", "reference 1.087 (Johnson & Patel)"),
              "pipe": ("pressure drop x = %d..%d / Hagen-Poiseuille's" % PIPE_PLANES,
                       "Hagen-Poiseuille")}
    fig, axes = plt.subplots(len(STUDIES), len(SCHEMES), figsize=(15, 9), sharey="row")
    for row, study in enumerate(STUDIES):
        res = results[study.name]
        scale = 1.0 if study.name == "sphere" else 1.0/study.reference
        reference = study.reference*scale
        shown = []
        for ax, (schemes, (title, _)) in zip(axes[row], SCHEMES.items()):
            if schemes not in study.scheme_sets:
                ax.axis("off")      # not solved with these schemes
                continue
            shown.append(ax)
            ax.axhspan(reference*0.985, reference*1.015, color="0.9", label="reference ±1.5 %")
            ax.axhline(reference, color="k", lw=1, label=labels[study.name][1])
            for family in FAMILY_ORDER:
                rows = family_rows(study, res, family, schemes)
                if rows:
                    ax.plot([r[0] for r in rows], [r[1]*scale for r in rows], "o-",
                            color=FAMILY_COLOURS[family], label=family)
            ax.set_xscale("log")
            ax.set_xlabel("cells")
            ax.set_title("%s: %s" % (study.name, title), fontsize=8)
            ax.grid(True, which="both", alpha=0.3)
        axes[row][0].set_ylabel(labels[study.name][0])
        shown[-1].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drag-study-cd.png"), dpi=100)
    plt.close(fig)

    fig, axes = plt.subplots(1, len(STUDIES), figsize=(12, 4.5), sharey=True)
    for ax, study in zip(axes, STUDIES):
        meshes_ = results[study.name]["meshes"]
        for family in FAMILY_ORDER:
            for grad, style in (("Gauss linear", "o-"), ("leastSquares", "s--")):
                rows = sorted((m["cells"], m["gradientError"][grad]["mean"])
                              for m in meshes_.values()
                              if m.get("family") == family and m.get("ok")
                              and "gradientError" in m)
                if rows:
                    ax.plot([r[0] for r in rows], [max(r[1], 1e-6) for r in rows], style,
                            color=FAMILY_COLOURS[family], label="%s, %s" % (family, grad))
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("cells")
        ax.set_title("%s: gradient of a linear field, error of the scheme" % study.name,
                     fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("mean |grad(C) - I| (cells away from the boundary)")
    axes[-1].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "drag-study-gradient.png"), dpi=100)
    plt.close(fig)


def answer_cells(study, s):
    if not s or not s.get("ok"):
        return [(s or {}).get("error", "-")[:40], "", ""]
    value = s[study.quantity]
    if diverged(study, s):
        return ["diverged (%s)" % fmt(value, 3), "", ""]
    extra = ("p %s, v %s" % (fmt(s.get("CdPressure")), fmt(s.get("CdViscous")))
             if study.name == "sphere" else
             "wall shear %s (%+.1f %%)" % (fmt(s.get("wallShear"), 4),
                                          100*(s["wallShear"]/(8*PIPE_NU) - 1))
             if s.get("wallShear") else "")
    return [fmt(value, 4) + ("" if s.get("settled") else " (not settled)"),
            pct(study, value), extra]


def study_report(study, res):
    lines = ["## %s: %s against cells, per mesh type and scheme set" % (
        study.name, study.quantity), ""]
    header = ["mesh", "family", "cells", "max non-orth", "|grad C - I| Gauss / LS"]
    for schemes in study.scheme_sets:
        header += [schemes, "error", ""]
    rows = []
    for family in FAMILY_ORDER + ["isolation"]:
        for name, m in sorted(res["meshes"].items(), key=lambda kv: kv[1].get("cells") or 0):
            if m.get("family") != family:
                continue
            if not m.get("ok"):
                rows.append([name, family, "failed: %s" % m.get("error", "?")]
                            + [""]*(len(header) - 3))
                continue
            ge = m.get("gradientError", {})
            row = [name, family, "%d" % m["cells"] if m.get("cells") is not None else "-", fmt(m.get("maxNonOrtho"), 1),
                   "%s / %s" % (fmt(ge.get("Gauss linear", {}).get("mean"), 3),
                                fmt(ge.get("leastSquares", {}).get("mean"), 3))]
            for schemes in study.scheme_sets:
                row += answer_cells(study, res["solutions"].get("%s/%s" % (name, schemes)))
            rows.append(row)
    lines += [pb.md_table(header, rows), ""]

    variants = [(n, SCHEME_VARIANTS[n][0]) for n in SCHEME_VARIANTS]
    found = [(n, t) for n, t in list((n, SCHEMES[n][0]) for n in SCHEMES) + variants
             if "%s/%s" % (study.reference_mesh, n) in res["solutions"]]
    if len(found) > len(study.scheme_sets):
        lines += ["### One change at a time, on %s" % study.reference_mesh, ""]
        rows = []
        for name, title in found:
            s = res["solutions"]["%s/%s" % (study.reference_mesh, name)]
            rows.append([name, title] + answer_cells(study, s) + [str(s.get("iterations", ""))])
        for key, s in res["solutions"].items():
            if "evaluatedWith" in key and s.get("ok"):
                rows.append([key.split("/", 1)[1], s["schemes"]] + answer_cells(study, s)
                            + ["-"])
        lines += [pb.md_table(["schemes", "what", study.quantity, "error", "", "iterations"],
                              rows), ""]

    lines += ["### The %s meshes" % study.name, ""]
    rows = []
    exact_volume = DOMAIN_VOLUME if study.name == "sphere" else math.pi/4*20
    for name, m in sorted(res["meshes"].items()):
        if not m.get("ok"):
            continue
        shapes = ", ".join("%s %d" % (k, m[k]) for k in ("tetrahedra", "prisms", "hexahedra",
                                                        "polyhedra") if m.get(k))
        # snappyHexMesh's report; a pmshFoam mesh's "layers" is its entries
        layers = m.get("layers") if isinstance(m.get("layers"), dict) else None
        own = m.get("pmshLayers")
        rows.append([name, "%d" % m["cells"] if m.get("cells") is not None else "-", shapes, fmt(m.get("meshTime"), 1),
                     "OK" if m.get("meshOK") else "FAILED", fmt(m.get("maxSkewness"), 2),
                     "%+.4f %%" % (100*(m["volume"]/exact_volume - 1)) if m.get("volume") else "-",
                     "%+.3f %%" % (100*m["ballAreaError"]) if "ballAreaError" in m else "-",
                     ("%.2f layers, %.0f %% of the thickness" % (layers["meanLayers"],
                                                                layers["thicknessPercent"]))
                     if layers else
                     ("%d layers on %.1f %% of the faces, %.3g thick" % (
                         own["layers"], 100*own["coverage"], own["thickness"][1]))
                     if own else "-"])
    lines += [pb.md_table(["mesh", "cells", "shapes", "mesh time [s]", "checkMesh",
                           "max skewness", "volume vs exact", "ball area vs pi",
                           "layers"], rows), ""]
    return lines


def write_report(results, out):
    lines = ["# Drag and pressure drop on every kind of mesh",
             "",
             "Made by `bench/run --drag` (bench/dragStudy.py); raw results in"
             " [drag-study.json](drag-study.json). Steady laminar flows solved by"
             " simpleFoam on %d ranks with each tutorial's fvSolution and controlDict,"
             " every run stopped by the tutorial's convergence condition:" % results.get("np", 2),
             "",
             "- **sphere** (tutorials/sphereDrag): Re = 100, D = 1 in a 20 x 10 x 10 box with"
             " symmetry sides; Cd against 1.087 (Johnson & Patel 1999);",
             "- **pipe** (tutorials/pipe): Re = 100, D = 1, %g D long, uniform inflow;"
             " the pressure drop between x = %d and %d against Hagen-Poiseuille's"
             " 32 nu U L / D^2 = %.2f." % ((PIPE_LENGTH,) + PIPE_PLANES + (PIPE_REFERENCE_DP,)),
             ""]
    lines += results.get("findings", [])
    lines += ["", "![Cd and pressure drop against cells](drag-study-cd.png)", "",
              "![Gradient error on a linear field](drag-study-gradient.png)", ""]
    for study in STUDIES:
        lines += study_report(study, results[study.name])
    lines += ["Machine: %s" % results.get("machine", "?"), ""]
    path = os.path.join(out, "drag-study.md")
    with open(path, "w") as f:
        f.write("\n".join(lines))
    pb.log("Written: %s" % path)


# ---------------------------------------------------------------------------

def save_json(data, path):
    with open(path, "w") as f:
        json.dump(data, f, indent=1, sort_keys=True)


def load_json(path):
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return json.load(f)


def machine_text():
    return "%s, %d cores; OpenFOAM %s; pmshFoam %s" % (
        pb.line_value("/proc/cpuinfo", "model name").split(":", 1)[-1].strip(),
        os.cpu_count(), pb.dpkg_version("openfoam"),
        pb.command_output(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"]))


def save(results, out):
    save_json(results, os.path.join(out, "drag-study.json"))


def load(path):
    results = load_json(path)
    if "meshes" in results:         # the first layout: the sphere's only
        results["sphere"] = {"meshes": results.pop("meshes"),
                             "solutions": results.pop("solutions")}
    for study in STUDIES:
        results.setdefault(study.name, {"meshes": {}, "solutions": {}})
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--drag", action="store_true", help="(the mode bench/run passes)")
    parser.add_argument("--work", default=os.path.join(os.environ.get("TMPDIR", "/tmp"),
                                                       "pmshFoam-drag"))
    parser.add_argument("--out", default=os.path.join(BENCH_DIR, "results"))
    parser.add_argument("--np", type=int, default=2)
    parser.add_argument("--studies", default="sphere,pipe")
    parser.add_argument("--only", default="",
                        help="comma-separated mesh names (default: all)")
    parser.add_argument("--schemes", default="",
                        help="comma-separated scheme sets (default: all)")
    parser.add_argument("--redo", default="", help="comma-separated mesh or solution names"
                        " (mesh/schemes) to measure again, or 'all'")
    parser.add_argument("--shipped", action="store_true",
                        help="only the mesher matrix (both meshers at four sizes, with and"
                        " without the tutorial's layers, and the finest), each solved with"
                        " its tutorial's own schemes")
    parser.add_argument("--keep", action="store_true", help="keep the solved cases' meshes")
    parser.add_argument("--rewrite", action="store_true", help="only rewrite the report")
    parser.add_argument("--no-build", action="store_true")
    parser.add_argument("--pmshFoam", default=None)
    args = parser.parse_args()
    args.redo = set(filter(None, args.redo.split(",")))
    args.gradients = True           # every mesh's gradient error (timeToAnswer.py: none)
    os.makedirs(args.work, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)

    results = load(os.path.join(args.out, "drag-study.json"))
    results["np"] = args.np
    results["machine"] = machine_text()

    if not args.rewrite:
        only = set(filter(None, args.only.split(",")))
        schemes = set(filter(None, args.schemes.split(","))) or set(SCHEMES)
        for study in STUDIES:
            if study.name not in args.studies.split(","):
                continue
            res = results[study.name]
            os.makedirs(os.path.join(args.work, study.name), exist_ok=True)
            for m in (study.mesher_matrix() if args.shipped else study.meshes()):
                if only and m["name"] not in only:
                    continue
                case = build_mesh(args, study, m, res)
                save(results, args.out)
                if not case:
                    continue
                for name in study.scheme_sets:
                    if name in schemes and (name == study.shipped or not args.shipped):
                        solve(args, study, res, m["name"], case, name, SCHEMES[name][1])
                        save(results, args.out)
                if m["name"] == study.reference_mesh and not args.shipped:
                    for name in study.variants:
                        text = (SCHEME_VARIANTS.get(name) or SCHEMES[name])[1]
                        solve(args, study, res, m["name"], case, name, text)
                        save(results, args.out)
                    if study.name == "sphere":
                        reevaluate_forces(args, study, res, m["name"], "gauss", "leastSquares")
                        reevaluate_forces(args, study, res, m["name"], "leastSquares", "gauss")
                        save(results, args.out)
    make_plots(results, args.out)
    write_report(results, args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
