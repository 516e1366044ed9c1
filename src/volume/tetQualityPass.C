#include "tetQualityPass.H"
#include "checkMeshFaceMetrics.H"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

// * * * * * * * * * * * * * * * Local functions * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

constexpr double infinite = std::numeric_limits<double>::infinity();

// A face's badness: the larger of tan^2(non-orthogonality)/tan^2(55 deg)
// and skewness^2/0.55^2, so that both count alike near what Netgen's own
// meshes reach (about 55 degrees and 0.6)
constexpr double nonOrthScale2 = 2.0396;    // tan^2(55 deg)
constexpr double skewScale2 = 0.3025;       // 0.55^2

// Faces worse than this (45 degrees or skewness 0.39) are visited: below
// it they do not set the maximum, and visiting them costs time
constexpr double visitBadness = 0.49;

// What lies across a tet face: another tet (>= 0) or a boundary triangle
constexpr label physicalBoundary = -1;
constexpr label processorBoundary = -2;

struct measure
{
    double tan2;    // tan^2 of the non-orthogonality
    double skew;
};

// checkMesh's measures of face (a, b, c) between tets with apexes d and
// e. The centre of a tet is the mean of its points (as OpenFOAM's for a
// tet), so Cpf and d need no centres.
measure internalMeasure
(
    const point3& a, const point3& b, const point3& c, const point3& d, const point3& e
)
{
    const point3 centre = (1.0/3.0)*(a + b + c);
    const vector3 area = cross(b - a, c - a);
    const vector3 D = 0.25*(e - d);          // cell centre to cell centre
    const vector3 Cpf = 0.25*(centre - d);   // cell centre to face centre
    return
    {
        nonOrthogonalityTan2(area, D),
        internalFaceSkewness(a, b, c, centre, area, Cpf, D)
    };
}

// Boundary face (a, b, c) of the tet with apex d: checkMesh's boundary
// skewness, and the angle between the face normal and the line from the
// face centre to the cell centre
measure boundaryMeasure
(
    const point3& a, const point3& b, const point3& c, const point3& d
)
{
    const point3 centre = (1.0/3.0)*(a + b + c);
    const boundaryFaceMetrics m = boundaryFaceMetricsOf
    (
        a, b, c, centre, cross(b - a, c - a), 0.25*(centre - d)
    );
    return {m.nonOrthogonalityTan2, m.skewness};
}

double badness(const measure& m, bool nonOrthCounts)
{
    const double s = m.skew*m.skew/skewScale2;
    return nonOrthCounts ? std::max(m.tan2/nonOrthScale2, s) : s;
}

// Slivers (flat tets) can have faces of fair non-orthogonality and
// skewness, yet checkMesh fails them (aspect ratio above 1000, or a volume
// it finds negative): a tet whose volume is below 1/20 of a regular tet's
// on its longest edge is bad by that factor squared. The common one is a
// crease sliver, two nearly coplanar surface triangles closed by an
// interior edge. At 1/1000 those were left with dihedral angles of 0.2
// degrees and aspect ratios near 400 (sphere, r = 4, 2 ranks); at 1/20
// the smallest angle is 5.6 degrees and non-orthogonality gets better too;
// at 1/10 the pass spends its steps on slivers and leaves worse faces
// (bench/results/quality-slivers.md)
constexpr double sliverVolume = 5e-2;

inline double sqr(double x) { return x*x; }

double sliverBadness(const point3& a, const point3& b, const point3& c, const point3& d)
{
    double longest2 = 0;
    const point3* p[4] = {&a, &b, &c, &d};
    for (int i = 0; i < 4; ++i)
    {
        for (int j = i + 1; j < 4; ++j)
        {
            longest2 = std::max(longest2, magSqr(*p[i] - *p[j]));
        }
    }
    const double v6 = tetVolume6(a, b, c, d);
    if (!(v6 > 0)) return infinite;
    // Regular: v6 = L^3/sqrt(2)
    const double relative = std::sqrt(2.0)*v6/(longest2*std::sqrt(longest2));
    return relative < sliverVolume ? sqr(sliverVolume/relative) : 0;
}


