#include "wallLayers.H"
#include "triangleCrossings.H"
#include "layerStars.H"
#include "triangleGeometry.H"

#include <algorithm>
#include <cmath>

namespace pmsh
{

namespace
{

constexpr double degToRad = 3.14159265358979323846/180;

//- Neighbouring points' thicknesses differ by at most this factor, and by
//  at most this much per unit of the distance between them: where stacks
//  thin (a groove, the end of a stack) they ramp down over a few
//  triangles. Without the slope, OpenFOAM's bullet with 5 layers kept the
//  stacks of its rear grooves 4-7 triangle edges thick beside thin ones:
//  crumpled tops that HXT's optimiser spent most of stage 4 on.
constexpr double maxNeighbourRatio = 1.5;
constexpr double maxThicknessSlope = 0.5;

//- Validity rounds that shrink thicknesses to this share; later ones set
//  them to 0. By halves the bullet's 0.74 mm stacks went 0.37, 0.185, then
//  0.09 mm, under their 0.1 mm minimum, and were dropped where 0.13 mm
//  would have been valid (coverage 94.5 %, 99.3 % with both changes).
constexpr label shrinkingRounds = 100;
constexpr double shrinkFactor = 0.7;

//- Where the risen interface crosses itself, the shift of the points
//  within selfCrossingRings edges of the crossing triangles is scaled by
//  selfCrossingScale, each round, until none crosses. The first version
//  halved the whole shift, on every rank: the stacks then crossed the
//  lowered interface wherever one was near, and thinned. OpenFOAM's bullet
//  with 5 layers (bench/results/layer-coverage.md), faces layered and
//  faces above 70 degrees on 2 and 4 ranks:
//
//      shift scaled              2 ranks          4 ranks
//      all of it by 0.5          99.31 %, 26      97.77 %, 95
//      0 rings by 0.7            99.95 %, 338     99.66 %, 393
//      1 ring by 0.7             99.79 %, 125     99.42 %, 204
//      3 rings by 0.8            99.82 %, 59      99.30 %, 119
//      5 rings by 0.8            99.89 %, 45      99.10 %, 88
//      6 rings by 0.7            99.79 %, 7       98.58 %, 71
//
//  A cliff in the shift makes the tets beside it poor; rings smooth it.
constexpr double selfCrossingScale = 0.8;
constexpr int selfCrossingRings = 5;

//- A lifted unlayered triangle keeps at least this share of its area,
//  projected on its original plane.
constexpr double minLiftedAreaShare = 0.25;

//- A stack's top triangle keeps at least this share of its wall
//  triangle's shape quality. HXT cannot mend the tets against a crumpled
//  top (all their points are on the surface): OpenFOAM's bullet with 5
//  layers ended stage 4 with 10,500 tets below HXT's threshold after 47 s
//  in its optimiser, and 2,113 faces above 70 degrees; with this rule (and
//  smoothed directions) 2,300 tets after 9 s, and 22 faces.
constexpr double minTopQualityShare = 0.5;


//- What the lifted surface's triangles cross (layerState::crossings):
//  every pair, within a piece, and per triangle whether it is in a pair
//  with an interface triangle and in one without. Kinds, not one triangle
//  crossed: which one of several a triangle would name depends on the
//  triangles' order, and so on the ranks.
struct liftedCrossings
{
    std::vector<std::pair<label, label>> pairs;
    std::vector<bool> withInterface;
    std::vector<bool> withoutInterface;

    bool crosses(label t) const { return withInterface[t] || withoutInterface[t]; }
};


//- Per layered triangle, per point: the current state of the rounds.
struct layerState
{
    const layerStars& stars;
    wallLayers& layers;
    std::vector<const layerSpecification*> pointSpec;

    const std::vector<point3>& points() const { return stars.surface().points; }

    //- Is t layered with the current thicknesses: its patch is, its points
    //  have layers from a spec equal to its own.
    bool canLayer(label t) const
    {
        const layerSpecification* spec = stars.specOf(t);
        if (!spec) return false;
        for (const label p : stars.surface().triangles[t])
        {
            if (!(layers.thickness[p] > 0) || !pointSpec[p] || *pointSpec[p] != *spec)
            {
                return false;
            }
        }
        return true;
    }

