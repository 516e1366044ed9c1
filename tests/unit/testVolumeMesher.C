// Volume meshers: selection, Netgen and HXT on closed surfaces, bad
// surfaces rejected with FatalError, and the contract check of
// VolumeMesher::mesh on results that break it.

#include "testPaths.H"
#include "VolumeMesher.H"
#include "hxtBackends.H"
#include "tetFaceMatching.H"
#include "acrossFace.H"
#include "Geometry.H"
#include "netgenInterface.H"
#include "partitionCoarseMesh.H"
#include "surfaceRefinement.H"
#include "testMeshers.H"
#include "tetQualityPass.H"
#include "testUtilities.H"
#include "wallCells.H"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <set>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

const std::string dataDir = std::string(PMSH_TEST_DATA) + "/geometry/";


using surface = closedSurface;


//- The boundary of a coarse mesh as a closed surface: its points renumbered
//  in order of first use.
surface boundarySurface(const CoarseMesh& m)
{
    surface s;
    std::map<label, label> index;
    for (const auto& f : m.boundary)
    {
        triVerts t;
        for (int k = 0; k < 3; ++k)
        {
            auto it = index.find(f.v[k]);
            if (it == index.end())
            {
                it = index.emplace(f.v[k], label(s.points.size())).first;
                s.points.push_back(m.points[f.v[k]]);
            }
            t[k] = it->second;
        }
        s.triangles.push_back(t);
    }
    return s;
}


//- Six times the volume a closed surface encloses.
double enclosed6(const closedSurface& c)
{
    double v = 0;
    for (const triVerts& t : c.triangles)
    {
        v += dot(c.points[t[0]], cross(c.points[t[1]], c.points[t[2]]));
    }
    return v;
}


} // End anonymous namespace


TEST(VolumeMesher, selection)
{
    EXPECT_EQ(VolumeMesher::names(), (std::vector<std::string>{"netgen", "hxt"}));
    EXPECT_EQ(VolumeMesher::New("netgen")->name(), "netgen");
    EXPECT_EQ(VolumeMesher::New("hxt")->name(), "hxt");
    const auto all = VolumeMesher::NewAll("hxt");
    ASSERT_EQ(all.size(), 2u);
    EXPECT_EQ(all[0]->name(), "hxt");
    EXPECT_EQ(all[1]->name(), "netgen");
    const std::string m = errorOf([]{ VolumeMesher::New("tetgen"); });
    EXPECT_NE(m.find("Unknown volumeMesher \"tetgen\""), std::string::npos) << m;
    EXPECT_NE(m.find("netgen"), std::string::npos) << m;
    EXPECT_NE(m.find("hxt"), std::string::npos) << m;
}


TEST(netgenVolumeMesher, coarseSphereBoundary)
{
    auto g = Geometry::New(dataDir + "sphere.geo");
    const surface s = boundarySurface(g->coarseMesh({0.5, 0.3}));

    auto mesher = VolumeMesher::New("netgen");
    volumeMeshParameters p;
    p.maxCellSize = 0.5;
    const TetMesh m = mesher->mesh(s.points, s.triangles, p);
    EXPECT_GT(m.tets.size(), s.triangles.size()/3);

    // Deterministic: the same input gives the same mesh
    const TetMesh m2 = mesher->mesh(s.points, s.triangles, p);
    EXPECT_EQ(m2.tets, m.tets);
    ASSERT_EQ(m2.points.size(), m.points.size());
    EXPECT_EQ(std::memcmp(m.points.data(), m2.points.data(), m.points.size()*sizeof(point3)), 0);
}


