#include "writeRankMesh.H"
#include "caseControl.H"
#include "cyclicFaces.H"
#include "failTogether.H"
#include "foamMeshOutput.H"
#include "pmshError.H"
#include "procAddressing.H"
#include "tetsToPolyMesh.H"

namespace
{

using namespace pmsh;

// The zone of every cell: the tets' then the prisms' (none without zones)
std::vector<label> cellZonesOf(rankTets& share, label nCells)
{
    std::vector<label> zones = std::move(share.tetZone);
    zones.insert(zones.end(), share.prismZone.begin(), share.prismZone.end());
    freeStorage(share.prismZone);
    if (!zones.empty() && label(zones.size()) != nCells)
    {
        throw FatalError
        (
            msg() << zones.size() << " cell zones (tetZone and prismZone)"
                " given for " << nCells << " cells (need one per cell, or none)",
            "writeRankMesh"
        );
    }
    return zones;
}


// The share's tets as a polyMesh (its arrays freed as they are used), the
// cyclic faces in the order both sides of a cyclic patch agree on
tetPolyMesh polyMeshOf
(
    const Communicator& comm,
    rankTets& share,
    const CoarseMesh& coarse,
    const std::vector<std::array<label, 2>>& zonePairs
)
{
    tetPolyMesh mesh;
    failTogether(comm, [&]
    {
        mesh = tetsToPolyMesh
        (
            std::move(share.points), share.tets,
            share.triangles, share.region,
            coarse.patches, comm.parallel() ? comm.rank() : -1,
            share.globalIds,
            share.prisms, share.quads, share.quadRegion
        );
        freeStorage(share.tets);
        freeStorage(share.triangles);
        freeStorage(share.region);
        freeStorage(share.prisms);
        freeStorage(share.quads);
        freeStorage(share.quadRegion);
        mesh.zoneNames = coarse.zones;
        mesh.cellZone = cellZonesOf(share, mesh.nCells);
        mesh.zonePairs = zonePairs;
    });
    if (!coarse.periodicPatches.empty())
    {
        // Collective: in its own failTogether
        failTogether(comm, [&]
        {
            orderCyclicFaces(comm, mesh, share.pointIds, coarse);
        });
        freeStorage(share.pointIds);
    }
    return mesh;
}

} // End anonymous namespace


pmsh::writtenMesh pmsh::writeRankMesh
(
    const Communicator& comm,
    rankTets& share,
    const CoarseMesh& coarse,
    const std::vector<std::array<label, 2>>& zonePairs,
    const partitionVolumeResult& volume,
    const std::vector<fieldTemplate>& fieldTemplates,
    const Foam::word& outputFileHandler,
    const caseOutput& output
)
{
    tetPolyMesh rankMesh = polyMeshOf(comm, share, coarse, zonePairs);
    writtenMesh written;
    written.sizes = meshSizesOf(rankMesh);
    procAddressing addressing;
    if (comm.parallel())
    {
        addressing = buildProcAddressing(comm, rankMesh, share.globalIds);
    }
    share = rankTets();

    failTogether(comm, [&]
    {
        useFileHandler(outputFileHandler);
        if (comm.parallel())
        {
            writeProcAddressing(output.time(), std::move(addressing));
        }
        const foamRankMesh foamMesh(output.time(), std::move(rankMesh));
        const Foam::fvMesh& mesh = foamMesh();
        foamMesh.write();
        for (const fieldTemplate& field : fieldTemplates)
        {
            writeProcessorField(field, mesh);
        }
        // Last, once the fields are gone: the mesh geometry it needs is
        // the peak of this stage
        written.quality = meshQualityOf
        (
            comm, mesh, {volume.minDihedral, volume.maxDihedral, volume.maxAspectRatio}
        );
    });
    return written;
}


void pmsh::checkFieldTemplates
(
    const Communicator& comm,
    const std::vector<meshPatch>& physicalPatches,
    const std::vector<fieldTemplate>& fieldTemplates,
    const caseOutput& output
)
{
    if (fieldTemplates.empty())
    {
        return;
    }
    failTogether(comm, [&]
    {
        checkPatchCoverage(fieldTemplates, physicalPatches);
        tetPolyMesh patchesOnly;
        patchesOnly.patches = physicalPatches;
        for (meshPatch& p : patchesOnly.patches)
        {
            p.start = 0;
            p.size = 0;
        }
        const foamRankMesh mesh(output.time(), std::move(patchesOnly));
        for (const fieldTemplate& field : fieldTemplates)
        {
            checkFieldOnPatches(field, mesh());
        }
    });
}
