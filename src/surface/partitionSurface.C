#include "partitionSurface.H"
#include "boundaryRegion.H"
#include "error.H"

#include <algorithm>
#include <tuple>

namespace
{

using namespace pmsh;

// A coarse tet face, keyed by its sorted points, for sort-based matching
// (the coarse mesh is broadcast to all ranks and may have millions of faces:
// one flat sort beats a hash map of faces in time and memory).
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


pmsh::coarsePartSurface pmsh::partitionSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label myPart
)
{
    const label nCells = coarse.nCells();
    auto partOf = [&](label cell) { return cellPart.empty() ? 0 : cellPart[cell]; };

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

    coarsePartSurface surf;
    auto addFace = [&](label celli, label fi, label region, label surface)
    {
        surf.faces.push_back(outwardTetFaces(coarse.tets[celli])[fi]);
        surf.region.push_back(region);
        surf.surface.push_back(surface);
    };

    // Every key occurs exactly twice: two tets (internal face) or a boundary
    // face (cell -1, sorted first) and its tet.
    for (std::size_t n = 0; n < faces.size(); n += 2)
    {
        if (n + 1 >= faces.size() || faces[n].key != faces[n + 1].key
         || (n + 2 < faces.size() && faces[n + 2].key == faces[n].key))
        {
            throw FatalError
            (
                msg() << "The coarse mesh is not closed: face ("
                    << faces[n].key[0] << ' ' << faces[n].key[1] << ' '
                    << faces[n].key[2] << ") is not shared by exactly two"
                    << " cells or one cell and the boundary",
                "partitionSurface"
            );
        }
        const keyedFace& a = faces[n];
        const keyedFace& b = faces[n + 1];
        if (a.cell < 0)
        {
            if (partOf(b.cell) == myPart)
            {
                const coarseBoundaryFace& bf = coarse.boundary[a.index];
                addFace(b.cell, b.index, bf.patch, bf.surface);
            }
        }
        else
        {
            const label partA = partOf(a.cell);
            const label partB = partOf(b.cell);
            if (partA == partB)
            {
                continue;
            }
            if (partA == myPart)
            {
                addFace(a.cell, a.index, interfaceRegion(partB), -1);
            }
            else if (partB == myPart)
            {
                addFace(b.cell, b.index, interfaceRegion(partA), -1);
            }
        }
    }
    return surf;
}
