/*---------------------------------------------------------------------------*\
  Tests of the prism layer kernel (src/layers/wallLayers) on analytic
  surfaces: a sphere in a box, a cube's inside and outside corners, two
  plates closer than twice the layers, a valley that folds the layers below
  the feature angle, side walls whose lifted triangles would turn over, a
  pipe wall meeting an unlayered inlet, a throat too narrow for layers, and
  the pipe split in two parts (the exchange done in-process, one thread per
  part) against the one-part run, bit for bit, also where the interface
  comes closer to the wall than the layers are thick (it rises with them),
  an unlayered ceiling closer than the layers (the lifted surface must
  not cross itself), and a faceted floor whose noisy normals would crumple
  thick stacks' tops.
\*---------------------------------------------------------------------------*/

#include "wallLayers.H"
#include "gapAlongTriangles.H"
#include "triangleCrossings.H"
#include "meshPatch.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <thread>

using namespace pmsh;
using pmsh::test::gapAlongTriangles;

namespace
{

const double pi = 3.14159265358979323846;

//- layerSurface::piece of a part meshed in one piece
const std::vector<label> onePiece;

//- A closed triangulated surface built face by face: points merged by
//  their exact coordinates, one barycentric id each, triangles turned to
//  face a given way (outward from the fluid).
struct testSurface
{
    std::vector<point3> points;
    std::vector<barycentricId> ids;
    std::vector<triVerts> triangles;
    std::vector<label> region;
    std::map<point3, label> index;

    label point(const point3& x)
    {
        const auto it = index.find(x);
        if (it != index.end()) return it->second;
        const label p = points.size();
        points.push_back(x);
        // Ids as a coarse vertex each: unique, ordered as created
        ids.push_back(barycentricId(std::uint32_t(p + 1), 1, 0, 0, 0, 0));
        index[x] = p;
        return p;
    }

    //- Triangle (a, b, c) of region r, turned so its normal has a positive
    //  component along `outward`.
    void triangle(const point3& a, const point3& b, const point3& c, label r, const vector3& outward)
    {
        triVerts f{point(a), point(b), point(c)};
        if (dot(cross(b - a, c - a), outward) < 0) std::swap(f[1], f[2]);
        triangles.push_back(f);
        region.push_back(r);
    }

    //- A grid quad (corners in order) as two triangles.
    void quad(const point3& a, const point3& b, const point3& c, const point3& d, label r, const vector3& outward)
    {
        triangle(a, b, c, r, outward);
        triangle(a, c, d, r, outward);
    }
};


//- The faces of the box [lo, hi] as grids of cells[axis] cells along each
//  axis, facing out of the box if `outwards`, else into it; face regions
//  from `faceRegion(axis, side)`.
void addBox
(
    testSurface& s,
    const point3& lo,
    const point3& hi,
    const std::array<int, 3>& cells,
    bool outwards,
    const std::function<label(int, int)>& faceRegion
)
{
    for (int axis = 0; axis < 3; ++axis)
    {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int side = 0; side < 2; ++side)
        {
            vector3 out{0, 0, 0};
            out[axis] = (side ? 1.0 : -1.0)*(outwards ? 1 : -1);
            auto at = [&](int i, int j)
            {
                point3 x;
                x[axis] = side ? hi[axis] : lo[axis];
                x[u] = lo[u] + (hi[u] - lo[u])*i/cells[u];
                x[v] = lo[v] + (hi[v] - lo[v])*j/cells[v];
                return x;
            };
            for (int i = 0; i < cells[u]; ++i)
            {
                for (int j = 0; j < cells[v]; ++j)
                {
                    s.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), faceRegion(axis, side), out);
                }
            }
        }
    }
}


//- A sphere of radius R: the octahedron's faces refined n times each way,
//  projected; facing its centre (the fluid is outside).
void addSphere(testSurface& s, double R, int n, label region)
{
    const point3 corner[6] = {{1,0,0}, {-1,0,0}, {0,1,0}, {0,-1,0}, {0,0,1}, {0,0,-1}};
    for (int a = 0; a < 2; ++a)
    for (int b = 2; b < 4; ++b)
    for (int c = 4; c < 6; ++c)
    {
        auto at = [&](int i, int j)
        {
            const int k = n - i - j;
            const point3 x = (double(i)/n)*corner[a] + (double(j)/n)*corner[b] + (double(k)/n)*corner[c];
            return (R/std::sqrt(magSqr(x)))*x;
        };
        for (int i = 0; i < n; ++i)
        {
            for (int j = 0; i + j < n; ++j)
            {
                const point3 centre = at(i, j);
                s.triangle(at(i, j), at(i + 1, j), at(i, j + 1), region, -1.0*centre);
                if (i + j + 2 <= n)
                {
                    s.triangle(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), region, -1.0*centre);
                }
            }
        }
    }
}


//- A disc at height z, radius R, nTheta points round, nRings rings.
void addDisc(testSurface& s, double R, double z, int nTheta, int nRings, label region, const vector3& outward)
{
    auto at = [&](int ring, int i)
    {
        const double r = R*ring/nRings, theta = 2*pi*(i % nTheta)/nTheta;
        return point3{ring ? r*std::cos(theta) : 0.0, ring ? r*std::sin(theta) : 0.0, z};
    };
    for (int i = 0; i < nTheta; ++i)
    {
        s.triangle(at(0, 0), at(1, i), at(1, i + 1), region, outward);
        for (int ring = 1; ring < nRings; ++ring)
        {
            s.quad(at(ring, i), at(ring + 1, i), at(ring + 1, i + 1), at(ring, i + 1), region, outward);
        }
    }
}


