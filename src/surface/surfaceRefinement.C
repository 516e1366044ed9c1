#include "surfaceRefinement.H"
#include "faceLattice.H"
#include "Geometry.H"
#include "pmshError.H"
#include "partitionSurface.H"

#include <algorithm>
#include <cmath>
#include <memory>
#include <unordered_map>

// * * * * * * * * * * * * * * * * refineSurface  * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

//- The fine surface of a part, built one coarse face at a time.
class fineSurfaceBuilder
{
    const CoarseMesh& coarse_;
    const coarsePartSurface& partSurface_;
    const boundaryEdgeSurfaces& edgeSurfaces_;
    const Geometry* geometry_;
    const int n_;
    faceLattice lattice_;
    std::unique_ptr<foldRepair> repair_;

    //- Points on coarse vertices and edges are shared by several faces
    //  and are looked up by id; points inside a face belong to that face
    //  alone.
    std::unordered_map<barycentricId, label, barycentricIdHash> sharedPoints_;

    //- A face between two zones of the part comes twice: the second time
    //  it takes the first one's points
    std::map<triVerts, std::vector<label>> betweenZonesPoints_;

    //- The fine point of each lattice point (i, j) of the current face, at
    //  [j*(n + 1) + i]
    std::vector<label> latticePoint_;

    //- Count a point a repair left off the geometry, with its distance
    //  from the surface (or the nearer of two)
    void countOff(const point3& p, label s1, label s2)
    {
        const double d1 = magSqr(p - geometry_->projectToSurface(p, s1));
        const double d2 =
            s2 == s1 ? d1 : magSqr(p - geometry_->projectToSurface(p, s2));
        const double d = std::sqrt(std::min(d1, d2));
        ++fine.repair.nPointsOff;
        fine.repair.sumDistance += d;
        fine.repair.maxDistance = std::max(fine.repair.maxDistance, d);
    }

    //- The points a repair left off the geometry: points inside a boundary
    //  face by the part holding the face, points on a boundary edge by the
    //  part holding the edge's lower boundary face (so every point counts
    //  once over all parts)
    void addRepairStats
    (
        const triVerts& v,
        label faceSurface,
        const std::vector<point3>& pos
    )
    {
        const int n = n_;
        auto P = [&](int i, int j) -> const point3& { return pos[j*(n + 1) + i]; };
        if (repair_->faceUnprojected(v))
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
                !edgeSurfaces_.find(a, b, s1, s2)
             || !repair_->edgeUnprojected(a, b)
             || repair_->boundaryFacesOf(a, b)[0] != v
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
    }

    //- The positions of the lattice points of the face with sorted points v
    std::vector<point3> facePositions(const triVerts& v, label faceSurface)
    {
        if (repair_)
        {
            std::vector<point3> positions = repair_->refinedFace(v);
            if (faceSurface >= 0)
            {
                addRepairStats(v, faceSurface, positions);
            }
            return positions;
        }
        fillFace
        (
            lattice_, coarse_, edgeSurfaces_, geometry_, v, faceSurface, false,
            [](label, label) { return false; }
        );
        return lattice_.positions();
    }

    //- The points of the face with sorted points v, into latticePoint_:
    //  new ones appended to the fine surface, shared ones looked up
    void makeFacePoints(const triVerts& v, label faceSurface)
    {
        const int n = n_;
        const std::vector<point3> positions = facePositions(v, faceSurface);
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
                    auto inserted = sharedPoints_.emplace(id, pointi);
                    if (!inserted.second)
                    {
                        latticePoint_[j*(n + 1) + i] = inserted.first->second;
                        continue;
                    }
                }
                fine.points.push_back(positions[j*(n + 1) + i]);
                fine.ids.push_back(id);
                latticePoint_[j*(n + 1) + i] = pointi;
            }
        }
    }

    //- Triangles of the lattice, oriented like (v0, v1, v2); flipped to the
    //  coarse face's outward orientation f where that differs
    void addFaceTriangles(label facei, const triVerts& v, const triVerts& f)
    {
        const int n = n_;
        const bool flip = !sameOrientation(v, f);
        auto P = [&](int i, int j) { return latticePoint_[j*(n + 1) + i]; };
        forEachLatticeTriangle(n, [&](int i0, int j0, int i1, int j1, int i2, int j2)
        {
            const label a = P(i0, j0), b = P(i1, j1), c = P(i2, j2);
            fine.triangles.push_back(flip ? triVerts{a, c, b} : triVerts{a, b, c});
            fine.region.push_back(partSurface_.region[facei]);
            if (!partSurface_.zone.empty())
            {
                fine.zone.push_back(partSurface_.zone[facei]);
            }
            if (!partSurface_.piece.empty())
            {
                fine.piece.push_back(partSurface_.piece[facei]);
            }
        });
    }

