#include "coarseMesh.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <numeric>

void pmsh::releaseGeometry(CoarseMesh& coarse)
{
    // Swapped out, not cleared: clear() keeps the capacity
    std::vector<point3>().swap(coarse.points);
    std::vector<tetVerts>().swap(coarse.tets);
    std::vector<coarseBoundaryFace>().swap(coarse.boundary);
    std::vector<label>().swap(coarse.cellZone);
    std::vector<coarseZoneFace>().swap(coarse.zoneFaces);
}


namespace
{

//- Broadcast the master's names as one '\0'-separated buffer.
void broadcastNames(const pmsh::Communicator& comm, std::vector<std::string>& names)
{
    std::vector<char> buffer;
    for (const std::string& name : names)
    {
        buffer.insert(buffer.end(), name.begin(), name.end());
        buffer.push_back('\0');
    }
    comm.broadcast(buffer);
    names.clear();
    for (auto it = buffer.begin(); it != buffer.end(); )
    {
        auto end = std::find(it, buffer.end(), '\0');
        names.emplace_back(it, end);
        it = (end == buffer.end()) ? end : end + 1;
    }
}

} // End anonymous namespace


void pmsh::broadcastCoarseMesh(const Communicator& comm, CoarseMesh& coarse)
{
    comm.broadcast(coarse.points);
    comm.broadcast(coarse.tets);
    comm.broadcast(coarse.boundary);
    comm.broadcast(coarse.cellZone);
    comm.broadcast(coarse.zoneFaces);
    broadcastNames(comm, coarse.zones);
    comm.broadcast(coarse.periodicPatches);
    comm.broadcast(coarse.periodicPoints);

    // Patch names only: the types come from pmshDict, which every rank reads
    std::vector<std::string> names;
    for (const meshPatch& p : coarse.patches)
    {
        names.push_back(p.name);
    }
    broadcastNames(comm, names);
    coarse.patches.clear();
    for (const std::string& name : names)
    {
        coarse.patches.push_back({name});
    }
}


pmsh::zoneFaceIndex::zoneFaceIndex(const CoarseMesh& coarse)
{
    keys_.reserve(coarse.zoneFaces.size());
    for (std::size_t i = 0; i < coarse.zoneFaces.size(); ++i)
    {
        triVerts f = coarse.zoneFaces[i].v;
        std::sort(f.begin(), f.end());
        keys_.emplace_back(f, label(i));
    }
    std::sort(keys_.begin(), keys_.end());
}


pmsh::label pmsh::zoneFaceIndex::find(const triVerts& face) const
{
    if (keys_.empty())
    {
        return -1;
    }
    triVerts f = face;
    std::sort(f.begin(), f.end());
    const auto it = std::lower_bound
    (
        keys_.begin(), keys_.end(), std::make_pair(f, label(-1))
    );
    return it != keys_.end() && it->first == f ? it->second : -1;
}


std::vector<pmsh::faceNeighbours> pmsh::coarseFaceNeighbours(const CoarseMesh& coarse)
{
    std::vector<triVerts> boundary(coarse.boundary.size());
    for (std::size_t b = 0; b < boundary.size(); ++b)
    {
        boundary[b] = coarse.boundary[b].v;
    }
    const tetFaceMatch match = fittingTetFaces
    (
        coarse.nPoints(), coarse.tets, boundary,
        "The coarse mesh and its boundary do not fit together", "coarseFaceNeighbours"
    );

    std::vector<faceNeighbours> neighbours(coarse.nCells());
    for (faceId id = 0; id < match.nTetFaces; ++id)
    {
        neighbours[id/4][id % 4] = match.acrossOf(id);
    }
    return neighbours;
}


pmsh::coarsePointCells::coarsePointCells(const CoarseMesh& coarse)
:
    offsets_(coarse.nPoints() + 1, 0)
{
    for (const tetVerts& t : coarse.tets)
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
