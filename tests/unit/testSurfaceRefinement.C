// Partition surfaces and their r-level refinement: counts, closedness,
// projection, and bit-identical interface vertices on both sides.

#include "surfaceRefinement.H"
#include "faceLattice.H"
#include "Geometry.H"
#include "meshPatch.H"
#include "surfaceChecks.H"
#include "testPaths.H"
#include "pmshError.H"
#include "surfaceCrossings.H"
#include "triangleCrossings.H"
#include "testMeshers.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstring>
#include <map>
#include <set>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

// The unit sphere as an analytic geometry: projection is normalisation
class analyticSphere : public Geometry
{
public:
    point3 projectToSurface(const point3& p, label) const override
    {
        return (1.0/std::sqrt(magSqr(p)))*p;
    }
    point3 projectToEdge(const point3& p, label s1, label) const override
    {
        return projectToSurface(p, s1);
    }
protected:
    CoarseMesh netgenMesh(const coarseMeshParameters&, bool) const override { return {}; }
};

// An octahedron around the origin split into 8 tets at the centre point 0
CoarseMesh octahedron()
{
    CoarseMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    m.patches = {{"sphere"}};
    for (label x : {1, 2})
    {
        for (label y : {3, 4})
        {
            for (label z : {5, 6})
            {
                tetVerts t{0, x, y, z};
                triVerts f{x, y, z};
                const auto& P = m.points;
                if (tetVolume6(P[t[0]], P[t[1]], P[t[2]], P[t[3]]) < 0)
                {
                    std::swap(t[2], t[3]);
                    std::swap(f[1], f[2]);
                }
                m.tets.push_back(t);
                m.boundary.push_back({f, 0, 0});
            }
        }
    }
    return m;
}

// Part 0: the tets with x > 0; part 1: the others
std::vector<label> splitByX(const CoarseMesh& m)
{
    std::vector<label> part;
    for (const tetVerts& t : m.tets)
    {
        part.push_back(t[1] == 1 ? 0 : 1);
    }
    return part;
}

double enclosedVolume(const std::vector<point3>& pts, const std::vector<triVerts>& tris)
{
    double v6 = 0;
    for (const triVerts& t : tris)
    {
        v6 += tetVolume6({0, 0, 0}, pts[t[0]], pts[t[1]], pts[t[2]]);
    }
    return v6/6;
}

FineSurface refinePart
(
    const CoarseMesh& m,
    const std::vector<label>& part,
    label myPart,
    const Geometry* g,
    int r
)
{
    const boundaryEdgeSurfaces edges(m);
    return refineSurface(m, partitionSurface(m, part, myPart), edges, g, r);
}

} // End anonymous namespace


TEST(partitionSurface, wholeMeshSurfaceIsTheCoarseBoundaryOrientedOutward)
{
    const CoarseMesh m = octahedron();
    const coarsePartSurface s = partitionSurface(m, {}, 0);
    ASSERT_EQ(s.faces.size(), 8u);
    EXPECT_TRUE(closedAndConsistent(s.faces));
    EXPECT_NEAR(enclosedVolume(m.points, s.faces), 4.0/3.0, 1e-12);
    for (label r : s.region)
    {
        EXPECT_EQ(r, 0);
    }
}


TEST(partitionSurface, eachPartIsClosedWithInterfaceFacesNamingTheOtherPart)
{
    const CoarseMesh m = octahedron();
    const std::vector<label> part = splitByX(m);
    for (label p : {0, 1})
    {
        const coarsePartSurface s = partitionSurface(m, part, p);
        EXPECT_TRUE(closedAndConsistent(s.faces));
        EXPECT_NEAR(enclosedVolume(m.points, s.faces), 2.0/3.0, 1e-12);
        int nInterface = 0;
        for (std::size_t f = 0; f < s.faces.size(); ++f)
        {
            if (isInterfaceRegion(s.region[f]))
            {
                ++nInterface;
                EXPECT_EQ(interfaceNeighbour(s.region[f]), 1 - p);
                EXPECT_EQ(s.surface[f], -1);
            }
        }
        EXPECT_EQ(nInterface, 4);
    }
}


