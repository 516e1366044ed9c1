#include "coarseMesh.H"
#include "Geometry.H"
#include "pmshError.H"
#include "failTogether.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <numeric>

pmsh::CoarseMesh pmsh::generateCoarseMesh
(
    const Communicator& comm,
    const Geometry& geometry,
    const coarseMeshParameters& parameters
)
{
    CoarseMesh coarse;
    failTogether(comm, [&]
    {
        comm.masterWorksOthersSleep([&]
        {
            coarse = geometry.coarseMesh(parameters);
        });
    });
    broadcastCoarseMesh(comm, coarse);
    return coarse;
}


void pmsh::broadcastCoarseMesh(const Communicator& comm, CoarseMesh& coarse)
{
    comm.broadcast(coarse.points);
    comm.broadcast(coarse.tets);
    comm.broadcast(coarse.boundary);

    // Patch names as one '\0'-separated buffer (the types come from
    // pmshDict, which every rank reads)
    std::vector<char> names;
    for (const meshPatch& p : coarse.patches)
    {
        names.insert(names.end(), p.name.begin(), p.name.end());
        names.push_back('\0');
    }
    comm.broadcast(names);
    coarse.patches.clear();
    for (auto it = names.begin(); it != names.end(); )
    {
        auto end = std::find(it, names.end(), '\0');
        coarse.patches.push_back({std::string(it, end)});
        it = (end == names.end()) ? end : end + 1;
    }
}


std::vector<pmsh::faceNeighbours> pmsh::coarseFaceNeighbours(const CoarseMesh& coarse)
{
    std::vector<triFace> boundary(coarse.boundary.size());
    for (std::size_t b = 0; b < boundary.size(); ++b)
    {
        boundary[b] = coarse.boundary[b].v;
    }
    const tetFaceMatch match = matchTetFaces(coarse.nPoints(), coarse.tets, boundary);
    if (!match.fits())
    {
        throw FatalError
        (
            msg() << "The coarse mesh and its boundary do not fit together:"
                << match.problems,
            "coarseFaceNeighbours"
        );
    }

    const faceId nTetFaces = faceId(4*coarse.tets.size());
    std::vector<faceNeighbours> neighbours(coarse.nCells());
    for (faceId id = 0; id < nTetFaces; ++id)
    {
        const faceId other = match.across[id];
        neighbours[id/4][id % 4] =
            other < nTetFaces ? label(other/4) : -label(other - nTetFaces + 1);
    }
    return neighbours;
}


pmsh::coarsePointCells::coarsePointCells(const CoarseMesh& coarse)
:
    offsets_(coarse.nPoints() + 1, 0)
{
    for (const tetCell& t : coarse.tets)
    {
        for (label p : t)
        {
            ++offsets_[p + 1];
        }
    }
    std::partial_sum(offsets_.begin(), offsets_.end(), offsets_.begin());
    cells_.resize(offsets_.back());
    std::vector<label> fill(offsets_.begin(), offsets_.end() - 1);
    for (label c = 0; c < coarse.nCells(); ++c)
    {
        for (label p : coarse.tets[c])
        {
            cells_[fill[p]++] = c;
        }
    }
}