public:

    FineSurface fine;

    fineSurfaceBuilder
    (
        const CoarseMesh& coarse,
        const coarsePartSurface& partSurface,
        const boundaryEdgeSurfaces& edgeSurfaces,
        const Geometry* geometry,
        int levels,
        bool repairFolds,
        const std::vector<label>& cellPart
    )
    :
        coarse_(coarse),
        partSurface_(partSurface),
        edgeSurfaces_(edgeSurfaces),
        geometry_(geometry),
        n_(1 << levels),
        lattice_(levels),
        latticePoint_((n_ + 1)*(n_ + 1))
    {
        const std::size_t nCoarseFaces = partSurface.faces.size();
        const std::size_t trianglesPerFace = std::size_t(n_)*n_;
        fine.triangles.reserve(nCoarseFaces*trianglesPerFace);
        fine.region.reserve(nCoarseFaces*trianglesPerFace);
        // Points: about half the triangles for a closed surface
        fine.points.reserve(nCoarseFaces*trianglesPerFace/2 + 4);
        fine.ids.reserve(fine.points.capacity());
        sharedPoints_.reserve(nCoarseFaces*(3*n_/2 + 1));
        if (geometry && repairFolds)
        {
            repair_.reset(new foldRepair(coarse, edgeSurfaces, geometry, levels, cellPart));
        }
    }

    //- Refine coarse face facei of the part surface
    void addFace(label facei)
    {
        const triVerts& f = partSurface_.faces[facei];
        triVerts v = f;
        std::sort(v.begin(), v.end());
        if (!isBetweenZones(partSurface_.region[facei]))
        {
            makeFacePoints(v, partSurface_.surface[facei]);
        }
        else
        {
            const auto seen = betweenZonesPoints_.find(v);
            if (seen != betweenZonesPoints_.end())
            {
                latticePoint_ = seen->second;
            }
            else
            {
                makeFacePoints(v, partSurface_.surface[facei]);
                betweenZonesPoints_.emplace(v, latticePoint_);
            }
        }
        addFaceTriangles(facei, v, f);
    }
};

//- Call visit(facei, a, b, c) for each refined triangle (a, b, c) of the
//  part's surface that folded (refinedTriangleFold), in face order
template<class Visit>
void visitFoldedTriangles
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const FineSurface& fine,
    int levels,
    Visit visit
)
{
    const std::size_t trianglesPerFace = std::size_t(1) << (2*levels);
    for (std::size_t facei = 0; facei < partSurface.faces.size(); ++facei)
    {
        const triVerts& f = partSurface.faces[facei];
        const refinedTriangleFold folded
        (
            coarse.points[f[0]], coarse.points[f[1]], coarse.points[f[2]], 1 << levels
        );
        for (std::size_t t = 0; t < trianglesPerFace; ++t)
        {
            const triVerts& tri = fine.triangles[facei*trianglesPerFace + t];
            const point3& a = fine.points[tri[0]];
            const point3& b = fine.points[tri[1]];
            const point3& c = fine.points[tri[2]];
            if (folded(a, b, c))
            {
                visit(facei, a, b, c);
            }
        }
    }
}

} // End anonymous namespace


pmsh::FineSurface pmsh::refineSurface
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const boundaryEdgeSurfaces& edgeSurfaces,
    const Geometry* geometry,
    int levels,
    bool repairFolds,
    const std::vector<label>& cellPart
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

    fineSurfaceBuilder builder
    (
        coarse, partSurface, edgeSurfaces, geometry, levels, repairFolds, cellPart
    );
    for (label facei = 0; facei < label(partSurface.faces.size()); ++facei)
    {
        builder.addFace(facei);
    }
    return std::move(builder.fine);
}


pmsh::label pmsh::countFoldedTriangles
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const FineSurface& fine,
    int levels
)
{
    label nFolded = 0;
    visitFoldedTriangles
    (
        coarse, partSurface, fine, levels,
        [&](std::size_t, const point3&, const point3&, const point3&) { ++nFolded; }
    );
    return nFolded;
}


pmsh::FineSurface pmsh::refinePartSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label part,
    const Geometry* geometry,
    int levels,
    const std::vector<label>& cellPiece
)
{
    const coarsePartSurface partSurface =
        partitionSurface(coarse, cellPart, part, cellPiece);
    // The fold repair sees the faces between pieces as interfaces, so that
    // it decides on the pieces alone, whatever rank holds them
    FineSurface fine = refineSurface
    (
        coarse, partSurface, boundaryEdgeSurfaces(coarse, geometry), geometry, levels,
        true, cellPiece.empty() ? cellPart : cellPiece
    );
    const label nFolded = countFoldedTriangles(coarse, partSurface, fine, levels);
    if (nFolded > 0)
    {
        // Where: the first folded triangle and its patch
        std::string where;
        visitFoldedTriangles
        (
            coarse, partSurface, fine, levels,
            [&](std::size_t facei, const point3& a, const point3& b, const point3& c)
            {
                if (where.empty())
                {
                    where = "at " + str((1.0/3.0)*(a + b + c)) + " on "
                      + regionDescription(partSurface.region[facei], coarse.patches);
                }
            }
        );
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
