#include "procAddressing.H"
#include "pmshError.H"

#include <algorithm>
#include <numeric>

pmsh::procAddressing pmsh::buildProcAddressing
(
    const Communicator& comm,
    const tetPolyMesh& mesh,
    const std::vector<globalLabel>& globalPointIds
)
{
    const int me = comm.rank();
    const int nRanks = comm.size();
    const label nInternal = mesh.nInternalFaces();

    procAddressing addr;
    addr.point = globalPointIds;

    const globalLabel cellOffset = comm.exclusiveScan(mesh.nCells);
    addr.cell.resize(mesh.nCells);
    std::iota(addr.cell.begin(), addr.cell.end(), cellOffset);

    // 1. Tell each neighbour the global cells behind our processor faces,
    //    in patch order (face i on both sides is the same face)
    std::vector<std::vector<globalLabel>> ownerCells(nRanks);
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
    struct procFace { label cell; globalLabel nbrCell; label face; };
    std::vector<procFace> upperFaces;
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo < me) continue;
        const std::vector<globalLabel>& nbr = neighbourCells[p.neighbProcNo];
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

    const globalLabel blockSize = nInternal + globalLabel(upperFaces.size());
    const globalLabel blockOffset = comm.exclusiveScan(blockSize);
    const globalLabel nGlobalInternal = comm.sum(blockSize);

    addr.face.assign(mesh.nFaces(), 0);
    globalLabel next = blockOffset;
    std::size_t u = 0;
    for (label f = 0; f < nInternal; ++f)
    {
        while (u < upperFaces.size() && upperFaces[u].cell < mesh.owner[f])
        {
            addr.face[upperFaces[u++].face] = ++next;     // +(index + 1)
        }
        addr.face[f] = ++next;
    }
    while (u < upperFaces.size())
    {
        addr.face[upperFaces[u++].face] = ++next;
    }

    // 3. The higher rank takes the lower rank's numbers, reversed
    std::vector<std::vector<globalLabel>> numbersToHigher(nRanks);
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo < me) continue;
        for (label f = p.start; f < p.start + p.size; ++f)
        {
            numbersToHigher[p.neighbProcNo].push_back(addr.face[f]);
        }
    }
    const auto fromLower = comm.exchange(numbersToHigher);
    for (const meshPatch& p : mesh.patches)
    {
        if (!p.isProcessor() || p.neighbProcNo > me) continue;
        const std::vector<globalLabel>& numbers = fromLower[p.neighbProcNo];
        for (label i = 0; i < p.size; ++i)
        {
            addr.face[p.start + i] = -numbers[i];
        }
    }

    // 4. Physical patches: rank by rank within each patch. A cyclic
    //    patch's faces whose image is on another rank (its processorCyclic
    //    patches) are faces of the cyclic patch, after the rank's own
    globalLabel patchStart = nGlobalInternal;
    for (std::size_t pi = 0; pi < mesh.patches.size(); ++pi)
    {
        const meshPatch& p = mesh.patches[pi];
        if (!p.isPhysical())
        {
            addr.boundary.push_back(-1);
            continue;
        }
        addr.boundary.push_back(globalLabel(pi));
        std::vector<const meshPatch*> parts{&p};
        for (const meshPatch& q : mesh.patches)
        {
            if (q.isProcessorCyclic() && q.neighbourPatch == p.name)
            {
                parts.push_back(&q);
            }
        }
        label nLocal = 0;
        for (const meshPatch* q : parts)
        {
            nLocal += q->size;
        }
        globalLabel next = patchStart + comm.exclusiveScan(nLocal);
        for (const meshPatch* q : parts)
        {
            for (label i = 0; i < q->size; ++i)
            {
                addr.face[q->start + i] = ++next;
            }
        }
        patchStart += comm.sum(std::int64_t(nLocal));
    }
    return addr;
}
