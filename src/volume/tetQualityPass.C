#include "tetQualityPass.H"
#include "qualityPassMesh.H"

#include <algorithm>

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * //

pmsh::qualityPassStats pmsh::improveWorstCells
(
    TetMesh& mesh,
    const label nFixedPoints,
    const std::vector<triVerts>& triangles,
    const std::vector<char>& interface,
    const int steps
)
{
    qualityPass::passMesh m(mesh, nFixedPoints, triangles, interface);
    qualityPassStats stats;

    m.rebuild();
    stats.worstBefore = m.worstFaces();
    for (int step = 0; step < steps; ++step)
    {
        // The tets of the bad faces, worst first
        std::vector<std::pair<double, label>> visit;
        for (label t = 0; t < m.nTets(); ++t)
        {
            if (m.sliver(t) > 0)
            {
                visit.push_back({m.sliver(t), t});
            }
            for (int k = 0; k < 4; ++k)
            {
                const double b = m.faceBadness(t, k);
                if (b > qualityPass::visitBadness)
                {
                    visit.push_back({b, t});
                    if (m.across(t, k) >= 0) visit.push_back({b, m.across(t, k)});
                }
            }
        }
        if (visit.empty()) break;
        std::sort(visit.rbegin(), visit.rend());
        for (const auto& v : visit)
        {
            m.improve(v.second);
        }
        m.rebuild();
    }

    stats.worstAfter = m.worstFaces();
    stats.nVisited = m.nVisited;
    stats.nMoved = m.nMoved;
    stats.nFlips = m.nFlips;
    return stats;
}


// ************************************************************************* //
