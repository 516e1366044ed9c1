#include "surfaceRefinement.H"
#include "Geometry.H"
#include "pmshError.H"
#include "partitionSurface.H"
#include "matchByPoints.H"

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <unordered_map>

// * * * * * * * * * * * * * * boundaryEdgeSurfaces  * * * * * * * * * * * * //

pmsh::boundaryEdgeSurfaces::boundaryEdgeSurfaces
(
    const CoarseMesh& coarse,
    const Geometry* geometry
)
{
    // Edge k of face b is 3*b + k, boundary faces first, then the faces
    // between zones. A boundary edge away from zones has exactly two
    // faces. Groups come in (p, q) order.
    const matchId nBoundary = matchId(coarse.boundary.size());
    auto faceOf = [&](matchId face) -> const triVerts&
    {
        return face < nBoundary
            ? coarse.boundary[face].v : coarse.zoneFaces[face - nBoundary].v;
    };
    auto surfaceOf = [&](matchId face)
    {
        return face < nBoundary
            ? coarse.boundary[face].surface
            : coarse.zoneFaces[face - nBoundary].surface;
    };
    auto edgeOf = [&](matchId id)
    {
        const triVerts& f = faceOf(id/3);
        return std::array<label, 2>{f[id % 3], f[(id + 1) % 3]};
    };
    edges_.reserve(3*coarse.boundary.size()/2);
    forEachSamePointsGroup
    (
        coarse.points.size(),
        matchId(3*(coarse.boundary.size() + coarse.zoneFaces.size())),
        edgeOf,
        [&](const matchId* ids, std::size_t n)
        {
            const auto e = sortedPoints(edgeOf(ids[0]));
            std::vector<label> surfaces;
            std::size_t nBoundaryFaces = 0;
            for (std::size_t i = 0; i < n; ++i)
            {
                nBoundaryFaces += ids[i]/3 < nBoundary;
                surfaces.push_back(surfaceOf(ids[i]/3));
            }
            if (nBoundaryFaces == n && n != 2)
            {
                throw FatalError
                (
                    msg() << "The coarse boundary is not a closed manifold: edge "
                        << e[0] << '-' << e[1] << " is used by " << n
                        << " boundary faces instead of 2",
                    "boundaryEdgeSurfaces"
                );
            }
            std::sort(surfaces.begin(), surfaces.end());
            surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
            label s1 = surfaces.front();
            label s2 = surfaces.size() > 1 ? surfaces[1] : s1;
            if (surfaces.size() > 2 && geometry)
            {
                // The first pair whose curve lies on all the surfaces here
                // (two of them may be one plane, given twice)
                const point3 mid = midPoint(coarse.points[e[0]], coarse.points[e[1]]);
                const double tolerance =
                    1e-6*std::sqrt(magSqr(coarse.points[e[1]] - coarse.points[e[0]]));
                s1 = s2 = -1;
                for (std::size_t i = 0; i < surfaces.size() && s1 < 0; ++i)
                {
                    for (std::size_t j = i + 1; j < surfaces.size() && s1 < 0; ++j)
                    {
                        const point3 q = geometry->projectToEdge(mid, surfaces[i], surfaces[j]);
                        double off = 0;
                        for (label s : surfaces)
                        {
                            off = std::max
                            (
                                off, std::sqrt(magSqr(q - geometry->projectToSurface(q, s)))
                            );
                        }
                        if (off < tolerance)
                        {
                            s1 = surfaces[i];
                            s2 = surfaces[j];
                        }
                    }
                }
            }
            edges_.push_back({e[0], e[1], s1, s2});
        }
    );
}


bool pmsh::boundaryEdgeSurfaces::find(label p, label q, label& s1, label& s2) const
{
    const edge key{std::min(p, q), std::max(p, q), 0, 0};
    auto it = std::lower_bound
    (
        edges_.begin(), edges_.end(), key,
        [](const edge& x, const edge& y) { return std::tie(x.p, x.q) < std::tie(y.p, y.q); }
    );
    if (it == edges_.end() || it->p != key.p || it->q != key.q)
    {
        return false;
    }
    s1 = it->s1;
    s2 = it->s2;
    return true;
}


// * * * * * * * * * * * * * * * * refineSurface  * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

// The lattice of one coarse face refined r times: point (i, j) has integer
// barycentric coordinates (n - i - j, i, j) on the face's points sorted by
// index (v0 < v1 < v2), so both ranks that hold an interface face walk it
// identically.
class faceLattice
{
public:

    explicit faceLattice(int levels)
    :
        levels_(levels),
        n_(1 << levels),
        pos_((n_ + 1)*(n_ + 1))
    {}