double degrees(double tan2)
{
    return std::atan(std::sqrt(tan2))*180/M_PI;
}

// Are faces of badness `b` better than faces of badness `a`: smaller at
// the first place where they differ, both sorted worst first? (Mostly the
// worst ones differ: sorting is left for ties.)
bool better(std::vector<double>& b, std::vector<double>& a)
{
    const double bMax = *std::max_element(b.begin(), b.end());
    const double aMax = *std::max_element(a.begin(), a.end());
    if (bMax < aMax*(1 - 1e-9)) return true;
    if (bMax > aMax*(1 + 1e-9)) return false;
    std::sort(b.rbegin(), b.rend());
    std::sort(a.rbegin(), a.rend());
    const std::size_t n = std::min(a.size(), b.size());
    for (std::size_t i = 1; i < n; ++i)
    {
        if (b[i] < a[i]*(1 - 1e-9)) return true;
        if (b[i] > a[i]*(1 + 1e-9)) return false;
    }
    return false;
}


//- The mesh with point-to-tet and tet-face addressing, rebuilt at every
//  step. Flips delete tets and append new ones without updating the
//  addressing: they lock their points instead, and nothing that needs the
//  addressing of a locked point or of a tet with one runs again before the
//  next rebuild.
class passMesh
{
    std::vector<point3>& points_;
    std::vector<tetVerts>& tets_;
    const label nFixed_;

    // Boundary triangles of each surface point (CSR), and their kind
    const std::vector<triVerts>& triangles_;
    std::vector<label> triStart_;
    std::vector<label> pointTris_;
    std::vector<label> kind_;

    std::vector<label> start_;      // tets of point p:
    std::vector<label> pointTets_;  // pointTets_[start_[p] .. start_[p+1])
    std::vector<label> across_;     // per tet face: tet or boundary kind
    std::vector<char> locked_;

public:

    label nVisited = 0;
    label nMoved = 0;
    label nFlips = 0;

    passMesh
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
        kind_(triangles.size(), physicalBoundary)
    {
        for (const triVerts& f : triangles)
        {
            for (label p : f) ++triStart_[p + 1];
        }
        std::partial_sum(triStart_.begin(), triStart_.end(), triStart_.begin());
        std::vector<label> fill(triStart_.begin(), triStart_.end() - 1);
        for (label t = 0; t < label(triangles.size()); ++t)
        {
            for (label p : triangles[t]) pointTris_[fill[p]++] = t;
            if (!interface.empty() && interface[t]) kind_[t] = processorBoundary;
        }
    }

    //- Remove deleted tets, rebuild the addressing, unlock every point.
    void rebuild()
    {
        tets_.erase
        (
            std::remove_if
            (
                tets_.begin(), tets_.end(), [](const tetVerts& c) { return c[0] < 0; }
            ),
            tets_.end()
        );
        start_.assign(points_.size() + 1, 0);
        for (const tetVerts& c : tets_)
        {
            for (label p : c) ++start_[p + 1];
        }
        std::partial_sum(start_.begin(), start_.end(), start_.begin());
        pointTets_.resize(start_.back());
        std::vector<label> fill(start_.begin(), start_.end() - 1);
        for (label t = 0; t < label(tets_.size()); ++t)
        {
            for (label p : tets_[t]) pointTets_[fill[p]++] = t;
        }
        across_.resize(4*tets_.size());
        for (label t = 0; t < label(tets_.size()); ++t)
        {
            for (int k = 0; k < 4; ++k)
            {
                const triVerts f = tetFace(tets_[t], k);
                const label u = findTet(t, f);
                across_[4*t + k] = u >= 0 ? u : boundaryKind(f);
            }
        }
        locked_.assign(points_.size(), 0);
    }

    //- Badness of face k of tet t (each face once: -1 for the second
    //  side of a face between two tets).
    double faceBadness(label t, int k) const
    {
        const label u = across_[4*t + k];
        if (u >= 0 && u < t) return -1;
        return badnessOf(tets_[t], k, u, [&](label q) -> const point3& { return points_[q]; });
    }

