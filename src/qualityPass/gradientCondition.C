#include "gradientCondition.H"
#include "acrossFace.H"
#include "qualityPassMeasures.H"

#include <algorithm>
#include <array>
#include <cmath>

// * * * * * * * * * * * * * * * Local Functions  * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

point3 centreOf(const std::vector<point3>& p, const tetVerts& c)
{
    return 0.25*((p[c[0]] + p[c[1]]) + (p[c[2]] + p[c[3]]));
}


//- leastSquares' matrix of the four directions d, (xx, yy, zz, xy, xz, yz)
std::array<double, 6> matrixOf(const std::array<vector3, 4>& d)
{
    std::array<double, 6> m{0, 0, 0, 0, 0, 0};
    for (const vector3& v : d)
    {
        const double w = 1/magSqr(v);
        m[0] += w*v[0]*v[0];
        m[1] += w*v[1]*v[1];
        m[2] += w*v[2]*v[2];
        m[3] += w*v[0]*v[1];
        m[4] += w*v[0]*v[2];
        m[5] += w*v[1]*v[2];
    }
    return m;
}


//- The determinant of m: its trace is 4 (four unit directions), so its
//  eigenvalues' product is det and the condition is at most 16/det (the
//  smallest is at least det/4, the largest at most 4): most tets are told
//  apart from the bad ones without their eigenvalues
double determinantOf(const std::array<double, 6>& m)
{
    return
        m[0]*(m[1]*m[2] - m[5]*m[5])
      - m[3]*(m[3]*m[2] - m[5]*m[4])
      + m[4]*(m[3]*m[5] - m[1]*m[4]);
}


//- Largest over smallest eigenvalue of the symmetric m, in closed form
//  (the trigonometric solution of the characteristic cubic)
double conditionOf(const std::array<double, 6>& m)
{
    const double q = (m[0] + m[1] + m[2])/3;
    const double off = m[3]*m[3] + m[4]*m[4] + m[5]*m[5];
    const double p = std::sqrt
    (
        ((m[0] - q)*(m[0] - q) + (m[1] - q)*(m[1] - q) + (m[2] - q)*(m[2] - q) + 2*off)/6
    );
    if (!(p > 1e-14*q)) return 1;
    const double b0 = (m[0] - q)/p, b1 = (m[1] - q)/p, b2 = (m[2] - q)/p;
    const double b3 = m[3]/p, b4 = m[4]/p, b5 = m[5]/p;
    const double r = 0.5*(b0*(b1*b2 - b5*b5) - b3*(b3*b2 - b5*b4) + b4*(b3*b5 - b1*b4));
    const double phi = std::acos(std::min(1.0, std::max(-1.0, r)))/3;
    const double largest = q + 2*p*std::cos(phi);
    const double smallest = q + 2*p*std::cos(phi + 2*M_PI/3);
    return smallest > 0 ? largest/smallest : qualityPass::infinite;
}


//- From tet t's centre to the centre of what lies across each face, the
//  tets' centres from centreOf(u)
template<class Centres>
std::array<vector3, 4> directionsOf(const TetMesh& m, label t, const Centres& centreOf)
{
    const tetVerts& c = m.tets[t];
    const point3 centre = centreOf(t);
    std::array<vector3, 4> d;
    for (int k = 0; k < 4; ++k)
    {
        const label u = m.across[4*t + k];
        if (!isAcrossBoundary(u))
        {
            d[k] = centreOf(u) - centre;
        }
        else
        {
            const triVerts f = tetFace(c, k);
            d[k] = (1.0/3.0)*((m.points[f[0]] + m.points[f[1]]) + m.points[f[2]]) - centre;
        }
    }
    return d;
}


std::array<vector3, 4> directionsOf(const TetMesh& m, label t)
{
    return directionsOf(m, t, [&](label u) { return centreOf(m.points, m.tets[u]); });
}


//- The tets that may be above the limit (16/det above it), and their
//  conditions: every tet's centre computed once
std::vector<std::pair<double, label>> tetsMaybeAbove(const TetMesh& m)
{
    std::vector<point3> centres(m.tets.size());
    for (std::size_t t = 0; t < m.tets.size(); ++t) centres[t] = centreOf(m.points, m.tets[t]);
    const auto centre = [&](label u) -> const point3& { return centres[u]; };
    std::vector<std::pair<double, label>> out;
    for (label t = 0; t < label(m.tets.size()); ++t)
    {
        const std::array<double, 6> matrix = matrixOf(directionsOf(m, t, centre));
        if (16 > gradientConditionLimit*determinantOf(matrix))
        {
            out.push_back({conditionOf(matrix), t});
        }
    }
    return out;
}


