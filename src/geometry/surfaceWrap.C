#include "surfaceWrap.H"
#include "cgalSurface.H"
#include "matchByPoints.H"

#include <CGAL/alpha_wrap_3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <cmath>
#include <vector>

namespace
{

//- The CAD's feature edges (two triangles of one solid meeting at more than
//  surfaceFeatureAngle, or of two solids), sampled every `spacing`,
//  ends included: where the wrap rounds the CAD's corners and trailing
//  edges. Edges of one triangle or of three and more (the dirt the wrap
//  is for) have no angle and are left out.
std::vector<pmsh::point3> featureEdgeSamples
(
    const pmsh::stlSurface& s,
    const double spacing,
    pmsh::label& nFeatureEdges
)
{
    using namespace pmsh;
    const double cosFeature = std::cos(surfaceFeatureAngle*M_PI/180.0);
    std::vector<point3> samples;
    nFeatureEdges = 0;
    forEachSamePointsGroup
    (
        s.points.size(), matchId(3*s.nTriangles()),
        [&](matchId id) { return triangleEdge(s.triangles, id); },
        [&](const matchId* ids, std::size_t n)
        {
            if (n != 2) return;
            const label t1 = label(ids[0]/3), t2 = label(ids[1]/3);
            const vector3 n1 = s.areaNormal(t1), n2 = s.areaNormal(t2);
            const double m = std::sqrt(magSqr(n1)*magSqr(n2));
            if (s.solid[t1] == s.solid[t2] && (m <= 0 || dot(n1, n2) >= cosFeature*m))
            {
                return;
            }
            ++nFeatureEdges;
            const triVerts& f = s.triangles[t1];
            const point3& a = s.points[f[ids[0] % 3]];
            const point3& b = s.points[f[(ids[0] + 1) % 3]];
            const int nSteps = std::max(1, int(std::ceil(std::sqrt(magSqr(b - a))/spacing)));
            for (int k = 0; k <= nSteps; ++k)
            {
                samples.push_back(a + (double(k)/nSteps)*(b - a));
            }
        }
    );
    return samples;
}

} // End anonymous namespace


pmsh::label pmsh::tidyWrapPatches(stlSurface& s, const label smallestIsland)
{
    // Each triangle's neighbours across its edges (the wrap is a closed
    // 2-manifold: two triangles an edge); edge k of triangle t is 3t + k
    const label nt = s.nTriangles();
    std::vector<std::array<label, 3>> across(nt, {-1, -1, -1});
    forEachSamePointsGroup
    (
        s.points.size(), matchId(3*nt),
        [&](matchId id) { return triangleEdge(s.triangles, id); },
        [&](const matchId* ids, std::size_t n)
        {
            if (n == 2)
            {
                across[ids[0]/3][ids[0] % 3] = label(ids[1]/3);
                across[ids[1]/3][ids[1] % 3] = label(ids[0]/3);
            }
        }
    );

    label nChanged = 0;
    // A triangle two of whose neighbours agree on another patch takes it:
    // spikes and single triangles go, borders straighten. A few sweeps
    // only: repeated, they eat into narrow strips from their ends
    for (int sweep = 0; sweep < 3; ++sweep)
    {
        label changed = 0;
        for (label t = 0; t < nt; ++t)
        {
            const std::array<label, 3>& n = across[t];
            for (int k = 0; k < 3; ++k)
            {
                const label a = n[k], b = n[(k + 1) % 3];
                if
                (
                    a >= 0 && b >= 0 && s.solid[a] == s.solid[b]
                 && s.solid[a] != s.solid[t]
                )
                {
                    s.solid[t] = s.solid[a];
                    ++changed;
                    break;
                }
            }
        }
        nChanged += changed;
        if (!changed) break;
    }

    // Islands of fewer than smallestIsland triangles join the patch they
    // share most edges with
    std::vector<label> island(nt, -1);
    std::vector<label> stack;
    for (label seed = 0; seed < nt; ++seed)
    {
        if (island[seed] >= 0) continue;
        std::vector<label> members{seed};
        island[seed] = seed;
        stack.assign(1, seed);
        std::map<label, label> bordering;
        while (!stack.empty())
        {
            const label t = stack.back();
            stack.pop_back();
            for (const label u : across[t])
            {
                if (u < 0) continue;
                if (s.solid[u] != s.solid[seed])
                {
                    ++bordering[s.solid[u]];
                }
                else if (island[u] < 0)
                {
                    island[u] = seed;
                    members.push_back(u);
                    stack.push_back(u);
                }
            }
        }
        if (label(members.size()) < smallestIsland && !bordering.empty())
        {
            const auto most = std::max_element
            (
                bordering.begin(), bordering.end(),
                [](const auto& x, const auto& y) { return x.second < y.second; }
            );
            for (const label t : members)
            {
                s.solid[t] = most->first;
                island[t] = -2;     // visited; may join a later island
            }
            nChanged += label(members.size());
        }
    }
    return nChanged;
}