    faceQuality worstFaces() const
    {
        double tan2 = 0, skew = 0;
        for (label t = 0; t < label(tets_.size()); ++t)
        {
            for (int k = 0; k < 4; ++k)
            {
                const label u = across_[4*t + k];
                if (u >= 0 && u < t) continue;
                const measure m = measureOf
                (
                    tets_[t], k, u, [&](label q) -> const point3& { return points_[q]; }
                );
                if (u != physicalBoundary) tan2 = std::max(tan2, m.tan2);
                skew = std::max(skew, m.skew);
            }
        }
        return {degrees(tan2), skew};
    }

    label nTets() const { return label(tets_.size()); }

    //- How much of a sliver tet t is (0: none).
    double sliver(label t) const
    {
        const tetVerts& c = tets_[t];
        return sliverBadness(points_[c[0]], points_[c[1]], points_[c[2]], points_[c[3]]);
    }

    //- What is across face k of tet t: a tet, or a boundary kind (< 0).
    label across(label t, int k) const { return across_[4*t + k]; }

    //- Visit one tet: the best improving flip, else smooth its points.
    void improve(label t)
    {
        if (tets_[t][0] < 0)
        {
            return;
        }
        ++nVisited;
        if (!flip(t))
        {
            const tetVerts c = tets_[t];
            for (label p : c)
            {
                if (p >= nFixed_ && !locked_[p])
                {
                    smooth(p);
                }
            }
        }
    }

private:

    bool has(label t, label p) const
    {
        const tetVerts& c = tets_[t];
        return c[0] == p || c[1] == p || c[2] == p || c[3] == p;
    }

    //- The tet other than t with the points of f; -1 if none.
    label findTet(label t, const triVerts& f) const
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

    //- Processor or physical boundary, for a face on no other tet.
    label boundaryKind(const triVerts& f) const
    {
        if (f[0] < nFixed_)
        {
            for (label i = triStart_[f[0]]; i < triStart_[f[0] + 1]; ++i)
            {
                const triVerts& g = triangles_[pointTris_[i]];
                const auto in = [&](label p) { return g[0] == p || g[1] == p || g[2] == p; };
                if (in(f[1]) && in(f[2])) return kind_[pointTris_[i]];
            }
        }
        return physicalBoundary;
    }

    //- The point of tet u that is not on face f.
    label apexOf(label u, const triVerts& f) const
    {
        for (label q : tets_[u])
        {
            if (q != f[0] && q != f[1] && q != f[2]) return q;
        }
        return -1;
    }

    //- Measures of face k of tet c, with `u` across it, points from pos.
    template<class Pos>
    measure measureOf(const tetVerts& c, int k, label u, const Pos& pos) const
    {
        const triVerts f = tetFace(c, k);
        const point3& d = pos(c[3 - k]);
        if (u >= 0)
        {
            return internalMeasure(pos(f[0]), pos(f[1]), pos(f[2]), d, pos(apexOf(u, f)));
        }
        return boundaryMeasure(pos(f[0]), pos(f[1]), pos(f[2]), d);
    }

    template<class Pos>
    double badnessOf(const tetVerts& c, int k, label u, const Pos& pos) const
    {
        return badness(measureOf(c, k, u, pos), u != physicalBoundary);
    }

    //- Badness of every face of tets `set` (each face once), points from
    //  pos. `acrossOf(i, k)` says what is across face k of set[i]: a tet
    //  index outside the set, a boundary kind, or (via `inSet`) set member.
    //- Badness of face k of set[i]: across it is set[inSet[i][k]] if that
    //  is >= 0, else acrossOf[i][k] (a tet outside, or a boundary kind).
    template<class Pos>
    double faceBadnessIn
    (
        const std::vector<tetVerts>& set,
        const std::vector<std::array<label, 4>>& acrossOf,
        const std::vector<std::array<label, 4>>& inSet,
        std::size_t i, int k,
        const Pos& pos
    ) const
    {
        const label j = inSet[i][k];
        if (j < 0)
        {
            return badnessOf(set[i], k, acrossOf[i][k], pos);
        }
        const triVerts f = tetFace(set[i], k);
        label e = -1;
        for (label q : set[j])
        {
            if (q != f[0] && q != f[1] && q != f[2]) e = q;
        }
        return badness
        (
            internalMeasure(pos(f[0]), pos(f[1]), pos(f[2]), pos(set[i][3 - k]), pos(e)),
            true
        );
    }

