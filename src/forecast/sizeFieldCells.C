#include "sizeFieldCells.H"

#include <cmath>
#include <queue>

namespace
{

using namespace pmsh;

// The coarse points' neighbours along the tets' edges, each edge once per
// tet holding it (a shortest-path search does not mind the repeats): the
// neighbours of point v are neighbour[first[v] .. first[v + 1]), 48 bytes
// a coarse tet
struct pointNeighbours
{
    std::vector<std::size_t> first;
    std::vector<label> neighbour;

    explicit pointNeighbours(const CoarseMesh& coarse)
    :
        first(coarse.nPoints() + 1, 0)
    {
        for (const tetVerts& t : coarse.tets)
        {
            for (const label v : t) first[v + 1] += 3;
        }
        for (std::size_t v = 0; v + 1 < first.size(); ++v) first[v + 1] += first[v];
        neighbour.resize(first.back());
        std::vector<std::size_t> next(first.begin(), first.end() - 1);
        for (const tetVerts& t : coarse.tets)
        {
            for (const auto& e : tetEdges)
            {
                neighbour[next[t[e[0]]]++] = t[e[1]];
                neighbour[next[t[e[1]]]++] = t[e[0]];
            }
        }
    }
};


double triangleArea(const CoarseMesh& coarse, const triVerts& f)
{
    const auto& x = coarse.points;
    return 0.5*std::sqrt(magSqr(cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]])));
}

double meanEdge(const CoarseMesh& coarse, const triVerts& f)
{
    const auto& x = coarse.points;
    return
    (
        distance(x[f[0]], x[f[1]]) + distance(x[f[1]], x[f[2]])
      + distance(x[f[2]], x[f[0]])
    )/3;
}

} // End anonymous namespace


pmsh::sizeFieldTerms pmsh::sizeFieldCells
(
    const CoarseMesh& coarse,
    double maxCellSize,
    double grading,
    int refinementLevels,
    const std::vector<sizeRegion>& regions,
    const std::map<label, layerSpecification>& layerSpecs
)
{
    const label nPoints = coarse.nPoints();
    const double refined = std::pow(2.0, refinementLevels);
    const auto& x = coarse.points;

    // The cap at every point, and at the boundary points the mean length
    // of their boundary edges, all at the fine scale
    std::vector<double> size(nPoints);
    for (label v = 0; v < nPoints; ++v)
    {
        size[v] = regionSizeAt(regions, x[v], maxCellSize)/refined;
    }
    std::vector<double> edgeSum(nPoints, 0), edgeCount(nPoints, 0);
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        for (int k = 0; k < 3; ++k)
        {
            const label a = f.v[k], b = f.v[(k + 1) % 3];
            const double l = distance(x[a], x[b]);
            edgeSum[a] += l;
            edgeSum[b] += l;
            edgeCount[a] += 1;
            edgeCount[b] += 1;
        }
    }
    for (label v = 0; v < nPoints; ++v)
    {
        if (edgeCount[v] > 0)
        {
            size[v] = std::min(size[v], edgeSum[v]/edgeCount[v]/refined);
        }
    }

    // Graded from every point (smallest first): s(u) <= s(v) + g |uv|
    {
        const pointNeighbours edges(coarse);
        using entry = std::pair<double, label>;
        std::priority_queue<entry, std::vector<entry>, std::greater<entry>> front;
        for (label v = 0; v < nPoints; ++v) front.push({size[v], v});
        std::vector<bool> done(nPoints, false);
        while (!front.empty())
        {
            const auto [s, v] = front.top();
            front.pop();
            if (done[v] || s > size[v]) continue;
            done[v] = true;
            for (std::size_t i = edges.first[v]; i < edges.first[v + 1]; ++i)
            {
                const label u = edges.neighbour[i];
                const double su = s + grading*distance(x[v], x[u]);
                if (su < size[u])
                {
                    size[u] = su;
                    front.push({su, u});
                }
            }
        }
    }

    sizeFieldTerms terms;
    for (const tetVerts& t : coarse.tets)
    {
        const double s = 0.25*(size[t[0]] + size[t[1]] + size[t[2]] + size[t[3]]);
        terms.sizeField += tetVolume6(x[t[0]], x[t[1]], x[t[2]], x[t[3]])/(6*s*s*s);
    }
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        const auto spec = layerSpecs.find(f.patch);
        if (spec != layerSpecs.end())
        {
            const double s = meanEdge(coarse, f.v)/refined;
            terms.layers += triangleArea(coarse, f.v)*spec->second.totalThickness()/(s*s*s);
        }
    }
    terms.coarse = double(coarse.nCells())*std::pow(8.0, refinementLevels);
    return terms;
}


// ************************************************************************* //
