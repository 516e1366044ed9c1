#include "layerStars.H"

#include <algorithm>

namespace pmsh
{

namespace
{

//- Tag of the layered triangles' sums; unlayered surfaces are tagged by
//  their region (>= 0), partition interfaces do not count.
constexpr label layeredTag = -1;

//- Directions are smoothed where they are noisy for the stacks standing on
//  them: where a point's direction is further from the mean of its star's
//  than this share of its shortest edge over its spec's total thickness
//  (the tops' edges would stretch or shrink by more than this share). A
//  faceted STL's normals jump at its facets' edges; OpenFOAM's bullet,
//  whose 5-layer stacks are 4-7 of its fine edges thick, kept tops so
//  crumpled there that HXT's optimiser spent 47 of stage 4's 51 s on the
//  tets against them. On a smooth wall (a sphere, a pipe) nothing is
//  smoothed, and Max's exact normals stay as they are.
constexpr double noisyShare = 0.1;

//- Averaging passes over the noisy points and the points round them.
//  The bullet's tops: 10 passes, stage 4 in 31 s; 30 passes, 20 s.
constexpr int smoothingPasses = 30;


//- Unit direction d made to slide along unlayered surfaces of these unit
//  normals: in the plane of one, along the line where two meet.
vector3 slide(const vector3& d, const std::vector<vector3>& planes)
{
    if (planes.empty())
    {
        return d;
    }
    if (planes.size() > 1)
    {
        const vector3 line = normalised(cross(planes[0], planes[1]));
        if (magSqr(line) > 0)
        {
            return dot(d, line) >= 0 ? line : -1.0*line;
        }
    }
    return normalised(d - dot(d, planes[0])*planes[0]);
}


//- Triangle t's share of the normal at its point p, by Max's weights
//  (N. Max, J. Graphics Tools 4(2), 1999): cross(e1, e2)/(|e1|^2 |e2|^2)
//  for the edges from p, exact for points on a sphere, unlike angle or
//  area weights on triangles of uneven shape.
vector3 weightedNormal(const layerStars& stars, label t, label p)
{
    const triVerts f = stars.canonical(t);
    const auto& x = stars.surface().points;
    const int i = f[0] == p ? 0 : f[1] == p ? 1 : 2;
    const vector3 e1 = x[f[(i + 1) % 3]] - x[p];
    const vector3 e2 = x[f[(i + 2) % 3]] - x[p];
    return (1/(magSqr(e1)*magSqr(e2)))*cross(e1, e2);
}

//- The unit mean of the directions of each point's star, over its layered
//  triangles on every rank (each triangle adds its points' but a feature
//  point's: a sharp edge's fanned directions are not noise).
std::vector<vector3> starMeans
(
    const layerStars& stars,
    const std::vector<bool>& feature,
    const std::vector<vector3>& direction
)
{
    const auto sums = stars.sums
    (
        [&](label t, label, label& tag, vector3& value)
        {
            if (!stars.specOf(t)) return false;
            tag = layeredTag;
            value = vector3{0, 0, 0};
            for (const label q : stars.surface().triangles[t])
            {
                if (!feature[q]) value = value + direction[q];
            }
            return true;
        }
    );
    std::vector<vector3> mean(direction.size(), vector3{0, 0, 0});
    for (std::size_t p = 0; p < sums.size(); ++p)
    {
        if (!sums[p].empty()) mean[p] = normalised(sums[p][0].second);
    }
    return mean;
}


//- The points whose directions are noisy (noisyShare), given the means
//  of their stars (starMeans), and the points of their stars, on every
//  rank alike; never a feature point.
std::vector<bool> noisyStars
(
    const layerStars& stars,
    const std::vector<bool>& feature,
    const std::vector<vector3>& direction,
    const std::vector<vector3>& mean
)
{
    const auto& x = stars.surface().points;
    const auto& triangles = stars.surface().triangles;
    // Per point: the least of an edge over the total thickness round it
    const std::vector<double> edgeOverThickness = stars.minimum
    (
        [&](label t, label p)
        {
            double least = layerStars::none;
            const layerSpecification* spec = stars.specOf(t);
            if (!spec) return least;
            for (const label q : triangles[t])
            {
                if (q != p) least = std::min(least, distance(x[p], x[q])/spec->totalThickness());
            }
            return least;
        }
    );
    std::vector<bool> noisy(direction.size(), false);
    for (std::size_t p = 0; p < direction.size(); ++p)
    {
        noisy[p] = magSqr(direction[p]) > 0 && !feature[p] && magSqr(mean[p]) > 0
            && std::sqrt(magSqr(direction[p] - mean[p])) > noisyShare*edgeOverThickness[p];
    }
    const std::vector<double> nearNoisy = stars.minimum
    (
        [&](label t, label)
        {
            if (!stars.specOf(t)) return layerStars::none;
            for (const label q : triangles[t])
            {
                if (noisy[q]) return -1.0;
            }
            return layerStars::none;
        }
    );
    for (std::size_t p = 0; p < direction.size(); ++p)
    {
        noisy[p] = nearNoisy[p] < 0 && magSqr(direction[p]) > 0 && !feature[p];
    }
    return noisy;
}

} // End anonymous namespace


std::vector<vector3> layerDirections
(
    const layerStars& stars,
    const std::vector<bool>& feature,
    label& nSmoothed
)
{
    const auto normals = stars.sums
    (
        [&](label t, label p, label& tag, vector3& value)
        {
            if (stars.isInterface(t)) return false;
            tag = stars.specOf(t) ? layeredTag : stars.surface().region[t];
            value = weightedNormal(stars, t, p);
            return true;
        }
    );

    const label nPoints = normals.size();
    std::vector<vector3> direction(nPoints, vector3{0, 0, 0});
    std::vector<bool> slides(nPoints, false);
    for (label p = 0; p < nPoints; ++p)
    {
        if (normals[p].empty() || normals[p][0].first != layeredTag)
        {
            continue;
        }
        std::vector<vector3> planes;
        for (std::size_t i = 1; i < normals[p].size(); ++i)
        {
            planes.push_back(normalised(normals[p][i].second));
        }
        // Outward normals: the layers grow the other way
        direction[p] = slide(-1.0*normalised(normals[p][0].second), planes);
        slides[p] = !planes.empty();
    }

    // Noisy directions smoothed; directions that slide stay in their planes
    std::vector<vector3> mean = starMeans(stars, feature, direction);
    std::vector<bool> smoothed = noisyStars(stars, feature, direction, mean);
    for (label p = 0; p < nPoints; ++p)
    {
        smoothed[p] = smoothed[p] && !slides[p];
    }
    nSmoothed = 0;
    for (label p = 0; p < label(smoothed.size()); ++p)
    {
        nSmoothed += smoothed[p] && stars.counts(p);
    }
    if (stars.anyRank(nSmoothed > 0))
    {
        for (int pass = 0; pass < smoothingPasses; ++pass)
        {
            if (pass > 0) mean = starMeans(stars, feature, direction);
            for (label p = 0; p < nPoints; ++p)
            {
                if (smoothed[p] && magSqr(mean[p]) > 0) direction[p] = mean[p];
            }
        }
    }
    return direction;
}

} // End namespace pmsh