    int n() const { return n_; }
    point3& at(int i, int j) { return pos_[j*(n_ + 1) + i]; }
    const std::vector<point3>& positions() const { return pos_; }

    // Fill positions level by level: each new point is the midpoint of the
    // coarser edge it splits, projected through `project(i, j, p)`.
    template<class Projector>
    void fill(const point3& x0, const point3& x1, const point3& x2, Projector project)
    {
        at(0, 0) = x0;
        at(n_, 0) = x1;
        at(0, n_) = x2;
        for (int level = 1; level <= levels_; ++level)
        {
            const int s = n_ >> level;
            for (int j = 0; j <= n_; j += s)
            {
                for (int i = 0; i + j <= n_; i += s)
                {
                    const bool oddI = (i/s) % 2;
                    const bool oddJ = (j/s) % 2;
                    const bool oddK = ((n_ - i - j)/s) % 2;
                    if (!oddI && !oddJ && !oddK)
                    {
                        continue;       // exists at a coarser level
                    }
                    point3 mid;
                    if (oddI && oddJ)
                    {
                        mid = midPoint(at(i + s, j - s), at(i - s, j + s));
                    }
                    else if (oddI)
                    {
                        mid = midPoint(at(i + s, j), at(i - s, j));
                    }
                    else
                    {
                        mid = midPoint(at(i, j + s), at(i, j - s));
                    }
                    at(i, j) = project(i, j, mid);
                }
            }
        }
    }

private:

    int levels_;
    int n_;
    std::vector<point3> pos_;
};


//- Fill the lattice of the face with sorted points v: points on a boundary
//  edge projected onto its surface(s) unless edgeOff(a, b), points inside
//  a boundary face onto its surface unless insideOff, the rest linear.
template<class EdgeOff>
void fillFace
(
    faceLattice& lattice,
    const CoarseMesh& coarse,
    const boundaryEdgeSurfaces& edgeSurfaces,
    const Geometry* geometry,
    const triVerts& v,
    label faceSurface,
    bool insideOff,
    const EdgeOff& edgeOff
)
{
    const int n = lattice.n();
    auto project = [&](int i, int j, const point3& p) -> point3
    {
        if (!geometry)
        {
            return p;
        }
        const int k = n - i - j;
        if (i != 0 && j != 0 && k != 0)
        {
            return faceSurface >= 0 && !insideOff
                ? geometry->projectToSurface(p, faceSurface) : p;
        }
        const label a = (k == 0) ? v[1] : v[0];
        const label b = (j == 0) ? v[1] : v[2];
        label s1, s2;
        if (!edgeSurfaces.find(a, b, s1, s2) || s1 < 0 || edgeOff(a, b))
        {
            return p;   // an edge inside a zone, or left linear
        }
        return s1 == s2
            ? geometry->projectToSurface(p, s1)
            : geometry->projectToEdge(p, s1, s2);
    };
    lattice.fill(coarse.points[v[0]], coarse.points[v[1]], coarse.points[v[2]], project);
}


//- The n^2 triangles of a coarse face whose edges are split n times, each
//  as three lattice points (i, j) (point i along v0-v1, j along v0-v2),
//  oriented like (v0, v1, v2): f(i0, j0, i1, j1, i2, j2).
template<class Triangle>
void forEachLatticeTriangle(int n, Triangle f)
{
    for (int j = 0; j < n; ++j)
    {
        for (int i = 0; i + j < n; ++i)
        {
            f(i, j, i + 1, j, i, j + 1);
            if (i + j + 1 < n)
            {
                f(i + 1, j, i + 1, j + 1, i, j + 1);
            }
        }
    }
}


