#include "prismFaces.H"
#include "matchByPoints.H"
#include "patchLayout.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <sstream>

namespace
{

using namespace pmsh;

const char* const where = "tetsToPolyMesh";


//- The cell faces and boundary faces of a mixed mesh in one id space: tet
//  face f of tet t is 4t + f, face f of prism j is nTetFaces + 5j + f,
//  then the boundary triangles, then the boundary quads.
struct mixedFaces
{
    const std::vector<tetVerts>& tets;
    const std::vector<prismVerts>& prisms;
    const std::vector<triVerts>& tris;
    const std::vector<quadVerts>& quads;
    faceId nTetFaces, nCellFaces, quadsStart, nAll;

    mixedFaces
    (
        const std::vector<tetVerts>& tets,
        const std::vector<prismVerts>& prisms,
        const std::vector<triVerts>& tris,
        const std::vector<quadVerts>& quads
    )
    :
        tets(tets), prisms(prisms), tris(tris), quads(quads)
    {
        const std::size_t n =
            4*tets.size() + 5*prisms.size() + tris.size() + quads.size();
        if (n >= std::size_t(noFace))
        {
            throw FatalError
            (
                msg() << "Too many faces for one rank: " << tets.size()
                    << " tets, " << prisms.size() << " prisms, " << tris.size()
                    << " boundary triangles, " << quads.size() << " boundary"
                    " quads.\nUse more ranks",
                where
            );
        }
        nTetFaces = faceId(4*tets.size());
        nCellFaces = nTetFaces + faceId(5*prisms.size());
        quadsStart = nCellFaces + faceId(tris.size());
        nAll = quadsStart + faceId(quads.size());
    }

    label nTets() const { return label(tets.size()); }

    //- The points of face id (cell faces outward from their cell); 3 or 4
    int pointsOf(faceId id, quadVerts& f) const
    {
        if (id < nTetFaces)
        {
            const triVerts t = tetFace(tets[id/4], int(id % 4));
            f = {t[0], t[1], t[2], -1};
            return 3;
        }
        if (id < nCellFaces)
        {
            const faceId k = id - nTetFaces;
            return prismFace(prisms[k/5], int(k % 5), f);
        }
        if (id < quadsStart)
        {
            const triVerts& t = tris[id - nCellFaces];
            f = {t[0], t[1], t[2], -1};
            return 3;
        }
        f = quads[id - quadsStart];
        return 4;
    }

    //- The cell of cell face id
    label cellOf(faceId id) const
    {
        return id < nTetFaces
            ? label(id/4)
            : nTets() + label((id - nTetFaces)/5);
    }

    //- The first face and the number of faces of cell c
    faceId firstFace(label c) const
    {
        return c < nTets()
            ? faceId(4*c)
            : nTetFaces + faceId(5*(c - nTets()));
    }
    int nFacesOf(label c) const { return c < nTets() ? 4 : 5; }