TEST(netgenVolumeMesher, fillsARefinedSphereExactlyWithPositiveTetsOfBoundedShape)
{
    // 5120 triangles (icosphere, 4 levels), graded interior. Checked here
    // from the points and tets alone, apart from VolumeMesher::mesh's own
    // contract check.
    const surface s = icosphere(4);
    volumeMeshParameters p;
    p.grading = 0.3;
    const TetMesh m = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, p);

    ASSERT_GT(m.points.size(), s.points.size()) << "no interior points";
    for (std::size_t i = 0; i < s.points.size(); ++i)
    {
        ASSERT_EQ(m.points[i], s.points[i]) << "surface point " << i;
    }

    // Positive tets that add up to the volume the surface encloses
    double enclosed = 0;
    for (const triVerts& t : s.triangles)
    {
        enclosed += dot(s.points[t[0]], cross(s.points[t[1]], s.points[t[2]]))/6;
    }
    double filled = 0;
    for (const tetVerts& t : m.tets)
    {
        const point3 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]], &d = m.points[t[3]];
        const double v = dot(b - a, cross(c - a, d - a))/6;
        ASSERT_GT(v, 0) << "tet " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3];
        filled += v;
    }
    EXPECT_NEAR(filled, enclosed, 1e-12*enclosed);

    // Every face twice, once from each side, but the surface's triangles:
    // once, outward
    std::map<triVerts, int> faces;      // oriented, smallest point first
    auto rotated = [](const triVerts& f)
    {
        const int k = int(std::min_element(f.begin(), f.end()) - f.begin());
        return triVerts{f[k], f[(k + 1)%3], f[(k + 2)%3]};
    };
    for (const tetVerts& t : m.tets)
    {
        for (const triVerts& f :
            {triVerts{t[0], t[2], t[1]}, triVerts{t[0], t[1], t[3]},
             triVerts{t[0], t[3], t[2]}, triVerts{t[1], t[2], t[3]}})
        {
            ++faces[rotated(f)];
        }
    }
    std::set<triVerts> boundary;
    for (const auto& [f, n] : faces)
    {
        ASSERT_EQ(n, 1) << "face used " << n << " times from one side";
        if (!faces.count(rotated({f[0], f[2], f[1]})))
        {
            boundary.insert(f);
        }
    }
    std::size_t notOnTheBoundary = 0;
    for (const triVerts& t : s.triangles)
    {
        notOnTheBoundary += !boundary.count(rotated(t));
    }
    EXPECT_EQ(notOnTheBoundary, 0u);
    EXPECT_EQ(boundary.size(), s.triangles.size());

    // No point left unused
    std::vector<bool> used(m.points.size(), false);
    for (const tetVerts& t : m.tets)
    {
        for (label p : t) used[p] = true;
    }
    EXPECT_EQ(std::count(used.begin(), used.end(), false), 0);

    // Shape: dihedral angles between 10 and 160 degrees (Netgen gives
    // about 22 and 141 here)
    double minDihedral = 180, maxDihedral = 0;
    for (const tetVerts& t : m.tets)
    {
        for (int i = 0; i < 4; ++i)
        {
            for (int j = i + 1; j < 4; ++j)
            {
                // The edge opposite (i, j) and the two faces on it
                int k = 0;
                while (k == i || k == j) ++k;
                int l = 6 - i - j - k;
                const point3& e0 = m.points[t[k]];
                const vector3 e = m.points[t[l]] - e0;
                const vector3 u = m.points[t[i]] - e0, w = m.points[t[j]] - e0;
                const vector3 nu = cross(e, u), nw = cross(e, w);
                const double cosAngle = dot(nu, nw)/std::sqrt(magSqr(nu)*magSqr(nw));
                const double angle = std::acos(std::max(-1.0, std::min(1.0, cosAngle)))*180/M_PI;
                minDihedral = std::min(minDihedral, angle);
                maxDihedral = std::max(maxDihedral, angle);
            }
        }
    }
    EXPECT_GT(minDihedral, 10);
    EXPECT_LT(maxDihedral, 160);
}