    //- Badness of every face of tets `set` (each face once, infinite for
    //  a tet that is not positive), points from pos.
    template<class Pos>
    std::vector<double> setBadness
    (
        const std::vector<tetVerts>& set,
        const std::vector<std::array<label, 4>>& acrossOf,
        const std::vector<std::array<label, 4>>& inSet,
        const Pos& pos
    ) const
    {
        std::vector<double> b;
        b.reserve(4*set.size());
        for (std::size_t i = 0; i < set.size(); ++i)
        {
            const tetVerts& c = set[i];
            const double sliver = sliverBadness(pos(c[0]), pos(c[1]), pos(c[2]), pos(c[3]));
            if (sliver > 0)
            {
                b.push_back(sliver);
                if (!std::isfinite(sliver)) continue;
            }
            for (int k = 0; k < 4; ++k)
            {
                // Between two tets of the set: once, from the first
                if (inSet[i][k] >= 0 && std::size_t(inSet[i][k]) < i) continue;
                b.push_back(faceBadnessIn(set, acrossOf, inSet, i, k, pos));
            }
        }
        return b;
    }

    //- What is across each face of each tet of `set`: members of the set
    //  (inSet), else what was across the same face of one of `old` tets
    //  (acrossOf). False if a face matches neither.
    bool addressSet
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
        acrossOf.assign(set.size(), {-3, -3, -3, -3});
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

    //- Replace tets `old` by `created`, locking every point involved.
    void replace(const std::vector<label>& old, const std::vector<tetVerts>& created)
    {
        for (label t : old)
        {
            for (label p : tets_[t]) locked_[p] = 1;
            tets_[t][0] = -1;
        }
        for (const tetVerts& c : created) tets_.push_back(c);
        ++nFlips;
    }

    //- Is every point of tet t and of the tets across its faces unlocked
    //  (their addressing current)?
    bool current(label t) const
    {
        for (label p : tets_[t])
        {
            if (locked_[p]) return false;
        }
        for (int k = 0; k < 4; ++k)
        {
            const label u = across_[4*t + k];
            if (u >= 0)
            {
                for (label p : tets_[u])
                {
                    if (locked_[p]) return false;
                }
            }
        }
        return true;
    }

    //- Is the replacement of tets `old` by `created` better for the
    //  faces it changes?
    bool improves
    (
        const std::vector<label>& old,
        const std::vector<tetVerts>& created,
        std::vector<double>& createdBadness
    ) const
    {
        const auto pos = [&](label q) -> const point3& { return points_[q]; };
        std::vector<tetVerts> oldSet;
        for (label t : old) oldSet.push_back(tets_[t]);
        std::vector<std::array<label, 4>> acrossOf, inSet;
        if (!addressSet(oldSet, old, acrossOf, inSet)) return false;
        std::vector<double> before = setBadness(oldSet, acrossOf, inSet, pos);
        if (!addressSet(created, old, acrossOf, inSet)) return false;
        createdBadness = setBadness(created, acrossOf, inSet, pos);
        return better(createdBadness, before);
    }

    //- The points around edge a-b in order, given the tets around it;
    //  empty unless they close a ring of 3..6.
    std::vector<label> ringPoints(const std::vector<label>& ring, label a, label b) const
    {
        if (ring.size() < 3 || ring.size() > 6) return {};
        std::vector<std::array<label, 2>> pairs;
        for (label u : ring)
        {
            std::array<label, 2> pair{-1, -1};
            int n = 0;
            for (label q : tets_[u])
            {
                if (q != a && q != b) pair[n++] = q;
            }
            pairs.push_back(pair);
        }
        std::vector<label> polygon{pairs[0][0], pairs[0][1]};
        std::vector<char> used(pairs.size(), 0);
        used[0] = 1;
        while (polygon.size() < pairs.size())
        {
            bool found = false;
            for (std::size_t i = 0; i < pairs.size() && !found; ++i)
            {
                if (used[i]) continue;
                for (int k = 0; k < 2 && !found; ++k)
                {
                    if (pairs[i][k] == polygon.back())
                    {
                        polygon.push_back(pairs[i][1 - k]);
                        used[i] = found = true;
                    }
                }
            }
            if (!found) return {};
        }
        // The last unused pair closes the ring
        for (std::size_t i = 0; i < pairs.size(); ++i)
        {
            if (used[i]) continue;
            const auto& p = pairs[i];
            const bool closes =
                (p[0] == polygon.back() && p[1] == polygon.front())
             || (p[1] == polygon.back() && p[0] == polygon.front());
            if (!closes) return {};
        }
        std::vector<label> sorted(polygon);
        std::sort(sorted.begin(), sorted.end());
        if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return {};
        return polygon;
    }