//- A pipe along z: wall (region 0) from 0 to H facing out of the pipe,
//  radius R*(1 + wobble(theta, z)), inlet (1) at z = 0, outlet (2) at H.
testSurface pipe
(
    double R,
    double H,
    int nTheta,
    int nZ,
    const std::function<double(double, double)>& wobble = nullptr
)
{
    testSurface s;
    auto at = [&](int i, int k)
    {
        const double theta = 2*pi*(i % nTheta)/nTheta, z = H*k/nZ;
        const bool end = k == 0 || k == nZ;
        const double r = R*(1 + (wobble && !end ? wobble(theta, z) : 0.0));
        return point3{r*std::cos(theta), r*std::sin(theta), z};
    };
    for (int i = 0; i < nTheta; ++i)
    {
        for (int k = 0; k < nZ; ++k)
        {
            const point3 mid = at(i, k);
            s.quad(at(i, k), at(i + 1, k), at(i + 1, k + 1), at(i, k + 1), 0, {mid[0], mid[1], 0});
        }
    }
    addDisc(s, R, 0, nTheta, 4, 1, {0, 0, -1});
    addDisc(s, R, H, nTheta, 4, 2, {0, 0, 1});
    return s;
}


layerSpecification spec(int n, double first, double ratio = 1.2)
{
    layerSpecification s;
    s.nLayers = n;
    s.firstLayerThickness = first;
    s.expansionRatio = ratio;
    s.minThickness = 0.1*first;
    return s;
}


wallLayers grow
(
    const testSurface& s,
    const std::map<label, layerSpecification>& specs,
    bool gapLimit = false
)
{
    noLayerExchange serial;
    layerSurface surface{s.points, s.ids, s.triangles, s.region, onePiece, specs, nullptr};
    if (gapLimit) surface.gapAlong = gapAlongTriangles(s.points, s.triangles);
    return growWallLayers(surface, serial);
}


//- Every prism valid (six positive corner tets) and of positive volume.
void expectValidPrisms(const testSurface& s, const wallLayers& layers)
{
    ASSERT_FALSE(layers.prisms.empty());
    label nInvalid = 0;
    for (const auto& prism : layers.prisms)
    {
        std::array<point3, 6> x;
        for (int i = 0; i < 6; ++i) x[i] = layers.levelPoint(s.points, prism[i]);
        const double volume6 =
            tetVolume6(x[0], x[1], x[2], x[3]) + tetVolume6(x[1], x[2], x[3], x[4])
          + tetVolume6(x[2], x[3], x[4], x[5]);
        if (!validPrism(x) || !(volume6 > 0)) ++nInvalid;
    }
    EXPECT_EQ(nInvalid, 0) << "of " << layers.prisms.size() << " prisms";
}


//- The share of triangle t's area that its lifted copy (each point at its
//  top level) keeps, projected on t's plane: negative if it turned over.
double liftedAreaShare(const testSurface& s, const wallLayers& layers, label t)
{
    const triVerts& f = s.triangles[t];
    const vector3 before = cross(s.points[f[1]] - s.points[f[0]], s.points[f[2]] - s.points[f[0]]);
    const point3 a = layers.topPoint(s.points, f[0]);
    const vector3 after = cross(layers.topPoint(s.points, f[1]) - a, layers.topPoint(s.points, f[2]) - a);
    return dot(after, before)/magSqr(before);
}


label countLayered(const wallLayers& layers)
{
    return std::count(layers.triangleLayered.begin(), layers.triangleLayered.end(), true);
}


//- The distance of x, on the unit cube's surface, from the nearest edge
//  of the cube's face it is on (0 on an edge).
double distanceToCubeEdge(const point3& x)
{
    double d = 1;
    int nInside = 0;
    for (int i = 0; i < 3; ++i)
    {
        if (x[i] > 0 && x[i] < 1)
        {
            ++nInside;
            d = std::min({d, x[i], 1 - x[i]});
        }
    }
    return nInside == 2 ? d : 0;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * Shapes * * * * * * * * * * * * * * * * //

TEST(wallLayers, sphereInBoxRadialUniformAndPositive)
{
    testSurface s;
    addBox(s, {-2, -2, -2}, {2, 2, 2}, {4, 4, 4}, true, [](int, int) { return 1; });
    addSphere(s, 0.5, 8, 0);
    const layerSpecification ball = spec(5, 0.005);
    const wallLayers layers = grow(s, {{0, ball}}, true);

    label nBall = 0;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        if (std::abs(std::sqrt(magSqr(s.points[p])) - 0.5) > 1e-9)
        {
            EXPECT_EQ(layers.nLayers[p], 0) << "box point " << p;
            continue;
        }
        ++nBall;
        const vector3 radial = (1/0.5)*s.points[p];
        EXPECT_LT(std::acos(std::min(1.0, dot(layers.direction[p], radial))), 1e-6) << "point " << p;
        EXPECT_EQ(layers.nLayers[p], 5);
        EXPECT_NEAR(layers.thickness[p], ball.totalThickness(), 1e-15);
    }
    EXPECT_EQ(nBall, 4*8*8 + 2);
    const label nBallTriangles = std::count(s.region.begin(), s.region.end(), 0);
    EXPECT_EQ(countLayered(layers), nBallTriangles);
    EXPECT_EQ(label(layers.prisms.size()), 5*nBallTriangles);
    EXPECT_TRUE(layers.sideFaces.empty());
    expectValidPrisms(s, layers);
}


TEST(wallLayers, insideCornersOfACubeAreThinnedNotFolded)
{
    // The fluid inside the unit cube, every face layered: concave edges
    const int n = 8;
    const double h = 1.0/n;
    testSurface s;
    addBox(s, {0, 0, 0}, {1, 1, 1}, {n, n, n}, true, [](int, int) { return 0; });
    const layerSpecification wall = spec(3, 0.03, 1.2);   // 0.109 > h/2
    const wallLayers layers = grow(s, {{0, wall}});

    for (label p = 0; p < label(s.points.size()); ++p)
    {
        const double edgeDistance = distanceToCubeEdge(s.points[p]);
        if (edgeDistance == 0)
        {
            // On an edge or a corner: at most half the shortest edge round it
            EXPECT_LE(layers.thickness[p], 0.5*h*(1 + 1e-12)) << "edge point " << p;
            EXPECT_GT(layers.thickness[p], 0) << "edge point " << p;
        }
        else if (edgeDistance > 0.3)
        {
            EXPECT_EQ(layers.thickness[p], wall.totalThickness()) << "face point " << p;
        }
    }
    EXPECT_EQ(countLayered(layers), label(s.triangles.size()));
    EXPECT_GT(layers.stats.nFeatureLimited, 0);
    expectValidPrisms(s, layers);
}


