#include "procAddressing.H"
#include "globalNumbering.H"
#include "pmshError.H"

#include <algorithm>
#include <numeric>

pmsh::procAddressingStarts pmsh::procAddressingStartsOf
(
    const Communicator& comm,
    std::int64_t nCells,
    std::int64_t nInternalBlock,
    const std::vector<std::int64_t>& nPatchFaces
)
{
    procAddressingStarts starts;
    starts.cell = numberRankByRank(comm, nCells, "cells").start;
    const globalRange internal = numberRankByRank(comm, nInternalBlock, "faces");
    starts.internalFace = internal.start;
    std::int64_t patchStart = internal.end;
    for (const std::int64_t n : nPatchFaces)
    {
        const globalRange faces = numberRankByRank(comm, n, "faces", patchStart);
        starts.patchFace.push_back(faces.start);
        patchStart = faces.end;
    }
    return starts;
}


namespace
{

//- Step 3 of buildProcAddressing: on each processor patch to a lower rank,
//  the faces take that rank's numbers, negated (reversed orientation)
void takeLowerRanksFaceNumbers
(
    const pmsh::Communicator& comm,
    const pmsh::tetPolyMesh& mesh,
    std::vector<pmsh::label>& faceNumbers
)
{
    using namespace pmsh;
    const int me = comm.rank();
    std::vector<std::vector<label>> numbersToHigher(comm.size());
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo < me) continue;
        for (label f = p.start; f < p.start + p.size; ++f)
        {
            numbersToHigher[p.neighbProcNo].push_back(faceNumbers[f]);
        }
    }
    const auto fromLower = comm.exchange(numbersToHigher);
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo > me) continue;
        const std::vector<label>& numbers = fromLower[p.neighbProcNo];
        for (label i = 0; i < p.size; ++i)
        {
            faceNumbers[p.start + i] = -numbers[i];
        }
    }
}

} // End anonymous namespace


pmsh::procAddressing pmsh::buildProcAddressing
(
    const Communicator& comm,
    const tetPolyMesh& mesh,
    const std::vector<label>& globalPointIds
)
{
    const int me = comm.rank();
    const int nRanks = comm.size();
    const label nInternal = mesh.nInternalFaces();

    procAddressing addr;
    addr.point = globalPointIds;

    // The counts: cells; internal faces and processor faces to higher
    // ranks (the lower rank's block holds a processor face); the faces of
    // each physical patch, a cyclic patch's faces whose image is on
    // another rank (its processorCyclic patches) after the rank's own
    std::int64_t nInternalBlock = nInternal;
    std::vector<std::vector<const meshPatch*>> physicalParts;
    std::vector<std::int64_t> nPatchFaces;
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const meshPatch& p = mesh.patches[pi];
        if (p.isProcessor() && p.neighbProcNo > me)
        {
            nInternalBlock += p.size;
        }
        if (!p.isPhysical())
        {
            addr.boundary.push_back(-1);
            continue;
        }
        addr.boundary.push_back(label(pi));
        std::vector<const meshPatch*> parts{&p};
        std::int64_t n = p.size;
        for (const meshPatch& q : mesh.patches)
        {
            if (q.isProcessorCyclic() && q.neighbourPatch == p.name)
            {
                parts.push_back(&q);
                n += q.size;
            }
        }
        physicalParts.push_back(std::move(parts));
        nPatchFaces.push_back(n);
    }
    const procAddressingStarts starts =
        procAddressingStartsOf(comm, mesh.nCells, nInternalBlock, nPatchFaces);

    const label cellOffset = label(starts.cell);
    addr.cell.resize(mesh.nCells);
    std::iota(addr.cell.begin(), addr.cell.end(), cellOffset);

    // 1. Tell each neighbour the global cells behind our processor faces,
    //    in patch order (face i on both sides is the same face)
    std::vector<std::vector<label>> ownerCells(nRanks);
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor()) continue;
        for (label f = p.start; f < p.start + p.size; ++f)
        {
            ownerCells[p.neighbProcNo].push_back(cellOffset + mesh.owner[f]);
        }
    }
    const auto neighbourCells = comm.exchange(ownerCells);

    // 2. Our block of global internal faces: for each cell in order, its
    //    internal faces (neighbours within this rank come first, being
    //    lower), then its processor faces to higher ranks by neighbour cell
    struct procFace { label cell; label nbrCell; label face; };
    std::vector<procFace> upperFaces;
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo < me) continue;
        const std::vector<label>& nbr = neighbourCells[p.neighbProcNo];
        if (label(nbr.size()) != p.size)
        {
            throw FatalError
            (
                msg() << p.name << " has " << p.size << " faces but rank "
                    << p.neighbProcNo << " has " << nbr.size() << " opposite",
                "buildProcAddressing"
            );
        }
        for (label i = 0; i < p.size; ++i)
        {
            upperFaces.push_back({mesh.owner[p.start + i], nbr[i], p.start + i});
        }
    }
    std::sort
    (
        upperFaces.begin(), upperFaces.end(),
        [](const procFace& a, const procFace& b)
        {
            return a.cell != b.cell ? a.cell < b.cell : a.nbrCell < b.nbrCell;
        }
    );

    // Faces are +(index + 1)
    addr.face.assign(mesh.nFaces(), 0);
    label next = label(starts.internalFace);
    std::size_t u = 0;
    for (label f = 0; f < nInternal; ++f)
    {
        while (u < upperFaces.size() && upperFaces[u].cell < mesh.owner[f])
        {
            addr.face[upperFaces[u++].face] = ++next;
        }
        addr.face[f] = ++next;
    }
    while (u < upperFaces.size())
    {
        addr.face[upperFaces[u++].face] = ++next;
    }

    // 3. The higher rank takes the lower rank's numbers, reversed
    takeLowerRanksFaceNumbers(comm, mesh, addr.face);

    // 4. Physical patches: rank by rank within each patch
    for (std::size_t k = 0; k < physicalParts.size(); ++k)
    {
        label next = label(starts.patchFace[k]);
        for (const meshPatch* q : physicalParts[k])
        {
            for (label i = 0; i < q->size; ++i)
            {
                addr.face[q->start + i] = ++next;
            }
        }
    }
    return addr;
}
