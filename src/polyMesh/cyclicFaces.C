#include "cyclicFaces.H"
#include "pmshError.H"

#include <algorithm>
#include <tuple>
#include <map>
#include <unordered_map>

namespace
{

using namespace pmsh;

using cyclicKey = std::array<barycentricId, 3>;

// A cyclic face's key on its way to the rank that pairs it with its image
struct cyclicQuery
{
    cyclicKey key;
    int rank;           //!< whose face
    label index;        //!< its index there
};

// The answer: the rank holding the image of face `index`
struct cyclicAnswer
{
    label index;
    int imageRank;
};

int rendezvousRank(const cyclicKey& key, int nRanks)
{
    std::size_t h = 0;
    for (const barycentricId& id : key)
    {
        h = h*1000003u ^ barycentricIdHash()(id);
    }
    return int(h % std::size_t(nRanks));
}

//- A boundary face with its key (sorted point keys; empty if not cyclic)
struct boundaryFace
{
    cyclicKey key;
    triVerts face;
    label owner;
};

const char* const orderFunction = "pmsh::orderCyclicFaces";


//- The key of a point of a cyclic face: its barycentric id, and for a
//  face of a second patch its image on the first, by mapping its coarse
//  points through its own pair only: a point on a cube's edge or corner
//  has an image through every pair it is in. Ids are 1-based.
class cyclicPointKeys
{
    const std::vector<barycentricId>& pointIds_;
    std::vector<std::unordered_map<std::uint32_t, std::uint32_t>> toFirst_;
    std::vector<label> secondOfPair_;

public:

    cyclicPointKeys
    (
        const tetPolyMesh& mesh,
        const std::vector<barycentricId>& pointIds,
        const CoarseMesh& coarse
    )
    :
        pointIds_(pointIds),
        toFirst_(coarse.periodicPatches.size()),
        secondOfPair_(mesh.patches.size(), -1)
    {
        for (const periodicPoint& p : coarse.periodicPoints)
        {
            toFirst_[p.pair][std::uint32_t(p.image + 1)] = std::uint32_t(p.point + 1);
        }
        for (std::size_t pair = 0; pair < coarse.periodicPatches.size(); ++pair)
        {
            secondOfPair_[coarse.periodicPatches[pair].second] = label(pair);
        }
    }

    barycentricId operator()(label pointi, label patchi) const
    {
        if
        (
            pointi < 0 || std::size_t(pointi) >= pointIds_.size()
         || pointIds_[pointi].nNonZero() == 0
        )
        {
            throw FatalError
            (
                msg() << "A cyclic face has point " << pointi
                    << ", which is not on the refined surface",
                orderFunction
            );
        }
        const barycentricId& id = pointIds_[pointi];
        if (secondOfPair_[patchi] < 0)
        {
            return id;
        }
        const auto& map = toFirst_[secondOfPair_[patchi]];
        std::array<std::uint32_t, 3> v = id.vertex;
        for (int k = 0; k < 3; ++k)
        {
            const auto it = map.find(v[k]);
            if (id.weight[k] != 0 && it != map.end())
            {
                v[k] = it->second;
            }
        }
        return barycentricId(v[0], id.weight[0], v[1], id.weight[1], v[2], id.weight[2]);
    }
};


//- The boundary faces of each patch: the non-cyclic ones into kept, the
//  cyclic ones with their keys (rotated to start at the point of lowest
//  key, keeping the orientation) into cyclicFaces with their patch.
void collectBoundaryFaces
(
    const tetPolyMesh& mesh,
    const cyclicPointKeys& keyOf,
    std::vector<std::vector<boundaryFace>>& kept,
    std::vector<std::pair<label, boundaryFace>>& cyclicFaces
)
{
    kept.assign(mesh.patches.size(), {});
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const meshPatch& patch = mesh.patches[pi];
        for (label facei = patch.start; facei < patch.start + patch.size; ++facei)
        {
            const triVerts& f = mesh.faces[facei];
            if (!patch.isCyclic())
            {
                kept[pi].push_back({{}, f, mesh.owner[facei]});
                continue;
            }
            const label p = label(pi);
            cyclicKey k{keyOf(f[0], p), keyOf(f[1], p), keyOf(f[2], p)};
            const int first = int(std::min_element(k.begin(), k.end()) - k.begin());
            const triVerts rotated{f[first], f[(first + 1) % 3], f[(first + 2) % 3]};
            std::sort(k.begin(), k.end());
            cyclicFaces.push_back({label(pi), {k, rotated, mesh.owner[facei]}});
        }
    }
}


//- The rank holding the image of each cyclic face: the two faces of a key
//  meet at one rank, which tells each where the other is.
std::vector<int> imageRanks
(
    const Communicator& comm,
    const std::vector<std::pair<label, boundaryFace>>& cyclicFaces
)
{
    std::vector<std::vector<cyclicQuery>> queries(comm.size());
    for (std::size_t i = 0; i < cyclicFaces.size(); ++i)
    {
        const cyclicKey& k = cyclicFaces[i].second.key;
        queries[rendezvousRank(k, comm.size())].push_back({k, int(comm.rank()), label(i)});
    }
    std::vector<std::vector<cyclicAnswer>> answers(comm.size());
    {
        std::map<cyclicKey, std::vector<cyclicQuery>> byKey;
        for (const auto& fromRank : comm.exchange(queries))
        {
            for (const cyclicQuery& q : fromRank)
            {
                byKey[q.key].push_back(q);
            }
        }
        for (const auto& [k, pair] : byKey)
        {
            if (pair.size() != 2)
            {
                throw FatalError
                (
                    msg() << "A cyclic face has " << pair.size() - 1
                        << " images instead of one",
                    orderFunction
                );
            }
            answers[pair[0].rank].push_back({pair[0].index, pair[1].rank});
            answers[pair[1].rank].push_back({pair[1].index, pair[0].rank});
        }
    }
    std::vector<int> imageRank(cyclicFaces.size(), -1);
    for (const auto& fromRank : comm.exchange(answers))
    {
        for (const cyclicAnswer& a : fromRank)
        {
            imageRank[a.index] = a.imageRank;
        }
    }
    return imageRank;
}