TEST(wallLayers, outsideCornersOfACubeAreLimitedToTheEdgeLength)
{
    // The fluid outside the unit cube: convex edges, layers fan out
    const int n = 8;
    const double h = 1.0/n;
    testSurface s;
    addBox(s, {0, 0, 0}, {1, 1, 1}, {n, n, n}, false, [](int, int) { return 0; });
    const layerSpecification wall = spec(4, 0.04, 1.2);   // 0.215 > h
    const wallLayers layers = grow(s, {{0, wall}});

    for (label p = 0; p < label(s.points.size()); ++p)
    {
        const double edgeDistance = distanceToCubeEdge(s.points[p]);
        if (edgeDistance == 0)
        {
            EXPECT_LE(layers.thickness[p], h*(1 + 1e-12)) << "edge point " << p;
            EXPECT_GT(layers.thickness[p], 0.5*h) << "edge point " << p;
            // Fanning out: between the normals of the faces it joins
            EXPECT_LT(dot(layers.direction[p], point3{0.5, 0.5, 0.5} - s.points[p]), 0);
        }
        else if (edgeDistance > 0.45)
        {
            EXPECT_EQ(layers.thickness[p], wall.totalThickness()) << "face point " << p;
        }
    }
    EXPECT_EQ(countLayered(layers), label(s.triangles.size()));
    expectValidPrisms(s, layers);
}


TEST(wallLayers, noisyNormalsOfAFacetedFloorAreSmoothedAndItsThickStacksKeepTheirTops)
{
    // The fluid inside a 2 x 2 x 1 box, its floor layered with stacks 5
    // grid cells thick; the floor's inner points moved up or down by up to
    // 0.2 of a cell, as a faceted STL's normals jump from facet to facet
    const int n = 16;
    const double h = 1.0/n;
    testSurface s;
    addBox(s, {0, 0, 0}, {2, 2, 1}, {2*n, 2*n, n}, true, [](int axis, int side) { return axis == 2 && side == 0 ? 0 : 1; });
    for (point3& x : s.points)
    {
        if (x[2] == 0 && x[0] > 0 && x[0] < 2 && x[1] > 0 && x[1] < 2)
        {
            const unsigned i = std::lround(x[0]/h), j = std::lround(x[1]/h);
            const unsigned hash = (i*73856093u) ^ (j*19349663u);
            x[2] = 0.1*h*(int(hash % 5) - 2);
        }
    }
    const layerSpecification floor = spec(4, 0.04, 1.5);    // 0.325, 5.2 cells
    const wallLayers layers = grow(s, {{0, floor}});

    EXPECT_GT(layers.stats.nSmoothedDirections, 0);
    // Away from the walls round it (where the concave edge thins the
    // stacks), nine in ten stacks keep their full height (76 of 81; none
    // without the smoothing, at most 0.63 of it), and every top at least
    // half its floor triangle's shape quality
    label nFull = 0, nInner = 0;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        const point3& x = s.points[p];
        if (std::abs(x[2]) > 0.5*h || std::min({x[0], x[1], 2 - x[0], 2 - x[1]}) < 0.7) continue;
        ++nInner;
        if (layers.thickness[p] == floor.totalThickness()) ++nFull;
    }
    EXPECT_GT(nInner, 0);
    EXPECT_GE(nFull, 0.9*nInner);
    auto quality = [](const point3& a, const point3& b, const point3& c)
    {
        return 2*std::sqrt(3.0)*std::sqrt(magSqr(cross(b - a, c - a)))
            /(magSqr(b - a) + magSqr(c - b) + magSqr(a - c));
    };
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (!layers.triangleLayered[t]) continue;
        const triVerts& f = s.triangles[t];
        const double top = quality
        (
            layers.topPoint(s.points, f[0]), layers.topPoint(s.points, f[1]), layers.topPoint(s.points, f[2])
        );
        EXPECT_GE(top, 0.5*quality(s.points[f[0]], s.points[f[1]], s.points[f[2]])) << "triangle " << t;
    }
    expectValidPrisms(s, layers);
}


TEST(wallLayers, platesCloserThanTwiceTheLayersDoNotOverlap)
{
    // Plates z = 0 and z = g layered, the box's sides not
    const double g = 0.1;
    testSurface s;
    addBox(s, {0, 0, 0}, {1, 1, g}, {10, 10, 1}, true, [](int axis, int) { return axis == 2 ? 0 : 1; });
    layerSpecification plate = spec(4, 0.015, 1.2);        // 0.080 > g/2
    plate.maxThicknessToGapRatio = 0.3;
    const wallLayers layers = grow(s, {{0, plate}}, true);

    double bottomTop = -1, topBottom = 2;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        if (s.points[p][2] != 0 && s.points[p][2] != g) continue;
        EXPECT_EQ(layers.nLayers[p], 4) << "plate point " << p;
        EXPECT_LE(layers.thickness[p], 0.3*g*(1 + 1e-12)) << "plate point " << p;
        const double z = layers.topPoint(s.points, p)[2];
        if (s.points[p][2] == 0) bottomTop = std::max(bottomTop, z);
        else topBottom = std::min(topBottom, z);
    }
    EXPECT_LT(bottomTop, topBottom);
    EXPECT_LE(topBottom - bottomTop, g*(1 - 2*0.3) + 1e-12);
    EXPECT_GT(layers.stats.nGapLimited, 0);
    expectValidPrisms(s, layers);
}


TEST(wallLayers, stackTopsDoNotRunThroughAnUnlayeredCeilingCloserThanTheStack)
{
    // A layered floor under an unlayered ceiling g above it, no gap query:
    // nothing local to a triangle sees the ceiling from the floor's middle
    // (the side walls thin only the rim), so only the crossing check of
    // the lifted surface keeps the tops below it
    const double g = 0.05;
    testSurface s;
    addBox(s, {0, 0, 0}, {1, 1, g}, {10, 10, 1}, true, [](int axis, int side) { return axis == 2 && side == 0 ? 0 : 1; });
    const wallLayers layers = grow(s, {{0, spec(4, 0.02, 1.2)}});    // 0.086 > g

    std::vector<point3> lifted(s.points.size());
    std::vector<bool> moved(s.triangles.size(), false);
    double highestTop = 0;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        lifted[p] = layers.topPoint(s.points, p);
        if (s.points[p][2] == 0) highestTop = std::max(highestTop, lifted[p][2]);
    }
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        for (label p : s.triangles[t]) moved[t] = moved[t] || layers.nLayers[p] > 0;
    }
    EXPECT_LT(highestTop, g);
    const std::vector<label> crossing = crossingTriangles(lifted, s.triangles, moved);
    EXPECT_EQ(std::count(crossing.begin(), crossing.end(), 0), label(crossing.size()));
    EXPECT_GT(layers.stats.nInvalidLimited, 0);
    expectValidPrisms(s, layers);
}


