/*---------------------------------------------------------------------------*\
  pmshFoam: what both ways into HXT share (hxtBackends.H): the closed
  shells of a partition's surface and the volumes they bound, and the
  largest interior size at each point.
\*---------------------------------------------------------------------------*/

#include "hxtBackends.H"
#include "surfaceTopology.H"

#include <algorithm>


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * //

pmsh::shellVolumes pmsh::findShellVolumes
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles
)
{
    shellVolumes result;
    label nShells = 0;
    result.shellOf = surfaceShells(label(points.size()), triangles, nShells);
    result.shells.resize(nShells);
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        result.shells[result.shellOf[t]].push_back(label(t));
    }

    // Outer shells enclose a positive volume (outward normals)
    std::vector<label> outers;
    std::vector<double> outerSize;
    for (std::size_t s = 0; s < result.shells.size(); ++s)
    {
        double volume6 = 0;
        for (label i : result.shells[s])
        {
            const triVerts& t = triangles[i];
            volume6 += dot(points[t[0]], cross(points[t[1]], points[t[2]]));
        }
        if (volume6 > 0)
        {
            outers.push_back(label(s));
            outerSize.push_back(volume6);
        }
    }
    for (label o : outers)
    {
        result.volumes.push_back({o});
    }
    if (outers.empty())
    {
        return result;
    }
    for (std::size_t s = 0; s < result.shells.size(); ++s)
    {
        if (std::find(outers.begin(), outers.end(), label(s)) != outers.end()) continue;
        const point3& p = points[triangles[result.shells[s][0]][0]];
        std::size_t owner = outers.size();
        for (std::size_t o = 0; o < outers.size(); ++o)
        {
            const bool around =
                outers.size() == 1
             || windingNumber(points, triangles, result.shells[outers[o]], p) > 0.5;
            if (around && (owner == outers.size() || outerSize[o] < outerSize[owner]))
            {
                owner = o;
            }
        }
        result.volumes[owner == outers.size() ? 0 : owner].push_back(label(s));
    }
    return result;
}


pmsh::ng::sizeField pmsh::hxtSizeField
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters
)
{
    // Netgen's tree, with two shares that make HXT's cells come out as
    // Netgen's do (bench/results/size-grading.md):
    // - Netgen's cells grow at about 0.6 of its tree's grading away from a
    //   body (its advancing front sizes each new cell by the front's faces
    //   too): with the tree's grading, HXT's edges were 1.1-1.3 times
    //   Netgen's 0.1-1.5 from sphereDrag's ball;
    // - inside a refinement region HXT's edges come out about 1.3 times
    //   the region's size, Netgen's at about its size (sphereDrag's wake).
    // Where maxCellSize holds alone, both make edges of about 1.35 times
    // it: the sphere tutorial (maxCellSize 0.1, r = 1) gets 124k cells from
    // HXT, 129k from Netgen. A share on maxCellSize too made HXT's 2.1
    // times Netgen's there.
    constexpr double gradingShare = 0.6;
    constexpr double regionShare = 0.75;
    ng::meshParameters sizes = ng::meshParametersOf(parameters);
    sizes.grading *= gradingShare;
    for (sizeRegion& r : sizes.regions)
    {
        r.size *= regionShare;
    }
    return ng::sizeField(surfacePoints, surfaceTriangles, sizes);
}


// ************************************************************************* //