    //- Every triangulation of the polygon of corners i..j (indices).
    static std::vector<std::vector<std::array<label, 3>>> triangulations(label i, label j)
    {
        if (j - i < 2) return {{}};
        std::vector<std::vector<std::array<label, 3>>> all;
        for (label k = i + 1; k < j; ++k)
        {
            for (const auto& left : triangulations(i, k))
            {
                for (const auto& right : triangulations(k, j))
                {
                    std::vector<std::array<label, 3>> t(left);
                    t.insert(t.end(), right.begin(), right.end());
                    t.push_back({i, k, j});
                    all.push_back(t);
                }
            }
        }
        return all;
    }

    //- The best flip involving tet t (2-3, or an edge removal) that makes
    //  its faces better; false if there is none.
    bool flip(label t)
    {
        const tetVerts c = tets_[t];
        for (label p : c)
        {
            if (locked_[p]) return false;
        }

        std::vector<label> bestOld;
        std::vector<tetVerts> bestNew;
        std::vector<double> bestBadness;
        const auto consider = [&](const std::vector<label>& old, const std::vector<tetVerts>& created)
        {
            for (label u : old)
            {
                if (!current(u)) return;
            }
            std::vector<double> b;
            if (improves(old, created, b) && (bestOld.empty() || better(b, bestBadness)))
            {
                bestOld = old;
                bestNew = created;
                bestBadness = b;
            }
        };

        // 2-3: the face opposite each point d, shared with tet u whose
        // other point is e, becomes three tets around edge d-e. With
        // (a, b, c) outward from t, (d, a, b, c) is positive, and so are
        // the new tets when d-e passes through the face
        for (int i = 0; i < 4; ++i)
        {
            const label u = across_[4*t + 3 - i];
            if (u < 0) continue;
            const label d = c[i];
            const triVerts f = tetFace(c, 3 - i);
            const label e = apexOf(u, f);
            consider
            (
                {t, u},
                {{d, f[0], f[1], e}, {d, f[1], f[2], e}, {d, f[2], f[0], e}}
            );
        }

        // Edge removal: an edge a-b with n = 3..6 tets around it in a
        // closed ring (an interior edge: at the boundary the fan is open)
        // becomes 2(n - 2) tets, a and b joined to the triangles of a
        // triangulation of the ring's points (the 3-2, 4-4, 5-6 and 6-8
        // flips). Rings of more than 3 cost more and lock more points: they
        // are for tets that smoothing does not mend, with all their points
        // on the surface, and for slivers
        bool movable = false;
        for (label p : c) movable = movable || p >= nFixed_;
        const bool isSliver = sliver(t) > 0;
        const std::size_t maxRing = movable && !isSliver ? 3 : 6;
        static const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
        for (const auto& e : edges)
        {
            const label a = c[e[0]];
            const label b = c[e[1]];
            std::vector<label> ring;
            for (label i = start_[a]; i < start_[a + 1]; ++i)
            {
                if (has(pointTets_[i], b)) ring.push_back(pointTets_[i]);
            }
            if (ring.size() > maxRing) continue;
            const std::vector<label> polygon = ringPoints(ring, a, b);
            if (polygon.empty()) continue;
            for (const auto& triangles : triangulations(0, label(polygon.size()) - 1))
            {
                std::vector<tetVerts> created;
                for (const auto& t : triangles)
                {
                    const label x = polygon[t[0]], y = polygon[t[1]], z = polygon[t[2]];
                    if (tetVolume6(points_[x], points_[y], points_[z], points_[a]) > 0)
                    {
                        created.push_back({x, y, z, a});
                        created.push_back({x, z, y, b});
                    }
                    else
                    {
                        created.push_back({x, z, y, a});
                        created.push_back({x, y, z, b});
                    }
                }
                consider(ring, created);
            }
        }

        if (bestOld.empty())
        {
            return false;
        }
        replace(bestOld, bestNew);
        return true;
    }