//- Refined triangles of a lattice (points v0 < v1 < v2 at `pos`) that
//  turned against the coarse face (v0, v1, v2).
label countLatticeFolds(const std::vector<point3>& pos, int n)
{
    auto P = [&](int i, int j) -> const point3& { return pos[j*(n + 1) + i]; };
    const vector3 coarseNormal =
        cross(P(n, 0) - P(0, 0), P(0, n) - P(0, 0));
    label nFolded = 0;
    forEachLatticeTriangle(n, [&](int i0, int j0, int i1, int j1, int i2, int j2)
    {
        const point3& a = P(i0, j0);
        if (dot(cross(P(i1, j1) - a, P(i2, j2) - a), coarseNormal) <= 0)
        {
            ++nFolded;
        }
    });
    return nFolded;
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
    int levels
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

pmsh::FineSurface pmsh::refineSurface
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const boundaryEdgeSurfaces& edgeSurfaces,
    const Geometry* geometry,
    int levels,
    bool repairFolds
)
{
    if (levels < 0 || levels > 15)
    {
        throw FatalError
        (
            msg() << "refinementLevels " << levels << " is outside 0..15",
            "refineSurface"
        );
    }

    const label nCoarseFaces = label(partSurface.faces.size());
    const int n = 1 << levels;
    const std::size_t trianglesPerFace = std::size_t(n)*n;

    FineSurface fine;
    fine.triangles.reserve(nCoarseFaces*trianglesPerFace);
    fine.region.reserve(nCoarseFaces*trianglesPerFace);
    // Points: about half the triangles for a closed surface
    fine.points.reserve(nCoarseFaces*trianglesPerFace/2 + 4);
    fine.ids.reserve(fine.points.capacity());

    // Points on coarse vertices and edges are shared by several faces and
    // are looked up by id; points inside a face belong to that face alone.
    std::unordered_map<barycentricId, label, barycentricIdHash> sharedPoints;
    sharedPoints.reserve(nCoarseFaces*(3*n/2 + 1));
    // A face between two zones of the part comes twice: the second time
    // it takes the first one's points
    std::map<triVerts, std::vector<label>> betweenZonesPoints;

    faceLattice lattice(levels);
    std::vector<label> latticePoint((n + 1)*(n + 1));

    std::unique_ptr<foldRepair> repair;
    if (geometry && repairFolds)
    {
        repair.reset(new foldRepair(coarse, edgeSurfaces, geometry, levels));
    }

    // The points a repair left off the geometry, and their distance from
    // it: points inside a boundary face by the part holding the face,
    // points on a boundary edge by the part holding the edge's lower
    // boundary face (so every point counts once over all parts)
    auto distanceOff = [&](const point3& p, label s1, label s2)
    {
        const double d1 = magSqr(p - geometry->projectToSurface(p, s1));
        const double d2 =
            s2 == s1 ? d1 : magSqr(p - geometry->projectToSurface(p, s2));
        return std::sqrt(std::min(d1, d2));
    };
    auto countOff = [&](const point3& p, label s1, label s2)
    {
        const double d = distanceOff(p, s1, s2);
        ++fine.repair.nPointsOff;
        fine.repair.sumDistance += d;
        fine.repair.maxDistance = std::max(fine.repair.maxDistance, d);
    };
    auto addRepairStats = [&](const triVerts& v, label faceSurface, const std::vector<point3>& pos)
    {
        auto P = [&](int i, int j) -> const point3& { return pos[j*(n + 1) + i]; };
        if (repair->faceUnprojected(v))
        {
            for (int j = 1; j < n; ++j)
            {
                for (int i = 1; i + j < n; ++i)
                {
                    countOff(P(i, j), faceSurface, faceSurface);
                }
            }
        }
        for (int e = 0; e < 3; ++e)
        {
            const label a = v[e == 1 ? 1 : 0];
            const label b = v[e == 0 ? 1 : 2];
            label s1, s2;
            if
            (
                !edgeSurfaces.find(a, b, s1, s2)
             || !repair->edgeUnprojected(a, b)
             || repair->boundaryFacesOf(a, b)[0] != v
            )
            {
                continue;
            }
            for (int m = 1; m < n; ++m)
            {
                // Edge (v0, v1): j = 0; (v1, v2): i + j = n; (v0, v2): i = 0
                countOff(e == 0 ? P(m, 0) : e == 1 ? P(n - m, m) : P(0, m), s1, s2);
            }
        }
    };

    // The points of the face with sorted points v, into latticePoint
    auto makeFacePoints = [&](const triVerts& v, label faceSurface)
    {
        std::vector<point3> positions;
        if (repair)
        {
            positions = repair->refinedFace(v);
            if (faceSurface >= 0)
            {
                addRepairStats(v, faceSurface, positions);
            }
        }
        else
        {
            fillFace
            (
                lattice, coarse, edgeSurfaces, geometry, v, faceSurface, false,
                [](label, label) { return false; }
            );
            positions = lattice.positions();
        }

        for (int j = 0; j <= n; ++j)
        {
            for (int i = 0; i + j <= n; ++i)
            {
                const barycentricId id
                (
                    std::uint32_t(v[0] + 1), std::uint32_t(n - i - j),
                    std::uint32_t(v[1] + 1), std::uint32_t(i),
                    std::uint32_t(v[2] + 1), std::uint32_t(j)
                );
                label pointi = label(fine.points.size());
                if (id.nNonZero() < 3)
                {
                    auto inserted = sharedPoints.emplace(id, pointi);
                    if (!inserted.second)
                    {
                        latticePoint[j*(n + 1) + i] = inserted.first->second;
                        continue;
                    }
                }
                fine.points.push_back(positions[j*(n + 1) + i]);
                fine.ids.push_back(id);
                latticePoint[j*(n + 1) + i] = pointi;
            }
        }
    };

    for (label facei = 0; facei < nCoarseFaces; ++facei)
    {
        const triVerts& f = partSurface.faces[facei];
        triVerts v = f;
        std::sort(v.begin(), v.end());
        if (!isBetweenZones(partSurface.region[facei]))
        {
            makeFacePoints(v, partSurface.surface[facei]);
        }
        else
        {
            const auto seen = betweenZonesPoints.find(v);
            if (seen != betweenZonesPoints.end())
            {
                latticePoint = seen->second;
            }
            else
            {
                makeFacePoints(v, partSurface.surface[facei]);
                betweenZonesPoints.emplace(v, latticePoint);
            }
        }

        // Triangles of the lattice, oriented like (v0, v1, v2); flipped to
        // the coarse face's outward orientation where that differs
        const bool flip = !sameOrientation(v, f);
        auto P = [&](int i, int j) { return latticePoint[j*(n + 1) + i]; };
        forEachLatticeTriangle(n, [&](int i0, int j0, int i1, int j1, int i2, int j2)
        {
            const label a = P(i0, j0), b = P(i1, j1), c = P(i2, j2);
            fine.triangles.push_back(flip ? triVerts{a, c, b} : triVerts{a, b, c});
            fine.region.push_back(partSurface.region[facei]);
            if (!partSurface.zone.empty())
            {
                fine.zone.push_back(partSurface.zone[facei]);
            }
        });
    }
    return fine;
}


