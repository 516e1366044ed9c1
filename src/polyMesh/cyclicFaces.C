#include "cyclicFaces.H"
#include "pmshError.H"

#include <algorithm>
#include <tuple>
#include <unordered_map>

pmsh::periodicFaceParts pmsh::periodicPartsOf
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart
)
{
    periodicFaceParts parts;
    if (coarse.periodicPatches.empty())
    {
        return parts;
    }
    auto partOf = [&](label cell) { return cellPart.empty() ? 0 : cellPart[cell]; };

    // The cell behind every boundary face
    std::vector<label> cellOf(coarse.boundary.size(), -1);
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    for (label c = 0; c < coarse.nCells(); ++c)
    {
        for (label nbr : neighbours[c])
        {
            if (isBoundaryNeighbour(nbr))
            {
                cellOf[boundaryFaceOf(nbr)] = c;
            }
        }
    }
    std::map<label, label> toFirst;
    for (const auto& pair : coarse.periodicPoints)
    {
        toFirst[pair[1]] = pair[0];
    }
    for (const periodicPatchPair& pp : coarse.periodicPatches)
    {
        for (std::size_t b = 0; b < coarse.boundary.size(); ++b)
        {
            const coarseBoundaryFace& f = coarse.boundary[b];
            const bool first = f.patch == pp.first;
            if (!first && f.patch != pp.second)
            {
                continue;
            }
            triFace key = f.v;
            if (!first)
            {
                for (label& p : key)
                {
                    p = toFirst.at(p);
                }
            }
            std::sort(key.begin(), key.end());
            parts[key][first ? 0 : 1] = partOf(cellOf[b]);
        }
    }
    return parts;
}


void pmsh::orderCyclicFaces
(
    tetPolyMesh& mesh,
    const std::vector<barycentricId>& pointIds,
    const CoarseMesh& coarse,
    const periodicFaceParts& parts,
    label myRank
)
{
    if (coarse.periodicPatches.empty())
    {
        return;
    }
    const char* function = "pmsh::orderCyclicFaces";

    // Ids are 1-based: an image's id maps to its first point's
    std::unordered_map<std::uint32_t, std::uint32_t> toFirst;
    for (const auto& pair : coarse.periodicPoints)
    {
        toFirst[std::uint32_t(pair[1] + 1)] = std::uint32_t(pair[0] + 1);
    }
    auto key = [&](label pointi)
    {
        if
        (
            pointi < 0 || std::size_t(pointi) >= pointIds.size()
         || pointIds[pointi].nNonZero() == 0
        )
        {
            throw FatalError
            (
                msg() << "A cyclic face has point " << pointi
                    << ", which is not on the refined surface",
                function
            );
        }
        const barycentricId& id = pointIds[pointi];
        std::array<std::uint32_t, 3> v = id.vertex;
        for (int k = 0; k < 3; ++k)
        {
            const auto it = toFirst.find(v[k]);
            if (id.weight[k] != 0 && it != toFirst.end())
            {
                v[k] = it->second;
            }
        }
        return barycentricId(v[0], id.weight[0], v[1], id.weight[1], v[2], id.weight[2]);
    };

    // Whether each patch is the first of its pair
    std::vector<int> side(mesh.patches.size(), -1);
    for (const periodicPatchPair& pp : coarse.periodicPatches)
    {
        side[pp.first] = 0;
        side[pp.second] = 1;
    }

    // A boundary face with its key (sorted point keys; empty if not cyclic)
    struct boundaryFace
    {
        std::array<barycentricId, 3> key;
        triFace face;
        label owner;
    };
    // Faces per new patch: the old patches (cyclic ones keep the faces
    // whose image is here), then processorCyclic (neighbour, cyclic patch)
    std::vector<std::vector<boundaryFace>> kept(mesh.patches.size());
    std::map<std::pair<label, label>, std::vector<boundaryFace>> toRank;
    const label nInternal = mesh.nInternalFaces();
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const meshPatch& patch = mesh.patches[pi];
        for (label facei = patch.start; facei < patch.start + patch.size; ++facei)
        {
            const triFace& f = mesh.faces[facei];
            if (!patch.isCyclic())
            {
                kept[pi].push_back({{}, f, mesh.owner[facei]});
                continue;
            }
            std::array<barycentricId, 3> k{key(f[0]), key(f[1]), key(f[2])};
            // Start at the point of lowest key, keeping the orientation
            const int first = int(std::min_element(k.begin(), k.end()) - k.begin());
            const triFace rotated{f[first], f[(first + 1) % 3], f[(first + 2) % 3]};
            std::sort(k.begin(), k.end());

            // The coarse face: the coarse points of its points' ids
            std::vector<label> coarsePoints;
            for (const barycentricId& id : k)
            {
                for (int j = 0; j < 3; ++j)
                {
                    if (id.weight[j]) coarsePoints.push_back(label(id.vertex[j]) - 1);
                }
            }
            std::sort(coarsePoints.begin(), coarsePoints.end());
            coarsePoints.erase
            (
                std::unique(coarsePoints.begin(), coarsePoints.end()), coarsePoints.end()
            );
            const auto it =
                coarsePoints.size() == 3
              ? parts.find({coarsePoints[0], coarsePoints[1], coarsePoints[2]})
              : parts.end();
            if (it == parts.end())
            {
                throw FatalError
                (
                    msg() << "A face of cyclic patch " << patch.name
                        << " lies on no periodic coarse face",
                    function
                );
            }
            const label imageRank = it->second[side[pi] == 0 ? 1 : 0];
            if (imageRank == myRank)
            {
                kept[pi].push_back({k, rotated, mesh.owner[facei]});
            }
            else
            {
                toRank[{imageRank, label(pi)}].push_back({k, rotated, mesh.owner[facei]});
            }
        }
    }

    auto byKey = [](const boundaryFace& a, const boundaryFace& b) { return a.key < b.key; };
    label next = nInternal;
    auto place = [&](meshPatch& patch, std::vector<boundaryFace>& faces, bool sort)
    {
        if (sort)
        {
            std::sort(faces.begin(), faces.end(), byKey);
        }
        patch.start = next;
        patch.size = label(faces.size());
        for (const boundaryFace& f : faces)
        {
            mesh.faces[next] = f.face;
            mesh.owner[next] = f.owner;
            ++next;
        }
    };
    std::vector<meshPatch> patches = mesh.patches;
    for (std::size_t pi = 0; pi < patches.size(); ++pi)
    {
        place(patches[pi], kept[pi], patches[pi].isCyclic());
    }
    for (auto& [where, faces] : toRank)
    {
        const meshPatch& cyclic = mesh.patches[where.second];
        meshPatch patch;
        patch.name = processorCyclicPatchName(myRank, where.first, cyclic.name);
        patch.type = "processorCyclic";
        patch.neighbProcNo = where.first;
        patch.neighbourPatch = cyclic.name;
        patch.separation = cyclic.separation;
        place(patch, faces, true);
        patches.push_back(patch);
    }
    mesh.patches = std::move(patches);
}
