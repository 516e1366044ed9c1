// Stages 2-5 across MPI ranks (run under mpiexec -np 1..4): interface
// vertices agree bit for bit on every rank holding them, and the global
// point numbers are unique and contiguous, also beyond 2^32.

#include "mpiTestMain.H"
#include "coarseMesh.H"
#include "cubeMesh.H"
#include "globalNumbering.H"
#include "partitionCoarseMesh.H"
#include "surfaceRefinement.H"

#include <mpi.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <map>

using namespace pmsh;

namespace
{

struct sharedSurface
{
    CoarseMesh coarse;
    std::vector<label> cellPart;
    FineSurface surface;
};

// Master builds the coarse mesh, every rank receives it: as pmshFoam does
sharedSurface refinedPart(int levels)
{
    const Communicator& comm = test::world();
    sharedSurface s;
    if (comm.master())
    {
        s.coarse = test::cubeMesh(5);
    }
    broadcastCoarseMesh(comm, s.coarse);
    s.cellPart = partitionCoarseMesh(comm, s.coarse);
    s.surface = refineSurface
    (
        s.coarse, partitionSurface(s.coarse, s.cellPart, comm.rank()),
        boundaryEdgeSurfaces(s.coarse), nullptr, levels
    );
    return s;
}

struct pointRecord
{
    barycentricId id;
    point position;
    globalLabel number;
    int surface;        // 1 for a surface point, 0 interior
};

std::vector<pointRecord> records
(
    const FineSurface& surface,
    const std::vector<globalLabel>& numbers
)
{
    std::vector<pointRecord> r;
    for (std::size_t p = 0; p < numbers.size(); ++p)
    {
        const bool onSurface = p < surface.points.size();
        r.push_back
        ({
            onSurface ? surface.ids[p] : barycentricId(),
            onSurface ? surface.points[p] : point{0, 0, 0},
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
                EXPECT_EQ(std::memcmp(&it->second.position, &r.position, sizeof(point)), 0)
                    << "coordinates of " << r.id << " differ between ranks";
            }
        }
    }
}


// On every rank, from an allreduce: each of the nGlobal numbers from base
// on is carried by some point, every carrier of a number is the same point
// (its key: a surface point's barycentric id, an interior point's rank and
// index) and no point carries a number outside: unique and contiguous.
void expectUniqueAndContiguous
(
    const FineSurface& surface,
    const std::vector<globalLabel>& numbers,
    globalLabel base,
    globalLabel nGlobal
)
{
    const int rank = test::world().rank();
    constexpr int nKey = 6;
    constexpr long long none = std::numeric_limits<long long>::max();
    std::vector<long long> smallest(nKey*nGlobal, none);
    std::vector<long long> largest(nKey*nGlobal, -none);
    for (std::size_t p = 0; p < numbers.size(); ++p)
    {
        const globalLabel n = numbers[p] - base;
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

    for (globalLabel n = 0; n < nGlobal; ++n)
    {
        ASSERT_NE(smallest[nKey*n], none) << "number " << base + n << " is carried by no point";
        for (int k = 0; k < nKey; ++k)
        {
            ASSERT_EQ(smallest[nKey*n + k], largest[nKey*n + k])
                << "number " << base + n << " is carried by different points";
        }
    }
}

} // End anonymous namespace


TEST(parallelNumbering, everyRankGetsANonEmptyClosedPartSurface)
{
    const sharedSurface s = refinedPart(1);
    EXPECT_GT(s.surface.triangles.size(), 0u);
    // Euler for a closed genus-0 surface: V = 2 + F/2
    EXPECT_EQ(s.surface.points.size(), 2 + s.surface.triangles.size()/2);
}


TEST(parallelNumbering, globalPointIdsAreUniqueAndContiguousAndSharedPointsAgree)
{
    const Communicator& comm = test::world();
    const sharedSurface s = refinedPart(2);
    const label nInterior = 3 + 7*comm.rank();
    const label nLocal = label(s.surface.points.size()) + nInterior;

    const globalPointNumbering numbering(comm, s.coarse, s.cellPart, s.surface, nLocal);
    if (comm.size() > 1)
    {
        EXPECT_GT(comm.sum(std::int64_t(numbering.nShared())), 0);
    }
    expectUniqueAndContiguous(s.surface, numbering.globalIds(), 0, numbering.nGlobal());

    const auto all = test::gatherOnMaster(records(s.surface, numbering.globalIds()));
    if (comm.master())
    {
        expectHoldersAgree(all);
    }
}


TEST(parallelNumbering, numbersBeyondTwoToThe32DoNotOverflow)
{
    const Communicator& comm = test::world();
    const sharedSurface s = refinedPart(1);
    const globalLabel base = globalLabel(5) << 32;
    const label nLocal = label(s.surface.points.size()) + 5;

    const globalPointNumbering numbering(comm, s.coarse, s.cellPart, s.surface, nLocal, base);
    expectUniqueAndContiguous(s.surface, numbering.globalIds(), base, numbering.nGlobal());
}
