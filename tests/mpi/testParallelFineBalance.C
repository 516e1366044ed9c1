// Stage 6 across MPI ranks (run under mpiexec -np 1..4): fine tets dealt
// out unevenly move until every rank has its share, every tet is held by
// exactly one rank afterwards, each rank's tets and surface fit together,
// the processor faces of two ranks are the same faces, and the physical
// boundary is all there. Serially nothing moves and the same checks hold.

#include "mpiTestMain.H"
#include "coarseMesh.H"
#include "cubeMesh.H"
#include "fineCellBalance.H"
#include "meshPatch.H"
#include "tetFaceMatching.H"

#include <mpi.h>

#include <algorithm>
#include <map>
#include <set>

using namespace pmsh;

namespace
{

// The cube's tets dealt out by x of their centroid, rank r taking a share
// growing with r + 1 (rank P - 1 about twice the mean at P = 4): as a rank's
// mesh after stage 5, with global point numbers and its boundary
rankTets unevenShare(const CoarseMesh& cube, std::vector<int>& owner)
{
    const Communicator& comm = test::world();
    const int P = comm.size();
    const label nTets = cube.nCells();
    std::vector<std::pair<double, label>> byX;
    for (label t = 0; t < nTets; ++t)
    {
        double x = 0;
        for (label p : cube.tets[t]) x += cube.points[p][0];
        byX.push_back({x, t});
    }
    std::sort(byX.begin(), byX.end());
    owner.assign(nTets, 0);
    const double shares = 0.5*P*(P + 1);
    double start = 0;
    for (int r = 0; r < P; ++r)
    {
        const double end = start + (r + 1)/shares*nTets;
        for (label i = label(start + 0.5); i < label(end + 0.5) && i < nTets; ++i)
        {
            owner[byX[i].second] = r;
        }
        start = end;
    }

    rankTets mine;
    std::map<label, label> local;
    auto pointOf = [&](label g)
    {
        const auto it = local.emplace(g, label(mine.points.size()));
        if (it.second)
        {
            mine.points.push_back(cube.points[g]);
            mine.globalIds.push_back(g);
        }
        return it.first->second;
    };
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(cube);
    for (label t = 0; t < nTets; ++t)
    {
        if (owner[t] != comm.rank()) continue;
        const tetVerts& c = cube.tets[t];
        mine.tets.push_back({pointOf(c[0]), pointOf(c[1]), pointOf(c[2]), pointOf(c[3])});
        const auto faces = outwardTetFaces(mine.tets.back());
        for (int f = 0; f < 4; ++f)
        {
            const label nbr = neighbours[t][f];
            if (isBoundaryNeighbour(nbr) || owner[nbr] != comm.rank())
            {
                mine.triangles.push_back(faces[f]);
                mine.region.push_back
                (
                    isBoundaryNeighbour(nbr) ? 0 : interfaceRegion(owner[nbr])
                );
            }
        }
    }
    return mine;
}

} // End anonymous namespace


TEST(parallelFineBalance, unevenRanksEndWithinOnePercentEveryTetOnceAndTheFacesAgree)
{
    const Communicator& comm = test::world();
    const CoarseMesh cube = test::cubeMesh(8);
    std::vector<int> owner;
    rankTets mine = unevenShare(cube, owner);

    const fineBalanceStats stats = balanceFineCells(comm, mine, 0.01);
    if (comm.size() > 1)
    {
        EXPECT_GT(stats.before, 1.3);
        EXPECT_GT(stats.moved, 0);
    }
    EXPECT_LE(stats.after, 1.01 + 1.0*comm.size()/cube.nCells());
    const std::vector<double> counts = comm.allGather(double(mine.tets.size()));
    double total = 0;
    for (double c : counts) total += c;
    EXPECT_EQ(total, double(cube.nCells()));
    EXPECT_NEAR(*std::max_element(counts.begin(), counts.end())/(total/comm.size()), stats.after, 1e-12);

    // Every tet of the cube on exactly one rank, by its global points
    std::map<std::array<label, 4>, label> tetIndex;
    for (label t = 0; t < cube.nCells(); ++t)
    {
        std::array<label, 4> k;
        for (int i = 0; i < 4; ++i) k[i] = cube.tets[t][i];
        std::sort(k.begin(), k.end());
        tetIndex[k] = t;
    }
    std::vector<int> held(cube.nCells(), 0);
    for (const tetVerts& t : mine.tets)
    {
        std::array<label, 4> k;
        for (int i = 0; i < 4; ++i) k[i] = mine.globalIds[t[i]];
        std::sort(k.begin(), k.end());
        ASSERT_TRUE(tetIndex.count(k)) << "a tet that is not the cube's";
        ++held[tetIndex.at(k)];
        // Positive: the points travelled with their coordinates
        EXPECT_GT(tetVolume6(mine.points[t[0]], mine.points[t[1]], mine.points[t[2]], mine.points[t[3]]), 0);
    }
    MPI_Allreduce(MPI_IN_PLACE, held.data(), int(held.size()), MPI_INT, MPI_SUM, MPI_COMM_WORLD);
    EXPECT_EQ(std::count(held.begin(), held.end(), 1), label(held.size()));

    // This rank's tets and surface fit together
    EXPECT_TRUE(matchTetFaces(mine.points.size(), mine.tets, mine.triangles).fits());

    // The processor faces to a rank are that rank's processor faces to
    // this one; the physical boundary is the cube's, once
    std::vector<std::vector<globalFaceKey>> send(comm.size());
    std::map<int, std::set<globalFaceKey>> toRank;
    double nPhysical = 0;
    for (std::size_t i = 0; i < mine.triangles.size(); ++i)
    {
        if (isInterfaceRegion(mine.region[i]))
        {
            const int s = int(interfaceNeighbour(mine.region[i]));
            EXPECT_NE(s, comm.rank());
            const globalFaceKey k = globalKeyOf(mine.triangles[i], mine.globalIds);
            send[s].push_back(k);
            toRank[s].insert(k);
        }
        else
        {
            EXPECT_EQ(mine.region[i], 0);
            ++nPhysical;
        }
    }
    const auto received = comm.exchange(send);
    for (int s = 0; s < comm.size(); ++s)
    {
        const std::set<globalFaceKey> theirs(received[s].begin(), received[s].end());
        EXPECT_EQ(theirs, toRank[s]) << "processor faces between ranks " << comm.rank()
            << " and " << s << " differ";
    }
    EXPECT_EQ(comm.sum(nPhysical), double(cube.boundary.size()));
}