    //- Move interior point p to make the faces of its tets better: to
    //  the centre of its neighbours if that is better, then down the
    //  gradient of the worst face while they get better.
    void smooth(label p)
    {
        std::vector<label> star(pointTets_.begin() + start_[p], pointTets_.begin() + start_[p + 1]);
        for (label t : star)
        {
            if (!current(t)) return;
        }
        std::vector<tetVerts> set;
        std::vector<std::array<label, 4>> acrossOf(star.size()), inSet(star.size());
        for (std::size_t i = 0; i < star.size(); ++i)
        {
            set.push_back(tets_[star[i]]);
            for (int k = 0; k < 4; ++k)
            {
                const label u = across_[4*star[i] + k];
                const auto j = std::find(star.begin(), star.end(), u);
                inSet[i][k] = j == star.end() ? -1 : label(j - star.begin());
                acrossOf[i][k] = u;
            }
        }

        point3 x = points_[p];
        const auto at = [&](const point3& y)
        {
            return setBadness
            (
                set, acrossOf, inSet,
                [&](label q) -> const point3& { return q == p ? y : points_[q]; }
            );
        };

        point3 centre{0, 0, 0};
        double length = 0;
        label n = 0;
        for (const tetVerts& c : set)
        {
            for (label q : c)
            {
                if (q != p)
                {
                    centre = centre + points_[q];
                    length += std::sqrt(magSqr(points_[q] - x));
                    ++n;
                }
            }
        }
        centre = (1.0/n)*centre;
        length /= n;

        std::vector<double> current = at(x);
        bool moved = false;
        {
            std::vector<double> b = at(centre);
            if (better(b, current))
            {
                x = centre;
                current = b;
                moved = true;
            }
        }

        // Down the gradient of the worst face's badness
        const double h = 1e-5*length;
        for (int iter = 0; iter < 6; ++iter)
        {
            label worstTet = -1;
            int worstFace = -1;
            double b0 = -1;
            const auto pos = [&](label q) -> const point3& { return q == p ? x : points_[q]; };
            for (std::size_t i = 0; i < set.size(); ++i)
            {
                for (int k = 0; k < 4; ++k)
                {
                    if (inSet[i][k] >= 0 && std::size_t(inSet[i][k]) < i) continue;
                    const double b = faceBadnessIn(set, acrossOf, inSet, i, k, pos);
                    if (b > b0)
                    {
                        b0 = b;
                        worstTet = label(i);
                        worstFace = k;
                    }
                }
            }
            if (!std::isfinite(b0)) break;
            vector3 g;
            for (int k = 0; k < 3; ++k)
            {
                point3 y = x;
                y[k] += h;
                g[k] =
                (
                    faceBadnessIn
                    (
                        set, acrossOf, inSet, worstTet, worstFace,
                        [&](label q) -> const point3& { return q == p ? y : points_[q]; }
                    )
                  - b0
                )/h;
            }
            const double gMag = std::sqrt(magSqr(g));
            if (!(gMag > 0) || !std::isfinite(gMag)) break;
            const vector3 dir = (-length/gMag)*g;
            bool improved = false;
            for (double step : {0.1, 0.03, 0.01, 0.003})
            {
                const point3 y = x + step*dir;
                std::vector<double> b = at(y);
                if (better(b, current))
                {
                    x = y;
                    current = b;
                    improved = moved = true;
                    break;
                }
            }
            if (!improved) break;
        }

        if (moved)
        {
            points_[p] = x;
            ++nMoved;
        }
    }
};

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
    passMesh m(mesh, nFixedPoints, triangles, interface);
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
                if (b > visitBadness)
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