TEST(triangleCrossings, findsASegmentThroughATriangleAndNotBesideOrAtItsEnds)
{
    const point3 p{0, 0, 0}, q{1, 0, 0}, r{0, 1, 0};
    EXPECT_TRUE(segmentCrossesTriangle({0.2, 0.2, -1}, {0.2, 0.2, 1}, p, q, r));
    EXPECT_FALSE(segmentCrossesTriangle({0.8, 0.8, -1}, {0.8, 0.8, 1}, p, q, r));     // beside
    EXPECT_FALSE(segmentCrossesTriangle({0.2, 0.2, 0}, {0.2, 0.2, 1}, p, q, r));      // an end on it
    EXPECT_FALSE(segmentCrossesTriangle({0.2, 0.2, 0.5}, {0.2, 0.2, 1}, p, q, r));    // short of it
    EXPECT_FALSE(segmentCrossesTriangle({-1, 0.2, 0}, {2, 0.2, 0}, p, q, r));         // in its plane

    // Two triangles sharing no point, one through the other; and apart
    const std::vector<point3> x{p, q, r, {0.2, 0.2, -1}, {0.3, 0.2, 1}, {0.2, 0.3, 1}, {5, 5, 5}};
    const std::vector<label> crossing = crossingTriangles
    (
        x, {{0, 1, 2}, {3, 4, 5}, {6, 4, 5}}, {true, false, false}
    );
    EXPECT_EQ(crossing, (std::vector<label>{2, 1, 0}));
}


TEST(triangleCrossings, pairsAreListedOnceAndOnlyWithinAGroup)
{
    // Triangle 0 pierced by 1 and by 2; 3 apart. Every crossing pair once,
    // whichever of its triangles is tested: which triangle a caller's
    // decision names must not depend on the triangles' order (that is
    // the ranks'). In groups (the layers' pieces), 2 is in another group
    // than 0, so that pair is not one: a piece's stacks see only its own
    // surface, whichever pieces share its rank
    const point3 p{0, 0, 0}, q{1, 0, 0}, r{0, 1, 0};
    const std::vector<point3> x
    {
        p, q, r,
        {0.2, 0.2, -1}, {0.3, 0.2, 1}, {0.2, 0.3, 1},
        {0.1, 0.1, -1}, {0.15, 0.1, 1}, {0.1, 0.15, 1},
        {5, 5, 5}, {6, 5, 5}, {5, 6, 5}
    };
    const std::vector<triVerts> t{{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}};
    using pairs = std::vector<std::pair<label, label>>;
    const std::vector<bool> all(t.size(), true);
    EXPECT_EQ(crossingPairs(x, t, all, true), (pairs{{0, 1}, {0, 2}}));
    EXPECT_EQ(crossingPairs(x, t, {false, true, true, false}, true), (pairs{{0, 1}, {0, 2}}));
    EXPECT_EQ(crossingPairs(x, t, all, true, {7, 7, 8, 7}), (pairs{{0, 1}}));
    EXPECT_EQ(crossingTriangles(x, t, all), (std::vector<label>{2, 1, 1, 0}));
}


TEST(triangleCrossings, aSurfaceFoldedOntoItselfCrossesBeforeStage4)
{
    // What no edge passing through a triangle shows: pairs in one plane
    // that overlap there, with no point shared, with an edge shared (a
    // triangle folded back over its neighbour) and with a point shared;
    // and a pair sharing a point whose far edge passes through the other.
    // Seen with alsoFolds (the check before stage 4) only
    const auto crossings = [](const std::vector<point3>& x, const std::vector<triVerts>& t)
    {
        const std::vector<bool> all(t.size(), true);
        const std::vector<label> with = crossingTriangles(x, t, all, true);
        const std::vector<label> without = crossingTriangles(x, t, all);
        EXPECT_EQ(std::count(without.begin(), without.end(), 0), label(t.size()));
        return label(t.size()) - label(std::count(with.begin(), with.end(), 0));
    };
    const point3 p{0, 0, 0}, q{1, 0, 0}, r{0.5, 1, 0};

    // Apart in one plane; overlapping there
    EXPECT_EQ(crossings({p, q, r, {2, 0, 0}, {3, 0, 0}, {2.5, 1, 0}}, {{0, 1, 2}, {3, 4, 5}}), 0);
    EXPECT_EQ(crossings({p, q, r, {0.2, 0.2, 0}, {1.2, 0.2, 0}, {0.7, 1.2, 0}}, {{0, 1, 2}, {3, 4, 5}}), 2);

    // Sharing edge p-q: flat across it (a fair surface); folded back over
    EXPECT_EQ(crossings({p, q, r, {0.5, -1, 0}}, {{0, 1, 2}, {1, 0, 3}}), 0);
    EXPECT_EQ(crossings({p, q, r, {0.5, 0.6, 0}}, {{0, 1, 2}, {1, 0, 3}}), 2);

    // Sharing point p: side by side in one plane; one over the other
    EXPECT_EQ(crossings({p, q, r, {-1, 0.5, 0}, {-1, -0.5, 0}}, {{0, 1, 2}, {0, 3, 4}}), 0);
    EXPECT_EQ(crossings({p, q, r, {0.8, 0.3, 0}, {0.3, 0.5, 0}}, {{0, 1, 2}, {0, 3, 4}}), 2);

    // Sharing point p, out of plane: the far edge of the second passes
    // through the first; and it stays above it
    EXPECT_EQ(crossings({p, q, r, {0.4, 0.3, -1}, {0.4, 0.3, 1}}, {{0, 1, 2}, {0, 3, 4}}), 2);
    EXPECT_EQ(crossings({p, q, r, {0.4, 0.3, 0.5}, {0.4, 0.3, 1}}, {{0, 1, 2}, {0, 3, 4}}), 0);
}