TEST(surfaceRefinement, makesFourToTheRTrianglesPerCoarseFace)
{
    const CoarseMesh m = octahedron();
    for (int r = 0; r <= 4; ++r)
    {
        const FineSurface s = refinePart(m, {}, 0, nullptr, r);
        EXPECT_EQ(s.triangles.size(), 8u << (2*r)) << "r = " << r;
        EXPECT_EQ(s.region.size(), s.triangles.size());
    }
}


TEST(surfaceRefinement, refinedSurfaceIsClosedWithEachSharedVertexOnce)
{
    const CoarseMesh m = octahedron();
    for (int r = 0; r <= 3; ++r)
    {
        const FineSurface s = refinePart(m, {}, 0, nullptr, r);
        EXPECT_TRUE(closedAndConsistent(s.triangles)) << "r = " << r;
        // Euler: V - E + F = 2 for a sphere, E = 3F/2
        EXPECT_EQ(s.points.size(), 2 + s.triangles.size()/2) << "r = " << r;
        const std::set<barycentricId> unique(s.ids.begin(), s.ids.end());
        EXPECT_EQ(unique.size(), s.ids.size());
    }
}


TEST(surfaceRefinement, refinedFaceCarriesTheIdsOfFigureFour)
{
    // Coarse face (3, 5, 8) in 1-based ids = points 2, 4, 7
    CoarseMesh m;
    m.points.assign(8, point3{0, 0, 0});
    m.points[2] = {0, 0, 0};
    m.points[4] = {1, 0, 0};
    m.points[7] = {0, 1, 0};
    coarsePartSurface face;
    face.faces = {{2, 4, 7}};
    face.region = {0};
    face.surface = {-1};
    const FineSurface s = refineSurface(m, face, boundaryEdgeSurfaces(m), nullptr, 2);

    EXPECT_EQ(s.points.size(), 15u);
    EXPECT_EQ(s.triangles.size(), 16u);
    const std::set<barycentricId> ids(s.ids.begin(), s.ids.end());
    for
    (
        const barycentricId& expected :
        {
            barycentricId(3, 4, 5, 0, 8, 0), barycentricId(3, 0, 5, 4, 8, 0),
            barycentricId(3, 0, 5, 0, 8, 4), barycentricId(3, 1, 5, 2, 8, 1),
            barycentricId(3, 3, 5, 1, 8, 0), barycentricId(3, 2, 5, 1, 8, 1),
            barycentricId(3, 0, 5, 1, 8, 3)
        }
    )
    {
        EXPECT_EQ(ids.count(expected), 1u) << expected;
    }
    // Linear positions: the id's weights are the barycentric coordinates
    for (std::size_t p = 0; p < s.points.size(); ++p)
    {
        double x = 0, y = 0;
        for (int n = 0; n < 3; ++n)
        {
            if (s.ids[p].vertex[n] == 5) x = s.ids[p].weight[n]/4.0;
            if (s.ids[p].vertex[n] == 8) y = s.ids[p].weight[n]/4.0;
        }
        EXPECT_DOUBLE_EQ(s.points[p][0], x);
        EXPECT_DOUBLE_EQ(s.points[p][1], y);
    }
}