//- One free point and what its moves change: the tets on it (star), those
//  and the tets across their faces (ring)
struct pointNeighbourhood
{
    std::vector<label> star;
    std::vector<label> ring;
};


class conditionMender
{
    TetMesh& m_;
    const label nFixed_;
    std::vector<label> start_;      // tets of point p:
    std::vector<label> pointTets_;  // pointTets_[start_[p] .. start_[p+1])

    pointNeighbourhood neighbourhoodOf(label v) const
    {
        pointNeighbourhood n;
        n.star.assign(pointTets_.begin() + start_[v], pointTets_.begin() + start_[v + 1]);
        n.ring = n.star;
        for (label t : n.star)
        {
            for (int k = 0; k < 4; ++k)
            {
                const label u = m_.across[4*t + k];
                if (!isAcrossBoundary(u)) n.ring.push_back(u);
            }
        }
        std::sort(n.ring.begin(), n.ring.end());
        n.ring.erase(std::unique(n.ring.begin(), n.ring.end()), n.ring.end());
        return n;
    }

    double worstCondition(const std::vector<label>& tets) const
    {
        double worst = 0;
        for (label t : tets)
        {
            worst = std::max(worst, gradientCondition(m_, t));
        }
        return worst;
    }

    //- The worst badness of the faces of the tets of `star`, each of
    //  checkMesh's measures on its own (non-orthogonality, skewness),
    //  and of their flatness (infinite if a tet is not positive), as the
    //  quality pass weighs them. Each is bounded on its own: a sliver's
    //  faces can be fair while its leastSquares condition is too (its
    //  neighbours' centres lie all round it), and a move that made one
    //  stopped HXT's first attempt on OpenFOAM's motorBike (aspect ratio
    //  3986); one bound for both let a sliver nearby excuse a face of
    //  skewness 4.9 (OpenFOAM's building_wtc2); one bound for both face
    //  measures let a skewed face on a prism top excuse a face of 60
    //  degrees just above it (a cylinder's 5 layers, its tets smoothed
    //  by Netgen: 53.7 degrees with the two apart)
    struct badnessOf
    {
        double nonOrth = 0;
        double skew = 0;
        double flatness = 0;
        bool within(const badnessOf& bound) const
        {
            return
                nonOrth <= bound.nonOrth && skew <= bound.skew
             && flatness <= bound.flatness;
        }
        //- At least `b` each
        void atLeast(const double b)
        {
            nonOrth = std::max(nonOrth, b);
            skew = std::max(skew, b);
            flatness = std::max(flatness, b);
        }
    };

    badnessOf worstBadness(const std::vector<label>& star) const
    {
        const std::vector<point3>& p = m_.points;
        badnessOf worst;
        for (label t : star)
        {
            const tetVerts& c = m_.tets[t];
            worst.flatness = std::max
            (
                worst.flatness, qualityPass::sliverBadness(p[c[0]], p[c[1]], p[c[2]], p[c[3]])
            );
            if (worst.flatness == qualityPass::infinite)
            {
                worst.atLeast(qualityPass::infinite);
                return worst;
            }
            for (int k = 0; k < 4; ++k)
            {
                const triVerts f = tetFace(c, k);
                const label u = m_.across[4*t + k];
                const qualityPass::measure measured =
                    isAcrossBoundary(u)
                  ? qualityPass::boundaryMeasure(p[f[0]], p[f[1]], p[f[2]], p[c[3 - k]], false)
                  : qualityPass::internalMeasure
                    (
                        p[f[0]], p[f[1]], p[f[2]], p[c[3 - k]], p[tetApex(m_.tets[u], f)]
                    );
                worst.nonOrth = std::max(worst.nonOrth, qualityPass::nonOrthBadness(measured));
                worst.skew = std::max(worst.skew, qualityPass::badness(measured, false));
            }
        }
        return worst;
    }

public:

    struct move
    {
        double before;      // the ring's worst condition where the point is
        double after;       // and where the search took it
        point3 to;
    };

    conditionMender(TetMesh& m, label nFixed)
    :
        m_(m),
        nFixed_(nFixed)
    {
        buildPointTets(m.points.size(), m.tets, start_, pointTets_);
    }

