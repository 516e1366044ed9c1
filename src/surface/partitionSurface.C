#include "partitionSurface.H"

pmsh::coarsePartSurface pmsh::partitionSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label myPart
)
{
    auto partOf = [&](label cell) { return cellPart.empty() ? 0 : cellPart[cell]; };
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);

    coarsePartSurface surf;
    for (label celli = 0; celli < coarse.nCells(); ++celli)
    {
        if (partOf(celli) != myPart)
        {
            continue;
        }
        const auto faces = outwardTetFaces(coarse.tets[celli]);
        for (int fi = 0; fi < 4; ++fi)
        {
            const label nbr = neighbours[celli][fi];
            if (isBoundaryNeighbour(nbr))
            {
                const coarseBoundaryFace& bf = coarse.boundary[boundaryFaceOf(nbr)];
                surf.faces.push_back(faces[fi]);
                surf.region.push_back(bf.patch);
                surf.surface.push_back(bf.surface);
            }
            else if (partOf(nbr) != myPart)
            {
                surf.faces.push_back(faces[fi]);
                surf.region.push_back(interfaceRegion(partOf(nbr)));
                surf.surface.push_back(-1);
            }
        }
    }
    return surf;
}