pmsh::stlSurface pmsh::wrapSurface
(
    const stlSurface& s,
    const double size,
    const double offset,
    surfaceWrapReport& report
)
{
    const auto start = std::chrono::steady_clock::now();

    std::vector<cgal::Point> points;
    points.reserve(s.points.size());
    for (const point3& p : s.points)
    {
        points.push_back(cgal::toCgal(p));
    }
    // alpha_wrap_3 takes a soup: repeated, crossing or open faces are all
    // fine, but a face is a range of point indices
    std::vector<std::array<std::size_t, 3>> faces;
    faces.reserve(s.triangles.size());
    for (const triVerts& t : s.triangles)
    {
        faces.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
    }

    cgal::Mesh wrap;
    CGAL::alpha_wrap_3(points, faces, size, offset, wrap);
    wrap.collect_garbage();     // nothing removed: vertex indices number points

    const cgal::triangleTree inputTree(s);

    stlSurface out;
    out.solidNames = s.solidNames;
    for (const cgal::Mesh::Vertex_index v : wrap.vertices())
    {
        out.points.push_back(cgal::toPoint3(wrap.point(v)));
    }
    for (const cgal::Mesh::Face_index f : wrap.faces())
    {
        out.triangles.push_back(cgal::triangleOf(wrap, f));
        out.solid.push_back(s.solid[inputTree.nearest(out.centroid(out.nTriangles() - 1))]);
    }

    report.nTidied = tidyWrapPatches(out, smallestPatchIsland);

    // How far the mesh's boundary may lie from the CAD: the wrap's points
    // lie on the offset surface, its triangles' centres further where
    // they bridge a concave corner or a gap narrower than size
    double maxDistance2 = 0;
    for (const point3& p : out.points)
    {
        maxDistance2 = std::max(maxDistance2, inputTree.squaredDistance(p));
    }
    for (label t = 0; t < out.nTriangles(); ++t)
    {
        maxDistance2 = std::max(maxDistance2, inputTree.squaredDistance(out.centroid(t)));
    }

    // How far the wrap lies from the CAD's feature edges: a convex edge is
    // rounded at about the offset, a concave one bridged further
    const cgal::triangleTree wrapTree(out);
    double featureDistance2 = -1;
    label nSamples = 0, nWithinSize = 0;
    for (const point3& p : featureEdgeSamples(s, 0.25*size, report.nFeatureEdges))
    {
        const double d2 = wrapTree.squaredDistance(p);
        ++nSamples;
        nWithinSize += (d2 <= size*size);
        if (d2 > featureDistance2)
        {
            featureDistance2 = d2;
            report.featureDistanceAt = p;
        }
    }
    report.featureDistance = std::sqrt(std::max(featureDistance2, 0.0));
    report.featureShareWithinSize = nSamples ? double(nWithinSize)/nSamples : 1.0;

    report.wrapped = true;
    report.size = size;
    report.offset = offset;
    report.nInputTriangles = s.nTriangles();
    report.nTriangles = out.nTriangles();
    report.maxDistance = std::sqrt(maxDistance2);
    report.seconds = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    return out;
}


// ************************************************************************* //