TEST(wallLayers, foldsBelowTheFeatureAngleAreThinnedUntilPrismsAreValid)
{
    // A valley bent by 50 degrees (below featureAngle 60), its triangles
    // far smaller than the layers: offset surfaces from its two sides would
    // cross
    const int n = 20;
    const double slope = std::tan(25*pi/180);
    testSurface s;
    auto at = [&](int i, int j)
    {
        const double x = -1 + 2.0*i/n;
        return point3{x, double(j)/n, slope*std::abs(x)};
    };
    for (int i = 0; i < n; ++i)
    {
        for (int j = 0; j < n; ++j)
        {
            s.quad(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), 0, {0, 0, -1});
        }
    }
    const layerSpecification valley = spec(3, 0.15, 1.2);     // 0.546 total
    const wallLayers layers = grow(s, {{0, valley}});

    EXPECT_EQ(layers.stats.nFeatureLimited, 0);
    EXPECT_GT(layers.stats.nInvalidLimited, 0);
    EXPECT_EQ(countLayered(layers), label(s.triangles.size()));
    expectValidPrisms(s, layers);
}


TEST(wallLayers, liftedNeighbourTrianglesStayValid)
{
    // Plates z = 0 and z = g layered, the sides not, in rows lower than the
    // layers: lifting the rows' plate points would turn them over
    const double g = 0.1;
    testSurface s;
    addBox(s, {0, 0, 0}, {1, 1, g}, {10, 10, 10}, true, [](int axis, int) { return axis == 2 ? 0 : 1; });
    layerSpecification plate = spec(4, 0.015, 1.2);
    plate.maxThicknessToGapRatio = 0.3;                     // 0.03, three rows
    const wallLayers layers = grow(s, {{0, plate}}, true);

    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (s.region[t] != 1) continue;
        EXPECT_GE(liftedAreaShare(s, layers, t), 0.25) << "side triangle " << t;
    }
    EXPECT_GT(layers.stats.nInvalidLimited, 0);
    EXPECT_EQ(countLayered(layers), 2*2*10*10);
    expectValidPrisms(s, layers);
}


TEST(wallLayers, pipeWallSlidesAlongTheUnlayeredInlet)
{
    // The wall bulges, so that its normals at the inlet lean out of the
    // inlet's plane
    const int nTheta = 32, nZ = 16;
    const testSurface s = pipe
    (
        0.5, 2, nTheta, nZ, [](double, double z) { return 0.2*std::sin(pi*z/2); }
    );
    const layerSpecification wall = spec(4, 0.01, 1.2);
    const wallLayers layers = grow(s, {{0, wall}}, true);

    // Rim points: the direction in the inlet's plane, radial; the top
    // level stays on the inlet
    label nRim = 0;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        const point3& x = s.points[p];
        const bool rim = x[2] == 0 && std::abs(std::hypot(x[0], x[1]) - 0.5) < 1e-12;
        if (!rim) continue;
        ++nRim;
        EXPECT_EQ(layers.nLayers[p], 4);
        EXPECT_NEAR(layers.direction[p][2], 0, 1e-15) << "rim point " << p;
        EXPECT_NEAR(layers.topPoint(s.points, p)[2], 0, 1e-15) << "rim point " << p;
        const vector3 inward{-x[0]/0.5, -x[1]/0.5, 0};
        EXPECT_GT(dot(layers.direction[p], inward), std::cos(0.01));
    }
    EXPECT_EQ(nRim, nTheta);

    // The inlet's triangles, lifted, still face out of the pipe and keep
    // more than half their area
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (s.region[t] != 1) continue;
        EXPECT_GT(liftedAreaShare(s, layers, t), 0.5) << "inlet triangle " << t;
    }

    // The stacks end on the inlet and outlet: a side quad per layer and rim edge
    label nInlet = 0, nOutlet = 0;
    for (const layerSideFace& f : layers.sideFaces)
    {
        (f.region == 1 ? nInlet : nOutlet) += 1;
    }
    EXPECT_EQ(nInlet, 4*nTheta);
    EXPECT_EQ(nOutlet, 4*nTheta);
    EXPECT_EQ(countLayered(layers), 2*nTheta*nZ);
    expectValidPrisms(s, layers);
}


TEST(wallLayers, stacksEndCleanlyWhereTheyWouldBeThinnerThanMinThickness)
{
    // A throat at z = 1 too narrow for the layers: no layers at its points,
    // none on its triangles; the stacks round it end as at an unlayered
    // patch, with side quads of the wall's own patch
    const int nTheta = 24, nZ = 12, L = 3;
    const testSurface s = pipe
    (
        0.5, 2, nTheta, nZ,
        [](double, double z) { return std::abs(z - 1) < 1e-9 ? -0.7 : 0.0; }
    );
    layerSpecification wall = spec(L, 0.01, 1.2);       // 0.0364 total
    wall.minThickness = 0.02;
    wall.maxThicknessToGapRatio = 0.05;                 // 0.015 at the throat
    const wallLayers layers = grow(s, {{0, wall}}, true);

    auto atThroat = [&](label p) { return std::abs(s.points[p][2] - 1) < 1e-9; };
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        if (atThroat(p))
        {
            EXPECT_EQ(layers.nLayers[p], 0) << "throat point " << p;
        }
    }
    label nLiftedWall = 0;
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (s.region[t] != 0) continue;
        const triVerts& f = s.triangles[t];
        const bool throat = atThroat(f[0]) || atThroat(f[1]) || atThroat(f[2]);
        EXPECT_EQ(layers.triangleLayered[t], !throat) << "wall triangle " << t;
        if (!throat) continue;

        // The unlayered wall triangles, their layered points lifted: still
        // facing the same way, with at least a quarter of their area
        EXPECT_GE(liftedAreaShare(s, layers, t), 0.25) << "wall triangle " << t;
        nLiftedWall += layers.nLayers[f[0]] + layers.nLayers[f[1]] + layers.nLayers[f[2]] > 0;
    }
    EXPECT_EQ(nLiftedWall, 4*nTheta);       // both triangles of each quad of the two bands

    // Side quads on the wall's patch: one per layer on each edge of the
    // two rings next to the throat
    label nWallQuads = 0;
    for (const layerSideFace& f : layers.sideFaces) nWallQuads += f.region == 0;
    EXPECT_EQ(nWallQuads, 2*nTheta*L);
    EXPECT_EQ(layers.stats.nInterfaceLimited, 0);
    expectValidPrisms(s, layers);
}


