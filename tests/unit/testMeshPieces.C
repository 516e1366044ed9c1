// Meshing in pieces (meshPieces.H): how many pieces there are, how they
// are grouped into ranks, each piece of a part closed on its own, and the
// pieces' meshes joining into one conforming mesh on the faces between
// them.

#include "meshPieces.H"
#include "partitionCoarseMesh.H"
#include "partitionSurface.H"
#include "partitionVolume.H"
#include "surfaceRefinement.H"
#include "cubeMesh.H"
#include "surfaceChecks.H"
#include "meshPatch.H"
#include "quietFoamInfo.H"
#include "testMeshers.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

using namespace pmsh;

namespace
{

// Quiet OpenFOAM's Info ("Selecting decompositionMethod ...")
class pieces : public test::quietFoamInfo {};

std::vector<label> piecesOfCube(const CoarseMesh& m, label nPieces)
{
    return partitionCells(m, nPieces);
}


//- Fails the first attempt on one piece, as a mesher may fail on one
//  surface; meshes everything else as HXT does
class failsOnePieceOnceMesher : public VolumeMesher
{
    const std::unique_ptr<VolumeMesher> hxt_ = VolumeMesher::New("hxt");
    const std::string piece_;

public:

    explicit failsOnePieceOnceMesher(label piece)
    :
        piece_(", piece " + std::to_string(piece))
    {}

    std::string name() const override { return "failsOnePieceOnce"; }

protected:

    std::string title() const override { return "The mesher that fails one piece once"; }

    TetMesh generate
    (
        const std::vector<point3>& points, const std::vector<triVerts>& triangles,
        const volumeMeshParameters& parameters
    ) const override
    {
        if (parameters.pointOrder == 0 && parameters.what.find(piece_) != std::string::npos)
        {
            throw FatalError("cannot mesh " + parameters.what);
        }
        return hxt_->mesh(points, triangles, parameters);
    }
};


//- The cube's coarse mesh in 3 pieces, one part: its fine surface at r = 1
struct cubeInPieces
{
    CoarseMesh coarse = test::cubeMesh(3);
    std::vector<label> cellPiece = partitionCells(coarse, 3);
    FineSurface surface = refinePartSurface(coarse, {}, 0, nullptr, 1, cellPiece);

    partitionVolumeResult mesh
    (
        std::vector<std::unique_ptr<VolumeMesher>> meshers,
        const std::string& failedFile
    ) const
    {
        volumeMeshParameters p;
        p.what = "partition 0";
        return meshVolumeInPieces
        (
            meshers, surface.points, surface.triangles,
            {surface.zone, {}, surface.piece, surface.ids}, p, failedFile, "Try another mesher."
        );
    }
};

} // End anonymous namespace


TEST_F(pieces, theNumberOfPiecesDependsOnTheMeshNotOnTheRanks)
{
    // 10.5 pieces' worth of cells: 11 pieces on 1, 2, 4, 8 and 11 ranks
    // (a piece a rank is still the same 11 pieces)
    for (label ranks : {1, 2, 4, 8, 11})
    {
        EXPECT_EQ(numberOfPieces(10.5e6, ranks, 1e6), 11) << ranks << " ranks";
    }
    // Less than a piece's worth a rank, or one piece: 0, one piece a rank
    // split by the case's own method, as without pieces
    EXPECT_EQ(numberOfPieces(10.5e6, 16, 1e6), 0);
    EXPECT_EQ(numberOfPieces(0.5e6, 2, 1e6), 0);
    EXPECT_EQ(numberOfPieces(0.5e6, 1, 1e6), 0);
    EXPECT_EQ(numberOfPieces(1.5e6, 2, 1e6), 2);
}


TEST_F(pieces, everyRankGetsAPieceAndEveryPieceOneRank)
{
    const CoarseMesh m = test::cubeMesh(5);
    for (const auto& [nPieces, nParts] : std::vector<std::pair<label, label>>{{3, 2}, {5, 4}, {9, 8}, {8, 8}, {7, 1}})
    {
        const std::vector<label> cellPiece = piecesOfCube(m, nPieces);
        const std::vector<label> pieceRank = groupPieces(m, cellPiece, nPieces, nParts);
        ASSERT_EQ(label(pieceRank.size()), nPieces);
        std::vector<label> piecesOf(nParts, 0);
        for (label r : pieceRank)
        {
            ASSERT_GE(r, 0);
            ASSERT_LT(r, nParts);
            ++piecesOf[r];
        }
        for (label r = 0; r < nParts; ++r)
        {
            EXPECT_GT(piecesOf[r], 0) << nPieces << " pieces on " << nParts << " ranks: rank " << r;
        }
    }
}


