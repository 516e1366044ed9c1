#include "tetQualityPass.H"
#include "qualityPassMesh.H"

#include <algorithm>

// * * * * * * * * * * * * * * * Local Functions  * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

//- The tets one step visits, worst first and once each: the slivers
//  worse than `sliverBadness`, and the tets on both sides of the faces
//  worse than `faceBadness`. Tets that were quiet at the last scan, and
//  still are, are not measured again. With `worst`, the worst measures of
//  the faces measured go there too.
std::vector<std::pair<double, label>> tetsToVisit
(
    qualityPass::passMesh& m,
    const double sliverBadness,
    const double faceBadness,
    qualityPass::measure* worst
)
{
    std::vector<std::pair<double, label>> visit;
    for (label t = 0; t < m.nTets(); ++t)
    {
        if (m.quiet(t)) continue;
        const std::size_t listed = visit.size();
        if (m.sliver(t) > sliverBadness)
        {
            visit.push_back({m.sliver(t), t});
        }
        for (int k = 0; k < 4; ++k)
        {
            const double b = m.faceBadness(t, k, worst);
            if (b > faceBadness)
            {
                visit.push_back({b, t});
                if (m.across(t, k) >= 0) visit.push_back({b, m.across(t, k)});
            }
        }
        m.setQuiet(t, visit.size() == listed);
    }
    // Worst first, each tet once: a second visit of a tet (listed for
    // two of its faces, or from both sides of one) found it flipped, or
    // smoothed it again to little effect (15 % of the visits on a sphere)
    std::sort(visit.rbegin(), visit.rend());
    std::vector<char> listed(m.nTets(), 0);
    std::size_t n = 0;
    for (const auto& v : visit)
    {
        if (!listed[v.second]++) visit[n++] = v;
    }
    visit.resize(n);
    return visit;
}


//- Up to `steps` steps, each visiting tetsToVisit(m, sliverBadness,
//  faceBadness); stops early when there is nothing left to visit. The
//  worst faces before are measured if measureWorst, by the first scan
//  (which measures every face).
qualityPassStats runSteps
(
    qualityPass::passMesh& m,
    const int steps,
    const double sliverBadness,
    const double faceBadness,
    const bool measureWorst
)
{
    qualityPassStats stats;
    m.rebuild();
    qualityPass::measure worst{0, 0};
    std::vector<std::pair<double, label>> visit =
        tetsToVisit(m, sliverBadness, faceBadness, measureWorst ? &worst : nullptr);
    if (measureWorst)
    {
        stats.worstBefore = {qualityPass::degrees(worst.tan2), worst.skew};
    }
    for (int step = 0; step < steps && !visit.empty(); ++step)
    {
        const label changesBefore = m.nFlips + m.nMoved;
        for (const auto& v : visit)
        {
            m.improve(v.second);
        }
        m.rebuild();
        // A step that changed nothing would be repeated exactly
        if (m.nFlips + m.nMoved == changesBefore) break;
        if (step + 1 < steps)
        {
            visit = tetsToVisit(m, sliverBadness, faceBadness, nullptr);
        }
    }
    stats.nVisited = m.nVisited;
    stats.nMoved = m.nMoved;
    stats.nFlips = m.nFlips;
    stats.nInserted = m.nInserted;
    return stats;
}

} // End anonymous namespace


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
    m.flatWallCellsCount = true;
    const qualityPassStats all = runSteps(m, steps, 0, qualityPass::visitBadness, true);
    // Then the worst faces alone (the counts in m run on), with a point
    // where neither flips nor smoothing mend them
    m.insertAbove = qualityPass::worstFaceBadness;
    const label insertedBefore = m.nInserted;
    runSteps(m, qualityPass::worstFaceSteps, 0, qualityPass::worstFaceBadness, false);
    const label insertedAtWorstFaces = m.nInserted - insertedBefore;
    m.insertAbove = qualityPass::infinite;
    m.flatWallCellsCount = false;
    // Last, what checkMesh would still reject, as removeSlivers does (a
    // point inserted where no flip or move mends it): with one step, a
    // sphere partition of 2.3M cells kept a sliver of aspect ratio 1.5e10,
    // which the contract refused, and was meshed again with two
    m.insertPoints = true;
    qualityPassStats stats = runSteps
    (
        m, sliverRemovalSteps, qualityPass::rejectSliverBadness, qualityPass::rejectBadness, false
    );
    stats.worstBefore = all.worstBefore;
    stats.nInsertedAtWorstFaces = insertedAtWorstFaces;
    // The last step ended with a rebuild: the faces were matched anew,
    // which the contract need not do again (VolumeMesher::mesh)
    mesh.across = m.takeAcross();
    return stats;
}


pmsh::qualityPassStats pmsh::removeSlivers
(
    TetMesh& mesh,
    const label nFixedPoints,
    const std::vector<triVerts>& triangles,
    const std::vector<char>& interface
)
{
    qualityPass::passMesh m(mesh, nFixedPoints, triangles, interface);
    m.insertPoints = true;
    const qualityPassStats stats = runSteps
    (
        m, sliverRemovalSteps, qualityPass::rejectSliverBadness, qualityPass::rejectBadness,
        false
    );
    mesh.across = m.takeAcross();
    return stats;
}


// ************************************************************************* //
