#!/usr/bin/env python3
"""How well OpenFOAM's leastSquares gradient is posed in each cell of a mesh.

OpenFOAM's leastSquares gradient (leastSquaresVectors) solves, in each
cell, the 3x3 system M = sum over the cell's faces of d d^T / |d|^2, where d
joins the cell centre to the neighbour's centre (internal faces) or to the
face centre (boundary faces). Where the directions d nearly lie in a plane,
M is nearly singular and the gradient normal to that plane amplifies any
noise in the field by M's condition number (largest over smallest
eigenvalue). A tetrahedron has only four such directions, so a tet of fair
shape can still have a badly posed gradient if its neighbours sit oddly;
checkMesh measures nothing of the kind (its cell determinant counts
internal faces only, by their areas).

Why it matters (bench/results/drag-study.md, "The finest layered hxt mesh"):
simpleFoam with the tutorials' schemes blew up locally on sphereDrag's
918k-cell layered hxt mesh at the cell with the second-worst condition
(40.9; the mesh's median is 2), and the same mesh converged once its
cells above 24 were mended.

Usage:
    bench/leastSquaresCondition.py CASE [--worst N] [--json FILE]

CASE holds a single mesh (serial, or reconstructed with reconstructParMesh)
in constant/polyMesh, ascii or binary; processor patches are not handled.
Cell centres are computed as OpenFOAM computes them (pyramids on the faces
about an estimated centre). Pure Python: about 30 s a million cells.
"""

import argparse
import json
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                "tools"))
from foamCase import PolyMeshFiles  # noqa: E402


def face_centres_and_areas(points, faces):
    """OpenFOAM's face centres and area vectors (primitiveMeshFaceCentresAndAreas):
    triangles about the mean of the face's points, weighted by area"""
    centres, areas = [], []
    for f in faces:
        pts = [points[i] for i in f]
        n = len(pts)
        if n == 3:
            a, b, c = pts
            u = (b[0]-a[0], b[1]-a[1], b[2]-a[2])
            v = (c[0]-a[0], c[1]-a[1], c[2]-a[2])
            centres.append(((a[0]+b[0]+c[0])/3, (a[1]+b[1]+c[1])/3, (a[2]+b[2]+c[2])/3))
            areas.append((0.5*(u[1]*v[2]-u[2]*v[1]), 0.5*(u[2]*v[0]-u[0]*v[2]),
                          0.5*(u[0]*v[1]-u[1]*v[0])))
            continue
        m = tuple(sum(p[k] for p in pts)/n for k in range(3))
        s_area = [0.0, 0.0, 0.0]
        s_ctr = [0.0, 0.0, 0.0]
        total = 0.0
        for i in range(n):
            a, b = pts[i], pts[(i + 1) % n]
            u = (a[0]-m[0], a[1]-m[1], a[2]-m[2])
            v = (b[0]-m[0], b[1]-m[1], b[2]-m[2])
            cr = (u[1]*v[2]-u[2]*v[1], u[2]*v[0]-u[0]*v[2], u[0]*v[1]-u[1]*v[0])
            mag = math.sqrt(cr[0]**2 + cr[1]**2 + cr[2]**2)
            for k in range(3):
                s_area[k] += 0.5*cr[k]
                s_ctr[k] += mag*(a[k] + b[k] + m[k])/3
            total += mag
        centres.append(tuple(c/total for c in s_ctr))
        areas.append(tuple(s_area))
    return centres, areas


def cell_centres(n_cells, owner, neighbour, fc, sf):
    """OpenFOAM's cell centres (primitiveMeshCellCentresAndVols): pyramids
    from an estimated centre (the mean of the face centres) to each face"""
    est = [[0.0, 0.0, 0.0] for _ in range(n_cells)]
    count = [0]*n_cells
    for f, o in enumerate(owner):
        c = fc[f]
        e = est[o]
        e[0] += c[0]; e[1] += c[1]; e[2] += c[2]
        count[o] += 1
    for f, n in enumerate(neighbour):
        c = fc[f]
        e = est[n]
        e[0] += c[0]; e[1] += c[1]; e[2] += c[2]
        count[n] += 1
    for c in range(n_cells):
        est[c] = [x/count[c] for x in est[c]]
    ctr = [[0.0, 0.0, 0.0] for _ in range(n_cells)]
    vol = [0.0]*n_cells

    def add(cell, f, sign):
        e = est[cell]
        c, s = fc[f], sf[f]
        pyr = sign*(s[0]*(c[0]-e[0]) + s[1]*(c[1]-e[1]) + s[2]*(c[2]-e[2]))
        for k in range(3):
            ctr[cell][k] += pyr*(0.75*c[k] + 0.25*e[k])
        vol[cell] += pyr

    for f, o in enumerate(owner):
        add(o, f, 1.0)
    for f, n in enumerate(neighbour):
        add(n, f, -1.0)
    return [tuple(x/vol[c] for x in ctr[c]) if abs(vol[c]) > 1e-300 else tuple(est[c])
            for c in range(n_cells)]