TEST(surfaceRefinement, projectsNewBoundaryVerticesOntoTheGeometry)
{
    const CoarseMesh m = octahedron();
    const analyticSphere sphere;

    const FineSurface projected = refinePart(m, {}, 0, &sphere, 2);
    for (const point3& p : projected.points)
    {
        EXPECT_NEAR(std::sqrt(magSqr(p)), 1.0, 1e-12);
    }

    // Without projection the refined points stay on the flat faces
    const FineSurface flat = refinePart(m, {}, 0, nullptr, 2);
    double maxOff = 0;
    for (const point3& p : flat.points)
    {
        maxOff = std::max(maxOff, std::abs(std::sqrt(magSqr(p)) - 1.0));
    }
    EXPECT_GT(maxOff, 1e-2);

    EXPECT_EQ(countFoldedTriangles(m, partitionSurface(m, {}, 0), projected, 2), 0);
}


TEST(surfaceRefinement, interfaceVerticesAreBitIdenticalOnBothParts)
{
    const CoarseMesh m = octahedron();
    const std::vector<label> part = splitByX(m);
    const analyticSphere sphere;
    const int r = 3;

    const FineSurface s0 = refinePart(m, part, 0, &sphere, r);
    const FineSurface s1 = refinePart(m, part, 1, &sphere, r);
    EXPECT_TRUE(closedAndConsistent(s0.triangles));
    EXPECT_TRUE(closedAndConsistent(s1.triangles));

    std::map<barycentricId, point3> onPart1;
    for (std::size_t p = 0; p < s1.ids.size(); ++p)
    {
        onPart1[s1.ids[p]] = s1.points[p];
    }
    std::size_t nShared = 0;
    for (std::size_t p = 0; p < s0.ids.size(); ++p)
    {
        auto it = onPart1.find(s0.ids[p]);
        if (it != onPart1.end())
        {
            ++nShared;
            EXPECT_EQ(std::memcmp(&it->second, &s0.points[p], sizeof(point3)), 0)
                << s0.ids[p];
        }
    }
    // The interface is the x = 0 square, 4 coarse faces refined into a disc
    // of F = 4n^2 triangles with 4n boundary edges: V = 1 + (F + 4n)/2
    const std::size_t n = 1 << r;
    EXPECT_EQ(nShared, 2*n*n + 2*n + 1);

    // Interface triangles: the same id triples, opposite orientation
    auto interfaceTriangles = [](const FineSurface& s)
    {
        std::set<std::array<barycentricId, 3>> tris;
        for (std::size_t t = 0; t < s.triangles.size(); ++t)
        {
            if (!isInterfaceRegion(s.region[t])) continue;
            std::array<barycentricId, 3> ids
                {s.ids[s.triangles[t][0]], s.ids[s.triangles[t][1]], s.ids[s.triangles[t][2]]};
            // rotate the smallest first, keeping orientation
            while (!(ids[0] < ids[1] && ids[0] < ids[2]))
            {
                std::rotate(ids.begin(), ids.begin() + 1, ids.end());
            }
            tris.insert(ids);
        }
        return tris;
    };
    const auto t0 = interfaceTriangles(s0);
    auto t1 = interfaceTriangles(s1);
    EXPECT_EQ(t0.size(), 4*n*n);
    for (std::array<barycentricId, 3> t : t0)
    {
        std::swap(t[1], t[2]);
        EXPECT_EQ(t1.count(t), 1u);
    }
}


namespace
{

// A "geometry" whose projection throws new points through the centre: the
// refined triangles turn against their coarse faces
class foldingGeometry : public analyticSphere
{
public:
    point3 projectToSurface(const point3& p, label) const override
    {
        return (-1.0/std::sqrt(magSqr(p)))*p;
    }
};

} // End anonymous namespace