TEST(netgenVolumeMesher, badSurfaces)
{
    const surface good = icosphere(1);
    auto mesher = VolumeMesher::New("netgen");
    volumeMeshParameters p;

    {
        // A hole: one triangle removed
        surface s = good;
        s.triangles.pop_back();
        EXPECT_FATAL(mesher->mesh(s.points, s.triangles, p), "is not closed");

        // Netgen itself, without the check, fails with an exception that
        // becomes a FatalError (not a crash)
        const std::string m = errorOf([&]
        {
            ng::surfaceVolumeMesh(s.points, s.triangles, ng::meshParameters(), "a sphere with a hole");
        });
        EXPECT_NE(m.find("Netgen failed to mesh the volume of a sphere with a hole"), std::string::npos) << m;
    }
    {
        // Inverted: every triangle points inward
        surface s = good;
        for (auto& t : s.triangles) std::swap(t[1], t[2]);
        EXPECT_FATAL(mesher->mesh(s.points, s.triangles, p), "negative");

        // Netgen itself: "too many attempts", as a FatalError
        EXPECT_FATAL
        (
            ng::surfaceVolumeMesh(s.points, s.triangles, ng::meshParameters(), "an inverted sphere"),
            "Netgen failed to mesh the volume of an inverted sphere"
        );
    }
    {
        // One triangle flipped
        surface s = good;
        std::swap(s.triangles[3][1], s.triangles[3][2]);
        EXPECT_FATAL(mesher->mesh(s.points, s.triangles, p), "inconsistently oriented");
    }
    {
        // A point no triangle uses: Netgen would renumber
        surface s = good;
        s.points.push_back({5, 5, 5});
        EXPECT_FATAL(mesher->mesh(s.points, s.triangles, p), "is used by no triangle");
    }
    {
        surface s = good;
        s.triangles[0][0] = 1000;
        EXPECT_FATAL(mesher->mesh(s.points, s.triangles, p), "refers to point 1000");
    }

    // After all these failures Netgen still works
    EXPECT_NO_THROW(mesher->mesh(good.points, good.triangles, p));
}


TEST(netgenVolumeMesher, optimisesAfterTheAdvancingFrontRecovers)
{
    // This partition surface (found by a scan of the tutorials) sends
    // Netgen 6.2's MeshVolume down its failure path ("Call remove
    // problem"), which leaves the tets flagged fixed: the optimiser then
    // removed no cells, 5931 tets instead of 4421 (4001-4069 for the same
    // surface with its points shuffled). See src/netgen/netgenSurfaceVolumeMesh.C.
    auto g = Geometry::New
    (
        std::string(PMSH_SOURCE_DIR) + "/tutorials/sphereSTL/constant/geometry/sphere.stl"
    );
    const CoarseMesh coarse = g->coarseMesh({0.4, 0.3});
    const std::vector<label> cellPart = partitionCells(coarse, 3);
    const FineSurface s = refinePartSurface(coarse, cellPart, 2, g.get(), 2);
    volumeMeshParameters p;
    p.maxCellSize = 0.1;
    p.grading = 0.3;
    const TetMesh m = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, p);
    EXPECT_LT(m.tets.size(), 5000u);
}


TEST(hxtVolumeMesher, partitionSurfacesWithEdgesLongerThanTheFineSize)
{
    // Partition interfaces are refined coarse interior faces, whose edges
    // exceed maxCellSize: at r = 2 they are longer than the fine size.
    // Gmsh 4.8.4 crashed on every such surface of this sphere when the fine
    // size was its Mesh.MeshSizeMax (hxtVolumeMesher.C)
    const double maxCellSize = 0.3;
    const int levels = 2;
    auto g = Geometry::New(dataDir + "sphere.geo");
    const CoarseMesh coarse = g->coarseMesh({maxCellSize, 0.3});
    const std::vector<label> cellPart = partitionCells(coarse, 2);
    volumeMeshParameters p;
    p.maxCellSize = maxCellSize/(1 << levels);
    auto mesher = VolumeMesher::New("hxt");
    for (label part = 0; part < 2; ++part)
    {
        const FineSurface s = refinePartSurface(coarse, cellPart, part, g.get(), levels);
        double longest = 0;
        for (const triVerts& t : s.triangles)
        {
            for (int k = 0; k < 3; ++k)
            {
                longest = std::max(longest, std::sqrt(magSqr(s.points[t[(k + 1)%3]] - s.points[t[k]])));
            }
        }
        ASSERT_GT(longest, 2*p.maxCellSize) << "partition " << part;
        EXPECT_NO_THROW(mesher->mesh(s.points, s.triangles, p));
    }
}