//- The index of each cyclic patch's neighbour patch (-1: not cyclic).
std::vector<label> neighbourPatches(const tetPolyMesh& mesh)
{
    std::vector<label> neighbourOf(mesh.patches.size(), -1);
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        for (std::size_t qi = 0; qi < mesh.patches.size(); ++qi)
        {
            if
            (
                mesh.patches[pi].isCyclic()
             && mesh.patches[qi].name == mesh.patches[pi].neighbourPatch
            )
            {
                neighbourOf[pi] = label(qi);
            }
        }
    }
    return neighbourOf;
}


//- The faces of one processorCyclic patch, keyed by (image rank, owner
//  side first, lower rank's cyclic patch, own cyclic patch).
using processorCyclicFaces =
    std::map<std::tuple<label, int, label, label>, std::vector<boundaryFace>>;


//- The cyclic faces whose image is on this rank into kept; the others
//  into the processorCyclic patches towards their image's rank. Those
//  between two ranks come in one order on both: OpenFOAM streams their
//  data to a rank one after the other (PstreamBuffers), so the k-th of A's
//  to B must be the partner of the k-th of B's to A. Both order them by
//  the lower rank's cyclic patch: OpenFOAM's owner ones (lower index than
//  their neighbour) first, by index, as decomposePar does on the lower
//  rank.
processorCyclicFaces sortByImageRank
(
    const tetPolyMesh& mesh,
    label myRank,
    const std::vector<std::pair<label, boundaryFace>>& cyclicFaces,
    const std::vector<int>& imageRank,
    std::vector<std::vector<boundaryFace>>& kept
)
{
    const std::vector<label> neighbourOf = neighbourPatches(mesh);
    auto orderBetweenRanks = [&](label imageRank, label pi)
    {
        const label lowerRankPatch = myRank < imageRank ? pi : neighbourOf[pi];
        const bool owner = lowerRankPatch < neighbourOf[lowerRankPatch];
        return std::make_tuple(imageRank, owner ? 0 : 1, lowerRankPatch, pi);
    };
    processorCyclicFaces toRank;
    for (std::size_t i = 0; i < cyclicFaces.size(); ++i)
    {
        const auto& [pi, face] = cyclicFaces[i];
        if (imageRank[i] < 0)
        {
            throw FatalError
            (
                msg() << "A face of cyclic patch " << mesh.patches[pi].name
                    << " has no image",
                orderFunction
            );
        }
        if (imageRank[i] == myRank)
        {
            kept[pi].push_back(face);
        }
        else
        {
            toRank[orderBetweenRanks(imageRank[i], pi)].push_back(face);
        }
    }
    return toRank;
}


//- The boundary faces back into the mesh, patch after patch, cyclic ones
//  sorted by key, then the processorCyclic patches.
void placeBoundaryFaces
(
    tetPolyMesh& mesh,
    label myRank,
    std::vector<std::vector<boundaryFace>>& kept,
    processorCyclicFaces& toRank
)
{
    auto byKey = [](const boundaryFace& a, const boundaryFace& b) { return a.key < b.key; };
    label next = mesh.nInternalFaces();
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
        const label imageRank = std::get<0>(where);
        const meshPatch& cyclic = mesh.patches[std::get<3>(where)];
        meshPatch patch;
        patch.name = processorCyclicPatchName(myRank, imageRank, cyclic.name);
        patch.type = "processorCyclic";
        patch.neighbProcNo = imageRank;
        patch.neighbourPatch = cyclic.name;
        patch.separation = cyclic.separation;
        place(patch, faces, true);
        patches.push_back(patch);
    }
    mesh.patches = std::move(patches);
}

} // End anonymous namespace


void pmsh::orderCyclicFaces
(
    const Communicator& comm,
    tetPolyMesh& mesh,
    const std::vector<barycentricId>& pointIds,
    const CoarseMesh& coarse
)
{
    if (coarse.periodicPatches.empty())
    {
        return;
    }
    // Faces here are triangles (boundaryFace): prism layers with cyclic
    // patches are not supported yet. Decided together, as one rank may
    // have no prisms
    if (comm.sum(std::int64_t(mesh.nPrisms > 0 || !mesh.quads.empty())) > 0)
    {
        throw FatalError
        (
            msg() << "Prism layers with cyclic patches are not supported yet:"
                " remove the layers or the periodic patches",
            "orderCyclicFaces"
        );
    }
    const label myRank = comm.rank();

    std::vector<std::vector<boundaryFace>> kept;
    std::vector<std::pair<label, boundaryFace>> cyclicFaces;
    collectBoundaryFaces
    (
        mesh, cyclicPointKeys(mesh, pointIds, coarse), kept, cyclicFaces
    );
    const std::vector<int> imageRank = imageRanks(comm, cyclicFaces);
    processorCyclicFaces toRank =
        sortByImageRank(mesh, myRank, cyclicFaces, imageRank, kept);
    placeBoundaryFaces(mesh, myRank, kept, toRank);
}