TEST(surfaceRefinement, projectionThatFoldsEverywhereIsRepairedByLeavingThePointsOnTheCoarseFaces)
{
    const CoarseMesh m = octahedron();
    const analyticSphere sphere;
    const FineSurface onSphere = refinePartSurface(m, {}, 0, &sphere, 2);
    EXPECT_EQ(onSphere.repair.nPointsOff, 0);

    const foldingGeometry folding;
    const coarsePartSurface ps = partitionSurface(m, {}, 0);
    const boundaryEdgeSurfaces edges(m);
    const FineSurface folded = refineSurface(m, ps, edges, &folding, 2, false);
    EXPECT_GT(countFoldedTriangles(m, ps, folded, 2), 0);

    const FineSurface repaired = refinePartSurface(m, {}, 0, &folding, 2);
    EXPECT_EQ(countFoldedTriangles(m, ps, repaired, 2), 0);
    // Every new point stays on its coarse face: 8 faces of 4^2 triangles
    // have 66 points, 6 of them coarse
    EXPECT_EQ(repaired.repair.nPointsOff, 60);
    // ... and the furthest, (3, 1, 0)/4 of a face, is 1 + its radius from
    // where the projection sends it
    EXPECT_NEAR(repaired.repair.maxDistance, 1 + std::sqrt(10.0)/4, 1e-12);
}


namespace
{

// The unit sphere, except that points within 25 degrees of the direction
// (0, 1, 1) go through the centre: a fold around coarse edge 3-5 (between
// +y and +z), which the boundary faces of both parts of splitByX share
class locallyFoldingSphere : public analyticSphere
{
public:
    point3 projectToSurface(const point3& p, label) const override
    {
        const point3 q = (1.0/std::sqrt(magSqr(p)))*p;
        const double cosAngle = (q[1] + q[2])/std::sqrt(2.0);
        return cosAngle > std::cos(25*M_PI/180) ? (-1.0)*q : q;
    }
};

std::map<barycentricId, point3> pointsById(const FineSurface& s)
{
    std::map<barycentricId, point3> byId;
    for (std::size_t i = 0; i < s.ids.size(); ++i)
    {
        byId[s.ids[i]] = s.points[i];
    }
    return byId;
}

} // End anonymous namespace


TEST(surfaceRefinement, localFoldIsRepairedLocallyAndOnlyThere)
{
    const CoarseMesh m = octahedron();
    const locallyFoldingSphere geometry;
    const coarsePartSurface ps = partitionSurface(m, {}, 0);
    const boundaryEdgeSurfaces edges(m);
    for (int levels : {1, 2, 3})
    {
        SCOPED_TRACE("levels " + std::to_string(levels));
        const FineSurface folded = refineSurface(m, ps, edges, &geometry, levels, false);
        EXPECT_GT(countFoldedTriangles(m, ps, folded, levels), 0);

        const FineSurface repaired = refinePartSurface(m, {}, 0, &geometry, levels);
        EXPECT_EQ(countFoldedTriangles(m, ps, repaired, levels), 0);
        EXPECT_GT(repaired.repair.nPointsOff, 0);
        // Faces away from the fold (x < 0 or z < 0 ...) keep their points
        // on the sphere: only the faces at edge 3-5 and their neighbours
        // are touched
        label onSphere = 0;
        for (const point3& p : repaired.points)
        {
            onSphere += std::abs(magSqr(p) - 1) < 1e-12;
        }
        EXPECT_EQ(label(repaired.points.size()) - onSphere, repaired.repair.nPointsOff);
        EXPECT_LT(repaired.repair.nPointsOff, label(repaired.points.size())/2);
    }
}


namespace
{

// The unit sphere, except that points within 25 degrees of the direction
// (0, 1, 1) land a ten-millionth of their distance away from a straight
// crease through it along x: the refined triangles there keep their turn
// but lie all but flat, as lattice points projected onto a CAD crease do
class creaseSphere : public analyticSphere
{
public:
    //- keep: the share of its distance from the crease a projected point keeps
    explicit creaseSphere(double keep = 1e-7) : keep_(keep) {}