TEST_F(pieces, aPoorGroupingIsBalancedByMovingPiecesToNeighbouringParts)
{
    // Four even pieces in a ring, grouped 1 + 3 (as metis grouped a
    // layered bullet's): one piece moves, 2 + 2
    const std::vector<double> weight{1, 1, 1, 1};
    const std::vector<std::vector<label>> ring{{1, 3}, {0, 2}, {1, 3}, {0, 2}};
    std::vector<label> rank{0, 1, 1, 1};
    EXPECT_EQ(balancePieceGroups(weight, ring, 2, rank), 1);
    EXPECT_EQ(std::count(rank.begin(), rank.end(), 0), 2);

    // A move that would make the other part the heavier is not made:
    // 2 + 2 against 3 stays, as 2 against 2 + 3 would be worse
    const std::vector<std::vector<label>> all{{1, 2}, {0, 2}, {0, 1}};
    std::vector<label> uneven{0, 0, 1};
    EXPECT_EQ(balancePieceGroups({2, 2, 3}, all, 2, uneven), 0);
    EXPECT_EQ(uneven, (std::vector<label>{0, 0, 1}));

    // Pieces move only to a part holding a neighbour: a chain 0-1-2-3
    // grouped {0, 1, 2} and {3} gives 2 to part 1, not 0 or 1
    const std::vector<std::vector<label>> chain{{1}, {0, 2}, {1, 3}, {2}};
    std::vector<label> grouped{0, 0, 0, 1};
    EXPECT_EQ(balancePieceGroups(weight, chain, 2, grouped), 1);
    EXPECT_EQ(grouped, (std::vector<label>{0, 0, 1, 1}));

    // A part keeps one piece at least, and balanced groups stay as they are
    std::vector<label> one{0, 1};
    EXPECT_EQ(balancePieceGroups({5, 1}, {{1}, {0}}, 2, one), 0);
    std::vector<label> even{0, 0, 1, 1};
    EXPECT_EQ(balancePieceGroups(weight, ring, 2, even), 0);
}


TEST_F(pieces, aPartsPiecesAreClosedEachAndTheFacesBetweenThemComeTwiceReversedOffTheGeometry)
{
    const CoarseMesh m = test::cubeMesh(4);
    const label nPieces = 6;
    const std::vector<label> cellPiece = piecesOfCube(m, nPieces);
    const std::vector<label> pieceRank = groupPieces(m, cellPiece, nPieces, 2);
    std::vector<label> cellPart(cellPiece.size());
    for (std::size_t c = 0; c < cellPiece.size(); ++c)
    {
        cellPart[c] = pieceRank[cellPiece[c]];
    }

    for (label part = 0; part < 2; ++part)
    {
        const coarsePartSurface s = partitionSurface(m, cellPart, part, cellPiece);
        ASSERT_EQ(s.piece.size(), s.faces.size());
        std::map<label, std::vector<triVerts>> facesOf;
        std::set<triVerts> betweenPieces;
        for (std::size_t f = 0; f < s.faces.size(); ++f)
        {
            EXPECT_EQ(pieceRank[s.piece[f]], part);
            facesOf[s.piece[f]].push_back(s.faces[f]);
            if (isBetweenZones(s.region[f]))
            {
                EXPECT_EQ(s.surface[f], -1) << "a face between pieces is not projected";
                betweenPieces.insert(s.faces[f]);
            }
        }
        EXPECT_GT(betweenPieces.size(), 0u) << "part " << part << " holds one piece only";
        for (const triVerts& f : betweenPieces)
        {
            EXPECT_EQ(betweenPieces.count({f[0], f[2], f[1]}), 1u)
                << "a face between pieces comes once, not once from each side";
        }
        for (const auto& [piece, faces] : facesOf)
        {
            EXPECT_TRUE(test::closedManifold(faces)) << "piece " << piece;
        }
    }

    // Without pieces the part is one closed surface, as before
    const coarsePartSurface whole = partitionSurface(m, cellPart, 0);
    EXPECT_TRUE(whole.piece.empty());
    EXPECT_TRUE(test::closedManifold(whole.faces));
}


