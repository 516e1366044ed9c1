#include "qualityPassMesh.H"

#include <algorithm>
#include <limits>
#include <numeric>

// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

pmsh::qualityPass::passMesh::passMesh
(
    TetMesh& mesh,
    label nFixed,
    const std::vector<triVerts>& triangles,
    const std::vector<char>& interface
)
:
    points_(mesh.points),
    tets_(mesh.tets),
    nFixed_(nFixed),
    triangles_(triangles),
    triStart_(nFixed + 1, 0),
    pointTris_(3*triangles.size()),
    processor_(triangles.size() + 1, 0)
{
    // The backend's matching, where there is one, addresses every tet
    // before the first rebuild; only the surface faces are left unknown
    if (mesh.tetsAcross.size() == 4*mesh.tets.size())
    {
        across_ = std::move(mesh.tetsAcross);
        for (label& u : across_)
        {
            if (u < 0) u = unknown;
        }
        nAddressed_ = label(mesh.tets.size());
    }
    freeStorage(mesh.tetsAcross);

    for (const triVerts& f : triangles)
    {
        for (label p : f) ++triStart_[p + 1];
    }
    std::partial_sum(triStart_.begin(), triStart_.end(), triStart_.begin());
    std::vector<label> fill(triStart_.begin(), triStart_.end() - 1);
    for (label t = 0; t < label(triangles.size()); ++t)
    {
        for (label p : triangles[t]) pointTris_[fill[p]++] = t;
        if (!interface.empty() && interface[t]) processor_[t] = 1;
    }
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void pmsh::qualityPass::passMesh::rebuild()
{
    // Nothing flipped, moved or inserted since the last rebuild (a step
    // that changed nothing, the first of the next run of steps): the
    // addressing holds, and a point whose smoothing failed would fail
    // again, so it is not tried again either
    const label changes = nFlips + nMoved + nInserted;
    if (nAddressed_ == nTets() && changes == changesAtRebuild_)
    {
        return;
    }
    changesAtRebuild_ = changes;

    // Remove the deleted tets; a tet addressed before keeps what is across
    // its faces, renumbered, unless that tet was deleted (unknown)
    std::vector<label> newIndex(tets_.size(), -1);
    label n = 0;
    for (label t = 0; t < label(tets_.size()); ++t)
    {
        if (tets_[t][0] >= 0) newIndex[t] = n++;
    }
    across_.resize(4*tets_.size(), unknown);
    quiet_.resize(tets_.size(), 0);
    for (label t = 0; t < label(tets_.size()); ++t)
    {
        const label to = newIndex[t];
        if (to < 0) continue;
        tets_[to] = tets_[t];
        quiet_[to] = t < nAddressed_ && quiet_[t];
        for (int k = 0; k < 4; ++k)
        {
            const label u = t < nAddressed_ ? across_[4*t + k] : unknown;
            across_[4*to + k] = u >= 0 ? (newIndex[u] >= 0 ? newIndex[u] : unknown) : u;
        }
    }
    tets_.resize(n);
    across_.resize(4*n);
    quiet_.resize(n);
    newIndex = std::vector<label>();

    buildPointTets(points_.size(), tets_, start_, pointTets_);
    for (label t = 0; t < n; ++t)
    {
        for (int k = 0; k < 4; ++k)
        {
            if (across_[4*t + k] != unknown) continue;
            const triVerts f = tetFace(tets_[t], k);
            const label u = findTet(t, f);
            if (u < 0)
            {
                across_[4*t + k] = acrossBoundary(boundaryTriangle(f));
                continue;
            }
            // Both sides at once: u's face is the one opposite its apex
            across_[4*t + k] = u;
            const label apex = apexOf(u, f);
            for (int l = 0; l < 4; ++l)
            {
                if (tets_[u][l] == apex) across_[4*u + 3 - l] = t;
            }
        }
    }
    nAddressed_ = n;
    locked_.assign(points_.size(), 0);
    moveClock_ = 0;
    movedAt_.assign(points_.size(), 0);
    failedAt_.assign(points_.size(), -1);
    forgetQuietNearChanges();
}


void pmsh::qualityPass::passMesh::forgetQuietNearChanges()
{
    // A tet reads a changed point when the point is on it or on a tet
    // across its faces: from each changed point's tets, those and the tets
    // across their faces (a few thousand tets after a step, not all)
    changed_.resize(points_.size(), 1);
    if (!anyQuiet_)
    {
        changed_.assign(points_.size(), 0);     // before the first scan
        return;
    }
    for (label p = 0; p < label(points_.size()); ++p)
    {
        if (!changed_[p]) continue;
        changed_[p] = 0;
        for (label i = start_[p]; i < start_[p + 1]; ++i)
        {
            const label u = pointTets_[i];
            quiet_[u] = 0;
            for (int k = 0; k < 4; ++k)
            {
                const label t = across_[4*u + k];
                if (t >= 0) quiet_[t] = 0;
            }
        }
    }
}


double pmsh::qualityPass::passMesh::faceBadness(label t, int k, measure* worst) const
{
    const label u = across_[4*t + k];
    if (u >= 0 && u < t) return -1;
    const measure m = measureOf(tets_[t], k, u, [&](label q) -> const point3& { return points_[q]; });
    const bool nonOrthCounts = nonOrthogonalityCounts(u);
    if (worst)
    {
        if (nonOrthCounts) worst->tan2 = std::max(worst->tan2, m.tan2);
        worst->skew = std::max(worst->skew, m.skew);
    }
    return badness(m, nonOrthCounts);
}


pmsh::label pmsh::qualityPass::passMesh::findTet(label t, const triVerts& f) const
{
    for (label i = start_[f[0]]; i < start_[f[0] + 1]; ++i)
    {
        const label u = pointTets_[i];
        if (u != t && has(u, f[1]) && has(u, f[2]))
        {
            return u;
        }
    }
    return -1;
}


pmsh::label pmsh::qualityPass::passMesh::boundaryTriangle(const triVerts& f) const
{
    if (f[0] < nFixed_)
    {
        for (label i = triStart_[f[0]]; i < triStart_[f[0] + 1]; ++i)
        {
            const triVerts& g = triangles_[pointTris_[i]];
            const auto in = [&](label p) { return g[0] == p || g[1] == p || g[2] == p; };
            if (in(f[1]) && in(f[2])) return pointTris_[i];
        }
    }
    return label(triangles_.size());
}


bool pmsh::qualityPass::passMesh::addressSet
(
    const std::vector<tetVerts>& set,
    const std::vector<label>& old,
    std::vector<std::array<label, 4>>& acrossOf,
    std::vector<std::array<label, 4>>& inSet
) const
{
    const auto sorted = [](triVerts f)
    {
        std::sort(f.begin(), f.end());
        return f;
    };
    std::vector<std::array<triVerts, 4>> faces(set.size());
    for (std::size_t i = 0; i < set.size(); ++i)
    {
        for (int k = 0; k < 4; ++k) faces[i][k] = sorted(tetFace(set[i], k));
    }
    // The faces of the old tets towards the rest of the mesh
    std::vector<std::pair<triVerts, label>> outer;
    for (label t : old)
    {
        for (int k = 0; k < 4; ++k)
        {
            const label u = across_[4*t + k];
            if (std::find(old.begin(), old.end(), u) == old.end())
            {
                outer.push_back({sorted(tetFace(tets_[t], k)), u});
            }
        }
    }
    acrossOf.assign(set.size(), {0, 0, 0, 0});      // each set below, or false
    inSet.assign(set.size(), {-1, -1, -1, -1});
    for (std::size_t i = 0; i < set.size(); ++i)
    {
        for (int k = 0; k < 4; ++k)
        {
            const triVerts& f = faces[i][k];
            bool found = false;
            for (std::size_t j = 0; j < set.size() && !found; ++j)
            {
                if (j == i) continue;
                for (int l = 0; l < 4 && !found; ++l)
                {
                    if (f == faces[j][l])
                    {
                        inSet[i][k] = label(j);
                        found = true;
                    }
                }
            }
            for (std::size_t j = 0; j < outer.size() && !found; ++j)
            {
                if (f == outer[j].first)
                {
                    acrossOf[i][k] = outer[j].second;
                    found = true;
                }
            }
            if (!found) return false;
        }
    }
    return true;
}


void pmsh::qualityPass::passMesh::replace(const std::vector<label>& old, const std::vector<tetVerts>& created)
{
    for (label t : old)
    {
        for (label p : tets_[t]) locked_[p] = changed_[p] = 1;
        tets_[t][0] = -1;
    }
    for (const tetVerts& c : created) tets_.push_back(c);
    ++nFlips;
}


bool pmsh::qualityPass::passMesh::movedSince(const std::vector<label>& star, label since) const
{
    const auto movedLater = [&](label p) { return movedAt_[p] > since; };
    for (label t : star)
    {
        if (anyPointRead(t, movedLater)) return true;
    }
    return false;
}


// ************************************************************************* //