    point3 projectToSurface(const point3& p, label) const override
    {
        const point3 q = (1.0/std::sqrt(magSqr(p)))*p;
        if ((q[1] + q[2])/std::sqrt(2.0) <= std::cos(25*M_PI/180))
        {
            return q;
        }
        const point3 onCrease{q[0], 1/std::sqrt(2.0), 1/std::sqrt(2.0)};
        return onCrease + keep_*(q - onCrease);
    }

private:
    double keep_;
};


// The smallest share of its coarse face's area, and of its coarse face's
// shape quality, that a refined triangle of a part's surface has
std::pair<double, double> smallestShares
(
    const CoarseMesh& m, const coarsePartSurface& ps, const FineSurface& fine, int levels
)
{
    const int n = 1 << levels;
    double area = 1, shape = 1;
    for (std::size_t facei = 0; facei < ps.faces.size(); ++facei)
    {
        const triVerts& f = ps.faces[facei];
        const point3& x0 = m.points[f[0]];
        const point3& x1 = m.points[f[1]];
        const point3& x2 = m.points[f[2]];
        const vector3 coarse = cross(x1 - x0, x2 - x0);
        for (int t = 0; t < n*n; ++t)
        {
            const triVerts& tri = fine.triangles[facei*n*n + t];
            const point3& a = fine.points[tri[0]];
            const point3& b = fine.points[tri[1]];
            const point3& c = fine.points[tri[2]];
            area = std::min(area, n*n*dot(cross(b - a, c - a), coarse)/magSqr(coarse));
            shape = std::min
            (
                shape,
                triangleShapeQuality(a, b, c)
               /triangleShapeQuality(x0, x1, x2)
            );
        }
    }
    return {area, shape};
}

} // End anonymous namespace


TEST(surfaceRefinement, refinedTrianglesLyingFlatOnACreaseAreRepairedLikeFolds)
{
    const CoarseMesh m = octahedron();
    const creaseSphere geometry;
    const coarsePartSurface ps = partitionSurface(m, {}, 0);
    const int levels = 2;

    const FineSurface projected = refineSurface(m, ps, boundaryEdgeSurfaces(m), &geometry, levels, false);
    EXPECT_GT(smallestShares(m, ps, projected, levels).first, 0);       // not turned: no fold by its sign
    EXPECT_LT(smallestShares(m, ps, projected, levels).first, 1e-5);    // but flat

    const FineSurface repaired = refinePartSurface(m, {}, 0, &geometry, levels);
    EXPECT_GT(repaired.repair.nPointsOff, 0);
    EXPECT_GT(smallestShares(m, ps, repaired, levels).first, 1e-3);
}


TEST(surfaceRefinement, refinedSliversOnACreaseAreRepairedLikeFolds)
{
    // Points pulled to 5 % of their distance from a crease: the refined
    // triangles across it keep a fair share of their area (no flat rule
    // catches them) but become slivers, on which the volume meshers put
    // tets with faces far from orthogonal (OpenFOAM's wrapped motorBike)
    const CoarseMesh m = octahedron();
    const creaseSphere geometry(0.05);
    const coarsePartSurface ps = partitionSurface(m, {}, 0);
    const int levels = 2;

    const FineSurface projected = refineSurface(m, ps, boundaryEdgeSurfaces(m), &geometry, levels, false);
    const auto [areaBefore, shapeBefore] = smallestShares(m, ps, projected, levels);
    EXPECT_GT(areaBefore, 1e-3);
    EXPECT_LT(shapeBefore, refinedTriangleFold::sliverShare);

    const FineSurface repaired = refinePartSurface(m, {}, 0, &geometry, levels);
    EXPECT_GT(repaired.repair.nPointsOff, 0);
    EXPECT_GE(smallestShares(m, ps, repaired, levels).second, refinedTriangleFold::sliverShare);
}