// * * * * * * * * * * * * * * * * Parallel * * * * * * * * * * * * * * * * //

namespace
{

//- The exchange between parts run in threads of one process: each call
//  posts this part's data, waits for all, reads the others', waits again.
class threadExchange
{
public:

    explicit threadExchange(int nParts) : nParts_(nParts), posted_(nParts) {}

    class part : public layerExchange
    {
    public:

        part(threadExchange& board, int rank) : board_(board), rank_(rank) {}

        void gatherContributions
        (
            const std::vector<barycentricId>& ids,
            std::vector<std::vector<keyedContribution>>& contributions
        ) override
        {
            board_.post(rank_, {ids, contributions, {}, false});
            std::vector<std::vector<keyedContribution>> all = contributions;
            for (int r = 0; r < board_.nParts_; ++r)
            {
                if (r == rank_) continue;
                const posting& other = board_.posted_[r];
                for (std::size_t i = 0; i < ids.size(); ++i)
                {
                    const auto it = std::find(other.ids.begin(), other.ids.end(), ids[i]);
                    if (it == other.ids.end()) continue;
                    const auto& theirs = other.contributions[it - other.ids.begin()];
                    all[i].insert(all[i].end(), theirs.begin(), theirs.end());
                }
            }
            board_.wait();
            contributions = std::move(all);
        }

        void minimum(const std::vector<barycentricId>& ids, std::vector<double>& values) override
        {
            board_.post(rank_, {ids, {}, values, false});
            std::vector<double> least = values;
            for (int r = 0; r < board_.nParts_; ++r)
            {
                const posting& other = board_.posted_[r];
                for (std::size_t i = 0; i < ids.size(); ++i)
                {
                    const auto it = std::find(other.ids.begin(), other.ids.end(), ids[i]);
                    if (it != other.ids.end())
                    {
                        least[i] = std::min(least[i], other.values[it - other.ids.begin()]);
                    }
                }
            }
            board_.wait();
            values = std::move(least);
        }

        bool anyRank(bool local) override
        {
            board_.post(rank_, {{}, {}, {}, local});
            bool any = false;
            for (const posting& other : board_.posted_) any = any || other.flag;
            board_.wait();
            return any;
        }

        int rank() const override { return rank_; }

    private:

        threadExchange& board_;
        int rank_;
    };

private:

    struct posting
    {
        std::vector<barycentricId> ids;
        std::vector<std::vector<keyedContribution>> contributions;
        std::vector<double> values;
        bool flag;
    };

    int nParts_;
    std::vector<posting> posted_;
    std::mutex mutex_;
    std::condition_variable arrived_;
    int nWaiting_ = 0;
    long generation_ = 0;

    //- Post, then wait until every part has posted.
    void post(int rank, posting data)
    {
        posted_[rank] = std::move(data);
        wait();
    }

    //- A barrier of all parts.
    void wait()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        const long gen = generation_;
        if (++nWaiting_ == nParts_)
        {
            nWaiting_ = 0;
            ++generation_;
            arrived_.notify_all();
        }
        else
        {
            arrived_.wait(lock, [&] { return generation_ != gen; });
        }
    }
};


//- Part of a surface: the given triangles, points renumbered, ids kept.
testSurface partOf(const testSurface& whole, const std::vector<label>& triangles)
{
    testSurface part;
    std::map<label, label> local;
    for (const label t : triangles)
    {
        triVerts f;
        for (int i = 0; i < 3; ++i)
        {
            const label p = whole.triangles[t][i];
            auto it = local.find(p);
            if (it == local.end())
            {
                it = local.emplace(p, label(part.points.size())).first;
                part.points.push_back(whole.points[p]);
                part.ids.push_back(whole.ids[p]);
            }
            f[i] = it->second;
        }
        part.triangles.push_back(f);
        part.region.push_back(whole.region[t]);
    }
    return part;
}


//- Every layered point's direction, thickness and levels by id, as bits;
//  every prism by the ids of its points and their levels.
struct layerBits
{
    std::map<barycentricId, std::vector<double>> points;
    std::set<std::vector<std::pair<barycentricId, int>>> prisms;

    layerBits(const testSurface& s, const wallLayers& layers)
    {
        for (label p = 0; p < label(s.points.size()); ++p)
        {
            if (!layers.nLayers[p]) continue;
            std::vector<double>& v = points[s.ids[p]];
            v.push_back(layers.thickness[p]);
            v.insert(v.end(), layers.direction[p].begin(), layers.direction[p].end());
            for (int k = 1; k <= layers.nLayers[p]; ++k)
            {
                const point3 x = layers.levelPoint(s.points, p, k);
                v.insert(v.end(), x.begin(), x.end());
            }
        }
        for (const auto& prism : layers.prisms)
        {
            std::vector<std::pair<barycentricId, int>> key;
            for (const layerPointRef& r : prism) key.push_back({s.ids[r.point], r.level});
            prisms.insert(key);
        }
    }
};