pmsh::label pmsh::countFoldedTriangles
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const FineSurface& fine,
    int levels
)
{
    const std::size_t trianglesPerFace = std::size_t(1) << (2*levels);
    label nFolded = 0;
    for (std::size_t facei = 0; facei < partSurface.faces.size(); ++facei)
    {
        const triVerts& f = partSurface.faces[facei];
        const vector3 coarseNormal = cross
        (
            coarse.points[f[1]] - coarse.points[f[0]],
            coarse.points[f[2]] - coarse.points[f[0]]
        );
        for (std::size_t t = 0; t < trianglesPerFace; ++t)
        {
            const triVerts& tri = fine.triangles[facei*trianglesPerFace + t];
            const vector3 normal = cross
            (
                fine.points[tri[1]] - fine.points[tri[0]],
                fine.points[tri[2]] - fine.points[tri[0]]
            );
            if (dot(normal, coarseNormal) <= 0)
            {
                ++nFolded;
            }
        }
    }
    return nFolded;
}


pmsh::FineSurface pmsh::refinePartSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label part,
    const Geometry* geometry,
    int levels
)
{
    const coarsePartSurface partSurface = partitionSurface(coarse, cellPart, part);
    FineSurface fine = refineSurface
    (
        coarse, partSurface, boundaryEdgeSurfaces(coarse, geometry), geometry, levels
    );
    const label nFolded = countFoldedTriangles(coarse, partSurface, fine, levels);
    if (nFolded > 0)
    {
        // Where: the first folded triangle and its patch
        const std::size_t trianglesPerFace = std::size_t(1) << (2*levels);
        std::string where;
        for (std::size_t facei = 0; facei < partSurface.faces.size() && where.empty(); ++facei)
        {
            const triVerts& f = partSurface.faces[facei];
            const vector3 coarseNormal = cross
            (
                coarse.points[f[1]] - coarse.points[f[0]],
                coarse.points[f[2]] - coarse.points[f[0]]
            );
            for (std::size_t t = 0; t < trianglesPerFace && where.empty(); ++t)
            {
                const triVerts& tri = fine.triangles[facei*trianglesPerFace + t];
                const point3& a = fine.points[tri[0]];
                const point3& b = fine.points[tri[1]];
                const point3& c = fine.points[tri[2]];
                if (dot(cross(b - a, c - a), coarseNormal) <= 0)
                {
                    const label region = partSurface.region[facei];
                    where = "at " + str((1.0/3.0)*(a + b + c)) + " on "
                      + (
                            isBetweenZones(region)
                          ? std::string("a face between two zones")
                          : isInterfaceRegion(region)
                          ? "the interface with part " + std::to_string(-region - 1)
                          : "patch " + coarse.patches[region].name
                        );
                }
            }
        }
        throw FatalError
        (
            msg() << nFolded << " refined surface triangles of part " << part
                << " folded over when projected onto the geometry, the first "
                << where << ", even with the refined points of the "
                << foldRepair::rounds << " rings of coarse faces around them"
                << " left off the geometry: the geometry there has features"
                << " much smaller than the coarse cells.\nReduce maxCellSize"
                << " in system/pmshDict, or remove the small features there"
                << " from the geometry",
            "refinePartSurface"
        );
    }
    return fine;
}