    //- Classify triangles and points with the current thicknesses.
    void classify()
    {
        const label nTriangles = stars.surface().triangles.size();
        for (label t = 0; t < nTriangles; ++t)
        {
            layers.triangleLayered[t] = canLayer(t);
        }
        const std::vector<double> layeredHere = stars.minimum
        (
            [&](label t, label) { return layers.triangleLayered[t] ? -1.0 : layerStars::none; }
        );
        for (std::size_t p = 0; p < layeredHere.size(); ++p)
        {
            layers.nLayers[p] = layeredHere[p] < 0 ? pointSpec[p]->nLayers : 0;
        }
    }

    //- Are t's prisms valid, and its top in shape (minTopQualityShare)?
    bool prismsValid(label t) const
    {
        const triVerts& f = stars.surface().triangles[t];
        const std::array<label, 3> up{f[0], f[2], f[1]};
        for (int k = 1; k <= layers.nLayers[f[0]]; ++k)
        {
            std::array<point3, 6> prism;
            for (int i = 0; i < 3; ++i)
            {
                prism[i] = layers.levelPoint(points(), up[i], k - 1);
                prism[i + 3] = layers.levelPoint(points(), up[i], k);
            }
            if (!validPrism(prism)) return false;
        }
        const auto& x = points();
        const double wall = triangleShapeQuality(x[f[0]], x[f[1]], x[f[2]]);
        const double top = triangleShapeQuality
        (
            layers.topPoint(x, f[0]), layers.topPoint(x, f[1]), layers.topPoint(x, f[2])
        );
        return top >= minTopQualityShare*wall;
    }