TEST_F(pieces, aPartMeshedInPiecesIsOneConformingMeshOfItsVolume)
{
    const CoarseMesh m = test::cubeMesh(3);
    const std::vector<label> cellPiece = piecesOfCube(m, 3);
    const FineSurface s = refinePartSurface(m, {}, 0, nullptr, 1, cellPiece);

    for (const std::string& backend : VolumeMesher::names())
    {
        volumeMeshParameters p;
        p.what = "partition 0";
        const partitionVolumeResult r = meshVolumeInPieces
        (
            VolumeMesher::NewAll(backend), s.points, s.triangles,
            {s.zone, {}, s.piece, s.ids}, p,
            (std::filesystem::path(::testing::TempDir())/"failedPieces.stl").string(), ""
        );
        EXPECT_EQ(r.nCalls, 3) << backend;
        EXPECT_LE(r.largestCall, r.nCells) << backend;
        EXPECT_TRUE(r.tetZone.empty()) << backend << ": pieces are not cellZones";

        // Its volume is the cube's, every tet positive
        double volume = 0;
        std::map<triVerts, int> uses;
        for (const tetVerts& t : r.mesh.tets)
        {
            const std::vector<point3>& x = r.mesh.points;
            const double v6 = tetVolume6(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
            EXPECT_GT(v6, 0) << backend;
            volume += v6/6;
            for (triVerts f : outwardTetFaces(t))
            {
                std::sort(f.begin(), f.end());
                ++uses[f];
            }
        }
        EXPECT_NEAR(volume, 1.0, 1e-9) << backend;

        // Conforming: a face is the cube's (one tet) or between two tets,
        // also where pieces meet; the faces of one tet are the cube's
        std::size_t nBoundary = 0;
        for (const auto& [f, n] : uses)
        {
            ASSERT_LE(n, 2) << backend;
            if (n == 1)
            {
                ++nBoundary;
                bool onSide = false;
                for (int d = 0; d < 3; ++d)
                {
                    for (double side : {0.0, 1.0})
                    {
                        onSide = onSide ||
                        (
                            r.mesh.points[f[0]][d] == side && r.mesh.points[f[1]][d] == side
                         && r.mesh.points[f[2]][d] == side
                        );
                    }
                }
                EXPECT_TRUE(onSide) << backend << ": a face of one tet inside the cube";
            }
        }
        EXPECT_EQ(nBoundary, m.boundary.size()*4) << backend;
    }
}


TEST_F(pieces, aPieceThatFailsIsRetriedAloneAndTheOthersKeepTheirFirstMesh)
{
    const cubeInPieces cube;
    const partitionVolumeResult r = cube.mesh
    (
        test::meshers(std::make_unique<failsOnePieceOnceMesher>(1)),
        (std::filesystem::path(::testing::TempDir())/"unused.stl").string()
    );
    EXPECT_EQ(r.nCalls, 3);
    EXPECT_EQ(r.attempts, 2) << "piece 1 needed a second attempt";
    EXPECT_HAS(r.failures, "piece 1:");
    EXPECT_HAS(r.failures, "cannot mesh partition 0, piece 1");
    EXPECT_EQ(r.failures.find("piece 0"), std::string::npos) << r.failures;
    EXPECT_EQ(r.failures.find("piece 2"), std::string::npos) << r.failures;
    double volume = 0;
    for (const tetVerts& t : r.mesh.tets)
    {
        const std::vector<point3>& x = r.mesh.points;
        volume += tetVolume6(x[t[0]], x[t[1]], x[t[2]], x[t[3]])/6;
    }
    EXPECT_NEAR(volume, 1.0, 1e-9);
}


TEST_F(pieces, aPieceThatFailsEverywhereIsNamedAndItsSurfaceWritten)
{
    const cubeInPieces cube;
    const std::string file =
        (std::filesystem::path(::testing::TempDir())/"failedPartition0.stl").string();
    const std::string pieceFile =
        (std::filesystem::path(::testing::TempDir())/"failedPartition0_piece0.stl").string();
    std::filesystem::remove(pieceFile);
    const std::string m = test::errorOf([&]
    {
        cube.mesh(test::meshers(std::make_unique<test::failingMesher>()), file);
    });
    EXPECT_HAS(m, "Volume meshing of partition 0, piece 0 failed in all");
    EXPECT_HAS(m, pieceFile);
    EXPECT_HAS(m, "Try another mesher.");

    // The file holds that piece's closed surface alone
    std::size_t pieceTriangles = 0;
    for (label p : cube.surface.piece)
    {
        pieceTriangles += p == 0;
    }
    std::ifstream is(pieceFile);
    ASSERT_TRUE(is.good()) << pieceFile;
    std::size_t facets = 0;
    for (std::string w; is >> w; ) facets += (w == "facet");
    EXPECT_EQ(facets, pieceTriangles);
    EXPECT_LT(facets, cube.surface.triangles.size());
}
