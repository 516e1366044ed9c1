#include "tetsToPolyMesh.H"
#include "patchLayout.H"
#include "pmshError.H"
#include "prismFaces.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <limits>
#include <unordered_set>

namespace
{

using namespace pmsh;

const char* const where = "tetsToPolyMesh";


//- Check the sizes of the input arrays and the rank.
void checkSizes
(
    std::size_t nPoints,
    std::size_t nTris,
    const std::vector<label>& boundaryRegion,
    std::size_t nQuads,
    const std::vector<label>& quadRegion,
    label myProcNo,
    const std::vector<label>& globalPointIds
)
{
    if (nPoints > std::size_t(std::numeric_limits<label>::max()))
    {
        throw FatalError
        (
            msg() << "Too large for one rank: " << nPoints << " points.\n"
                "Use more ranks",
            where
        );
    }
    if (boundaryRegion.size() != nTris)
    {
        throw FatalError
        (
            msg() << boundaryRegion.size() << " boundary regions given for "
                << nTris << " boundary triangles (need one per triangle)",
            where
        );
    }
    if (quadRegion.size() != nQuads)
    {
        throw FatalError
        (
            msg() << quadRegion.size() << " quad regions given for "
                << nQuads << " boundary quads (need one per quad)",
            where
        );
    }
    if (myProcNo < -1)
    {
        throw FatalError(msg() << "Invalid rank " << myProcNo, where);
    }
    if (!globalPointIds.empty() && globalPointIds.size() != nPoints)
    {
        throw FatalError
        (
            msg() << globalPointIds.size() << " global point ids given for "
                << nPoints << " points (need one per point, or none)",
            where
        );
    }
}


//- Physical patches: not processor patches, named, names unique.
void checkPatchNames(const std::vector<meshPatch>& physicalPatches)
{
    std::unordered_set<std::string> names;
    for (const meshPatch& p : physicalPatches)
    {
        if (p.isProcessor())
        {
            throw FatalError
            (
                msg() << "Physical patch " << p.name << " has type processor;"
                    " processor patches are made from interface regions",
                where
            );
        }
        if (p.name.empty() || !names.insert(p.name).second)
        {
            throw FatalError
            (
                msg() << "Patch name '" << p.name << "' is empty or not"
                    " unique among the physical patches",
                where
            );
        }
    }
}


//- Is every index of cell or face c a point below nPoints?
template<class Verts>
bool inRange(const Verts& c, std::size_t nPoints)
{
    return std::all_of
    (
        c.begin(), c.end(),
        [&](label v) { return v >= 0 && std::size_t(v) < nPoints; }
    );
}


//- A positive prism: each top point above the base's plane, each base
//  point below the top's (both planes by the right-hand rule of (0 1 2)
//  and (3 4 5), the base's normal towards the top).
bool positivePrism(const std::vector<point3>& p, const prismVerts& c)
{
    for (int k = 0; k < 3; ++k)
    {
        if
        (
            !(tetVolume6(p[c[0]], p[c[1]], p[c[2]], p[c[3 + k]]) > 0)
         || !(tetVolume6(p[c[3]], p[c[5]], p[c[4]], p[c[k]]) > 0)
        )
        {
            return false;
        }
    }
    return true;
}


//- Point indices in range, tets of positive volume, positive prisms, every
//  point used.
void checkCellsAndFaces
(
    const std::vector<point3>& points,
    const std::vector<tetVerts>& tets,
    const std::vector<prismVerts>& prisms,
    const std::vector<triVerts>& boundaryTriangles,
    const std::vector<quadVerts>& boundaryQuads
)
{
    const std::size_t nPoints = points.size();
    const std::size_t nTets = tets.size();
    const std::size_t nTris = boundaryTriangles.size();

    std::vector<char> used(nPoints, 0);
    problemCount badIndex, badVolume, badPrism;
    for (std::size_t t = 0; t < nTets; ++t)
    {
        const tetVerts& c = tets[t];
        bool inRange = true;
        for (const label v : c)
        {
            if (v < 0 || std::size_t(v) >= nPoints)
            {
                inRange = false;
            }
            else
            {
                used[v] = 1;
            }
        }
        if (!inRange)
        {
            badIndex.add([&] { return "tet " + std::to_string(t); });
        }
        else if (!(tetVolume6(points[c[0]], points[c[1]], points[c[2]], points[c[3]]) > 0))
        {
            badVolume.add([&] { return "tet " + std::to_string(t); });
        }
    }
    for (std::size_t j = 0; j < prisms.size(); ++j)
    {
        if (!inRange(prisms[j], nPoints))
        {
            badIndex.add([&] { return "prism " + std::to_string(j); });
            continue;
        }
        for (const label v : prisms[j])
        {
            used[v] = 1;
        }
        if (!positivePrism(points, prisms[j]))
        {
            badPrism.add([&] { return "prism " + std::to_string(j); });
        }
    }
    for (std::size_t b = 0; b < nTris; ++b)
    {
        if (!inRange(boundaryTriangles[b], nPoints))
        {
            badIndex.add([&] { return "boundary triangle " + std::to_string(b); });
        }
    }
    for (std::size_t b = 0; b < boundaryQuads.size(); ++b)
    {
        if (!inRange(boundaryQuads[b], nPoints))
        {
            badIndex.add([&] { return "boundary quad " + std::to_string(b); });
        }
    }
    if (badIndex.count)
    {
        throw FatalError
        (
            msg() << badIndex.count << " cells or boundary faces have a"
                " point index outside 0.." << nPoints - 1 << " (first: "
                << badIndex.first << ")",
            where
        );
    }
    if (badVolume.count)
    {
        throw FatalError
        (
            msg() << badVolume.count << " of " << nTets << " tets have a"
                " non-positive volume (first: " << badVolume.first << ").\n"
                "Every tet (a b c d) must have tetVolume6 > 0",
            where
        );
    }
    if (badPrism.count)
    {
        throw FatalError
        (
            msg() << badPrism.count << " of " << prisms.size() << " prisms are"
                " not positive (first: " << badPrism.first << ").\n"
                "Every prism (0 1 2 3 4 5) needs its top points above the"
                " plane of (0 1 2) and its base points below that of (3 4 5)",
            where
        );
    }
    const std::size_t nUnused = std::count(used.begin(), used.end(), 0);
    if (nUnused)
    {
        throw FatalError
        (
            msg() << nUnused << " of " << nPoints << " points are used by no"
                " tet or prism; OpenFOAM rejects unused points",
            where
        );
    }
}


//- A region is a physical patch, or an interface with another rank
//  (which needs global point ids to order the processor faces).
void checkRegions
(
    const std::vector<label>& boundaryRegion,
    const char* kind,                   // "triangle" or "quad"
    const std::vector<meshPatch>& physicalPatches,
    label myProcNo,
    const std::vector<label>& globalPointIds
)
{
    const std::size_t nTris = boundaryRegion.size();
    problemCount badRegion;
    for (std::size_t b = 0; b < nTris; ++b)
    {
        const label r = boundaryRegion[b];
        const std::string triangle = kind + (' ' + std::to_string(b));
        if (!isInterfaceRegion(r) && std::size_t(r) >= physicalPatches.size())
        {
            badRegion.add([&]
            {
                return triangle + " has region " + std::to_string(r) + " but there are "
                    + std::to_string(physicalPatches.size()) + " physical patches";
            });
        }
        else if
        (
            isInterfaceRegion(r)
         && (myProcNo < 0 || interfaceNeighbour(r) == myProcNo || globalPointIds.empty())
        )
        {
            badRegion.add([&]
            {
                return triangle + " is an interface with rank "
                    + std::to_string(interfaceNeighbour(r)) + " on rank "
                    + std::to_string(myProcNo)
                    + (globalPointIds.empty() ? " without global point ids" : "");
            });
        }
    }
    if (badRegion.count)
    {
        throw FatalError
        (
            msg() << badRegion.count << " boundary " << kind << "s have an"
                " invalid region (first: " << badRegion.first << ")",
            where
        );
    }
}


//- Internal faces: owner < neighbour, ordered by (owner, neighbour), each
//  outward from its owner (towards the neighbour).
void addInternalFaces
(
    tetPolyMesh& mesh,
    const std::vector<tetVerts>& tets,
    const std::vector<faceId>& across
)
{
    const faceId nTetFaces = faceId(4*tets.size());
    for (std::size_t t = 0; t < tets.size(); ++t)
    {
        // The faces towards higher tets, by neighbour (at most 4: insertion
        // sort)
        std::array<std::pair<label, int>, 4> upper;
        int n = 0;
        for (int f = 0; f < 4; ++f)
        {
            const faceId other = across[4*t + f];
            if (other < nTetFaces && other/4 > t)
            {
                upper[n++] = {label(other/4), f};
                for (int k = n - 1; k > 0 && upper[k] < upper[k - 1]; --k)
                {
                    std::swap(upper[k], upper[k - 1]);
                }
            }
        }
        for (int k = 0; k < n; ++k)
        {
            mesh.faces.push_back(tetFace(tets[t], upper[k].second));
            mesh.owner.push_back(label(t));
            mesh.neighbour.push_back(upper[k].first);
        }
    }
}


//- The physical patches, in the given order (also those with no face
//  here), their faces ordered by (owner, local tet face) and outward.
void addPhysicalPatches
(
    tetPolyMesh& mesh,
    const std::vector<tetVerts>& tets,
    const std::vector<faceId>& across,
    const std::vector<label>& boundaryRegion,
    const std::vector<meshPatch>& physicalPatches
)
{
    const faceId nTetFaces = faceId(4*tets.size());
    auto physicalPatchOf = [&](faceId id) -> label
    {
        const faceId other = across[id];
        if (other == noFace || other < nTetFaces)
        {
            return -1;
        }
        const label r = boundaryRegion[other - nTetFaces];
        return isInterfaceRegion(r) ? -1 : r;
    };

    // Tet faces in id order stay in owner order
    detail::layOutPhysicalPatches
    (
        mesh, physicalPatches, nTetFaces, physicalPatchOf,
        [&](std::size_t facei, faceId id)
        {
            mesh.faces[facei] = tetFace(tets[id/4], int(id % 4));
            mesh.owner[facei] = label(id/4);
        }
    );
}


//- One processor patch per neighbouring rank, in ascending rank. Its faces
//  are sorted by their sorted global point ids (both sides compute the same
//  key, so face i on one side is face i on the other) and rotated to start
//  at their smallest global id: outward from each side's own cell, the
//  other side's face is then OpenFOAM's reverseFace.
void addProcessorPatches
(
    tetPolyMesh& mesh,
    const std::vector<tetVerts>& tets,
    const std::vector<faceId>& across,
    const std::vector<label>& boundaryRegion,
    label myProcNo,
    const std::vector<label>& globalPointIds
)
{
    const faceId nTetFaces = faceId(4*tets.size());
    using processorFace = detail::processorFace<3, faceId>;
    std::vector<processorFace> faces;
    for (faceId id = 0; id < nTetFaces; ++id)
    {
        const faceId other = across[id];
        if (other != noFace && other >= nTetFaces)
        {
            const label r = boundaryRegion[other - nTetFaces];
            if (isInterfaceRegion(r))
            {
                const globalFaceKey key =
                    globalKeyOf(tetFace(tets[id/4], int(id % 4)), globalPointIds);
                faces.push_back({interfaceNeighbour(r), key, id});
            }
        }
    }
    detail::layOutProcessorPatches
    (
        mesh, faces, myProcNo,
        [&](const processorFace& pf)
        {
            const triVerts f = tetFace(tets[pf.id/4], int(pf.id % 4));
            const int first = detail::smallestGlobalIdAt(f, 3, globalPointIds);
            mesh.faces.push_back({f[first], f[(first + 1) % 3], f[(first + 2) % 3]});
            mesh.owner.push_back(label(pf.id/4));
        }
    );
}

} // End anonymous namespace


