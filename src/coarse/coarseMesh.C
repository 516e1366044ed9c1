#include "coarseMesh.H"
#include "pmshError.H"
#include "failTogether.H"

#include <algorithm>
#include <numeric>
#include <tuple>

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
        if (comm.master())
        {
            coarse = geometry.coarseMesh(parameters);
        }
    });
    broadcastCoarseMesh(comm, coarse);
    return coarse;
}


void pmsh::broadcastCoarseMesh(const Communicator& comm, CoarseMesh& coarse)
{
    comm.broadcast(coarse.points);
    comm.broadcast(coarse.tets);
    comm.broadcast(coarse.boundary);

    // Patch names as one '\0'-separated buffer
    std::vector<char> names;
    for (const std::string& n : coarse.patchNames)
    {
        names.insert(names.end(), n.begin(), n.end());
        names.push_back('\0');
    }
    comm.broadcast(names);
    coarse.patchNames.clear();
    for (auto it = names.begin(); it != names.end(); )
    {
        auto end = std::find(it, names.end(), '\0');
        coarse.patchNames.emplace_back(it, end);
        it = (end == names.end()) ? end : end + 1;
    }
}


namespace
{

using namespace pmsh;

// A coarse face keyed by its sorted points, for sort-based matching (the
// coarse mesh may have millions of faces: one flat sort beats a hash map of
// faces in time and memory).
struct keyedFace
{
    triFace key;
    label cell;     // owning tet, or -1 for a boundary face
    label index;    // local face 0..3 of the tet, or the boundary face index

    bool operator<(const keyedFace& o) const
    {
        return std::tie(key, cell) < std::tie(o.key, o.cell);
    }
};

triFace sortedKey(triFace f)
{
    std::sort(f.begin(), f.end());
    return f;
}

} // End anonymous namespace


std::vector<pmsh::faceNeighbours> pmsh::coarseFaceNeighbours(const CoarseMesh& coarse)
{
    const label nCells = coarse.nCells();
    std::vector<keyedFace> faces;
    faces.reserve(4*std::size_t(nCells) + coarse.boundary.size());
    for (label celli = 0; celli < nCells; ++celli)
    {
        const auto tetFaces = outwardTetFaces(coarse.tets[celli]);
        for (label fi = 0; fi < 4; ++fi)
        {
            faces.push_back({sortedKey(tetFaces[fi]), celli, fi});
        }
    }
    for (label bfi = 0; bfi < label(coarse.boundary.size()); ++bfi)
    {
        faces.push_back({sortedKey(coarse.boundary[bfi].v), -1, bfi});
    }
    std::sort(faces.begin(), faces.end());

    // Every key occurs exactly twice: two tets (internal face) or a boundary
    // face (cell -1, sorted first) and its tet
    std::vector<faceNeighbours> neighbours(nCells, faceNeighbours{-1, -1, -1, -1});
    for (std::size_t n = 0; n < faces.size(); n += 2)
    {
        if
        (
            n + 1 >= faces.size() || faces[n].key != faces[n + 1].key
         || (n + 2 < faces.size() && faces[n + 2].key == faces[n].key)
         || faces[n + 1].cell < 0
        )
        {
            throw FatalError
            (
                msg() << "The coarse mesh is not closed: face ("
                    << faces[n].key[0] << ' ' << faces[n].key[1] << ' '
                    << faces[n].key[2] << ") is not shared by exactly two"
                    << " cells or one cell and the boundary",
                "coarseFaceNeighbours"
            );
        }
        const keyedFace& a = faces[n];
        const keyedFace& b = faces[n + 1];
        if (a.cell < 0)
        {
            neighbours[b.cell][b.index] = -(a.index + 1);
        }
        else
        {
            neighbours[a.cell][a.index] = b.cell;
            neighbours[b.cell][b.index] = a.cell;
        }
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