    bool movable(label v) const { return v >= nFixed_; }

    //- The tets whose condition a move of point v changes
    std::vector<label> ringOf(label v) const { return neighbourhoodOf(v).ring; }

    //- Pattern search for point v: steps along the axes from a quarter of
    //  its shortest edge, halved where no step lowers the ring's worst
    //  condition within the face bound, five halvings at most. The point
    //  is left where it was.
    move search(label v)
    {
        const pointNeighbourhood n = neighbourhoodOf(v);
        const point3 original = m_.points[v];
        badnessOf bound = worstBadness(n.star);
        bound.atLeast(qualityPass::visitBadness);
        move best{worstCondition(n.ring), 0, original};
        best.after = best.before;
        double shortest2 = qualityPass::infinite;
        for (label t : n.star)
        {
            for (label q : m_.tets[t])
            {
                if (q != v) shortest2 = std::min(shortest2, magSqr(m_.points[q] - original));
            }
        }
        double h = 0.25*std::sqrt(shortest2);
        static const vector3 axes[6] =
            {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (int halvings = 0, trials = 0; halvings < 5 && trials < 40; ++trials)
        {
            bool better = false;
            for (const vector3& a : axes)
            {
                m_.points[v] = best.to + h*a;
                if (!worstBadness(n.star).within(bound)) continue;
                const double w = worstCondition(n.ring);
                if (w < best.after)
                {
                    best.after = w;
                    best.to = m_.points[v];
                    better = true;
                }
            }
            if (!better)
            {
                h *= 0.5;
                ++halvings;
            }
        }
        m_.points[v] = original;
        return best;
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * //

double pmsh::gradientCondition(const TetMesh& mesh, const label t)
{
    return conditionOf(matrixOf(directionsOf(mesh, t)));
}


pmsh::gradientConditionStats pmsh::mendGradientConditions(TetMesh& mesh, const label nFixed)
{
    gradientConditionStats stats;
    std::vector<std::pair<double, label>> above = tetsMaybeAbove(mesh);
    above.erase
    (
        std::remove_if
        (
            above.begin(), above.end(),
            [](const std::pair<double, label>& c) { return c.first <= gradientConditionLimit; }
        ),
        above.end()
    );
    stats.nAbove = label(above.size());
    if (above.empty()) return stats;

    std::sort(above.rbegin(), above.rend());
    conditionMender mender(mesh, nFixed);
    // A tet's condition changes only where a point of it, or of a tet
    // across its faces, moves: the tets above and the rings of the points
    // moved are all that can be above after
    std::vector<label> mayStillBeAbove;
    for (const auto& [c, t] : above) mayStillBeAbove.push_back(t);
    for (const auto& [c, t] : above)
    {
        // An earlier move may have mended it already
        if (gradientCondition(mesh, t) <= gradientConditionLimit) continue;
        // Its points and the apexes of the tets across its faces, whose
        // centres set its directions: a tet on the partition's surface
        // (atop the prism stacks, say) may have one free point of its own
        std::vector<label> candidates(mesh.tets[t].begin(), mesh.tets[t].end());
        for (int k = 0; k < 4; ++k)
        {
            const label u = mesh.across[4*t + k];
            if (!isAcrossBoundary(u))
            {
                candidates.push_back(tetApex(mesh.tets[u], tetFace(mesh.tets[t], k)));
            }
        }
        label bestPoint = -1;
        conditionMender::move best{0, 0, {0, 0, 0}};
        for (label v : candidates)
        {
            if (!mender.movable(v)) continue;
            const conditionMender::move m = mender.search(v);
            if (m.after < m.before && (bestPoint < 0 || m.after < best.after))
            {
                bestPoint = v;
                best = m;
            }
        }
        if (bestPoint >= 0)
        {
            mesh.points[bestPoint] = best.to;
            ++stats.nMoved;
            const std::vector<label> ring = mender.ringOf(bestPoint);
            mayStillBeAbove.insert(mayStillBeAbove.end(), ring.begin(), ring.end());
        }
    }

    std::sort(mayStillBeAbove.begin(), mayStillBeAbove.end());
    mayStillBeAbove.erase
    (
        std::unique(mayStillBeAbove.begin(), mayStillBeAbove.end()), mayStillBeAbove.end()
    );
    for (label t : mayStillBeAbove)
    {
        stats.nAboveAfter += gradientCondition(mesh, t) > gradientConditionLimit;
    }
    return stats;
}


// ************************************************************************* //