def condition(m):
    """Largest over smallest eigenvalue of the symmetric 3x3 matrix
    m = (xx, yy, zz, xy, xz, yz) (closed form, trigonometric)"""
    a, b, c, d, e, f = m
    q = (a + b + c)/3
    p1 = d*d + e*e + f*f
    p = math.sqrt(((a-q)**2 + (b-q)**2 + (c-q)**2 + 2*p1)/6)
    if p < 1e-14*max(q, 1e-300):
        return 1.0
    B = ((a-q)/p, d/p, e/p, d/p, (b-q)/p, f/p, e/p, f/p, (c-q)/p)
    r = (B[0]*(B[4]*B[8]-B[5]*B[7]) - B[1]*(B[3]*B[8]-B[5]*B[6])
         + B[2]*(B[3]*B[7]-B[4]*B[6]))/2
    phi = math.acos(max(-1.0, min(1.0, r)))/3
    largest = q + 2*p*math.cos(phi)
    smallest = q + 2*p*math.cos(phi + 2*math.pi/3)
    return largest/smallest if smallest > 0 else math.inf


def conditions(mesh_dir):
    """(condition of each cell, cell centres)"""
    mesh = PolyMeshFiles(mesh_dir)
    points = mesh.points()
    faces = mesh.faces()
    owner = mesh.labels("owner")
    neighbour = mesh.labels("neighbour")
    n_cells = max(max(owner), max(neighbour) if neighbour else -1) + 1
    fc, sf = face_centres_and_areas(points, faces)
    cc = cell_centres(n_cells, owner, neighbour, fc, sf)
    dd = [[0.0]*6 for _ in range(n_cells)]

    def add(cell, d):
        w = 1.0/(d[0]*d[0] + d[1]*d[1] + d[2]*d[2])
        m = dd[cell]
        m[0] += w*d[0]*d[0]; m[1] += w*d[1]*d[1]; m[2] += w*d[2]*d[2]
        m[3] += w*d[0]*d[1]; m[4] += w*d[0]*d[2]; m[5] += w*d[1]*d[2]

    for f, n in enumerate(neighbour):
        o = owner[f]
        d = (cc[n][0]-cc[o][0], cc[n][1]-cc[o][1], cc[n][2]-cc[o][2])
        add(o, d)
        add(n, d)
    for f in range(len(neighbour), len(owner)):
        o = owner[f]
        add(o, (fc[f][0]-cc[o][0], fc[f][1]-cc[o][1], fc[f][2]-cc[o][2]))
    return [condition(m) for m in dd], cc


def summary(cond, centres, worst=10):
    ordered = sorted(cond)
    n = len(ordered)
    top = sorted(range(n), key=lambda c: -cond[c])[:worst]
    return {
        "cells": n,
        "median": ordered[n//2],
        "p99": ordered[int(0.99*n)],
        "p999": ordered[int(0.999*n)],
        "max": ordered[-1],
        "above20": sum(1 for x in cond if x > 20),
        "above30": sum(1 for x in cond if x > 30),
        "worst": [{"cell": c, "condition": cond[c], "centre": list(centres[c])} for c in top],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("case")
    parser.add_argument("--worst", type=int, default=10, help="cells to list (default 10)")
    parser.add_argument("--json", help="write the summary there too")
    args = parser.parse_args()
    mesh_dir = os.path.join(args.case, "constant", "polyMesh")
    if not os.path.isfile(os.path.join(mesh_dir, "owner")):
        sys.exit("leastSquaresCondition: no mesh in %s (reconstructParMesh -constant first "
                 "for a decomposed case)" % mesh_dir)
    cond, centres = conditions(mesh_dir)
    s = summary(cond, centres, args.worst)
    print("cells %d: leastSquares condition median %.2f, p99 %.2f, p99.9 %.2f, max %.1f; "
          "above 20: %d, above 30: %d" % (s["cells"], s["median"], s["p99"], s["p999"],
                                          s["max"], s["above20"], s["above30"]))
    for w in s["worst"]:
        c = w["centre"]
        print("  %8.1f  cell %d at (%.4g %.4g %.4g)" % (w["condition"], w["cell"], *c))
    if args.json:
        with open(args.json, "w") as f:
            json.dump(s, f, indent=1)


if __name__ == "__main__":
    main()