//- The pipe `whole` split at z = H/2, each part closed by a disc of
//  nRings rings (partition interface), and the layers grown on both parts
//  at once, one thread each. The lower part's disc faces rank
//  lowerDiscFaces (1, the upper part, unless a test wants another part
//  there).
void growInTwoParts
(
    testSurface whole,
    double H,
    int nTheta,
    int nRings,
    const std::map<label, layerSpecification>& specs,
    const std::function<double(const point3&, const vector3&, double)>& gap,
    testSurface parts[2],
    wallLayers split[2],
    int lowerDiscFaces = 1
)
{
    const double R = std::hypot(whole.points[0][0], whole.points[0][1]);
    std::vector<label> lower, upper;
    for (label t = 0; t < label(whole.triangles.size()); ++t)
    {
        double z = 0;
        for (const label p : whole.triangles[t]) z += whole.points[p][2];
        (z < 1.5*H ? lower : upper).push_back(t);
    }
    const label nWhole = whole.triangles.size();
    addDisc(whole, R, H/2, nTheta, nRings, interfaceRegion(lowerDiscFaces), {0, 0, 1});
    const label nDisc = label(whole.triangles.size()) - nWhole;
    for (label t = nWhole; t < nWhole + nDisc; ++t) lower.push_back(t);
    addDisc(whole, R, H/2, nTheta, nRings, interfaceRegion(0), {0, 0, -1});
    for (label t = nWhole + nDisc; t < label(whole.triangles.size()); ++t) upper.push_back(t);
    parts[0] = partOf(whole, lower);
    parts[1] = partOf(whole, upper);

    threadExchange board(2);
    std::vector<std::thread> threads;
    for (int r = 0; r < 2; ++r)
    {
        threads.emplace_back
        (
            [&, r]
            {
                threadExchange::part exchange(board, r);
                split[r] = growWallLayers
                (
                    {parts[r].points, parts[r].ids, parts[r].triangles, parts[r].region, onePiece, specs, gap},
                    exchange
                );
            }
        );
    }
    for (std::thread& t : threads) t.join();
}


bool sameBits(const std::vector<double>& a, const std::vector<double>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size()*sizeof(double)) == 0;
}

} // End anonymous namespace


TEST(wallLayers, twoPartsGiveTheOnePartLayersBitForBit)
{
    // A wobbly pipe (normals and gap limits differ from point to point),
    // layers thick enough for the gap limit and smoothing to act, and a
    // narrow ring just above the interface: its thin layers hold the
    // interface's points down from the upper part only
    const int nTheta = 24, nZ = 12, nRings = 2;
    const double R = 0.5, H = 2;
    const testSurface whole = pipe
    (
        R, H, nTheta, nZ,
        // None at the ends and at z = H/2, where the discs meet the wall
        [](double theta, double z)
        {
            const double narrow = std::abs(z - (1 + 1.0/6)) < 1e-9 ? -0.4 : 0;
            return narrow + (z - 1)*(0.08*std::sin(3*theta)*std::cos(2.3*z) + 0.03*std::cos(7*theta + z));
        }
    );
    layerSpecification wall = spec(4, 0.02, 1.3);     // 0.125 total
    wall.maxThicknessToGapRatio = 0.12;
    const std::map<label, layerSpecification> specs{{0, wall}};
    const auto gap = gapAlongTriangles(whole.points, whole.triangles);

    noLayerExchange serial;
    const wallLayers one = growWallLayers
    (
        {whole.points, whole.ids, whole.triangles, whole.region, onePiece, specs, gap}, serial
    );
    ASSERT_GT(one.stats.nGapLimited, 0);
    const layerBits oneBits(whole, one);

    testSurface parts[2];
    wallLayers split[2];
    growInTwoParts(whole, H, nTheta, nRings, specs, gap, parts, split);

    std::set<std::vector<std::pair<barycentricId, int>>> prisms;
    label nShared = 0;
    for (int r = 0; r < 2; ++r)
    {
        EXPECT_EQ(split[r].stats.nInterfaceLimited, 0) << "part " << r;
        const layerBits partBits(parts[r], split[r]);
        for (const auto& [id, bits] : partBits.points)
        {
            ASSERT_TRUE(oneBits.points.count(id));
            EXPECT_TRUE(sameBits(bits, oneBits.points.at(id))) << "point " << id << " of part " << r;
        }
        for (label p = 0; p < label(parts[r].points.size()); ++p)
        {
            nShared += parts[r].points[p][2] == H/2 && split[r].nLayers[p] > 0;
        }
        prisms.insert(partBits.prisms.begin(), partBits.prisms.end());

        // The interface's side quads: one per layer and rim edge
        label nInterfaceQuads = 0;
        for (const layerSideFace& f : split[r].sideFaces)
        {
            nInterfaceQuads += f.region == interfaceRegion(1 - r);
        }
        EXPECT_EQ(nInterfaceQuads, 4*nTheta) << "part " << r;
    }
    EXPECT_EQ(nShared, 2*nTheta);
    EXPECT_EQ(prisms, oneBits.prisms);
}


TEST(wallLayers, sideQuadsBetweenTwoPartsStacksFaceTheOtherStacksPartWhenAThirdPartTouchesTheirEdge)
{
    // The lower part's interface at the rim faces a third part (rank 2,
    // which holds no wall there), as where three parts meet on a wall
    // edge: the stacks on both sides of the rim still meet each other, so
    // their side quads are processor faces between parts 0 and 1, which
    // both make, not toward the part across the lower part's interface
    const int nTheta = 24, nZ = 12, nRings = 2;
    const double H = 2;
    const testSurface whole = pipe(0.5, H, nTheta, nZ);
    const std::map<label, layerSpecification> specs{{0, spec(4, 0.02, 1.3)}};
    testSurface parts[2];
    wallLayers split[2];
    growInTwoParts(whole, H, nTheta, nRings, specs, nullptr, parts, split, 2);

    for (int r = 0; r < 2; ++r)
    {
        std::map<label, label> quadsPerRegion;
        for (const layerSideFace& f : split[r].sideFaces) ++quadsPerRegion[f.region];
        EXPECT_EQ(quadsPerRegion[interfaceRegion(1 - r)], 4*nTheta) << "part " << r;
        EXPECT_EQ(quadsPerRegion.count(interfaceRegion(2)), 0u) << "part " << r;
    }
}