TEST(VolumeMesher, meshRejectsAResultThatBreaksTheContract)
{
    const surface s = icosphere(1);
    const TetMesh good = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, {});
    ASSERT_GT(good.points.size(), s.points.size()) << "no interior point";
    auto meshGiven = [&](const TetMesh& m)
    {
        return givenMeshMesher(m).mesh(s.points, s.triangles, {});
    };
    EXPECT_NO_THROW(meshGiven(good));
    {
        TetMesh m = good;
        m.points[3][0] = std::nextafter(m.points[3][0], 2.0);
        EXPECT_FATAL(meshGiven(m), "does not keep surface point 3");
    }
    {
        TetMesh m = good;
        std::swap(m.tets[0][0], m.tets[0][1]);
        EXPECT_FATAL(meshGiven(m), "is inverted");
    }
    {
        TetMesh m = good;
        m.tets.pop_back();
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
    {
        // One tet with its own copy of an interior point: the volumes still
        // add up (multithreaded HXT in Gmsh 4.8 did this)
        TetMesh m = good;
        const label interior = label(s.points.size());
        for (tetVerts& t : m.tets)
        {
            auto it = std::find(t.begin(), t.end(), interior);
            if (it != t.end())
            {
                m.points.push_back(m.points[interior]);
                *it = label(m.points.size() - 1);
                break;
            }
        }
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
    EXPECT_FATAL(meshGiven(TetMesh()), "has no tets");
}


TEST(VolumeMesher, theContractChecksWhatTheBackendSaysIsAcrossEachFaceClaimByClaim)
{
    // The quality pass hands its own face matching to the contract
    // (TetMesh::across), which checks every claim in one pass instead of
    // matching the faces again: a claim that does not hold is refused as a
    // non-conforming mesh, as the matching would refuse the mesh itself
    const surface s = icosphere(1);
    TetMesh good = VolumeMesher::New("netgen")->mesh(s.points, s.triangles, {});
    const tetFaceMatch match = matchTetFaces(good.points.size(), good.tets, s.triangles);
    ASSERT_TRUE(match.fits());
    for (faceId id = 0; id < match.nTetFaces; ++id)
    {
        good.across.push_back(match.acrossOf(id));
    }
    const auto meshGiven = [&](const TetMesh& m)
    {
        return givenMeshMesher(m).mesh(s.points, s.triangles, {});
    };
    EXPECT_TRUE(meshGiven(good).across.empty()) << "checked, then cleared";

    // A tet across that does not claim this one back
    const label t = label(std::find_if(good.across.begin(), good.across.end(), [](label a) { return a >= 0; }) - good.across.begin());
    {
        TetMesh m = good;
        m.across[t] = m.across[t] == 0 ? 1 : 0;
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
    // A boundary face said to be another surface triangle, or none
    const label b = label(std::find_if(good.across.begin(), good.across.end(), isAcrossBoundary) - good.across.begin());
    {
        TetMesh m = good;
        m.across[b] = acrossBoundary((boundaryAcross(m.across[b]) + 1) % label(s.triangles.size()));
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
    {
        TetMesh m = good;
        m.across[b] = acrossBoundary(label(s.triangles.size()));
        EXPECT_FATAL(meshGiven(m), "on no surface triangle");
    }
    // An internal face said to be a surface triangle: its triangle is then
    // claimed twice or it is not the face
    {
        TetMesh m = good;
        m.across[t] = m.across[b];
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
    // The tets wrong and the claims unchanged: the claims no longer hold
    {
        TetMesh m = good;
        m.tets.pop_back();
        m.across.resize(4*m.tets.size());
        EXPECT_FATAL(meshGiven(m), "is not conforming");
    }
}


TEST(VolumeMesher, meshRejectsASliverThatCheckMeshWouldFail)
{
    // One positive tet, 1e-5 high over a unit triangle: its volume is
    // positive, its aspect ratio (checkMesh's) far above 1000
    TetMesh sliver;
    sliver.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1e-5}};
    sliver.tets = {{0, 1, 2, 3}};
    std::vector<triVerts> surface;
    for (int f = 0; f < 4; ++f)
    {
        surface.push_back(tetFace(sliver.tets[0], f));
    }
    EXPECT_FATAL
    (
        givenMeshMesher(sliver).mesh(sliver.points, surface, {}),
        "is a sliver that checkMesh would reject"
    );

    // The same tet 0.1 high is a fair cell
    sliver.points[3][2] = 0.1;
    EXPECT_NO_THROW(givenMeshMesher(sliver).mesh(sliver.points, surface, {}));
}


TEST(hxtVolumeMesher, surfacesOfSeveralShellsWithHolesAndApartParts)
{
    // A partition around the body of a body-in-box domain is bounded by
    // two shells, the inner one pointing into the body; a partition may
    // also be two separate parts. One surface loop around all of them made
    // HXT fail, and every such partition went to Netgen.
    const closedSurface outer = icosphere(2);
    closedSurface s = outer;
    const auto addShell = [&s](const closedSurface& c, double scale, const point3& shift, bool flip)
    {
        const label offset = label(s.points.size());
        for (const point3& p : c.points) s.points.push_back(scale*p + shift);
        for (triVerts t : c.triangles)
        {
            if (flip) std::swap(t[1], t[2]);
            s.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
        }
    };
    addShell(icosphere(1), 0.3, {0, 0, 0}, true);       // the body: a hole
    addShell(outer, 1, {3, 0, 0}, false);               // a part apart
    addShell(icosphere(1), 0.3, {3, 0, 0}, true);       // with its own hole

    volumeMeshParameters p;
    p.maxCellSize = 0.2;
    const TetMesh m = VolumeMesher::New("hxt")->mesh(s.points, s.triangles, p);

    // The tets fill the two balls less their holes: their volume is the
    // surface's (the contract check in mesh() has already seen every
    // triangle the face of one tet)
    double volume6 = 0;
    for (const tetVerts& t : m.tets)
    {
        volume6 += tetVolume6(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
    }
    const double ball6 = enclosed6(outer);
    const double hole6 = 0.3*0.3*0.3*enclosed6(icosphere(1));
    EXPECT_NEAR(volume6, enclosed6(s), 1e-9*ball6);
    EXPECT_NEAR(volume6, 2*(ball6 - hole6), 1e-9*ball6);
}


namespace
{

//- An icosphere around a hole, an icosphere turned inside out: the
//  domain of a body in a box
closedSurface ballAroundAHole
(
    int levels, double radius, int holeLevels, double holeRadius
)
{
    closedSurface s = icosphere(levels);
    for (point3& p : s.points) p = radius*p;
    const closedSurface hole = icosphere(holeLevels);
    const label offset = label(s.points.size());
    for (const point3& p : hole.points) s.points.push_back(holeRadius*p);
    for (triVerts t : hole.triangles)
    {
        s.triangles.push_back({t[0] + offset, t[2] + offset, t[1] + offset});
    }
    return s;
}


//- An icosphere of radius 1 with a hole of radius 0.4 (the body of a
//  body-in-box partition)
closedSurface ballWithAHole()
{
    return ballAroundAHole(3, 1, 2, 0.4);
}


//- What both ways into HXT must give before the quality pass: the surface
//  points kept, positive tets, every surface triangle the face of a tet,
//  and the tets' volumes adding up to the enclosed volume (no tet in the
//  hole, none outside)
void expectTheSurfaceFilled(const closedSurface& s, const TetMesh& m)
{
    ASSERT_GT(m.points.size(), s.points.size());
    for (std::size_t i = 0; i < s.points.size(); ++i)
    {
        ASSERT_EQ(m.points[i], s.points[i]) << "surface point " << i;
    }
    double volume6 = 0;
    std::set<std::array<label, 3>> faces;
    for (const tetVerts& t : m.tets)
    {
        const double v = tetVolume6(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
        ASSERT_GT(v, 0);
        volume6 += v;
        for (int f = 0; f < 4; ++f)
        {
            triVerts tri = tetFace(t, f);
            std::sort(tri.begin(), tri.end());
            faces.insert(tri);
        }
    }
    EXPECT_NEAR(volume6, enclosed6(s), 1e-9*enclosed6(s));
    for (triVerts t : s.triangles)
    {
        std::sort(t.begin(), t.end());
        EXPECT_TRUE(faces.count(t)) << "a surface triangle is no tet's face";
    }
}


//- Mean cell volume inside and outside a ball
std::pair<double, double> meanVolumeInAndOut(const TetMesh& m, const point3& centre, double radius)
{
    double in = 0, out = 0;
    std::size_t nIn = 0, nOut = 0;
    for (const tetVerts& t : m.tets)
    {
        const point3 c = 0.25*(m.points[t[0]] + m.points[t[1]] + m.points[t[2]] + m.points[t[3]]);
        const double v = tetVolume6(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
        if (magSqr(c - centre) < radius*radius) { in += v; ++nIn; } else { out += v; ++nOut; }
    }
    return {in/std::max<std::size_t>(nIn, 1), out/std::max<std::size_t>(nOut, 1)};
}

} // End anonymous namespace


TEST(hxtVolumeMesher, bothWaysIntoHxtFillABallAroundAHoleAlike)
{
    const closedSurface s = ballWithAHole();
    const shellVolumes v = findShellVolumes(s.points, s.triangles);
    ASSERT_EQ(v.volumes.size(), 1u);
    ASSERT_EQ(v.volumes[0].size(), 2u) << "the outer shell and its hole";
    volumeMeshParameters p;
    p.maxCellSize = 0.1;

    const TetMesh viaGmsh = gmshModelMesh(s.points, s.triangles, v, p);
    expectTheSurfaceFilled(s, viaGmsh);
    if (!hxtLibraryAvailable())
    {
        GTEST_SKIP() << "Gmsh " << gmshVersion() << " is not 4.8: HXT is reached through Gmsh's model only";
    }
    const TetMesh direct = hxtLibraryMesh(s.points, s.triangles, v, p);
    expectTheSurfaceFilled(s, direct);
    // The same algorithm and sizes, another insertion order
    const double ratio = double(direct.tets.size())/double(viaGmsh.tets.size());
    EXPECT_GT(ratio, 0.9) << direct.tets.size() << " against " << viaGmsh.tets.size();
    EXPECT_LT(ratio, 1.1) << direct.tets.size() << " against " << viaGmsh.tets.size();
}


TEST(hxtVolumeMesher, calledDirectlyHxtSaysWhichTetIsAcrossEachFaceAsMatchingFindsIt)
{
    if (!hxtLibraryAvailable())
    {
        GTEST_SKIP() << "Gmsh " << gmshVersion() << " is not 4.8: HXT is reached through Gmsh's model only";
    }
    // Two shells, and HXT's optimiser on: it deletes and adds tets, and
    // its adjacency must still hold once the tets outside are dropped
    const closedSurface s = ballWithAHole();
    const shellVolumes v = findShellVolumes(s.points, s.triangles);
    volumeMeshParameters p;
    p.maxCellSize = 0.1;
    p.optimisationSteps = 1;
    const TetMesh m = hxtLibraryMesh(s.points, s.triangles, v, p);
    ASSERT_EQ(m.tetsAcross.size(), 4*m.tets.size());

    const tetFaceMatch match = matchTetFaces(m.points.size(), m.tets, s.triangles);
    ASSERT_TRUE(match.fits()) << match.problems;
    label nSurfaceFaces = 0;
    for (std::size_t id = 0; id < m.tetsAcross.size(); ++id)
    {
        const label matched = match.acrossOf(faceId(id));
        const label expected = isAcrossBoundary(matched) ? -1 : matched;
        ASSERT_EQ(m.tetsAcross[id], expected) << "tet " << id/4 << " face " << id % 4;
        nSurfaceFaces += expected < 0;
    }
    EXPECT_EQ(nSurfaceFaces, label(s.triangles.size()));

    // The quality pass started from it does what it does from its own
    TetMesh seeded = m;
    TetMesh unseeded = m;
    unseeded.tetsAcross.clear();
    const label nFixed = label(s.points.size());
    improveWorstCells(seeded, nFixed, s.triangles, {}, 2);
    improveWorstCells(unseeded, nFixed, s.triangles, {}, 2);
    EXPECT_TRUE(seeded.tetsAcross.empty());
    EXPECT_EQ(seeded.tets, unseeded.tets);
    EXPECT_EQ(seeded.points, unseeded.points);
    EXPECT_EQ(seeded.across, unseeded.across);
}


TEST(hxtVolumeMesher, calledDirectlyHxtInsertsThePointsInAnotherOrderForAnotherAttempt)
{
    if (!hxtLibraryAvailable())
    {
        GTEST_SKIP() << "Gmsh " << gmshVersion() << " is not 4.8: HXT is reached through Gmsh's model only";
    }
    // A retry must not repeat a walk in circles (hxtLibrary.C): each
    // attempt's pointOrder gives HXT the points in another order, so
    // another mesh of the same surface, and the same one again for the
    // same order
    const closedSurface s = icosphere(3);
    const shellVolumes v = findShellVolumes(s.points, s.triangles);
    volumeMeshParameters p;
    p.maxCellSize = 0.15;
    const TetMesh first = hxtLibraryMesh(s.points, s.triangles, v, p);
    p.pointOrder = 1;
    const TetMesh second = hxtLibraryMesh(s.points, s.triangles, v, p);
    const TetMesh secondAgain = hxtLibraryMesh(s.points, s.triangles, v, p);
    expectTheSurfaceFilled(s, first);
    expectTheSurfaceFilled(s, second);
    EXPECT_NE(first.points, second.points);
    EXPECT_EQ(second.points, secondAgain.points);
    EXPECT_EQ(second.tets, secondAgain.tets);
}


TEST(hxtVolumeMesher, bothWaysIntoHxtRefineInsideARefinementRegion)
{
    const closedSurface s = icosphere(3);
    const shellVolumes v = findShellVolumes(s.points, s.triangles);
    volumeMeshParameters p;
    p.maxCellSize = 0.15;
    sizeRegion ball;
    ball.type = sizeRegion::shape::sphere;
    ball.centre = {0.2, 0, 0};
    ball.radius = 0.4;
    ball.size = 0.04;
    p.regions = {ball};
    // Netgen's size tree sets a size where it has none below 1.2 times it
    const ng::sizeField sizes = hxtSizeField(s.points, s.triangles, p);
    EXPECT_LE(sizes({0.2, 0.1, 0}), 1.2*0.04);
    EXPECT_GT(sizes({-0.7, 0, 0}), 1.2*0.04);
    EXPECT_LE(sizes({-0.7, 0, 0}), 0.15);

    std::vector<TetMesh> meshes{gmshModelMesh(s.points, s.triangles, v, p)};
    if (hxtLibraryAvailable())
    {
        meshes.push_back(hxtLibraryMesh(s.points, s.triangles, v, p));
    }
    for (const TetMesh& m : meshes)
    {
        // (0.15/0.04)^3 = 53 times smaller cells where the region is; the
        // cells outside it grow to maxCellSize by `grading` (10 times the
        // volume of those inside on average, 26 times without grading)
        const auto [in, out] = meanVolumeInAndOut(m, ball.centre, 0.8*ball.radius);
        EXPECT_LT(in, out/6) << "in " << in << ", out " << out;
    }
}


TEST(hxtVolumeMesher, calledDirectlyHxtMeshesTheSameSurfaceTheSameWayWhateverTheHeap)
{
    // Through Gmsh's model, Gmsh 4.8 orders the nodes by address, so a
    // forked rank would mesh differently from run to run: that is why such
    // meshers run in a fresh process. Called directly, HXT must not need it.
    if (!hxtLibraryAvailable())
    {
        EXPECT_TRUE(VolumeMesher::New("hxt")->dependsOnTheHeap());
        GTEST_SKIP() << "Gmsh " << gmshVersion() << " is not 4.8: HXT is reached through Gmsh's model only";
    }
    EXPECT_FALSE(VolumeMesher::New("hxt")->dependsOnTheHeap());
    const closedSurface s = icosphere(3);
    const shellVolumes v = findShellVolumes(s.points, s.triangles);
    volumeMeshParameters p;
    p.maxCellSize = 0.08;
    const TetMesh first = hxtLibraryMesh(s.points, s.triangles, v, p);
    // The heap used otherwise in between: blocks of many sizes, every
    // other one kept
    std::vector<std::vector<double>> kept;
    for (std::size_t n = 1; n < 3000; n += 7)
    {
        std::vector<double> block(n, 1.0);
        if (n % 2) kept.push_back(std::move(block));
    }
    const TetMesh second = hxtLibraryMesh(s.points, s.triangles, v, p);
    EXPECT_EQ(first.points, second.points);
    EXPECT_EQ(first.tets, second.tets);
}



namespace
{

//- A ball of radius 0.5 (2562 points, edges about 0.04) in a sphere of
//  radius 4 (162 points, edges about 1.2): a body in a box, the body's
//  size far below the far field's
closedSurface bodyInAFarField()
{
    return ballAroundAHole(2, 4, 4, 0.5);
}

volumeMeshParameters farFieldParameters(const std::string& mesher)
{
    volumeMeshParameters p;
    p.maxCellSize = 1;
    p.grading = 0.3;
    p.optimisationSteps = VolumeMesher::New(mesher)->defaultOptimisationSteps();
    return p;
}

} // End anonymous namespace


TEST(hxtVolumeMesher, leavesNoCellFlatAgainstTheBodyOfABodyInAFarField)
{
    // HXT put interior points 0.06-0.1 face edges above the ball of
    // sphereDrag, and simpleFoam diverged on those cells; Netgen's are no
    // flatter than 0.23 (a regular tet: 0.82)
    const closedSurface s = bodyInAFarField();
    const TetMesh m = VolumeMesher::New("hxt")->mesh(s.points, s.triangles, farFieldParameters("hxt"));
    EXPECT_GT(test::flattestWallCell(m, s.triangles), 0.2);
}


TEST(hxtVolumeMesher, gradesItsCellsAwayFromTheBodyAsNetgenDoes)
{
    // HXT alone interpolates the surface's sizes into the volume: 1.3-1.5x
    // Netgen's edges 0.2-8 away from sphereDrag's ball, and a drag 5-10 %
    // high. Held to Netgen's size field, each band of distance from the
    // body has mean edges within 15 % of Netgen's.
    const closedSurface s = bodyInAFarField();
    const std::vector<double> bands{0, 0.1, 0.25, 0.5, 1, 2, 3.4};
    const std::vector<double> netgen = test::meanEdgeByDistance
    (
        VolumeMesher::New("netgen")->mesh(s.points, s.triangles, farFieldParameters("netgen")),
        {0, 0, 0}, 0.5, bands
    );
    const std::vector<double> hxt = test::meanEdgeByDistance
    (
        VolumeMesher::New("hxt")->mesh(s.points, s.triangles, farFieldParameters("hxt")),
        {0, 0, 0}, 0.5, bands
    );
    for (std::size_t k = 0; k < netgen.size(); ++k)
    {
        EXPECT_NEAR(hxt[k]/netgen[k], 1, 0.15)
            << "distance " << bands[k] << " to " << bands[k + 1] << " from the body: mean edge "
            << hxt[k] << " (hxt) against " << netgen[k] << " (netgen)";
    }
}