TEST(surfaceRefinement, foldRepairDecidesAnInterfaceEdgeAlikeOnBothSidesAndAsInSerial)
{
    // Edge 3-5's boundary faces are in different parts: each part decides
    // from its own copy of the coarse mesh, and must leave the same points
    // off the geometry, bit for bit, as the other part and the serial run
    const CoarseMesh m = octahedron();
    const std::vector<label> part = splitByX(m);
    const locallyFoldingSphere geometry;
    for (int levels : {1, 2})
    {
        SCOPED_TRACE("levels " + std::to_string(levels));
        const FineSurface s0 = refinePartSurface(m, part, 0, &geometry, levels);
        const FineSurface s1 = refinePartSurface(m, part, 1, &geometry, levels);
        const FineSurface serial = refinePartSurface(m, {}, 0, &geometry, levels);
        const auto p0 = pointsById(s0);
        const auto p1 = pointsById(s1);
        const auto pSerial = pointsById(serial);
        label nSharedOff = 0;
        for (const auto& [id, x] : p0)
        {
            const auto it = p1.find(id);
            if (it != p1.end())
            {
                EXPECT_EQ(std::memcmp(&x, &it->second, sizeof(point3)), 0);
                nSharedOff += std::abs(magSqr(x) - 1) > 1e-12;
            }
        }
        EXPECT_GT(nSharedOff, 0) << "no shared point was left off: the test tests nothing";
        for (const auto* p : {&p0, &p1})
        {
            for (const auto& [id, x] : *p)
            {
                const auto it = pSerial.find(id);
                if (it != pSerial.end())
                {
                    EXPECT_EQ(std::memcmp(&x, &it->second, sizeof(point3)), 0);
                }
            }
        }
        // Every point left off is counted by one part
        EXPECT_EQ
        (
            s0.repair.nPointsOff + s1.repair.nPointsOff, serial.repair.nPointsOff
        );
    }
}


namespace
{

// Fine edges across which the two triangles are nearly back to back (their
// normals more than 155 degrees apart) where their coarse faces are not:
// the surface folds onto itself there
label edgesFoldedOntoThemselves
(
    const CoarseMesh& m,
    const coarsePartSurface& ps,
    const FineSurface& s,
    int levels
)
{
    auto unitNormal = [](const point3& a, const point3& b, const point3& c)
    {
        const vector3 n = cross(b - a, c - a);
        return (1/std::sqrt(magSqr(n)))*n;
    };
    const std::size_t perFace = std::size_t(1) << (2*levels);
    std::map<std::pair<label, label>, std::vector<std::pair<vector3, vector3>>> normalsOfEdge;
    for (std::size_t ti = 0; ti < s.triangles.size(); ++ti)
    {
        const triVerts& t = s.triangles[ti];
        const triVerts& f = ps.faces[ti/perFace];
        const vector3 n = unitNormal(s.points[t[0]], s.points[t[1]], s.points[t[2]]);
        const vector3 nc = unitNormal(m.points[f[0]], m.points[f[1]], m.points[f[2]]);
        for (int k = 0; k < 3; ++k)
        {
            const label a = t[k];
            const label b = t[(k + 1) % 3];
            normalsOfEdge[{std::min(a, b), std::max(a, b)}].push_back({n, nc});
        }
    }
    label nFolded = 0;
    for (const auto& e : normalsOfEdge)
    {
        if (e.second.size() == 2)
        {
            const double fineCos = dot(e.second[0].first, e.second[1].first);
            const double coarseCos = dot(e.second[0].second, e.second[1].second);
            nFolded += fineCos < -0.9 && fineCos < coarseCos - 0.01;
        }
    }
    return nFolded;
}

} // End anonymous namespace


