// Stages 2-5 across MPI ranks (run under mpiexec -np 1..4): interface
// vertices agree bit for bit on every rank holding them, and the global
// point numbers are unique and contiguous. The numbering rank by rank of
// points, cells and faces (prefix scans, starts, totals) with per-rank
// counts past 2^31 and 2^32: right with 64-bit labels, a stop with
// 32-bit ones.

#include "mpiTestMain.H"
#include "failTogether.H"
#include "globalNumbering.H"
#include "labelLimit.H"
#include "partitionedCube.H"
#include "procAddressing.H"
#include "testUtilities.H"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>

using namespace pmsh;

namespace
{

struct pointRecord
{
    barycentricId id;
    point3 position;
    label number;
    int surface;        // 1 for a surface point, 0 interior
};

std::vector<pointRecord> records
(
    const FineSurface& surface,
    const std::vector<label>& numbers
)
{
    std::vector<pointRecord> r;
    for (std::size_t p = 0; p < numbers.size(); ++p)
    {
        const bool onSurface = p < surface.points.size();
        r.push_back
        ({
            onSurface ? surface.ids[p] : barycentricId(),
            onSurface ? surface.points[p] : point3{0, 0, 0},
            numbers[p],
            onSurface
        });
    }
    return r;
}

// On the master: the ranks holding a surface point agree on its number and
// on its coordinates, bit for bit.
void expectHoldersAgree(const std::vector<std::vector<pointRecord>>& all)
{
    std::map<barycentricId, pointRecord> byId;
    for (const auto& rank : all)
    {
        for (const pointRecord& r : rank)
        {
            if (!r.surface)
            {
                continue;
            }
            auto [it, inserted] = byId.emplace(r.id, r);
            if (!inserted)
            {
                EXPECT_EQ(it->second.number, r.number) << r.id;
                EXPECT_EQ(std::memcmp(&it->second.position, &r.position, sizeof(point3)), 0)
                    << "coordinates of " << r.id << " differ between ranks";
            }
        }
    }
}


// On every rank, from an allreduce: each of the nGlobal numbers is
// carried by some point, every carrier of a number is the same point
// (its key: a surface point's barycentric id, an interior point's rank and
// index) and no point carries a number outside: unique and contiguous.
void expectUniqueAndContiguous
(
    const FineSurface& surface,
    const std::vector<label>& numbers,
    label nGlobal
)
{
    const int rank = test::world().rank();
    constexpr int nKey = 6;
    constexpr long long none = std::numeric_limits<long long>::max();
    std::vector<long long> smallest(nKey*nGlobal, none);
    std::vector<long long> largest(nKey*nGlobal, -none);
    for (std::size_t p = 0; p < numbers.size(); ++p)
    {
        const label n = numbers[p];
        if (n < 0 || n >= nGlobal)
        {
            // No return before the collective: the other ranks wait in it
            ADD_FAILURE() << "number " << numbers[p] << " of point " << p << " is out of range";
            continue;
        }
        std::array<long long, nKey> key{-1 - rank, static_cast<long long>(p), 0, 0, 0, 0};
        if (p < surface.points.size())
        {
            const barycentricId& id = surface.ids[p];
            key = {id.vertex[0], id.weight[0], id.vertex[1], id.weight[1], id.vertex[2], id.weight[2]};
        }
        for (int k = 0; k < nKey; ++k)
        {
            smallest[nKey*n + k] = std::min(smallest[nKey*n + k], key[k]);
            largest[nKey*n + k] = std::max(largest[nKey*n + k], key[k]);
        }
    }
    auto allReduce = [](std::vector<long long>& v, MPI_Op op)
    {
        const std::vector<long long> mine = v;
        MPI_Allreduce(mine.data(), v.data(), int(v.size()), MPI_LONG_LONG, op, MPI_COMM_WORLD);
    };
    allReduce(smallest, MPI_MIN);
    allReduce(largest, MPI_MAX);

    for (label n = 0; n < nGlobal; ++n)
    {
        ASSERT_NE(smallest[nKey*n], none) << "number " << n << " is carried by no point";
        for (int k = 0; k < nKey; ++k)
        {
            ASSERT_EQ(smallest[nKey*n + k], largest[nKey*n + k])
                << "number " << n << " is carried by different points";
        }
    }
}

} // End anonymous namespace


TEST(parallelNumbering, everyRankGetsANonEmptyClosedPartSurface)
{
    const test::partitionedSurface s = test::partitionedCube(5, 1);
    EXPECT_GT(s.part.triangles.size(), 0u);
    // Euler for a closed genus-0 surface: V = 2 + F/2
    EXPECT_EQ(s.part.points.size(), 2 + s.part.triangles.size()/2);
}


