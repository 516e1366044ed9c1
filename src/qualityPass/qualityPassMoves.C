#include "qualityPassMesh.H"

#include <algorithm>
#include <cmath>
#include <utility>

// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * //

void pmsh::qualityPass::passMesh::improve(label t)
{
    if (tets_[t][0] < 0)
    {
        return;
    }
    ++nVisited;
    if (flip(t))
    {
        return;
    }
    const tetVerts c = tets_[t];
    for (label p : c)
    {
        if (p >= nFixed_ && !locked_[p])
        {
            smooth(p);
        }
    }
    if (insertAbove < infinite && current(t))
    {
        double worst = 0;
        for (int k = 0; k < 4; ++k)
        {
            worst = std::max
            (
                worst,
                badnessOf(c, k, across_[4*t + k], [&](label q) -> const point3& { return points_[q]; })
            );
        }
        if (worst > insertAbove)
        {
            insertPoint(t);
        }
    }
}


bool pmsh::qualityPass::passMesh::improves
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
    if (!allPositive(created, pos) || !addressSet(created, old, acrossOf, inSet)) return false;
    createdBadness = setBadness(created, acrossOf, inSet, pos, rejectionBound(before));
    return !createdBadness.empty() && better(createdBadness, before);
}


std::vector<pmsh::label> pmsh::qualityPass::passMesh::ringPoints
(
    const std::vector<label>& ring,
    label a,
    label b,
    std::size_t maxSize
) const
{
    if (ring.size() < 3 || ring.size() > maxSize) return {};
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


bool pmsh::qualityPass::passMesh::ringTurnsCounterClockwise
(
    const std::vector<label>& ring,
    const std::vector<label>& polygon,
    label a,
    label b
) const
{
    // Read from the ring's largest tet: HXT's flat tets (volume 1e-19 on
    // a sphere) may be oriented either way, which would turn every new
    // tet inside out
    label largest = ring[0];
    double largestVolume = -1;
    for (label u : ring)
    {
        const tetVerts& c = tets_[u];
        const double v = tetVolume6(points_[c[0]], points_[c[1]], points_[c[2]], points_[c[3]]);
        if (v > largestVolume)
        {
            largest = u;
            largestVolume = v;
        }
    }
    // Its two ring points in the polygon's order
    const std::size_t n = polygon.size();
    std::size_t i = 0;
    while (!has(largest, polygon[i]) || !has(largest, polygon[(i + 1) % n])) ++i;
    // (x_i, x_i+1, a, b) is negative when the ring turns counterclockwise
    // seen from a (then (x, y, z, a) is positive for its triangles)
    return !sameParity(tets_[largest], {polygon[i], polygon[(i + 1) % n], a, b});
}


std::vector<std::vector<std::array<pmsh::label, 3>>> pmsh::qualityPass::passMesh::triangulations(label i, label j)
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


bool pmsh::qualityPass::passMesh::flip(label t)
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
        const std::vector<label> ring = edgeTets(a, b);
        if (ring.size() > maxRing) continue;
        const std::vector<label> polygon = ringPoints(ring, a, b);
        if (polygon.empty()) continue;
        // The triangles keep the polygon's turn about a-b: a triangle
        // oriented by the sign of its own tet would also make a positive
        // tet of a triangle outside a ring that is not convex, and the new
        // tets would overlap
        const bool counterClockwiseFromA = ringTurnsCounterClockwise(ring, polygon, a, b);
        for (const auto& triangles : triangulations(0, label(polygon.size()) - 1))
        {
            std::vector<tetVerts> created;
            for (const auto& t : triangles)
            {
                const label x = polygon[t[0]];
                label y = polygon[t[1]], z = polygon[t[2]];
                if (!counterClockwiseFromA) std::swap(y, z);
                created.push_back({x, y, z, a});
                created.push_back({x, z, y, b});
            }
            consider(ring, created);
        }
    }

    // A tet that is not positive (HXT now and then returns one, flat to
    // the last bit) makes the mesh invalid: it gets a point even when
    // slivers do not
    if (bestOld.empty() && isSliver && (insertPoints || !std::isfinite(sliver(t))))
    {
        return insertPoint(t);
    }
    if (bestOld.empty())
    {
        return false;
    }
    replace(bestOld, bestNew);
    return true;
}