TEST(surfaceRefinement, thinBodyWhoseSurfaceFoldsOntoItselfAcrossCoarseEdgesIsRepaired)
{
    // A needle thinner than the coarse cells: no fine triangle turns
    // against its own coarse face, yet projected edge midpoints land beyond
    // the neighbouring face's triangles (Netgen: "boundary mesh is
    // overlapping")
    const auto g = Geometry::New(testDataDir() + "/geometry/needleInBox.stl");
    const CoarseMesh m = g->coarseMesh(coarseMeshParameters(2.5, 0.3));
    const coarsePartSurface ps = partitionSurface(m, {}, 0);
    const boundaryEdgeSurfaces edges(m);
    const FineSurface folded = refineSurface(m, ps, edges, g.get(), 1, false);
    EXPECT_EQ(countFoldedTriangles(m, ps, folded, 1), 0);
    EXPECT_GT(edgesFoldedOntoThemselves(m, ps, folded, 1), 0);

    const FineSurface repaired = refinePartSurface(m, {}, 0, g.get(), 1);
    EXPECT_EQ(edgesFoldedOntoThemselves(m, ps, repaired, 1), 0);
    EXPECT_GT(repaired.repair.nPointsOff, 0);
    // A few points, off by less than the needle's radius
    EXPECT_LT(repaired.repair.nPointsOff, 20);
    EXPECT_LT(repaired.repair.maxDistance, 0.03);
}


namespace
{

// Two coarse tets sharing the face (0, 1, 3), in parts 0 and 1: tet 0
// stands on the boundary face (0, 1, 2) in the plane z = 0 and rises only
// to z = 0.05 y at that face, so it is a thin wedge along edge 0-1 (a
// coarse cell on a crease, as on OpenFOAM's motorBike's front tyre)
CoarseMesh wedgeOnTheInterface()
{
    CoarseMesh m;
    m.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 1, 0.05}, {0.5, 0.3, 1}};
    m.patches = {{"wall"}};
    m.tets = {{0, 1, 2, 3}, {0, 1, 3, 4}};
    const triVerts shared{0, 1, 3};
    for (const tetVerts& t : m.tets)
    {
        for (const triVerts& f : outwardTetFaces(t))
        {
            triVerts sorted = f;
            std::sort(sorted.begin(), sorted.end());
            if (sorted == shared) continue;
            const label surface = sorted == triVerts{0, 1, 2} ? 0 : 1;
            m.boundary.push_back({f, 0, surface});
        }
    }
    return m;
}

// The wedge's floor (surface 0) projects its points 0.2 up, through the
// face the wedge shares with the other part, without turning a triangle
// (a move along the floor's normal); everything else stays where it is
class liftedFloor : public analyticSphere
{
public:
    point3 projectToSurface(const point3& p, label s) const override
    {
        return s == 0 ? point3{p[0], p[1], p[2] + 0.2} : p;
    }
    point3 projectToEdge(const point3& p, label, label) const override
    {
        return p;
    }
};

label crossingCount(const FineSurface& s)
{
    const std::vector<label> crossing = crossingTriangles
    (
        s.points, s.triangles, std::vector<bool>(s.triangles.size(), true), true
    );
    return std::count_if(crossing.begin(), crossing.end(), [](label c) { return c != 0; });
}

} // End anonymous namespace


TEST(surfaceRefinement, boundaryFaceProjectedThroughThePartitionInterfaceOfItsCellStaysLinear)
{
    const CoarseMesh m = wedgeOnTheInterface();
    const std::vector<label> part{0, 1};
    const liftedFloor geometry;
    const int levels = 2;

    // Repaired for folds alone (no partition given), the floor's inside
    // runs through the interface: part 0's surface crosses itself
    const FineSurface unaware = refineSurface
    (
        m, partitionSurface(m, part, 0), boundaryEdgeSurfaces(m), &geometry, levels
    );
    EXPECT_EQ(countFoldedTriangles(m, partitionSurface(m, part, 0), unaware, levels), 0);
    EXPECT_GT(crossingCount(unaware), 0) << "nothing crosses: the test tests nothing";

    const FineSurface s0 = refinePartSurface(m, part, 0, &geometry, levels);
    EXPECT_EQ(crossingCount(s0), 0);
    // Linear like a fold: the floor's 3 inside points and the 9 on its edges
    EXPECT_EQ(s0.repair.nPointsOff, 12);
    const FineSurface s1 = refinePartSurface(m, part, 1, &geometry, levels);
    EXPECT_EQ(crossingCount(s1), 0);
}


