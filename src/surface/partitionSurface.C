#include "partitionSurface.H"
#include "pmshError.H"

pmsh::coarsePartSurface pmsh::partitionSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label myPart,
    const std::vector<label>& cellPiece
)
{
    auto partOf = [&](label cell) { return cellPart.empty() ? 0 : cellPart[cell]; };
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);

    const bool zoned = !coarse.zones.empty();
    const zoneFaceIndex zoneFaces(coarse);

    coarsePartSurface surf;
    auto pieceOf = [&](label cell) { return cellPiece.empty() ? 0 : cellPiece[cell]; };
    // A face of `cell`, with the zone and piece behind it
    auto add = [&](const triVerts& f, label region, label surface, label cell)
    {
        surf.faces.push_back(f);
        surf.region.push_back(region);
        surf.surface.push_back(surface);
        if (zoned)
        {
            surf.zone.push_back(coarse.zoneOf(cell));
        }
        if (!cellPiece.empty())
        {
            surf.piece.push_back(cellPiece[cell]);
        }
    };
    for (label celli = 0; celli < coarse.nCells(); ++celli)
    {
        if (partOf(celli) != myPart)
        {
            continue;
        }
        const label zone = coarse.zoneOf(celli);
        const auto faces = outwardTetFaces(coarse.tets[celli]);
        for (int fi = 0; fi < 4; ++fi)
        {
            const label nbr = neighbours[celli][fi];
            if (isBoundaryNeighbour(nbr))
            {
                const coarseBoundaryFace& bf = coarse.boundary[boundaryFaceOf(nbr)];
                add(faces[fi], bf.patch, bf.surface, celli);
                continue;
            }
            const bool otherPart = partOf(nbr) != myPart;
            const bool otherZone = coarse.zoneOf(nbr) != zone;
            const bool otherPiece = pieceOf(nbr) != pieceOf(celli);
            if (!otherPart && !otherZone && !otherPiece)
            {
                continue;
            }
            label surface = -1;
            if (otherZone)
            {
                const label z = zoneFaces.find(faces[fi]);
                if (z < 0)
                {
                    throw FatalError
                    (
                        msg() << "Coarse cells " << celli << " and " << nbr
                            << " of zones " << coarse.zones[zone] << " and "
                            << coarse.zones[coarse.zoneOf(nbr)] << " share a"
                            << " face that is not a face between zones",
                        "partitionSurface"
                    );
                }
                surface = coarse.zoneFaces[z].surface;
            }
            add
            (
                faces[fi],
                otherPart ? interfaceRegion(partOf(nbr)) : betweenZonesRegion,
                surface, celli
            );
        }
    }
    return surf;
}
