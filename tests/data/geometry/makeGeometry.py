#!/usr/bin/env python3
"""Generate the STL test inputs of pmshFoam's geometry tests (run once;
the outputs are committed). Broken variants are made by the tests
themselves, in a temporary directory.

  sphere.stl        icosphere (3 subdivisions, 1280 triangles), radius 1,
                    outward, ascii, one solid "sphere"
  sphereBinary.stl  the same triangles, binary
  box.stl           box [0,2]x[0,1]x[0,1], faces split 2x2, ascii, two
                    solids: "inlet" (x = 0) and "walls" (the rest)
  sphereInBox.stl   external flow: box [-5,5]^3 (solids inlet x = -5,
                    outlet x = 5, sides) around a sphere of radius 0.5
                    (icosphere, 3 subdivisions, solid "body") whose
                    triangles point into it, out of the fluid
  cylinderInBox.stl the same box around a CAD-like body: a cylinder of
                    radius 0.5 and length 2 along x, tessellated as CAD
                    exporters do (sides as long strips, caps as fans of
                    thin triangles), 90 degree edges, inner orientation
  needleInBox.stl   the same box around a needle: a capsule of radius 0.03
                    and length 1.06 along x (16 segments round), thinner
                    than the coarse cells, so that projection folds the
                    refined surface onto itself unless repaired
  roomWithDesk.stl  touching shells: a room [0,4]x[0,3]x[0,2.5] (solid
                    "room") holding a desk whose four legs (solid
                    "deskLegs", four closed boxes) stand on the floor and
                    touch the desk top (solid "deskTop") from below:
                    coplanar faces without shared vertices
  twoCubesSharingAFace.stl  two unit cubes, solids "left" and "right",
                    sharing the face x = 1 (the same two triangles in both)
  twoBlocksWithASlot.stl  two unit cubes, solids "blockA" and "blockB",
                    outward, 0.06 apart along x: a slot of the fluid for
                    gap sizing, with a domain box round them

Coordinates are float32 values (written exactly in ascii), so the ascii and
binary spheres hold bit-identical points."""

import math
import struct


def f32(x):
    return struct.unpack('<f', struct.pack('<f', x))[0]


