#include "prismFaces.H"
#include "mixedFaceMatching.H"
#include "patchLayout.H"
#include "pmshError.H"

#include <algorithm>

namespace
{

using namespace pmsh;

const char* const where = "tetsToPolyMesh";


//- Face facei of the mesh is f (n points): a triangle, or a quad's first
//  three points here and its fourth in mesh.quads (sorted at the end).
void setFace(tetPolyMesh& mesh, std::size_t facei, const quadVerts& f, int n)
{
    mesh.faces[facei] = {f[0], f[1], f[2]};
    if (n == 4)
    {
        mesh.quads.push_back({label(facei), f[3]});
    }
}


//- The region of the boundary face across cell face id, or none (-1 as
//  a flag: regions of interfaces are negative too, so a bool says which).
bool boundaryRegionAcross
(
    const mixedFaces& m,
    const std::vector<faceId>& across,
    faceId id,
    const std::vector<label>& triRegion,
    const std::vector<label>& quadRegion,
    label& region
)
{
    const faceId other = across[id];
    if (other == noFace || other < m.nCellFaces)
    {
        return false;
    }
    region = other < m.quadsStart
        ? triRegion[other - m.nCellFaces]
        : quadRegion[other - m.quadsStart];
    return true;
}


//- Internal faces: owner < neighbour, ordered by (owner, neighbour), each
//  outward from its owner (towards the neighbour).
void addInternalFaces
(
    tetPolyMesh& mesh,
    const mixedFaces& m,
    const std::vector<faceId>& across
)
{
    for (label c = 0; c < mesh.nCells; ++c)
    {
        // The faces towards higher cells, by neighbour (at most 5:
        // insertion sort)
        const faceId first = m.firstFace(c);
        std::array<std::pair<label, int>, 5> upper;
        int n = 0;
        for (int f = 0; f < m.nFacesOf(c); ++f)
        {
            const faceId other = across[first + f];
            if (other < m.nCellFaces && m.cellOf(other) > c)
            {
                upper[n++] = {m.cellOf(other), f};
                for (int k = n - 1; k > 0 && upper[k] < upper[k - 1]; --k)
                {
                    std::swap(upper[k], upper[k - 1]);
                }
            }
        }
        for (int k = 0; k < n; ++k)
        {
            quadVerts v;
            const int np = m.pointsOf(first + upper[k].second, v);
            mesh.faces.emplace_back();
            setFace(mesh, mesh.faces.size() - 1, v, np);
            mesh.owner.push_back(c);
            mesh.neighbour.push_back(upper[k].first);
        }
    }
}


//- The physical patches, in the given order (also those with no face
//  here), their faces ordered by (owner, local cell face) and outward.
void addPhysicalPatches
(
    tetPolyMesh& mesh,
    const mixedFaces& m,
    const std::vector<faceId>& across,
    const std::vector<label>& triRegion,
    const std::vector<label>& quadRegion,
    const std::vector<meshPatch>& physicalPatches
)
{
    auto physicalPatchOf = [&](faceId id) -> label
    {
        label r;
        return boundaryRegionAcross(m, across, id, triRegion, quadRegion, r)
            && !isInterfaceRegion(r) ? r : -1;
    };

    // Cell faces in id order stay in owner order
    detail::layOutPhysicalPatches
    (
        mesh, physicalPatches, m.nCellFaces, physicalPatchOf,
        [&](std::size_t facei, faceId id)
        {
            quadVerts v;
            setFace(mesh, facei, v, m.pointsOf(id, v));
            mesh.owner[facei] = m.cellOf(id);
        }
    );
}



//- One processor patch per neighbouring rank, in ascending rank, faces
//  sorted by processorKeyOf and rotated to start at their smallest global
//  id (see tetsToPolyMesh.H).
void addProcessorPatches
(
    tetPolyMesh& mesh,
    const mixedFaces& m,
    const std::vector<faceId>& across,
    const std::vector<label>& triRegion,
    const std::vector<label>& quadRegion,
    label myProcNo,
    const std::vector<label>& globalPointIds
)
{
    using processorFace = detail::processorFace<4, faceId>;
    std::vector<processorFace> faces;
    for (faceId id = 0; id < m.nCellFaces; ++id)
    {
        label r;
        if
        (
            boundaryRegionAcross(m, across, id, triRegion, quadRegion, r)
         && isInterfaceRegion(r)
        )
        {
            quadVerts v;
            const int n = m.pointsOf(id, v);
            faces.push_back
            (
                {interfaceNeighbour(r), processorKeyOf(v, n, globalPointIds), id}
            );
        }
    }
    detail::layOutProcessorPatches
    (
        mesh, faces, myProcNo,
        [&](const processorFace& pf)
        {
            quadVerts f, r;
            const int n = m.pointsOf(pf.id, f);
            const int first = detail::smallestGlobalIdAt(f, n, globalPointIds);
            r = f;
            for (int j = 0; j < n; ++j)
            {
                r[j] = f[(first + j) % n];
            }
            mesh.faces.emplace_back();
            setFace(mesh, mesh.faces.size() - 1, r, n);
            mesh.owner.push_back(m.cellOf(pf.id));
        }
    );
}

} // End anonymous namespace


pmsh::tetPolyMesh pmsh::detail::mixedCellsToPolyMesh
(
    std::vector<point3>&& points,
    const std::vector<tetVerts>& tets,
    const std::vector<prismVerts>& prisms,
    const std::vector<triVerts>& boundaryTriangles,
    const std::vector<label>& boundaryRegion,
    const std::vector<quadVerts>& boundaryQuads,
    const std::vector<label>& quadRegion,
    const std::vector<meshPatch>& physicalPatches,
    label myProcNo,
    const std::vector<label>& globalPointIds
)
{
    const mixedFaces m(tets, prisms, boundaryTriangles, boundaryQuads, where);
    const std::vector<faceId> across = matchMixedFaces(points.size(), m);

    tetPolyMesh mesh;
    mesh.points = std::move(points);
    mesh.nCells = label(tets.size() + prisms.size());
    mesh.nPrisms = label(prisms.size());

    // Every cell face is one face, an internal one from both of its cells
    const std::size_t nBoundary = boundaryTriangles.size() + boundaryQuads.size();
    const std::size_t nFaces = (std::size_t(m.nCellFaces) + nBoundary)/2;
    mesh.faces.reserve(nFaces);
    mesh.owner.reserve(nFaces);
    mesh.neighbour.reserve(nFaces - nBoundary);

    addInternalFaces(mesh, m, across);
    addPhysicalPatches(mesh, m, across, boundaryRegion, quadRegion, physicalPatches);
    addProcessorPatches
    (
        mesh, m, across, boundaryRegion, quadRegion, myProcNo, globalPointIds
    );

    // The physical patches were filled out of face order
    std::sort
    (
        mesh.quads.begin(), mesh.quads.end(),
        [](const quadFace& a, const quadFace& b) { return a.face < b.face; }
    );
    return mesh;
}


// ************************************************************************* //