TEST(parallelNumbering, globalPointIdsAreUniqueAndContiguousAndSharedPointsAgree)
{
    const Communicator& comm = test::world();
    const test::partitionedSurface s = test::partitionedCube(5, 2);
    const label nInterior = 3 + 7*comm.rank();
    const label nLocal = label(s.part.points.size()) + nInterior;

    const globalPointNumbering numbering(comm, s.coarse, s.cellPart, s.part, nLocal);
    if (comm.size() > 1)
    {
        EXPECT_GT(comm.sum(std::int64_t(numbering.nShared())), 0);
    }
    expectUniqueAndContiguous(s.part, numbering.globalIds(), numbering.nGlobal());

    const auto all = test::gatherOnMaster(records(s.part, numbering.globalIds()));
    if (comm.master())
    {
        expectHoldersAgree(all);
    }
}


// Rank r's count in the tests below: past 2^31 on every rank, past 2^32
// from rank 1 on, and the ranks' sum past 2^32 from 1 rank on
std::int64_t largeCount(int r, int kind)
{
    return (std::int64_t(3) << 31) + (std::int64_t(r) << 32) + 1000*r + kind;
}

// The sum of largeCount(., kind) over ranks [0, n)
std::int64_t largeSum(int n, int kind)
{
    std::int64_t sum = 0;
    for (int r = 0; r < n; ++r)
    {
        sum += largeCount(r, kind);
    }
    return sum;
}

// The label-limit stop of a collective with counts past 2^31: every rank
// stops, the master says why, naming the exact (64-bit) total
template<class Call>
void expectLabelStop(Call call, const std::string& total)
{
    const Communicator& comm = test::world();
    try
    {
        call();
        ADD_FAILURE() << "no stop with 32-bit labels";
    }
    catch (const collectiveFailure& e)
    {
        EXPECT_EQ(e.print(), comm.master());
        EXPECT_HAS(e.message(), "too large for this OpenFOAM's 32-bit labels");
        EXPECT_HAS(e.message(), "it has " + total);
    }
}


TEST(parallelNumbering, rankByRankNumbersFromCountsPastTwoToThe31And32)
{
    const Communicator& comm = test::world();
    const int me = comm.rank();
    const std::int64_t below = largeSum(me, 0);
    const std::int64_t all = largeSum(comm.size(), 0);
    const std::int64_t first = std::int64_t(5) << 32;

    // The scan and the sum under it, whatever the label size
    EXPECT_EQ(comm.exclusiveScan(largeCount(me, 0)), below);
    EXPECT_EQ(comm.sum(largeCount(me, 0)), all);

    if (labelBits == 64)
    {
        const globalRange points = numberRankByRank(comm, largeCount(me, 0), "points");
        EXPECT_EQ(points.start, below);
        EXPECT_EQ(points.end, all);

        // A block after another (procAddressing's patches after the faces)
        const globalRange faces = numberRankByRank(comm, largeCount(me, 0), "faces", first);
        EXPECT_EQ(faces.start, first + below);
        EXPECT_EQ(faces.end, first + all);
    }
    else
    {
        expectLabelStop
        (
            [&] { numberRankByRank(comm, largeCount(me, 0), "points"); },
            std::to_string(all) + " points"
        );
    }
}


TEST(parallelNumbering, procAddressingStartsFromCountsPastTwoToThe31And32)
{
    const Communicator& comm = test::world();
    const int me = comm.rank();
    // Cells, the block of internal faces, two physical patches
    const std::vector<std::int64_t> patches{largeCount(me, 2), largeCount(me, 3)};
    auto starts = [&]
    {
        return procAddressingStartsOf(comm, largeCount(me, 0), largeCount(me, 1), patches);
    };

    if (labelBits == 64)
    {
        const procAddressingStarts s = starts();
        const int n = comm.size();
        EXPECT_EQ(s.cell, largeSum(me, 0));
        EXPECT_EQ(s.internalFace, largeSum(me, 1));
        ASSERT_EQ(s.patchFace.size(), 2u);
        // Patch faces after all internal faces, rank by rank in each patch
        EXPECT_EQ(s.patchFace[0], largeSum(n, 1) + largeSum(me, 2));
        EXPECT_EQ(s.patchFace[1], largeSum(n, 1) + largeSum(n, 2) + largeSum(me, 3));
    }
    else
    {
        // The cells come first
        expectLabelStop(starts, std::to_string(largeSum(comm.size(), 0)) + " cells");
    }
}