    std::string name(faceId id) const
    {
        quadVerts f;
        const int n = pointsOf(id, f);
        std::ostringstream os;
        if (id < nCellFaces)
        {
            const label c = cellOf(id);
            os  << (c < nTets() ? "tet " : "prism ")
                << (c < nTets() ? c : c - nTets()) << " face";
        }
        else
        {
            os  << (id < quadsStart ? "boundary triangle " : "boundary quad ")
                << (id < quadsStart ? id - nCellFaces : id - quadsStart);
        }
        os  << " (";
        for (int k = 0; k < n; ++k)
        {
            os  << (k ? " " : "") << f[k];
        }
        os  << ')';
        return os.str();
    }
};


//- +1 when b is a's cycle (a rotation of it), -1 when it is the reversed
//  cycle, 0 otherwise (the same points in another cyclic order: a twisted
//  quad). a and b have the same n points.
int orientationOf(const quadVerts& a, const quadVerts& b, int n)
{
    int k = 0;
    while (k < n && b[k] != a[0]) ++k;
    if (k == n) return 0;
    bool same = true, reversed = true;
    for (int i = 1; i < n; ++i)
    {
        same = same && b[(k + i) % n] == a[i];
        reversed = reversed && b[(k - i + n) % n] == a[i];
    }
    return same ? 1 : (reversed ? -1 : 0);
}


void report(std::ostream& os, const problemCount& p, const char* what)
{
    if (p.count)
    {
        os  << "\n    " << p.count << ' ' << what << " (first: " << p.first << ')';
    }
}


//- Per cell face: the cell face or boundary face across it, noFace when
//  none. Throws FatalError (with counts and a first example of each
//  problem) unless the faces fit.
std::vector<faceId> matchMixedFaces(std::size_t nPoints, const mixedFaces& m)
{
    std::vector<faceId> across(m.nCellFaces, noFace);
    problemCount open, notCellFace, internalInBoundary, nonManifold;
    problemCount wrongSide, overlapping;

    // Keyed by the three smallest points; the fourth splits the group
    auto key3 = [&](faceId id) -> std::array<label, 3>
    {
        quadVerts f;
        const int n = m.pointsOf(id, f);
        // The three smallest, sorted (insertion sort of 3 or 4)
        for (int i = 1; i < n; ++i)
        {
            for (int k = i; k > 0 && f[k] < f[k - 1]; --k) std::swap(f[k], f[k - 1]);
        }
        return {f[0], f[1], f[2]};
    };
    std::vector<std::pair<label, faceId>> group;
    auto classify = [&](const std::pair<label, faceId>* g, std::size_t n)
    {
        std::size_t nCell = 0;
        while (nCell < n && g[nCell].second < m.nCellFaces) ++nCell;
        const std::size_t nBoundary = n - nCell;
        const faceId a = g[0].second;
        quadVerts fa, fb;
        const int np = m.pointsOf(a, fa);
        if (nCell == 2 && nBoundary == 0)
        {
            const faceId b = g[1].second;
            m.pointsOf(b, fb);
            if (orientationOf(fa, fb, np) != -1)
            {
                overlapping.add([&] { return m.name(a) + " and " + m.name(b); });
            }
            across[a] = b;
            across[b] = a;
        }
        else if (nCell == 1 && nBoundary == 1)
        {
            const faceId b = g[1].second;
            m.pointsOf(b, fb);
            if (orientationOf(fa, fb, np) != 1)
            {
                wrongSide.add([&] { return m.name(b) + " of " + m.name(a); });
            }
            across[a] = b;
        }
        else if (nCell == 1 && nBoundary == 0)
        {
            open.add([&] { return m.name(a); });
        }
        else if (nCell == 0 || nCell == 2)
        {
            problemCount& p = nCell ? internalInBoundary : notCellFace;
            for (std::size_t k = nCell; k < n; ++k)
            {
                p.add([&] { return m.name(g[k].second); });
            }
        }
        else
        {
            nonManifold.add([&]
            {
                return std::to_string(nCell) + " cells and "
                    + std::to_string(nBoundary) + " boundary faces share "
                    + m.name(a);
            });
        }
    };

    forEachSamePointsGroup
    (
        nPoints, m.nAll, key3,
        [&](const faceId* ids, std::size_t n)
        {
            // Split by the fourth point (-1: a triangle), ids ascending
            group.clear();
            for (std::size_t i = 0; i < n; ++i)
            {
                quadVerts f;
                const int np = m.pointsOf(ids[i], f);
                group.push_back
                (
                    {np == 3 ? -1 : *std::max_element(f.begin(), f.end()), ids[i]}
                );
            }
            std::sort(group.begin(), group.end());
            for (std::size_t i = 0; i < group.size(); )
            {
                std::size_t j = i + 1;
                while (j < group.size() && group[j].first == group[i].first) ++j;
                // Cell faces first within the sub-group (ids ascend)
                classify(group.data() + i, j - i);
                i = j;
            }
        }
    );

    std::ostringstream os;
    report(os, open, "cell faces are on no other cell and in no boundary"
        " list (boundary face missing)");
    report(os, notCellFace, "boundary triangles or quads are no cell face");
    report(os, internalInBoundary, "boundary triangles or quads lie on a"
        " face between two cells");
    report(os, nonManifold, "faces are shared by more than two cells or"
        " boundary faces (duplicates)");
    report(os, wrongSide, "boundary triangles or quads are not oriented"
        " outward from their cell (orientation mismatch)");
    report(os, overlapping, "faces are shared by two cells on the same side"
        " or in another point order (overlapping cells)");
    if (!os.str().empty())
    {
        throw FatalError
        (
            msg() << "The cells (" << m.tets.size() << " tets, "
                << m.prisms.size() << " prisms) and the boundary ("
                << m.tris.size() << " triangles, " << m.quads.size()
                << " quads) do not match:" << os.str(),
            where
        );
    }
    return across;
}

} // End anonymous namespace


namespace
{

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


//- A processor face's key: its sorted global ids, a triangle's led by -1
//  (no quad's key equals a triangle's; triangles keep the tet-only order).
std::array<label, 4> processorKeyOf
(
    const quadVerts& f,
    int n,
    const std::vector<label>& globalPointIds
)
{
    std::array<label, 4> k{-1, -1, -1, -1};
    for (int i = 0; i < n; ++i)
    {
        k[4 - n + i] = globalPointIds[f[i]];
    }
    std::sort(k.begin() + (4 - n), k.end());
    return k;
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
    const mixedFaces m(tets, prisms, boundaryTriangles, boundaryQuads);
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
