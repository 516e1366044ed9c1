#include "fineCellWeights.H"

#include <algorithm>
#include <cmath>

std::vector<double> pmsh::fineCellWeights
(
    const CoarseMesh& coarse,
    double maxCellSize,
    int refinementLevels,
    const std::vector<sizeRegion>& regions
)
{
    const label nPoints = coarse.nPoints();
    const label nCells = coarse.nCells();
    const double H = maxCellSize;

    // Vertex sizes: the mean length of the edges at a vertex (every edge
    // counted once per cell holding it: a fair average all the same)
    std::vector<double> size(nPoints, 0), count(nPoints, 0);
    for (const tetVerts& t : coarse.tets)
    {
        for (const auto& e : tetEdges)
        {
            const double l = distance(coarse.points[t[e[0]]], coarse.points[t[e[1]]]);
            size[t[e[0]]] += l;
            size[t[e[1]]] += l;
            count[t[e[0]]] += 1;
            count[t[e[1]]] += 1;
        }
    }
    for (label v = 0; v < nPoints; ++v)
    {
        size[v] = count[v] > 0 ? size[v]/count[v] : H;
    }

    // Smoothed twice over the neighbouring vertices, as the volume meshers
    // smooth their size fields
    for (int pass = 0; pass < 2; ++pass)
    {
        std::vector<double> sum(nPoints, 0);
        for (const tetVerts& t : coarse.tets)
        {
            for (const auto& e : tetEdges)
            {
                sum[t[e[0]]] += size[t[e[1]]];
                sum[t[e[1]]] += size[t[e[0]]];
            }
        }
        for (label v = 0; v < nPoints; ++v)
        {
            if (count[v] > 0)
            {
                size[v] = 0.5*size[v] + 0.5*sum[v]/count[v];
            }
        }
    }

    std::vector<double> weights(nCells);
    for (label c = 0; c < nCells; ++c)
    {
        const tetVerts& t = coarse.tets[c];
        const auto& x = coarse.points;
        const double volume = tetVolume6(x[t[0]], x[t[1]], x[t[2]], x[t[3]])/6;
        const double h = 0.25*(size[t[0]] + size[t[1]] + size[t[2]] + size[t[3]]);
        weights[c] = volume/(H*H*h);

        // Inside a refinement region the volume mesher is held to the
        // region's size, as to H in a uniform mesh: 1/h^3 there
        const point3 centroid = 0.25*(x[t[0]] + x[t[1]] + x[t[2]] + x[t[3]]);
        const double regionSize = regionSizeAt(regions, centroid, H);
        if (regionSize < H)
        {
            weights[c] = std::max(weights[c], 2*volume/(h*h*h));
        }
    }

    // Geometry faces, each added to its cell
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    const double beta = 0.6/double(1 << std::min(refinementLevels, 30));
    for (label c = 0; c < nCells; ++c)
    {
        for (label nbr : neighbours[c])
        {
            if (!isBoundaryNeighbour(nbr))
            {
                continue;
            }
            const triVerts& f = coarse.boundary[boundaryFaceOf(nbr)].v;
            const auto& x = coarse.points;
            const double area =
                0.5*std::sqrt(magSqr(cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]])));
            const double h = std::min
            (
                H,
                (distance(x[f[0]], x[f[1]]) + distance(x[f[1]], x[f[2]])
               + distance(x[f[2]], x[f[0]]))/3
            );
            weights[c] += beta*area/(h*h);
        }
    }

    // Never zero: every cell gives some fine cells (and metis divides by
    // the smallest weight)
    double mean = 0;
    for (double w : weights) mean += w;
    mean /= std::max<label>(nCells, 1);
    for (double& w : weights)
    {
        w = std::max(w, 1e-3*mean);
    }
    return weights;
}
