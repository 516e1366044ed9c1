// Stages 2-5 across MPI ranks (run under mpiexec -np 1..4): interface
// vertices agree bit for bit on every rank holding them, and the global
// point numbers are unique and contiguous, also beyond 2^32.

#include "mpiTestMain.H"
#include "coarseMesh.H"
#include "cubeMesh.H"
#include "globalNumbering.H"
#include "partitionCoarseMesh.H"
#include "surfaceRefinement.H"

#include <algorithm>
#include <cstring>
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

// On the master: every distinct point (surface points by id, interior
// points each their own) has one number; the numbers are base..base+N-1.
void expectUniqueContiguous
(
    const std::vector<std::vector<pointRecord>>& all,
    globalLabel base,
    globalLabel nGlobal
)
{
    std::map<barycentricId, pointRecord> byId;
    std::vector<globalLabel> numbers;
    for (const auto& rank : all)
    {
        for (const pointRecord& r : rank)
        {
            if (!r.surface)
            {
                numbers.push_back(r.number);
                continue;
            }
            auto [it, inserted] = byId.emplace(r.id, r);
            if (inserted)
            {
                numbers.push_back(r.number);
            }
            else
            {
                EXPECT_EQ(it->second.number, r.number) << r.id;
                EXPECT_EQ(std::memcmp(&it->second.position, &r.position, sizeof(point)), 0)
                    << "coordinates of " << r.id << " differ between ranks";
            }
        }
    }
    std::sort(numbers.begin(), numbers.end());
    ASSERT_EQ(globalLabel(numbers.size()), nGlobal);
    for (std::size_t i = 0; i < numbers.size(); ++i)
    {
        ASSERT_EQ(numbers[i], base + globalLabel(i)) << "numbers not unique and contiguous";
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
    EXPECT_EQ(comm.sum(std::int64_t(numbering.nOwned())), numbering.nGlobal());
    if (comm.size() > 1)
    {
        EXPECT_GT(comm.sum(std::int64_t(numbering.nShared())), 0);
    }

    const auto all = test::gatherOnMaster(records(s.surface, numbering.globalIds()));
    if (comm.master())
    {
        expectUniqueContiguous(all, 0, numbering.nGlobal());
    }
}


TEST(parallelNumbering, numbersBeyondTwoToThe32DoNotOverflow)
{
    const Communicator& comm = test::world();
    const sharedSurface s = refinedPart(1);
    const globalLabel base = globalLabel(5) << 32;
    const label nLocal = label(s.surface.points.size()) + 5;

    const globalPointNumbering numbering(comm, s.coarse, s.cellPart, s.surface, nLocal, base);
    for (globalLabel n : numbering.globalIds())
    {
        EXPECT_GE(n, base);
    }
    const auto all = test::gatherOnMaster(records(s.surface, numbering.globalIds()));
    if (comm.master())
    {
        expectUniqueContiguous(all, base, numbering.nGlobal());
    }
}