def icosphere(levels):
    t = (1 + math.sqrt(5)) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0),
         (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
         (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
         (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
         (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]

    def unit(p):
        r = math.sqrt(sum(c * c for c in p))
        return tuple(c / r for c in p)

    v = [unit(p) for p in v]
    for _ in range(levels):
        mid = {}

        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                mid[key] = len(v)
                v.append(unit(tuple((v[a][k] + v[b][k]) / 2 for k in range(3))))
            return mid[key]

        nf = []
        for a, b, c in f:
            ab, bc, ca = m(a, b), m(b, c), m(c, a)
            nf += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = nf
    v = [tuple(f32(c) for c in p) for p in v]
    return v, f


def volume(v, f):
    s = 0
    for a, b, c in f:
        pa, pb, pc = v[a], v[b], v[c]
        s += (pa[0] * (pb[1] * pc[2] - pb[2] * pc[1])
              - pa[1] * (pb[0] * pc[2] - pb[2] * pc[0])
              + pa[2] * (pb[0] * pc[1] - pb[1] * pc[0]))
    return s / 6


def normal(pa, pb, pc):
    u = [pb[k] - pa[k] for k in range(3)]
    w = [pc[k] - pa[k] for k in range(3)]
    n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
    r = math.sqrt(sum(c * c for c in n))
    return tuple(c / r for c in n)


def write_ascii(name, solids):
    """solids: list of (solid name, points, triangles)"""
    with open(name, 'w') as out:
        for sname, v, f in solids:
            out.write('solid %s\n' % sname)
            for a, b, c in f:
                n = normal(v[a], v[b], v[c])
                out.write('  facet normal %r %r %r\n    outer loop\n' % n)
                for p in (v[a], v[b], v[c]):
                    out.write('      vertex %r %r %r\n' % p)
                out.write('    endloop\n  endfacet\n')
            out.write('endsolid %s\n' % sname)


def write_binary(name, v, f):
    with open(name, 'wb') as out:
        out.write(b'pmshFoam test sphere (binary STL)'.ljust(80, b' '))
        out.write(struct.pack('<I', len(f)))
        for a, b, c in f:
            n = normal(v[a], v[b], v[c])
            out.write(struct.pack('<12fH', *n, *v[a], *v[b], *v[c], 0))


def box(nx, ny, nz, lx, ly, lz):
    """Faces of [0,lx]x[0,ly]x[0,lz] split n x n, outward, tagged by side."""
    pts = {}
    tris = []

    def pid(p):
        p = tuple(f32(c) for c in p)
        if p not in pts:
            pts[p] = len(pts)
        return pts[p]

    def quad_grid(origin, du, dv, nu, nv, tag):
        for i in range(nu):
            for j in range(nv):
                def P(a, b):
                    return tuple(origin[k] + du[k] * a / nu + dv[k] * b / nv for k in range(3))
                p00, p10, p11, p01 = P(i, j), P(i + 1, j), P(i + 1, j + 1), P(i, j + 1)
                tris.append((tag, (pid(p00), pid(p10), pid(p11))))
                tris.append((tag, (pid(p00), pid(p11), pid(p01))))

    # du x dv points outward on every face
    quad_grid((0, 0, 0), (0, 0, lz), (0, ly, 0), nz, ny, 'inlet')     # x = 0, normal -x
    quad_grid((lx, 0, 0), (0, ly, 0), (0, 0, lz), ny, nz, 'walls')    # x = lx, +x
    quad_grid((0, 0, 0), (lx, 0, 0), (0, 0, lz), nx, nz, 'walls')     # y = 0, -y
    quad_grid((0, ly, 0), (0, 0, lz), (lx, 0, 0), nz, nx, 'walls')    # y = ly, +y
    quad_grid((0, 0, 0), (0, ly, 0), (lx, 0, 0), ny, nx, 'walls')     # z = 0, -z
    quad_grid((0, 0, lz), (lx, 0, 0), (0, ly, 0), nx, ny, 'walls')    # z = lz, +z
    v = [None] * len(pts)
    for p, i in pts.items():
        v[i] = p
    return v, tris


def flipped(f):
    return [(a, c, b) for a, b, c in f]


def cad_cylinder(segments, radius, x0, x1):
    """A closed cylinder along x as CAD exporters tessellate it: each side
    strip one quad (two long thin triangles), each cap a fan from its first
    rim point (thin slivers), outward."""
    v = []
    for x in (x0, x1):
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append((f32(x), f32(radius * math.cos(a)), f32(radius * math.sin(a))))
    f = []
    for i in range(segments):
        j = (i + 1) % segments
        # outward: the rim runs counter-clockwise seen from +x
        f.append((i, segments + j, segments + i))
        f.append((i, j, segments + j))
    for i in range(1, segments - 1):
        f.append((0, i + 1, i))                                 # x0 cap, -x
        f.append((segments, segments + i, segments + i + 1))   # x1 cap, +x
    return v, f


def capsule(segments, radius, x0, x1):
    """A closed capsule along x (a cylinder with hemispherical ends, poles
    at its tips), outward."""
    half = segments // 2
    profile = []    # (x, r) from the x0 tip to the x1 tip
    for k in range(half + 1):
        a = math.pi / 2 * k / half
        profile.append((x0 - radius * math.cos(a), radius * math.sin(a)))
    for k in range(half + 1):
        a = math.pi / 2 * k / half
        profile.append((x1 + radius * math.sin(a), radius * math.cos(a)))
    v = [(profile[0][0], 0.0, 0.0)]
    rings = []
    for x, r in profile[1:-1]:
        rings.append(len(v))
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append((x, r * math.cos(a), r * math.sin(a)))
    v.append((profile[-1][0], 0.0, 0.0))
    v = [tuple(f32(c) for c in p) for p in v]
    last = len(v) - 1
    f = []
    for i in range(segments):
        j = (i + 1) % segments
        f.append((0, rings[0] + j, rings[0] + i))
        f.append((last, rings[-1] + i, rings[-1] + j))
    for r0, r1 in zip(rings[:-1], rings[1:]):
        for i in range(segments):
            j = (i + 1) % segments
            f.append((r0 + i, r0 + j, r1 + j))
            f.append((r0 + i, r1 + j, r1 + i))
    if volume(v, f) < 0:
        f = flipped(f)
    return v, f


def body_in_box(body_v, body_f, half):
    """Solids inlet (x = -half), outlet (x = half), sides of the box
    [-half, half]^3 and "body", the given closed outward surface flipped so
    that its normals point out of the fluid."""
    v, tagged = box(2, 2, 2, 2.0 * half, 2.0 * half, 2.0 * half)
    v = [tuple(f32(c - half) for c in p) for p in v]

    def side(t):
        xs = [v[i][0] for i in t]
        if all(x == -half for x in xs):
            return 'inlet'
        if all(x == half for x in xs):
            return 'outlet'
        return 'sides'

    offset = len(v)
    body = [tuple(i + offset for i in t) for t in flipped(body_f)]
    allv = v + list(body_v)
    boxf = [t for _, t in tagged]
    assert volume(allv, boxf + body) > 0
    return [(name, allv, [t for t in boxf if side(t) == name])
            for name in ('inlet', 'outlet', 'sides')] + [('body', allv, body)]


def closed_box(lo, hi):
    """The 12 outward triangles of the box [lo, hi], its own points."""
    v = [tuple(f32(hi[k] if (i >> k) & 1 else lo[k]) for k in range(3)) for i in range(8)]
    quads = [(0, 2, 6, 4), (1, 5, 7, 3), (0, 4, 5, 1), (2, 3, 7, 6), (0, 1, 3, 2), (4, 6, 7, 5)]
    f = []
    for a, b, c, d in quads:
        f += [(a, b, c), (a, c, d)]
    if volume(v, f) < 0:
        f = flipped(f)
    return v, f


def merged(parts):
    """One point list for several (points, triangles): (points, [triangles])."""
    v, out = [], []
    for pv, pf in parts:
        offset = len(v)
        v += pv
        out.append([tuple(i + offset for i in t) for t in pf])
    return v, out


def room_with_desk():
    room = closed_box((0, 0, 0), (4, 3, 2.5))
    top = closed_box((1, 1, 0.7), (3, 2, 0.75))
    legs = [closed_box((x, y, 0), (x + 0.05, y + 0.05, 0.7))
            for x in (1, 2.95) for y in (1, 1.95)]
    v, (room_f, top_f, *legs_f) = merged([room, top] + legs)
    # The desk is a body in the room: its normals point into it
    return [('room', v, room_f), ('deskTop', v, flipped(top_f)),
            ('deskLegs', v, flipped([t for f in legs_f for t in f]))]


def two_cubes_sharing_a_face():
    left = closed_box((0, 0, 0), (1, 1, 1))
    right = closed_box((1, 0, 0), (2, 1, 1))
    v, (lf, rf) = merged([left, right])
    # Merge the shared points as an STL reader does (exact coordinates)
    index = {}
    remap = [index.setdefault(p, len(index)) for p in v]
    points = [None] * len(index)
    for p, i in index.items():
        points[i] = p
    return [('left', points, [tuple(remap[i] for i in t) for t in lf]),
            ('right', points, [tuple(remap[i] for i in t) for t in rf])]


def two_blocks_with_a_slot(gap):
    a = closed_box((0, 0, 0), (1, 1, 1))
    b = closed_box((1 + gap, 0, 0), (2 + gap, 1, 1))
    v, (af, bf) = merged([a, b])
    return [('blockA', v, af), ('blockB', v, bf)]


def curved_wall(radius, thickness, angle, length, n_arc, n_length):
    """A closed slab bent into a cylindrical arc: outer radius `radius`,
    inner radius - thickness, `angle` radians around the z axis, z in
    [0, length]; n_arc x n_length quads on each curved face, outward.
    Netgen's STL mesher stops on it ("boundary mesh is overlapping") where
    the sag of its triangles, h^2/(8 radius), exceeds the thickness."""
    v = []
    index = {}

    def pid(side, i, j):
        key = (side, i, j)
        if key not in index:
            a = -angle / 2 + angle * i / n_arc
            r = radius if side == 0 else radius - thickness
            index[key] = len(v)
            v.append((f32(r * math.cos(a)), f32(r * math.sin(a)), f32(length * j / n_length)))
        return index[key]

    f = []

    def quad(a, b, c, d):       # counterclockwise seen from outside
        f.extend([(a, b, c), (a, c, d)])

    for i in range(n_arc):
        for j in range(n_length):
            quad(pid(0, i, j), pid(0, i + 1, j), pid(0, i + 1, j + 1), pid(0, i, j + 1))
            quad(pid(1, i, j), pid(1, i, j + 1), pid(1, i + 1, j + 1), pid(1, i + 1, j))
        quad(pid(1, i, 0), pid(1, i + 1, 0), pid(0, i + 1, 0), pid(0, i, 0))
        quad(pid(1, i, n_length), pid(0, i, n_length),
             pid(0, i + 1, n_length), pid(1, i + 1, n_length))
    for j in range(n_length):
        quad(pid(1, 0, j), pid(0, 0, j), pid(0, 0, j + 1), pid(1, 0, j + 1))
        quad(pid(1, n_arc, j), pid(1, n_arc, j + 1),
             pid(0, n_arc, j + 1), pid(0, n_arc, j))
    return v, f


if __name__ == '__main__':
    v, f = icosphere(3)
    assert volume(v, f) > 0
    write_ascii('sphere.stl', [('sphere', v, f)])
    write_binary('sphereBinary.stl', v, f)

    v, tagged = box(2, 2, 2, 2.0, 1.0, 1.0)
    assert volume(v, [t for _, t in tagged]) > 0
    write_ascii('box.stl', [
        ('inlet', v, [t for tag, t in tagged if tag == 'inlet']),
        ('walls', v, [t for tag, t in tagged if tag == 'walls']),
    ])

    v, f = icosphere(3)
    write_ascii('sphereInBox.stl', body_in_box([tuple(f32(0.5 * c) for c in p) for p in v], f, 5.0))

    v, f = cad_cylinder(48, 0.5, -1.0, 1.0)
    assert volume(v, f) > 0
    write_ascii('cylinderInBox.stl', body_in_box(v, f, 5.0))

    v, f = capsule(16, 0.03, -0.5, 0.5)
    write_ascii('needleInBox.stl', body_in_box(v, f, 5.0))

    write_ascii('roomWithDesk.stl', room_with_desk())
    write_ascii('twoCubesSharingAFace.stl', two_cubes_sharing_a_face())
    write_ascii('twoBlocksWithASlot.stl', two_blocks_with_a_slot(0.06))
