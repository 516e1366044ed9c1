#include "stageData.H"
#include <algorithm>

std::vector<std::array<pmsh::label, 2>> pmsh::zonePairsOf(const CoarseMesh& coarse)
{
    std::vector<std::array<label, 2>> pairs;
    for (const coarseZoneFace& f : coarse.zoneFaces)
    {
        pairs.push_back({std::min(f.inside, f.outside), std::max(f.inside, f.outside)});
    }
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    return pairs;
}


void pmsh::dropFacesBetweenZones(FineSurface& surface)
{
    if (surface.zone.empty() && surface.piece.empty())
    {
        return;
    }
    std::size_t kept = 0;
    for (std::size_t t = 0; t < surface.triangles.size(); ++t)
    {
        if (!isBetweenZones(surface.region[t]))
        {
            surface.triangles[kept] = surface.triangles[t];
            surface.region[kept] = surface.region[t];
            if (!surface.zone.empty())
            {
                surface.zone[kept] = surface.zone[t];
            }
            ++kept;
        }
    }
    surface.triangles.resize(kept);
    surface.region.resize(kept);
    if (!surface.zone.empty())
    {
        surface.zone.resize(kept);
    }
    // The pieces are meshed and joined: the rank's surface is one again
    std::vector<label>().swap(surface.piece);
}


pmsh::rankTets pmsh::rankShareOf
(
    partitionVolumeResult& volume,
    FineSurface& surface,
    globalPointNumbering& numbering,
    bool keepPointIds,
    const wallLayers& layers,
    const layerPointList& layerPoints
)
{
    layerCells cells;
    if (!layers.prisms.empty())
    {
        cells = layerCellsOf(surface, layers, layerPoints, surface.points);
    }
    dropFacesBetweenZones(surface);
    rankTets share;
    share.points = std::move(volume.mesh.points);
    share.tets = std::move(volume.mesh.tets);
    volume.mesh = TetMesh();
    share.tetZone = std::move(volume.tetZone);
    share.triangles = std::move(surface.triangles);
    share.region = std::move(surface.region);
    share.globalIds = numbering.releaseGlobalIds();
    if (keepPointIds)
    {
        share.pointIds = std::move(surface.ids);
        share.pointIds.resize(share.points.size());
    }
    surface = FineSurface();
    appendLayerCells(share, std::move(cells));
    return share;
}


pmsh::meshSizes pmsh::meshSizesOf(const tetPolyMesh& mesh)
{
    // Faces count quads (prism layers) too: a quad is one face of faces;
    // cellZone holds the prisms' zones after the tets'
    meshSizes sizes;
    sizes.faces = double(mesh.nFaces());
    sizes.points = double(mesh.points.size());
    for (const meshPatch& p : mesh.patches)
    {
        if (p.isPhysical())
        {
            sizes.patches.push_back(p);
        }
    }
    sizes.zones = mesh.zoneNames;
    sizes.zoneCells.assign(mesh.zoneNames.size(), 0);
    for (label z : mesh.cellZone)
    {
        ++sizes.zoneCells[z];
    }
    // A cyclic patch's faces whose image is on another rank count too
    for (const meshPatch& p : mesh.patches)
    {
        if (p.isProcessorCyclic())
        {
            for (meshPatch& q : sizes.patches)
            {
                q.size += q.name == p.neighbourPatch ? p.size : 0;
            }
        }
    }
    return sizes;
}


// ************************************************************************* //