TEST(wallLayers, aFlatUnlayeredInletBesideThickStacksSlidesWithThemInsteadOfThinningThem)
{
    // Stacks 0.124 thick end on the inlet, whose outer ring of triangles
    // is 0.125 wide: lifted alone, the rim would squash it and the stacks
    // would thin. The inlet's points slide in its plane instead, each
    // ring less than the one outside it
    const int nTheta = 24, nZ = 12, L = 4;
    const testSurface s = pipe(0.5, 2, nTheta, nZ);
    const layerSpecification wall = spec(L, 0.02, 1.3);
    const wallLayers layers = grow(s, {{0, wall}});

    EXPECT_EQ(layers.stats.nInvalidLimited, 0);
    EXPECT_EQ(countLayered(layers), 2*nTheta*nZ);
    double thinnest = 1, thickest = 0;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        if (layers.nLayers[p] == 0) continue;
        thinnest = std::min(thinnest, layers.thickness[p]);
        thickest = std::max(thickest, layers.thickness[p]);
    }
    EXPECT_EQ(thinnest, thickest);
    EXPECT_NEAR(thickest, 0.02*(1 + 1.3 + 1.3*1.3 + 1.3*1.3*1.3), 1e-12);

    std::map<long, double> slideAtRadius;
    for (label p = 0; p < label(s.points.size()); ++p)
    {
        const point3& x = s.points[p];
        if (x[2] != 0 || layers.nLayers[p] > 0) continue;
        const point3 top = layers.topPoint(s.points, p);
        EXPECT_EQ(top[2], 0) << "inlet point " << p << " left its plane";
        const long ring = std::lround(4*std::hypot(x[0], x[1])/0.5);
        const double moved = std::sqrt(magSqr(top - x));
        auto it = slideAtRadius.emplace(ring, moved).first;
        it->second = std::min(it->second, moved);
    }
    ASSERT_EQ(slideAtRadius.size(), std::size_t(4));     // the centre and rings 1-3
    EXPECT_GT(slideAtRadius[3], 0.02);
    EXPECT_GT(slideAtRadius[3], slideAtRadius[2]);
    EXPECT_GT(slideAtRadius[2], slideAtRadius[1]);
    for (label t = 0; t < label(s.triangles.size()); ++t)
    {
        if (s.region[t] != 1) continue;
        EXPECT_GT(liftedAreaShare(s, layers, t), 0.25) << "inlet triangle " << t;
    }
    expectValidPrisms(s, layers);
}


TEST(wallLayers, interfaceCloserThanTheLayersRisesWithThemInsteadOfThinningThem)
{
    // The interface's rings closer than the layers are thick: its lifted
    // triangles would turn over. Its points inside the domain rise with
    // the stacks (interfaceShift), alike in both parts, so its triangles
    // stay valid, nothing crosses, and the layers are the one-part ones
    const int nTheta = 24, nZ = 12, nRings = 4, L = 4;
    const double H = 2;
    const testSurface whole = pipe(0.5, H, nTheta, nZ);
    const std::map<label, layerSpecification> specs{{0, spec(L, 0.02, 1.3)}};   // 0.124 > 3/4 of a ring
    const layerBits oneBits(whole, grow(whole, specs));
    testSurface parts[2];
    wallLayers split[2];
    growInTwoParts(whole, H, nTheta, nRings, specs, nullptr, parts, split);

    std::map<barycentricId, point3> risen[2];
    std::set<std::vector<std::pair<barycentricId, int>>> prisms;
    for (int r = 0; r < 2; ++r)
    {
        EXPECT_EQ(split[r].stats.nInterfaceLimited, 0) << "part " << r;
        const testSurface& s = parts[r];
        std::vector<point3> lifted(s.points.size());
        std::vector<bool> moved(s.triangles.size(), true);
        // The interface's points inside the domain (the flat end caps'
        // points slide along them as well)
        std::vector<bool> onWall(s.points.size(), false);
        for (label t = 0; t < label(s.triangles.size()); ++t)
        {
            if (s.region[t] >= 0) for (const label p : s.triangles[t]) onWall[p] = true;
        }
        for (label p = 0; p < label(s.points.size()); ++p)
        {
            lifted[p] = split[r].topPoint(s.points, p);
            if (!onWall[p] && lifted[p] != s.points[p]) risen[r][s.ids[p]] = lifted[p];
        }
        for (label t = 0; t < label(s.triangles.size()); ++t)
        {
            if (s.region[t] >= 0) continue;
            EXPECT_GE(liftedAreaShare(s, split[r], t), 0.25) << "interface triangle " << t << " of part " << r;
        }
        const std::vector<label> crossing = crossingTriangles(lifted, s.triangles, moved);
        EXPECT_EQ(std::count(crossing.begin(), crossing.end(), 0), label(crossing.size())) << "part " << r;
        const layerBits partBits(s, split[r]);
        for (const auto& [id, bits] : partBits.points)
        {
            ASSERT_TRUE(oneBits.points.count(id));
            EXPECT_TRUE(sameBits(bits, oneBits.points.at(id))) << "point " << id << " of part " << r;
        }
        prisms.insert(partBits.prisms.begin(), partBits.prisms.end());
        expectValidPrisms(s, split[r]);
    }
    EXPECT_EQ(prisms, oneBits.prisms);
    // Both parts moved the same interface points to the same bits
    EXPECT_GE(risen[0].size(), std::size_t(nTheta));
    EXPECT_EQ(risen[0], risen[1]);
}


TEST(wallLayers, risenInterfaceOverRingsFinerThanTheStacksPassesStageFoursFoldTest)
{
    // Stacks six rings of the interface tall: the risen interface slides
    // ring over ring in its own plane (its shift is along the wall's
    // normal, which lies in it). The validity rounds tested crossings
    // without folds (pairs sharing a point, coplanar overlaps), stage 4
    // with them: 384 of each part's 912 triangles folded, which the
    // rounds passed and stage 4 would have stopped on
    const int nTheta = 24, nZ = 12, nRings = 10;
    const double H = 2;
    const testSurface whole = pipe(0.5, H, nTheta, nZ);
    const std::map<label, layerSpecification> specs{{0, spec(4, 0.05, 1.3)}};   // 0.31, six rings
    testSurface parts[2];
    wallLayers split[2];
    growInTwoParts(whole, H, nTheta, nRings, specs, nullptr, parts, split);
    for (int r = 0; r < 2; ++r)
    {
        const testSurface& s = parts[r];
        std::vector<point3> lifted(s.points.size());
        for (label p = 0; p < label(s.points.size()); ++p) lifted[p] = split[r].topPoint(s.points, p);
        const std::vector<label> crossing =
            crossingTriangles(lifted, s.triangles, std::vector<bool>(s.triangles.size(), true), true);
        EXPECT_EQ(std::count(crossing.begin(), crossing.end(), 0), label(crossing.size())) << "part " << r;
        expectValidPrisms(s, split[r]);
    }
}