pmsh::tetPolyMesh pmsh::tetsToPolyMesh
(
    std::vector<point3>&& points,
    const std::vector<tetVerts>& tets,
    const std::vector<triVerts>& boundaryTriangles,
    const std::vector<label>& boundaryRegion,
    const std::vector<meshPatch>& physicalPatches,
    label myProcNo,
    const std::vector<label>& globalPointIds,
    const std::vector<prismVerts>& prisms,
    const std::vector<quadVerts>& boundaryQuads,
    const std::vector<label>& quadRegion
)
{
    // The input's sizes, indices, cell volumes, point usage, patches and
    // regions (the cells and the boundary are matched afterwards)
    checkSizes
    (
        points.size(), boundaryTriangles.size(), boundaryRegion,
        boundaryQuads.size(), quadRegion, myProcNo, globalPointIds
    );
    checkPatchNames(physicalPatches);
    checkCellsAndFaces(points, tets, prisms, boundaryTriangles, boundaryQuads);
    checkRegions(boundaryRegion, "triangle", physicalPatches, myProcNo, globalPointIds);
    checkRegions(quadRegion, "quad", physicalPatches, myProcNo, globalPointIds);
    if (!prisms.empty() || !boundaryQuads.empty())
    {
        return detail::mixedCellsToPolyMesh
        (
            std::move(points), tets, prisms, boundaryTriangles,
            boundaryRegion, boundaryQuads, quadRegion, physicalPatches,
            myProcNo, globalPointIds
        );
    }
    const tetFaceMatch match = fittingTetFaces
    (
        points.size(), tets, boundaryTriangles,
        msg() << "The tets (" << tets.size() << ") and the boundary surface ("
            << boundaryTriangles.size() << " triangles) do not match",
        where
    );

    tetPolyMesh mesh;
    mesh.points = std::move(points);
    mesh.nCells = label(tets.size());

    // Every tet face is one face, an internal one from both of its tets
    const std::size_t nBoundary = boundaryTriangles.size();
    const std::size_t nFaces = (4*tets.size() + nBoundary)/2;
    mesh.faces.reserve(nFaces);
    mesh.owner.reserve(nFaces);
    mesh.neighbour.reserve(nFaces - nBoundary);

    addInternalFaces(mesh, tets, match.across);
    addPhysicalPatches(mesh, tets, match.across, boundaryRegion, physicalPatches);
    addProcessorPatches(mesh, tets, match.across, boundaryRegion, myProcNo, globalPointIds);
    return mesh;
}


// ************************************************************************* //
