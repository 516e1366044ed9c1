#include "surfaceTopology.H"

#include <algorithm>
#include <tuple>

pmsh::surfaceEdgeDefects pmsh::findSurfaceEdgeDefects
(
    const std::vector<triFace>& triangles
)
{
    // Directed edge uses sorted by their undirected key: one flat sort
    struct edgeUse
    {
        label lo, hi;
        bool forward;   // lo -> hi

        bool operator<(const edgeUse& o) const
        {
            return std::tie(lo, hi, forward) < std::tie(o.lo, o.hi, o.forward);
        }
    };
    std::vector<edgeUse> uses;
    uses.reserve(3*triangles.size());
    for (const triFace& f : triangles)
    {
        for (int k = 0; k < 3; ++k)
        {
            const label a = f[k];
            const label b = f[(k + 1) % 3];
            uses.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    }
    std::sort(uses.begin(), uses.end());

    surfaceEdgeDefects d;
    for (std::size_t i = 0; i < uses.size(); )
    {
        std::size_t j = i;
        int nForward = 0;
        while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi)
        {
            nForward += uses[j].forward;
            ++j;
        }
        const std::pair<label, label> edge{uses[i].lo, uses[i].hi};
        const std::size_t n = j - i;
        if (n == 1)
        {
            if (!d.nOpen++) d.firstOpen = edge;
        }
        else if (n > 2)
        {
            if (!d.nNonManifold++) d.firstNonManifold = edge;
        }
        else if (nForward != 1)
        {
            if (!d.nInconsistent++) d.firstInconsistent = edge;
        }
        i = j;
    }
    return d;
}


pmsh::surfacePointDefects pmsh::findSurfacePointDefects
(
    label nPoints,
    const std::vector<triFace>& triangles
)
{
    surfacePointDefects defects;
    std::vector<bool> used(nPoints, false);
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
        for (label p : triangles[t])
        {
            if (p < 0 || p >= nPoints)
            {
                defects.badTriangle = label(t);
                defects.badPoint = p;
                return defects;
            }
            used[p] = true;
        }
    }
    const auto unused = std::find(used.begin(), used.end(), false);
    if (unused != used.end())
    {
        defects.firstUnused = label(unused - used.begin());
    }
    return defects;
}