// * * * * * * * * * * * Surfaces crossing before stage 4  * * * * * * * * * //

namespace
{

//- Icospheres of radius 1 as one partition surface, each on its own patch
//  ("ball0", "ball1", ...), centred at `centres`
FineSurface icospheresAt(const std::vector<point3>& centres, std::vector<meshPatch>& patches)
{
    FineSurface s;
    patches.clear();
    for (std::size_t k = 0; k < centres.size(); ++k)
    {
        const closedSurface ball = icosphere(2);
        const label offset = label(s.points.size());
        for (const point3& p : ball.points) s.points.push_back(p + centres[k]);
        for (const triVerts& t : ball.triangles)
        {
            s.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
            s.region.push_back(label(k));
            s.zone.push_back(0);
        }
        meshPatch patch;
        patch.name = "ball" + std::to_string(k);
        patches.push_back(patch);
    }
    return s;
}

} // End anonymous namespace


TEST(surfaceCrossings, aClosedSurfaceThatCrossesNothingPasses)
{
    std::vector<meshPatch> patches;
    const FineSurface s = icospheresAt({{0, 0, 0}, {3, 0, 0}}, patches);
    const tempDir dir("crossings");
    EXPECT_NO_THROW(checkSurfaceCrossings(s.points, s, patches, 0, dir/"failed.stl"));
    EXPECT_FALSE(std::filesystem::exists(dir/"failed.stl"));
}


TEST(surfaceCrossings, twoShellsThroughEachOtherStopWithThePlaceAndThePatches)
{
    // What HXT refused on the bullet's partition at r = 2 ("failed to
    // recover constrained lines/triangles") and Netgen too ("boundary mesh
    // is overlapping"), four attempts later
    std::vector<meshPatch> patches;
    const FineSurface s = icospheresAt({{0, 0, 0}, {1, 0, 0}}, patches);
    const tempDir dir("crossings");
    const std::string m = errorOf([&]
    {
        checkSurfaceCrossings(s.points, s, patches, 3, dir/"failed.stl");
    });
    EXPECT_HAS(m, "The surface of partition 3 crosses itself");
    EXPECT_HAS(m, "on patch ball0, through a triangle on patch ball1");
    EXPECT_HAS(m, "reduce maxCellSize");
    EXPECT_HAS(m, dir/"failed.stl");
    EXPECT_TRUE(std::filesystem::exists(dir/"failed.stl"));
    // The place named lies where the spheres cross: x = 0.5, radius 0.87
    const std::size_t at = m.find(" at (");
    ASSERT_NE(at, std::string::npos);
    double x = 0, y = 0, z = 0;
    ASSERT_EQ(std::sscanf(m.c_str() + at, " at (%lf %lf %lf)", &x, &y, &z), 3) << m;
    EXPECT_NEAR(x, 0.5, 0.2);
    EXPECT_NEAR(std::hypot(y, z), std::sqrt(0.75), 0.2);
}


TEST(surfaceCrossings, aCrossingOfLiftedPointsAsksForThinnerLayers)
{
    // Two balls apart, the second's points lifted (as stage 3b lifts a
    // wall's points to its layers' tops) into the first
    std::vector<meshPatch> patches;
    const FineSurface s = icospheresAt({{0, 0, 0}, {2.5, 0, 0}}, patches);
    std::vector<point3> lifted = s.points;
    for (std::size_t p = s.points.size()/2; p < s.points.size(); ++p)
    {
        lifted[p][0] -= 1.5;
    }
    const tempDir dir("crossings");
    EXPECT_FATAL
    (
        checkSurfaceCrossings(lifted, s, patches, 0, dir/"failed.stl"),
        "The tops of the prism layers cross there"
    );
}