bool pmsh::qualityPass::passMesh::insertPoint(label t)
{
    // A flat tet between two coplanar surface triangles (an STL facet, a
    // planar interface), its points fixed: no flip mends it when the ring
    // around its interior edge does not see across it. A new point inside
    // the ring, joined to every face of the ring's cavity, does: each ring
    // tet gives two, one end of the edge replaced by the point (so they
    // keep the ring tets' orientation)
    const tetVerts c = tets_[t];
    static const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
    std::vector<label> bestOld;
    std::vector<tetVerts> bestNew;
    std::vector<double> bestBadness;
    point3 bestPoint{0, 0, 0};
    for (const auto& e : edges)
    {
        const label a = c[e[0]];
        const label b = c[e[1]];
        const std::vector<label> ring = edgeTets(a, b);
        const std::vector<label> polygon = ringPoints(ring, a, b, maxInsertionRing);
        if (polygon.empty()) continue;
        bool allCurrent = true;
        for (label u : ring) allCurrent = allCurrent && current(u);
        if (!allCurrent) continue;

        // Where the point goes: on the way from the edge's middle to the
        // centre of the ring's polygon (a flat ring may see its faces
        // only from near the edge)
        point3 polygonCentre{0, 0, 0};
        for (label q : polygon) polygonCentre = polygonCentre + points_[q];
        polygonCentre = (1.0/polygon.size())*polygonCentre;
        const point3 edgeMiddle = 0.5*(points_[a] + points_[b]);

        const label p = label(points_.size());
        std::vector<tetVerts> created;
        for (label u : ring)
        {
            for (const label end : {a, b})
            {
                tetVerts n = tets_[u];
                for (label& q : n) if (q == end) q = p;
                created.push_back(n);
            }
        }
        for (const double f : {0.5, 0.25, 0.75, 0.1})
        {
            const point3 x = edgeMiddle + f*(polygonCentre - edgeMiddle);
            points_.push_back(x);
            std::vector<double> badness;
            const bool wins = improves(ring, created, badness)
             && (bestOld.empty() || better(badness, bestBadness));
            points_.pop_back();
            if (wins)
            {
                bestOld = ring;
                bestNew = created;
                bestBadness = badness;
                bestPoint = x;
            }
        }
    }
    if (bestOld.empty())
    {
        return false;
    }
    points_.push_back(bestPoint);
    locked_.push_back(1);
    changed_.push_back(1);
    movedAt_.push_back(0);
    failedAt_.push_back(-1);
    replace(bestOld, bestNew);
    ++nInserted;
    return true;
}


void pmsh::qualityPass::passMesh::smooth(label p)
{
    std::vector<label> star(pointTets_.begin() + start_[p], pointTets_.begin() + start_[p + 1]);
    for (label t : star)
    {
        if (!current(t)) return;
    }
    if (failedAt_[p] >= 0 && !movedSince(star, failedAt_[p]))
    {
        return;     // as it was when smoothing p last failed
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
    // The star's faces with p at y; for a candidate y, none if one is
    // worse than `bound` or if p at y inverts a tet
    const auto at = [&](const point3& y, const double bound, const bool candidate)
    {
        const auto pos = [&](label q) -> const point3& { return q == p ? y : points_[q]; };
        if (candidate && !allPositive(set, pos)) return std::vector<double>();
        return setBadness(set, acrossOf, inSet, pos, bound);
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

    std::vector<double> current = at(x, infinite, false);
    bool moved = false;
    {
        std::vector<double> b = at(centre, rejectionBound(current), true);
        if (!b.empty() && better(b, current))
        {
            x = centre;
            current = b;
            moved = true;
        }
    }

    // Down the gradient of the worst face's badness
    const double h = 1e-5*length;
    for (int iter = 0; iter < smoothingIterations; ++iter)
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
            std::vector<double> b = at(y, rejectionBound(current), true);
            if (!b.empty() && better(b, current))
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
        changed_[p] = 1;
        movedAt_[p] = ++moveClock_;
        ++nMoved;
    }
    else
    {
        failedAt_[p] = moveClock_;
    }
}


// ************************************************************************* //
