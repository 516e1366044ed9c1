/*---------------------------------------------------------------------------*\
  pmshFoam: the refined points that stay off the geometry (see
  foldRepair.H).
\*---------------------------------------------------------------------------*/

#include "foldRepair.H"
#include "faceLattice.H"
#include "triangleCrossings.H"
#include "pmshError.H"

#include <cmath>

namespace
{

using namespace pmsh;

//- Refined triangles of a lattice (points v0 < v1 < v2 at `pos`) that
//  turned against the coarse face (v0, v1, v2) or lie flat on it.
label countLatticeFolds(const std::vector<point3>& pos, int n)
{
    auto P = [&](int i, int j) -> const point3& { return pos[j*(n + 1) + i]; };
    const refinedTriangleFold folded(P(0, 0), P(n, 0), P(0, n), n);
    label nFolded = 0;
    forEachLatticeTriangle(n, [&](int i0, int j0, int i1, int j1, int i2, int j2)
    {
        if (folded(P(i0, j0), P(i1, j1), P(i2, j2)))
        {
            ++nFolded;
        }
    });
    return nFolded;
}


//- The lattices of faces, as one surface: their triangles in the order of
//  the faces, a point on the edge two faces share once (both compute its
//  bits alike, surfaceRefinement.H).
void appendLattice
(
    const std::vector<point3>& pos,
    int n,
    std::map<point3, label>& pointIndex,
    std::vector<point3>& points,
    std::vector<triVerts>& triangles
)
{
    std::vector<label> index(pos.size());
    for (std::size_t k = 0; k < pos.size(); ++k)
    {
        const auto inserted = pointIndex.emplace(pos[k], label(points.size()));
        if (inserted.second) points.push_back(pos[k]);
        index[k] = inserted.first->second;
    }
    auto P = [&](int i, int j) { return index[j*(n + 1) + i]; };
    forEachLatticeTriangle(n, [&](int i0, int j0, int i1, int j1, int i2, int j2)
    {
        triangles.push_back({P(i0, j0), P(i1, j1), P(i2, j2)});
    });
}


//- The three edges of the face with sorted points v.
std::array<foldRepair::edgeKey, 3> edgesOf(const triVerts& v)
{
    return {{{v[0], v[1]}, {v[1], v[2]}, {v[0], v[2]}}};
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * foldRepair  * * * * * * * * * * * * * * * //

pmsh::foldRepair::foldRepair
(
    const CoarseMesh& coarse,
    const boundaryEdgeSurfaces& edgeSurfaces,
    const Geometry* geometry,
    int levels,
    const std::vector<label>& cellPart
)
:
    coarse_(coarse),
    edgeSurfaces_(edgeSurfaces),
    geometry_(geometry),
    levels_(levels)
{
    for (const coarseBoundaryFace& b : coarse.boundary)
    {
        const faceKey f = sortedFace(b.v);
        boundarySurface_[f] = {b.surface, !sameOrientation(f, b.v)};
    }
    for (const coarseZoneFace& z : coarse.zoneFaces)
    {
        const faceKey f = sortedFace(z.v);
        boundarySurface_[f] = {z.surface, !sameOrientation(f, z.v)};
    }
    // Every face of every tet that holds a boundary edge: all ranks hold
    // the whole coarse mesh, so all see the same faces around an edge
    for (const tetVerts& t : coarse.tets)
    {
        for (int fi = 0; fi < 4; ++fi)
        {
            const faceKey f = sortedFace(tetFace(t, fi));
            for (const edgeKey& e : edgesOf(f))
            {
                label s1, s2;
                if (edgeSurfaces.find(e[0], e[1], s1, s2))
                {
                    facesAround_[e].push_back(f);
                }
            }
        }
    }
    for (auto& around : facesAround_)
    {
        std::vector<faceKey>& faces = around.second;
        std::sort(faces.begin(), faces.end());
        faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    }
    if (cellPart.empty())
    {
        return;
    }
    // The interface faces of each cell with a boundary face, from the
    // whole partition (every rank holds it, so every rank that decides on
    // an edge decides alike)
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    for (label c = 0; c < coarse.nCells(); ++c)
    {
        std::vector<faceKey> onSurface, interfaces;
        for (int fi = 0; fi < 4; ++fi)
        {
            const faceKey f = sortedFace(tetFace(coarse.tets[c], fi));
            const label nbr = neighbours[c][fi];
            if (surfaceOf(f) >= 0)
            {
                onSurface.push_back(f);
            }
            else if (!isBoundaryNeighbour(nbr) && cellPart[nbr] != cellPart[c])
            {
                interfaces.push_back(f);
            }
        }
        if (interfaces.empty()) continue;
        for (const faceKey& f : onSurface)
        {
            std::vector<faceKey>& beside = interfacesBeside_[f];
            beside.insert(beside.end(), interfaces.begin(), interfaces.end());
        }
    }
}


pmsh::label pmsh::foldRepair::surfaceOf(const faceKey& f) const
{
    const auto it = boundarySurface_.find(f);
    return it == boundarySurface_.end() ? -1 : it->second.first;
}


std::array<pmsh::triVerts, 2> pmsh::foldRepair::boundaryFacesOf(label p, label q) const
{
    std::array<triVerts, 2> faces{};
    int nFound = 0;
    const auto it = facesAround_.find(sortedEdge(p, q));
    if (it != facesAround_.end())
    {
        // Sorted, so the lower triple comes first (where zones meet, more
        // than two faces on the geometry share the edge: the first two)
        for (const faceKey& f : it->second)
        {
            if (nFound < 2 && surfaceOf(f) >= 0)
            {
                faces[nFound++] = f;
            }
        }
    }
    if (nFound != 2)
    {
        throw FatalError
        (
            msg() << "Coarse edge " << p << '-' << q << " is not an edge of"
                << " two coarse boundary faces",
            "pmsh::foldRepair::boundaryFacesOf"
        );
    }
    return faces;
}


bool pmsh::foldRepair::edgeUnprojected(const edgeKey& e, int round) const
{
    if (round <= 0)
    {
        return false;
    }
    const auto key = std::make_pair(round, e);
    const auto memo = edgeMemo_.find(key);
    if (memo != edgeMemo_.end())
    {
        return memo->second;
    }
    bool off = edgeUnprojected(e, round - 1) || foldsAcross(e, round);
    const auto around = facesAround_.find(e);
    if (!off && around != facesAround_.end())
    {
        for (const faceKey& f : around->second)
        {
            if (folds(f, round))
            {
                off = true;
                break;
            }
        }
    }
    edgeMemo_[key] = off;
    return off;
}


bool pmsh::foldRepair::faceUnprojected(const faceKey& f, int round) const
{
    return round > 0 && (faceUnprojected(f, round - 1) || folds(f, round));
}


bool pmsh::foldRepair::inputsChanged(const faceKey& f, int round) const
{
    if (round <= 0)
    {
        return false;
    }
    for (const edgeKey& e : edgesOf(f))
    {
        if
        (
            facesAround_.count(e)
         && edgeUnprojected(e, round) != edgeUnprojected(e, round - 1)
        )
        {
            return true;
        }
    }
    return surfaceOf(f) >= 0
        && faceUnprojected(f, round) != faceUnprojected(f, round - 1);
}


bool pmsh::foldRepair::folds(const faceKey& f, int round) const
{
    if (crossesInterface(f, round))
    {
        return true;
    }
    // A boundary face whose surface still folds across one of its edges
    // after that edge was left linear: the face itself must go linear
    if (surfaceOf(f) >= 0)
    {
        for (const edgeKey& e : edgesOf(f))
        {
            if (edgeUnprojected(e, round - 1) && foldsAcross(e, round))
            {
                return true;
            }
        }
    }
    return latticeFolds(f, round);
}


bool pmsh::foldRepair::latticeFolds(const faceKey& f, int round) const
{
    // With the previous round's inputs unchanged the answer is the same
    if (round > 1 && !inputsChanged(f, round - 1))
    {
        return latticeFolds(f, round - 1);
    }
    const auto key = std::make_pair(round, f);
    const auto memo = foldsMemo_.find(key);
    if (memo != foldsMemo_.end())
    {
        return memo->second;
    }
    const bool result =
        countLatticeFolds(refinedFace(f, round - 1), 1 << levels_) > 0;
    foldsMemo_[key] = result;
    return result;
}


bool pmsh::foldRepair::foldsAcross(const edgeKey& e, int round) const
{
    label s1, s2;
    if (!geometry_ || !edgeSurfaces_.find(e[0], e[1], s1, s2) || s1 != s2 || s1 < 0)
    {
        return false;   // a feature edge may be as sharp as it likes
    }
    // With the previous round's decisions unchanged the answer is the same
    if (round > 1)
    {
        bool changed = false;
        for (const faceKey& f : boundaryFacesOf(e[0], e[1]))
        {
            changed = changed || inputsChanged(f, round - 1);
        }
        if (!changed)
        {
            return foldsAcross(e, round - 1);
        }
    }
    const auto key = std::make_pair(round, e);
    const auto memo = acrossMemo_.find(key);
    if (memo != acrossMemo_.end())
    {
        return memo->second;
    }

    // The outward unit normal of the fine triangle at segment m of the
    // edge (counted from e[0]) in each boundary face, and of the coarse face
    const int n = 1 << levels_;
    std::array<std::vector<vector3>, 2> normals;
    std::array<vector3, 2> coarseNormal;
    const std::array<triVerts, 2> faces = boundaryFacesOf(e[0], e[1]);
    auto unit = [](const vector3& v, bool flip)
    {
        return (flip ? -1.0 : 1.0)/std::sqrt(magSqr(v))*v;
    };
    for (int side = 0; side < 2; ++side)
    {
        const faceKey& v = faces[side];
        const std::vector<point3> pos = refinedFace(v, round - 1);
        auto P = [&](int i, int j) -> const point3& { return pos[j*(n + 1) + i]; };
        const bool flip = boundarySurface_.at(v).second;
        coarseNormal[side] = unit(cross(P(n, 0) - P(0, 0), P(0, n) - P(0, 0)), flip);
        for (int m = 0; m < n; ++m)
        {
            // Lattice triangle (i, j), (i + 1, j), (i, j + 1) on the edge
            int i = 0, j = 0;
            if (e[0] == v[0] && e[1] == v[1]) { i = m; j = 0; }
            else if (e[0] == v[1]) { i = n - m - 1; j = m; }
            else { i = 0; j = m; }
            normals[side].push_back
            (
                unit(cross(P(i + 1, j) - P(i, j), P(i, j + 1) - P(i, j)), flip)
            );
        }
    }
    // Folded onto itself: the two fine triangles nearly back to back (less
    // than about 25 degrees between them), clearly sharper than the coarse faces
    // (where the coarse surface is that sharp already, as round a thin
    // part, linear points would not help)
    const double coarseCos = dot(coarseNormal[0], coarseNormal[1]);
    bool result = false;
    for (int m = 0; m < n && !result; ++m)
    {
        const double fineCos = dot(normals[0][m], normals[1][m]);
        result = fineCos < -0.9 && fineCos < coarseCos - 0.01;
    }
    acrossMemo_[key] = result;
    return result;
}


bool pmsh::foldRepair::crossesInterface(const faceKey& f, int round) const
{
    const auto beside = interfacesBeside_.find(f);
    if (beside == interfacesBeside_.end())
    {
        return false;
    }
    const auto key = std::make_pair(round, f);
    const auto memo = interfaceMemo_.find(key);
    if (memo != interfaceMemo_.end())
    {
        return memo->second;
    }
    // The interface faces' triangles first: a triangle of f that crosses
    // one of them and one of f's own names the interface's (crossingTriangles
    // gives the smallest index)
    const int n = 1 << levels_;
    std::map<point3, label> pointIndex;
    std::vector<point3> points;
    std::vector<triVerts> triangles;
    for (const faceKey& F : beside->second)
    {
        appendLattice(refinedFace(F, round - 1), n, pointIndex, points, triangles);
    }
    const label nInterface = triangles.size();
    appendLattice(refinedFace(f, round - 1), n, pointIndex, points, triangles);
    std::vector<bool> tested(triangles.size(), false);
    std::fill(tested.begin() + nInterface, tested.end(), true);
    const std::vector<label> crossing = crossingTriangles(points, triangles, tested, true);
    bool result = false;
    for (label t = nInterface; t < label(triangles.size()) && !result; ++t)
    {
        result = crossing[t] != 0 && crossing[t] - 1 < nInterface;
    }
    interfaceMemo_[key] = result;
    return result;
}


std::vector<pmsh::point3> pmsh::foldRepair::refinedFace(const faceKey& v, int round) const
{
    faceLattice lattice(levels_);
    fillFace
    (
        lattice, coarse_, edgeSurfaces_, geometry_, v, surfaceOf(v),
        faceUnprojected(v, round),
        [&](label a, label b) { return edgeUnprojected(sortedEdge(a, b), round); }
    );
    return lattice.positions();
}


std::vector<pmsh::point3> pmsh::foldRepair::refinedFace(const triVerts& f) const
{
    return refinedFace(sortedFace(f), rounds);
}


// * * * * * * * * * * * * * * * * refineSurface  * * * * * * * * * * * * * //


// ************************************************************************* //