    //- Does unlayered t stay valid with its layered points lifted?
    bool liftedValid(label t) const
    {
        const triVerts& f = stars.surface().triangles[t];
        const auto& x = points();
        const vector3 before = cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]]);
        const point3 a = layers.topPoint(x, f[0]);
        const vector3 after = cross(layers.topPoint(x, f[1]) - a, layers.topPoint(x, f[2]) - a);
        return dot(after, before) >= minLiftedAreaShare*magSqr(before);
    }

    //- Per triangle, what it crosses once every point is at its top level
    //  and the interface has risen (triangleCrossings.H), folds included
    //  as in stage 4's check: a risen interface slides in its own plane
    //  where the stacks are several of its rings tall, and folds there.
    liftedCrossings crossings() const
    {
        const auto& triangles = stars.surface().triangles;
        std::vector<point3> lifted(points().size());
        for (label p = 0; p < label(lifted.size()); ++p)
        {
            lifted[p] = layers.topPoint(points(), p);
        }
        std::vector<bool> moved(triangles.size(), false);
        for (label t = 0; t < label(triangles.size()); ++t)
        {
            for (label p : triangles[t])
            {
                moved[t] = moved[t] || layers.nLayers[p] > 0
                    || (!layers.shift.empty() && magSqr(layers.shift[p]) > 0);
            }
        }
        liftedCrossings crossing;
        crossing.pairs = crossingPairs(lifted, triangles, moved, true, stars.surface().piece);
        crossing.withInterface.assign(triangles.size(), false);
        crossing.withoutInterface.assign(triangles.size(), false);
        for (const auto& [t, u] : crossing.pairs)
        {
            auto& kind = stars.isInterface(t) || stars.isInterface(u)
                ? crossing.withInterface : crossing.withoutInterface;
            kind[t] = kind[u] = true;
        }
        return crossing;
    }

    //- Scale down the shift of the points near every triangle that
    //  crosses one with which it has no layered point (only the
    //  interface's shift moved them), alike on every rank that holds them.
    //  Whether any rank found one.
    bool scaleDownSelfCrossings
    (
        const liftedCrossings& crossing,
        std::vector<double>& shiftScale
    ) const
    {
        const auto& triangles = stars.surface().triangles;
        const auto layered = [&](label t)
        {
            for (label p : triangles[t]) if (layers.nLayers[p] > 0) return true;
            return false;
        };
        std::vector<bool> selfCrossing(triangles.size(), false);
        bool found = false;
        for (const auto& [t, u] : crossing.pairs)
        {
            if (!layered(t) && !layered(u))
            {
                selfCrossing[t] = selfCrossing[u] = true;
                found = true;
            }
        }
        if (!stars.anyRank(found)) return false;

        std::vector<double> near = stars.minimum
        (
            [&](label t, label) { return selfCrossing[t] ? -1.0 : layerStars::none; }
        );
        for (int ring = 0; ring < selfCrossingRings; ++ring)
        {
            near = stars.minimum
            (
                [&](label t, label)
                {
                    for (label q : triangles[t]) if (near[q] < 0) return -1.0;
                    return layerStars::none;
                }
            );
        }
        for (std::size_t p = 0; p < near.size(); ++p)
        {
            if (near[p] < 0) shiftScale[p] *= selfCrossingScale;
        }
        return true;
    }

    //- Set every thickness below its spec's minThickness to 0.
    void dropThinStacks()
    {
        for (std::size_t p = 0; p < pointSpec.size(); ++p)
        {
            if (pointSpec[p] && layers.thickness[p] < pointSpec[p]->minThickness)
            {
                layers.thickness[p] = 0;
            }
        }
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Thickness * * * * * * * * * * * * * * * //

std::vector<bool> featurePoints
(
    const layerStars& stars,
    const std::vector<const layerSpecification*>& pointSpec
)
{
    const auto unitNormals = stars.gather
    (
        [&](label t, label, label& tag, vector3& value)
        {
            if (!stars.specOf(t)) return false;
            tag = 0;
            value = normalised(stars.areaVector(t));
            return true;
        }
    );
    std::vector<bool> feature(pointSpec.size(), false);
    for (std::size_t p = 0; p < pointSpec.size(); ++p)
    {
        if (!pointSpec[p]) continue;
        const double featureCos = std::cos(pointSpec[p]->featureAngle*degToRad);
        const auto& n = unitNormals[p];
        for (std::size_t i = 0; i < n.size() && !feature[p]; ++i)
        {
            for (std::size_t j = i + 1; j < n.size() && !feature[p]; ++j)
            {
                feature[p] = dot(n[i].value, n[j].value) < featureCos;
            }
        }
    }
    return feature;
}


std::vector<double> featureAndGapThickness
(
    const layerStars& stars,
    const std::vector<vector3>& direction,
    const std::vector<const layerSpecification*>& pointSpec,
    const std::vector<bool>& feature,
    wallLayerStats& stats,
    std::vector<layerThinning>& thinnedBy
)
{
    const layerSurface& surface = stars.surface();
    const auto& x = surface.points;
    // Over the star's other points q: the shortest edge, and the least of
    // -cos(q - p, d) (negative where the surface bends towards the layers:
    // a concave point)
    auto overNeighbours = [&](const std::function<double(label, label)>& f)
    {
        return stars.minimum
        (
            [&](label t, label p)
            {
                double least = layerStars::none;
                if (!stars.specOf(t)) return least;
                for (const label q : surface.triangles[t])
                {
                    if (q != p) least = std::min(least, f(p, q));
                }
                return least;
            }
        );
    };
    const std::vector<double> shortestEdge = overNeighbours
    (
        [&](label p, label q) { return distance(x[p], x[q]); }
    );
    const std::vector<double> convexity = overNeighbours
    (
        [&](label p, label q)
        {
            const vector3 e = x[q] - x[p];
            return -dot(e, direction[p])/std::sqrt(magSqr(e));
        }
    );

    std::vector<double> thickness(x.size(), 0);
    for (std::size_t p = 0; p < x.size(); ++p)
    {
        if (!(magSqr(direction[p]) > 0) || !pointSpec[p]) continue;
        const layerSpecification& spec = *pointSpec[p];
        double T = spec.totalThickness();
        if (feature[p])
        {
            const double limit = (convexity[p] < 0 ? 0.5 : 1.0)*shortestEdge[p];
            if (limit < T)
            {
                T = limit;
                if (stars.counts(p)) ++stats.nFeatureLimited;
                thinnedBy[p] = layerThinning::sharpEdge;
            }
        }

        if (surface.gapAlong)
        {
            const double gap = surface.gapAlong(x[p], direction[p], 1e-6*shortestEdge[p]);
            if (spec.maxThicknessToGapRatio*gap < T)
            {
                T = spec.maxThicknessToGapRatio*gap;
                if (stars.counts(p)) ++stats.nGapLimited;
                thinnedBy[p] = layerThinning::gap;
            }
        }
        thickness[p] = T;
    }
    return thickness;
}


void smoothThickness(const layerStars& stars, std::vector<double>& thickness)
{
    const auto& triangles = stars.surface().triangles;
    const auto& x = stars.surface().points;
    for (;;)
    {
        const std::vector<double> limit = stars.minimum
        (
            [&](label t, label p)
            {
                double least = layerStars::none;
                if (!stars.specOf(t)) return least;
                for (const label q : triangles[t])
                {
                    // Points without layers do not hold their neighbours down
                    if (q != p && thickness[q] > 0)
                    {
                        least = std::min
                        ({
                            least,
                            maxNeighbourRatio*thickness[q],
                            thickness[q] + maxThicknessSlope*distance(x[p], x[q])
                        });
                    }
                }
                return least;
            }
        );
        bool changed = false;
        for (std::size_t p = 0; p < thickness.size(); ++p)
        {
            if (limit[p] < thickness[p])
            {
                thickness[p] = limit[p];
                changed = true;
            }
        }
        if (!stars.anyRank(changed)) break;
    }
}


// * * * * * * * * * * * * * * * * wallLayers  * * * * * * * * * * * * * * //

point3 wallLayers::levelPoint
(
    const std::vector<point3>& points,
    label p,
    int k
) const
{
    const point3& x = points[p];
    if (nLayers[p] == 0)
    {
        return shift.empty() ? x : x + shift[p];
    }
    if (k == 0)
    {
        return x;
    }
    const double s = thickness[p]*levelFractions.at(specPatch[p])[k];
    const vector3& d = direction[p];
    return {x[0] + s*d[0], x[1] + s*d[1], x[2] + s*d[2]};
}


bool validPrism(const std::array<point3, 6>& v)
{
    for (int i = 0; i < 3; ++i)
    {
        const int j = (i + 1) % 3, k = (i + 2) % 3;
        if
        (
            !(tetVolume6(v[i], v[j], v[k], v[i + 3]) > 0)
         || !(tetVolume6(v[i + 3], v[k + 3], v[j + 3], v[i]) > 0)
        )
        {
            return false;
        }
    }
    return true;
}


namespace
{

//- Promote the points inside the domain of the interface triangles that
//  squash or cross a stack's top (interfaceShift.C). Whether any rank
//  promoted one.
bool promote
(
    const layerState& state,
    const std::vector<bool>& interfaceOnly,
    const liftedCrossings& crossing,
    std::vector<bool>& promoted
)
{
    const layerStars& stars = state.stars;
    const std::vector<double> promote = stars.minimum
    (
        [&](label t, label p)
        {
            if (!interfaceOnly[p] || promoted[p] || !stars.isInterface(t))
            {
                return layerStars::none;
            }
            return crossing.crosses(t) || !state.liftedValid(t) ? -1.0 : layerStars::none;
        }
    );
    bool more = false;
    for (std::size_t p = 0; p < promote.size(); ++p)
    {
        if (promote[p] < 0)
        {
            promoted[p] = true;
            more = true;
        }
    }
    return stars.anyRank(more);
}


//- Shrink the thickness round invalid prisms and lifted triangles (after
//  shrinkingRounds: set it to 0) until nothing changes on any rank.
void validityRounds(layerState& state)
{
    const layerStars& stars = state.stars;
    wallLayers& layers = state.layers;
    const label nPoints = layers.thickness.size();
    std::vector<bool> limited(nPoints, false), interfaceLimited(nPoints, false);
    const std::vector<bool> interfaceOnly = interfaceOnlyPoints(stars);
    std::vector<bool> promoted(nPoints, false);
    std::vector<double> shiftScale(nPoints, 1.0);
    std::vector<vector3> slidePlanes;
    for (label round = 1; ; ++round)
    {
        state.classify();
        // Once: a point that loses its layers in the rounds stays put
        if (round == 1) slidePlanes = slidingPlanes(stars, layers, interfaceOnly);
        layers.shift = interfaceShift
        (
            stars, layers, interfaceOnly, promoted, slidePlanes, shiftScale
        );
        const bool shrink = round <= shrinkingRounds;
        auto shrunk = [&](label p) { return shrink ? shrinkFactor*layers.thickness[p] : 0.0; };
        auto lifted = [&](label t, label p, bool interface)
        {
            if (layers.triangleLayered[t] || layers.nLayers[p] == 0 || stars.isInterface(t) != interface)
            {
                return layerStars::none;
            }
            return state.liftedValid(t) ? layerStars::none : shrunk(p);
        };
        const std::vector<double> wallLimit = stars.minimum
        (
            [&](label t, label p)
            {
                if (layers.triangleLayered[t])
                {
                    return state.prismsValid(t) ? layerStars::none : shrunk(p);
                }
                return lifted(t, p, false);
            }
        );
        // Tops of stacks through a triangle nearby, mostly an interface
        // closer to the wall than the stack is thick
        const liftedCrossings crossing = state.crossings();
        auto crossed = [&](label t, label p, bool interface)
        {
            if (layers.nLayers[p] == 0) return layerStars::none;
            const bool kind = interface ? crossing.withInterface[t] : crossing.withoutInterface[t];
            return kind ? shrunk(p) : layerStars::none;
        };
        const std::vector<double> wallCrossingLimit = stars.minimum
        (
            [&](label t, label p) { return crossed(t, p, false); }
        );
        // An interface triangle that squashes or crosses a stack's top:
        // its points inside the domain rise with the stacks first
        // (promoted); stacks thin for it only once none is left to promote
        const bool promoting = promote(state, interfaceOnly, crossing, promoted);
        // The risen interface crossing itself where no stack is there to
        // thin: the shift is scaled down there, on every rank alike
        const bool selfCrossing = !promoting && state.scaleDownSelfCrossings(crossing, shiftScale);
        const std::vector<double> interfaceLimit = stars.minimum
        (
            [&](label t, label p)
            {
                if (promoting) return layerStars::none;
                return std::min(lifted(t, p, true), crossed(t, p, true));
            }
        );

        bool changed = false;
        for (label p = 0; p < nPoints; ++p)
        {
            const double ownLimit = std::min(wallLimit[p], wallCrossingLimit[p]);
            const double limit = std::min(ownLimit, interfaceLimit[p]);
            if (limit < layers.thickness[p])
            {
                layers.thickness[p] = limit;
                changed = true;
                limited[p] = true;
                if (interfaceLimit[p] < ownLimit) interfaceLimited[p] = true;
            }
        }
        layers.stats.nRounds = round;
        if (!stars.anyRank(changed) && !promoting && !selfCrossing) break;
        smoothThickness(stars, layers.thickness);
        state.dropThinStacks();
    }
    for (label p = 0; p < nPoints; ++p)
    {
        if (interfaceLimited[p]) layers.thinnedBy[p] = layerThinning::partitionInterface;
        else if (limited[p]) layers.thinnedBy[p] = layerThinning::validity;
    }
    for (label p = 0; p < nPoints; ++p)
    {
        if (!stars.counts(p)) continue;
        layers.stats.nInvalidLimited += limited[p];
        layers.stats.nInterfaceLimited += interfaceLimited[p];
    }
}


//- What a stack meets across a partition interface on its edge (u, v),
//  by the interface triangle n there: the other part's boundary triangle
//  on that edge. Its stack, if it has one: the side quads are processor
//  faces toward the part that holds that triangle, matched by its quads.
//  That part need not be the one across n: a third part may touch the
//  edge between the two, and its tets end at the stacks' tops (a
//  hierarchical split of a layered bullet at P = 4 had 20 side quads
//  facing a part that had made none). Else the triangle's region: the
//  stack ends at an unlayered triangle, whose region the quads take, as
//  on one rank. The boundary triangles round the interface's points come
//  from every rank that holds them (stars.gather).
class acrossInterface
{
public:

    acrossInterface(const layerStars& stars, const wallLayers& layers)
    :
        surface_(stars.surface()),
        round_
        (
            stars.gather
            (
                [&](label t, label, label& tag, vector3& value)
                {
                    if (stars.isInterface(t)) return false;
                    tag = surface_.region[t];
                    value =
                    {
                        layers.triangleLayered[t] ? 1.0 : 0.0,
                        double(interfaceRegion(stars.rank())),
                        0
                    };
                    return true;
                }
            )
        )
    {}

    //- The region of the quads of layered t on edge (u, v), whose other
    //  triangle here is the interface triangle n (when no rank holds a
    //  boundary triangle across the edge, n's region).
    label region(label t, label u, label v, label n) const
    {
        const auto& ids = surface_.ids;
        const triVerts& f = surface_.triangles[t];
        for (const keyedContribution& c : round_[u])
        {
            const bool onEdge =
                std::find(c.key.begin(), c.key.end(), ids[v]) != c.key.end();
            const bool mine =
                std::is_permutation(c.key.begin(), c.key.end(), triangleKey{ids[f[0]], ids[f[1]], ids[f[2]]}.begin());
            if (onEdge && !mine)
            {
                return c.value[0] > 0 ? label(c.value[1]) : c.tag;
            }
        }
        return surface_.region[n];
    }

private:

    const layerSurface& surface_;
    const std::vector<std::vector<keyedContribution>> round_;
};


//- The prisms of the layered triangles, and the side quads where their
//  stacks meet unlayered triangles.
void buildStacks(const layerStars& stars, wallLayers& layers)
{
    const layerSurface& surface = stars.surface();
    const acrossInterface across(stars, layers);
    const label nTriangles = surface.triangles.size();
    std::map<std::pair<label, label>, std::vector<label>> edgeTriangles;
    for (label t = 0; t < nTriangles; ++t)
    {
        const triVerts& f = surface.triangles[t];
        for (int i = 0; i < 3; ++i)
        {
            const label u = f[i], v = f[(i + 1) % 3];
            edgeTriangles[{std::min(u, v), std::max(u, v)}].push_back(t);
        }
    }
    for (label t = 0; t < nTriangles; ++t)
    {
        if (!layers.triangleLayered[t]) continue;
        const triVerts& f = surface.triangles[t];
        const int L = layers.nLayers[f[0]];
        for (int k = 1; k <= L; ++k)
        {
            layers.prisms.push_back
            ({{
                {f[0], k - 1}, {f[2], k - 1}, {f[1], k - 1},
                {f[0], k}, {f[2], k}, {f[1], k}
            }});
            layers.prismTriangle.push_back(t);
        }
        for (int i = 0; i < 3; ++i)
        {
            const label u = f[i], v = f[(i + 1) % 3];
            for (const label n : edgeTriangles.at({std::min(u, v), std::max(u, v)}))
            {
                if (layers.triangleLayered[n]) continue;
                const label region =
                    stars.isInterface(n) ? across.region(t, u, v, n) : surface.region[n];
                // A stack of this rank across a face between its pieces:
                // the prisms meet in internal faces, no side quads
                if (region == interfaceRegion(stars.rank())) break;
                for (int k = 1; k <= L; ++k)
                {
                    layers.sideFaces.push_back
                    ({
                        {{{v, k - 1}, {u, k - 1}, {u, k}, {v, k}}},
                        region
                    });
                }
                break;
            }
        }
    }
}

} // End anonymous namespace


wallLayers growWallLayers(const layerSurface& surface, layerExchange& exchange)
{
    const layerStars stars(surface, exchange);
    const label nPoints = surface.points.size();
    const label nTriangles = surface.triangles.size();

    wallLayers layers;
    layers.nLayers.assign(nPoints, 0);
    layers.specPatch.assign(nPoints, -1);
    layers.triangleLayered.assign(nTriangles, false);
    for (const auto& [patch, spec] : surface.specs)
    {
        std::vector<double>& fractions = layers.levelFractions[patch];
        for (int k = 0; k <= spec.nLayers; ++k)
        {
            fractions.push_back(spec.layered() ? spec.levelOffset(k)/spec.totalThickness() : 0);
        }
    }

    layerState state{stars, layers, std::vector<const layerSpecification*>(nPoints, nullptr)};
    const std::vector<double> lowestPatch = stars.minimum
    (
        [&](label t, label) { return stars.specOf(t) ? double(surface.region[t]) : layerStars::none; }
    );
    for (label p = 0; p < nPoints; ++p)
    {
        if (lowestPatch[p] < layerStars::none)
        {
            layers.specPatch[p] = label(lowestPatch[p]);
            state.pointSpec[p] = &surface.specs.at(layers.specPatch[p]);
        }
    }

    const std::vector<bool> feature = featurePoints(stars, state.pointSpec);
    layers.thinnedBy.assign(nPoints, layerThinning::none);
    layers.direction = layerDirections(stars, feature, layers.stats.nSmoothedDirections);
    layers.thickness = featureAndGapThickness
    (
        stars, layers.direction, state.pointSpec, feature, layers.stats, layers.thinnedBy
    );
    smoothThickness(stars, layers.thickness);
    state.dropThinStacks();

    validityRounds(state);

    for (label p = 0; p < nPoints; ++p)
    {
        if (layers.nLayers[p] == 0)
        {
            layers.thickness[p] = 0;
            layers.direction[p] = {0, 0, 0};
            layers.specPatch[p] = -1;
        }
    }

    buildStacks(stars, layers);
    return layers;
}


} // End namespace pmsh


// ************************************************************************* //
