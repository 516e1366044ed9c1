#include "tetsToPolyMesh.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_set>

namespace
{

using namespace pmsh;

const char* const where = "tetsToPolyMesh";


template<class T>
std::array<T, 3> sorted3(T a, T b, T c)
{
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return {a, b, c};
}


//- Counts (and a first example) of one kind of inconsistency.
struct problem
{
    std::size_t count = 0;
    std::string example;

    //- describe() is only called for the first one: formatting every
    //  bad face of a big mesh would be slow.
    template<class Describe>
    void add(const Describe& describe)
    {
        if (count++ == 0)
        {
            example = describe();
        }
    }
};


//- Rotate f so that its point with the smallest global id comes first.
triFace rotateToSmallestGlobal
(
    const triFace& f,
    const std::vector<globalLabel>& globalIds
)
{
    int k = 0;
    if (globalIds[f[1]] < globalIds[f[k]]) k = 1;
    if (globalIds[f[2]] < globalIds[f[k]]) k = 2;
    return {f[k], f[(k + 1) % 3], f[(k + 2) % 3]};
}


//- Check the input sizes, indices, tet volumes and point usage.
void checkInput
(
    const std::vector<point>& points,
    const std::vector<tetCell>& tets,
    const std::vector<triFace>& boundaryTriangles,
    const std::vector<label>& boundaryRegion,
    const std::vector<polyPatchInfo>& physicalPatches,
    label myProcNo,
    const std::vector<globalLabel>& globalPointIds
)
{
    const std::size_t nPoints = points.size();
    const std::size_t nTets = tets.size();
    const std::size_t nTris = boundaryTriangles.size();
    constexpr std::size_t labelMax = std::numeric_limits<label>::max();

    if (nPoints > labelMax || 4*nTets + nTris >= std::size_t(noFace))
    {
        throw FatalError
        (
            msg() << "Too large for one rank: " << nPoints << " points, "
                << nTets << " tets, " << nTris << " boundary triangles.\n"
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

    std::unordered_set<std::string> names;
    for (const polyPatchInfo& p : physicalPatches)
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

    std::vector<char> used(nPoints, 0);
    problem badIndex, badVolume;
    for (std::size_t t = 0; t < nTets; ++t)
    {
        const tetCell& c = tets[t];
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
            badIndex.add([&]() { return "tet " + std::to_string(t); });
            continue;
        }
        const double v6 = tetVolume6
        (
            points[c[0]], points[c[1]], points[c[2]], points[c[3]]
        );
        if (!(v6 > 0))
        {
            badVolume.add([&]() { return "tet " + std::to_string(t); });
        }
    }
    for (std::size_t b = 0; b < nTris; ++b)
    {
        for (const label v : boundaryTriangles[b])
        {
            if (v < 0 || std::size_t(v) >= nPoints)
            {
                badIndex.add
                (
                    [&]() { return "boundary triangle " + std::to_string(b); }
                );
                break;
            }
        }
    }
    if (badIndex.count)
    {
        throw FatalError
        (
            msg() << badIndex.count << " tets or boundary triangles have a"
                " point index outside 0.." << nPoints - 1 << " (first: "
                << badIndex.example << ")",
            where
        );
    }
    if (badVolume.count)
    {
        throw FatalError
        (
            msg() << badVolume.count << " of " << nTets << " tets have a"
                " non-positive volume (first: " << badVolume.example << ").\n"
                "Every tet (a b c d) must have tetVolume6 > 0",
            where
        );
    }
    const std::size_t nUnused = std::count(used.begin(), used.end(), 0);
    if (nUnused)
    {
        throw FatalError
        (
            msg() << nUnused << " of " << nPoints << " points are used by no"
                " tet; OpenFOAM rejects unused points",
            where
        );
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Free functions  * * * * * * * * * * * * * //

std::string pmsh::processorPatchName(label myProcNo, label neighbProcNo)
{
    return
        "procBoundary" + std::to_string(myProcNo)
      + "to" + std::to_string(neighbProcNo);
}


pmsh::PolyMesh pmsh::tetsToPolyMesh
(
    std::vector<point>&& points,
    const std::vector<tetCell>& tets,
    const std::vector<triFace>& boundaryTriangles,
    const std::vector<label>& boundaryRegion,
    const std::vector<polyPatchInfo>& physicalPatches,
    label myProcNo,
    const std::vector<globalLabel>& globalPointIds,
    tetsToPolyMeshMaps* maps
)
{
    checkInput
    (
        points, tets, boundaryTriangles, boundaryRegion, physicalPatches,
        myProcNo, globalPointIds
    );

    const std::size_t nPoints = points.size();
    const std::size_t nTets = tets.size();
    const std::size_t nTris = boundaryTriangles.size();
    const faceId nTetFaces = faceId(4*nTets);


    // Regions: physical patch index, or the neighbouring rank
    std::vector<label> nbrRanks;
    {
        problem badRegion;
        for (std::size_t b = 0; b < nTris; ++b)
        {
            const label r = boundaryRegion[b];
            if (!isInterfaceRegion(r))
            {
                if (std::size_t(r) >= physicalPatches.size())
                {
                    badRegion.add
                    (
                        [&]()
                        {
                            return
                                "triangle " + std::to_string(b)
                              + " has region " + std::to_string(r)
                              + " but there are "
                              + std::to_string(physicalPatches.size())
                              + " physical patches";
                        }
                    );
                }
                continue;
            }
            const label nbr = interfaceNeighbour(r);
            if (myProcNo < 0 || nbr == myProcNo || globalPointIds.empty())
            {
                badRegion.add
                (
                    [&]()
                    {
                        return
                            "triangle " + std::to_string(b)
                          + " is an interface with rank " + std::to_string(nbr)
                          + " on rank " + std::to_string(myProcNo)
                          + (
                                globalPointIds.empty()
                              ? " without global point ids" : ""
                            );
                    }
                );
                continue;
            }
            if (nbrRanks.empty() || nbrRanks.back() != nbr)
            {
                nbrRanks.push_back(nbr);
            }
        }
        if (badRegion.count)
        {
            throw FatalError
            (
                msg() << badRegion.count << " boundary triangles have an"
                    " invalid region (first: " << badRegion.example << ")",
                where
            );
        }
        std::sort(nbrRanks.begin(), nbrRanks.end());
        nbrRanks.erase
        (
            std::unique(nbrRanks.begin(), nbrRanks.end()), nbrRanks.end()
        );
    }
    const std::size_t nPhysical = physicalPatches.size();
    const std::size_t nPatches = nPhysical + nbrRanks.size();

    auto patchOfRegion = [&](label r) -> std::size_t
    {
        if (!isInterfaceRegion(r))
        {
            return std::size_t(r);
        }
        return nPhysical
          + std::size_t
            (
                std::lower_bound
                (
                    nbrRanks.begin(), nbrRanks.end(), interfaceNeighbour(r)
                ) - nbrRanks.begin()
            );
    };


    const tetFaceMatch match = matchTetFaces(nPoints, tets, boundaryTriangles);
    if (!match.fits())
    {
        throw FatalError
        (
            msg() << "The tets (" << nTets << ") and the boundary surface ("
                << nTris << " triangles) do not match:" << match.problems,
            where
        );
    }
    const std::vector<faceId>& partner = match.across;


    PolyMesh mesh;
    mesh.points = std::move(points);
    mesh.nCells = label(nTets);

    std::size_t nBoundaryFaces = 0;
    for (faceId id = 0; id < nTetFaces; ++id)
    {
        if (partner[id] >= nTetFaces)
        {
            ++nBoundaryFaces;
        }
    }
    const std::size_t nInternal = (nTetFaces - nBoundaryFaces)/2;
    const std::size_t nFaces = nInternal + nBoundaryFaces;

    mesh.faces.resize(nFaces);
    mesh.owner.resize(nFaces);
    mesh.neighbour.resize(nInternal);

    // The tet face each PolyMesh face comes from (for the optional maps)
    std::vector<faceId> faceSource;
    if (maps)
    {
        faceSource.resize(nFaces);
    }


    // Internal faces: owner = lower tet, sorted by (owner, neighbour)
    {
        std::size_t facei = 0;
        for (std::size_t t = 0; t < nTets; ++t)
        {
            std::array<std::pair<label, int>, 4> upper;
            int n = 0;
            for (int f = 0; f < 4; ++f)
            {
                const faceId p = partner[4*t + f];
                if (p < nTetFaces && p/4 > t)
                {
                    upper[n++] = {label(p/4), f};
                }
            }
            // At most 4 entries: insertion sort by neighbour
            for (int a = 1; a < n; ++a)
            {
                for (int b = a; b > 0 && upper[b] < upper[b - 1]; --b)
                {
                    std::swap(upper[b], upper[b - 1]);
                }
            }
            for (int k = 0; k < n; ++k)
            {
                if (k && upper[k].first == upper[k - 1].first)
                {
                    throw FatalError
                    (
                        msg() << "Tets " << t << " and " << upper[k].first
                            << " share more than one face (duplicate tets)",
                        where
                    );
                }
                // Outward from the owner = towards the neighbour
                mesh.faces[facei] = tetFace(tets[t], upper[k].second);
                mesh.owner[facei] = label(t);
                mesh.neighbour[facei] = upper[k].first;
                if (maps)
                {
                    faceSource[facei] = faceId(4*t + upper[k].second);
                }
                ++facei;
            }
        }
    }


    // Boundary faces grouped by patch (counting sort keeps them ordered by
    // owner, then local face)
    mesh.patches.resize(nPatches);
    for (std::size_t p = 0; p < nPhysical; ++p)
    {
        mesh.patches[p] = physicalPatches[p];
        mesh.patches[p].size = 0;
    }
    for (std::size_t k = 0; k < nbrRanks.size(); ++k)
    {
        polyPatchInfo& pp = mesh.patches[nPhysical + k];
        pp.name = processorPatchName(myProcNo, nbrRanks[k]);
        pp.type = "processor";
        pp.myProcNo = myProcNo;
        pp.neighbProcNo = nbrRanks[k];
    }
    for (faceId id = 0; id < nTetFaces; ++id)
    {
        if (partner[id] != noFace && partner[id] >= nTetFaces)
        {
            const label r = boundaryRegion[partner[id] - nTetFaces];
            ++mesh.patches[patchOfRegion(r)].size;
        }
    }
    {
        label start = label(nInternal);
        for (polyPatchInfo& pp : mesh.patches)
        {
            pp.start = start;
            start += pp.size;
        }
    }
    {
        std::vector<std::size_t> next(nPatches);
        for (std::size_t p = 0; p < nPatches; ++p)
        {
            next[p] = std::size_t(mesh.patches[p].start);
        }
        for (faceId id = 0; id < nTetFaces; ++id)
        {
            if (partner[id] != noFace && partner[id] >= nTetFaces)
            {
                const label r = boundaryRegion[partner[id] - nTetFaces];
                const std::size_t facei = next[patchOfRegion(r)]++;
                mesh.faces[facei] = tetFace(tets[id/4], int(id % 4));
                mesh.owner[facei] = label(id/4);
                if (maps)
                {
                    faceSource[facei] = id;
                }
            }
        }
    }


    // Processor faces: same order on both sides (sorted global point ids),
    // vertex 0 = smallest global id, so the other side is reverseFace
    for (std::size_t p = nPhysical; p < nPatches; ++p)
    {
        const polyPatchInfo& pp = mesh.patches[p];
        const std::size_t start = std::size_t(pp.start);
        const std::size_t size = std::size_t(pp.size);

        struct keyed
        {
            std::array<globalLabel, 3> key;
            std::size_t facei;
        };
        std::vector<keyed> order(size);
        for (std::size_t i = 0; i < size; ++i)
        {
            const triFace& f = mesh.faces[start + i];
            order[i] =
            {
                sorted3
                (
                    globalPointIds[f[0]],
                    globalPointIds[f[1]],
                    globalPointIds[f[2]]
                ),
                start + i
            };
        }
        std::sort
        (
            order.begin(), order.end(),
            [](const keyed& a, const keyed& b) { return a.key < b.key; }
        );
        for (std::size_t i = 0; i < size; ++i)
        {
            const auto& k = order[i].key;
            if
            (
                (i && k == order[i - 1].key)
             || k[0] == k[1]
             || k[1] == k[2]
            )
            {
                throw FatalError
                (
                    msg() << "Patch " << pp.name << ": two faces or two"
                        " points of a face have the same global point ids ("
                        << k[0] << ' ' << k[1] << ' ' << k[2] << ").\n"
                        "Global point ids must be unique per point",
                    where
                );
            }
        }

        std::vector<triFace> faces(size);
        std::vector<label> owner(size);
        std::vector<faceId> source(maps ? size : 0);
        for (std::size_t i = 0; i < size; ++i)
        {
            const std::size_t from = order[i].facei;
            faces[i] = rotateToSmallestGlobal(mesh.faces[from], globalPointIds);
            owner[i] = mesh.owner[from];
            if (maps)
            {
                source[i] = faceSource[from];
            }
        }
        std::copy(faces.begin(), faces.end(), mesh.faces.begin() + start);
        std::copy(owner.begin(), owner.end(), mesh.owner.begin() + start);
        if (maps)
        {
            std::copy(source.begin(), source.end(), faceSource.begin() + start);
        }
    }


    if (maps)
    {
        maps->tetFaceToFace.assign(nTetFaces, -1);
        maps->boundaryTriangleToFace.assign(nTris, -1);
        for (std::size_t facei = 0; facei < nFaces; ++facei)
        {
            const faceId id = faceSource[facei];
            maps->tetFaceToFace[id] = label(facei);
            if (facei < nInternal)
            {
                maps->tetFaceToFace[partner[id]] = label(facei);
            }
            else
            {
                maps->boundaryTriangleToFace[partner[id] - nTetFaces] =
                    label(facei);
            }
        }
    }

    return mesh;
}


// ************************************************************************* //
