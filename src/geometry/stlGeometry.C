/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: regions, projection and the coarse mesh (see
  stlGeometry.H). Netgen itself is behind netgenInterface.
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "netgenInterface.H"
#include "pmshError.H"
#include "Info.H"
#include "matchByPoints.H"
#include "retryLadder.H"
#include "triangleGeometry.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <sstream>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- Squared distance from p to the box [lo, hi] (0 inside).
inline double boxDistSqr(const point3& p, const point3& lo, const point3& hi)
{
    double d2 = 0;
    for (int k = 0; k < 3; ++k)
    {
        const double d =
            p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0.0);
        d2 += d*d;
    }
    return d2;
}


//- A bounding box tree (median split on the widest axis, leaves of up to
//  four items) for nearest-item queries. Queries are deterministic: the
//  traversal order is fixed and ties go to the first item found.
class boxTree
{
public:

    struct entry
    {
        label id;
        point3 lo, hi, centre;
    };

private:

    struct node
    {
        point3 lo, hi;
        label begin, end;       // item range (leaves)
        label left, right;      // children; -1 for a leaf
    };

    std::vector<node> nodes_;
    std::vector<label> ids_;

    static constexpr label leafSize = 4;

    label build(std::vector<entry>& e, label b, label n)
    {
        node nd;
        nd.lo = e[b].lo;
        nd.hi = e[b].hi;
        point3 clo = e[b].centre;
        point3 chi = e[b].centre;
        for (label i = b; i < b + n; ++i)
        {
            for (int k = 0; k < 3; ++k)
            {
                nd.lo[k] = std::min(nd.lo[k], e[i].lo[k]);
                nd.hi[k] = std::max(nd.hi[k], e[i].hi[k]);
                clo[k] = std::min(clo[k], e[i].centre[k]);
                chi[k] = std::max(chi[k], e[i].centre[k]);
            }
        }
        nd.begin = b;
        nd.end = b + n;
        nd.left = nd.right = -1;

        const label index = label(nodes_.size());
        nodes_.push_back(nd);

        if (n > leafSize)
        {
            int axis = 0;
            for (int k = 1; k < 3; ++k)
            {
                if (chi[k] - clo[k] > chi[axis] - clo[axis])
                {
                    axis = k;
                }
            }
            const label half = n/2;
            std::nth_element
            (
                e.begin() + b, e.begin() + b + half, e.begin() + b + n,
                [axis](const entry& x, const entry& y)
                {
                    return x.centre[axis] != y.centre[axis]
                        ? x.centre[axis] < y.centre[axis]
                        : x.id < y.id;
                }
            );
            const label left = build(e, b, half);
            const label right = build(e, b + half, n - half);
            nodes_[index].left = left;
            nodes_[index].right = right;
        }
        return index;
    }

public:

    boxTree() = default;

    explicit boxTree(std::vector<entry> e)
    {
        if (e.empty())
        {
            return;
        }
        nodes_.reserve(2*e.size()/leafSize + 2);
        build(e, 0, label(e.size()));
        ids_.resize(e.size());
        for (std::size_t i = 0; i < e.size(); ++i)
        {
            ids_[i] = e[i].id;
        }
    }

    bool empty() const
    {
        return nodes_.empty();
    }

    //- Item nearest to p; eval(id, p, closest) returns the squared
    //  distance from p to item id and sets closest. -1 if the tree is empty.
    template<class Eval>
    label nearest(const point3& p, const Eval& eval, point3& closest, double& d2) const
    {
        label best = -1;
        d2 = std::numeric_limits<double>::infinity();
        if (nodes_.empty())
        {
            return best;
        }

        // Depth is about log2(n/4) + 1, so 128 entries never overflow
        std::pair<label, double> stack[128];
        int top = 0;
        stack[top++] = {0, boxDistSqr(p, nodes_[0].lo, nodes_[0].hi)};
        while (top)
        {
            const auto cur = stack[--top];
            if (cur.second >= d2)
            {
                continue;
            }
            const node& nd = nodes_[cur.first];
            if (nd.left < 0)
            {
                for (label i = nd.begin; i < nd.end; ++i)
                {
                    point3 q;
                    const double di = eval(ids_[i], p, q);
                    if (di < d2)
                    {
                        d2 = di;
                        best = ids_[i];
                        closest = q;
                    }
                }
            }
            else
            {
                const double dl = boxDistSqr(p, nodes_[nd.left].lo, nodes_[nd.left].hi);
                const double dr = boxDistSqr(p, nodes_[nd.right].lo, nodes_[nd.right].hi);
                // Far child first: the near one is popped next
                if (dl <= dr)
                {
                    stack[top++] = {nd.right, dr};
                    stack[top++] = {nd.left, dl};
                }
                else
                {
                    stack[top++] = {nd.left, dl};
                    stack[top++] = {nd.right, dr};
                }
            }
        }
        return best;
    }

    //- Call visit(id) for every item whose box is within sqrt(r2) of p.
    template<class Visit>
    void near(const point3& p, double r2, const Visit& visit) const
    {
        if (nodes_.empty())
        {
            return;
        }
        std::vector<label> stack{0};
        while (!stack.empty())
        {
            const node& nd = nodes_[stack.back()];
            stack.pop_back();
            if (boxDistSqr(p, nd.lo, nd.hi) > r2)
            {
                continue;
            }
            if (nd.left < 0)
            {
                for (label i = nd.begin; i < nd.end; ++i)
                {
                    visit(ids_[i]);
                }
            }
            else
            {
                stack.push_back(nd.right);
                stack.push_back(nd.left);
            }
        }
    }
};

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * * Private data * * * * * * * * * * * * * * //

struct pmsh::stlGeometry::impl
{
    stlSurface surface;

    std::vector<label> region;              // per triangle
    std::vector<label> regionSolid;         // per region
    label nRegions = 0;

    std::vector<std::array<label, 2>> featureEdges;

    boxTree allTriangles;
    std::vector<boxTree> regionTriangles;   // per region

    //- Original edges between two regions, keyed by (lower, higher) region
    struct edgeSet
    {
        std::vector<std::array<label, 2>> segments;
        boxTree tree;
    };
    std::map<std::pair<label, label>, edgeSet> regionEdges;

    double diagonal = 0;

    //- An edge between two triangles of one region that meet at an angle:
    //  the radius of the surface across it.
    struct curvedEdge
    {
        label a, b;
        double radius;
    };
    std::vector<curvedEdge> curvedEdges;

    boxTree::entry triangleEntry(label t) const
    {
        const triVerts& f = surface.triangles[t];
        boxTree::entry e;
        e.id = t;
        e.lo = e.hi = surface.points[f[0]];
        for (int k = 1; k < 3; ++k)
        {
            for (int j = 0; j < 3; ++j)
            {
                e.lo[j] = std::min(e.lo[j], surface.points[f[k]][j]);
                e.hi[j] = std::max(e.hi[j], surface.points[f[k]][j]);
            }
        }
        for (int j = 0; j < 3; ++j)
        {
            e.centre[j] = 0.5*(e.lo[j] + e.hi[j]);
        }
        return e;
    }

    //- Squared distance from p to triangle t and the closest point.
    double triangleDistSqr(label t, const point3& p, point3& q) const
    {
        const triVerts& f = surface.triangles[t];
        q = closestOnTriangle
        (
            p, surface.points[f[0]], surface.points[f[1]], surface.points[f[2]]
        );
        return magSqr(p - q);
    }
};


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

pmsh::stlGeometry::stlGeometry(const std::string& fileName)
:
    fileName_(fileName),
    impl_(new impl)
{
    impl& d = *impl_;
    d.surface = readStl(fileName);
    checkStl(d.surface, fileName);

    const stlSurface& s = d.surface;
    const label nt = s.nTriangles();

    {
        point3 lo = s.points[0], hi = s.points[0];
        for (const point3& p : s.points)
        {
            for (int k = 0; k < 3; ++k)
            {
                lo[k] = std::min(lo[k], p[k]);
                hi[k] = std::max(hi[k], p[k]);
            }
        }
        d.diagonal = std::sqrt(magSqr(hi - lo));
    }

    // Unit normals
    std::vector<vector3> normal(nt);
    for (label t = 0; t < nt; ++t)
    {
        const vector3 n = s.areaNormal(t);
        normal[t] = (1/std::sqrt(magSqr(n)))*n;
    }

    // Triangle neighbours across non-feature edges, and the feature edges.
    // Edge k of triangle t is 3*t + k; each is shared by two triangles
    // (checkStl: closed and manifold)
    const double cosFeature = std::cos(featureAngle*M_PI/180.0);
    std::vector<std::array<label, 3>> smoothNeighbour(nt, {-1, -1, -1});
    std::vector<int> nSmooth(nt, 0);
    std::vector<std::array<label, 2>> featureEdgeTriangles;
    auto edgeOf = [&](matchId id)
    {
        const triVerts& f = s.triangles[id/3];
        return std::array<label, 2>{f[id % 3], f[(id + 1) % 3]};
    };
    forEachSamePointsGroup
    (
        s.points.size(), matchId(3*nt), edgeOf,
        [&](const matchId* ids, std::size_t)
        {
            const label t1 = label(ids[0]/3);
            const label t2 = label(ids[1]/3);
            const bool feature =
                s.solid[t1] != s.solid[t2]
             || dot(normal[t1], normal[t2]) < cosFeature;
            if (feature)
            {
                d.featureEdges.push_back(sortedPoints(edgeOf(ids[0])));
                featureEdgeTriangles.push_back({t1, t2});
            }
            else
            {
                smoothNeighbour[t1][nSmooth[t1]++] = t2;
                smoothNeighbour[t2][nSmooth[t2]++] = t1;

                // The radius of the circle through both centroids with
                // the normals' angle between them, measured across the
                // edge (a CAD cylinder's long facets would otherwise add
                // their axial offset)
                const double cosAngle =
                    std::max(-1.0, std::min(1.0, dot(normal[t1], normal[t2])));
                const double angle = std::acos(cosAngle);
                if (angle > 1e-6)
                {
                    const std::array<label, 2> e = edgeOf(ids[0]);
                    const vector3 along = s.points[e[1]] - s.points[e[0]];
                    const vector3 apart = s.centroid(t1) - s.centroid(t2);
                    const vector3 across =
                        apart - (dot(apart, along)/magSqr(along))*along;
                    const double radius =
                        std::sqrt(magSqr(across))/(2*std::sin(angle/2));
                    d.curvedEdges.push_back({e[0], e[1], radius});
                }
            }
        }
    );

    // Regions: flood fill across smooth edges, seeded in triangle order
    d.region.assign(nt, -1);
    std::vector<label> stack;
    for (label seed = 0; seed < nt; ++seed)
    {
        if (d.region[seed] >= 0)
        {
            continue;
        }
        const label r = d.nRegions++;
        d.regionSolid.push_back(s.solid[seed]);
        d.region[seed] = r;
        stack.push_back(seed);
        while (!stack.empty())
        {
            const label t = stack.back();
            stack.pop_back();
            for (int k = 0; k < nSmooth[t]; ++k)
            {
                const label u = smoothNeighbour[t][k];
                if (d.region[u] < 0)
                {
                    d.region[u] = r;
                    stack.push_back(u);
                }
            }
        }
    }

    // Trees over all triangles and over each region's
    {
        std::vector<boxTree::entry> all(nt);
        std::vector<std::vector<boxTree::entry>> perRegion(d.nRegions);
        for (label t = 0; t < nt; ++t)
        {
            all[t] = d.triangleEntry(t);
            perRegion[d.region[t]].push_back(all[t]);
        }
        d.allTriangles = boxTree(std::move(all));
        d.regionTriangles.resize(d.nRegions);
        for (label r = 0; r < d.nRegions; ++r)
        {
            d.regionTriangles[r] = boxTree(std::move(perRegion[r]));
        }
    }

    // Original edges between two regions (feature edges all), with a tree
    // per region pair
    for (std::size_t i = 0; i < d.featureEdges.size(); ++i)
    {
        const label r1 = d.region[featureEdgeTriangles[i][0]];
        const label r2 = d.region[featureEdgeTriangles[i][1]];
        if (r1 != r2)
        {
            d.regionEdges[{std::min(r1, r2), std::max(r1, r2)}]
                .segments.push_back(d.featureEdges[i]);
        }
    }
    for (auto& re : d.regionEdges)
    {
        std::vector<boxTree::entry> entries;
        const auto& segs = re.second.segments;
        for (std::size_t i = 0; i < segs.size(); ++i)
        {
            boxTree::entry e;
            e.id = label(i);
            const point3& a = s.points[segs[i][0]];
            const point3& b = s.points[segs[i][1]];
            for (int k = 0; k < 3; ++k)
            {
                e.lo[k] = std::min(a[k], b[k]);
                e.hi[k] = std::max(a[k], b[k]);
                e.centre[k] = 0.5*(e.lo[k] + e.hi[k]);
            }
            entries.push_back(e);
        }
        re.second.tree = boxTree(std::move(entries));
    }
}


pmsh::stlGeometry::~stlGeometry() = default;


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

const pmsh::stlSurface& pmsh::stlGeometry::surface() const
{
    return impl_->surface;
}


pmsh::label pmsh::stlGeometry::nRegions() const
{
    return impl_->nRegions;
}


const std::vector<pmsh::label>& pmsh::stlGeometry::triangleRegion() const
{
    return impl_->region;
}


const std::vector<std::array<pmsh::label, 2>>&
pmsh::stlGeometry::featureEdges() const
{
    return impl_->featureEdges;
}


pmsh::label pmsh::stlGeometry::nearestTriangle(const point3& p, point3& nearest) const
{
    const impl& d = *impl_;
    double d2;
    return d.allTriangles.nearest
    (
        p,
        [&d](label t, const point3& x, point3& q) { return d.triangleDistSqr(t, x, q); },
        nearest,
        d2
    );
}


pmsh::point3 pmsh::stlGeometry::projectToSurface(const point3& p, label s) const
{
    const impl& d = *impl_;
    if (s < 0 || s >= d.nRegions)
    {
        throw FatalError
        (
            msg()
                << "Surface " << s << " does not exist in STL geometry \""
                << fileName_ << "\": valid surfaces are 0.." << d.nRegions - 1,
            "pmsh::stlGeometry::projectToSurface"
        );
    }
    point3 q = p;
    double d2;
    d.regionTriangles[s].nearest
    (
        p,
        [&d](label t, const point3& x, point3& c) { return d.triangleDistSqr(t, x, c); },
        q,
        d2
    );
    return q;
}


pmsh::point3 pmsh::stlGeometry::projectToEdge
(
    const point3& p,
    label s1,
    label s2
) const
{
    const impl& d = *impl_;
    if (s2 < 0 || s2 >= d.nRegions)
    {
        // Throws naming the valid surfaces (s1 is checked the same way)
        return projectToSurface(p, s2);
    }
    const auto it = d.regionEdges.find({std::min(s1, s2), std::max(s1, s2)});
    if (s1 == s2 || it == d.regionEdges.end())
    {
        // The regions share no original edge (or are one): the surface is
        // the best there is
        return projectToSurface(p, s1);
    }
    const auto& segs = it->second.segments;
    const auto& pts = d.surface.points;
    point3 q = p;
    double d2;
    it->second.tree.nearest
    (
        p,
        [&segs, &pts](label i, const point3& x, point3& c)
        {
            c = closestOnSegment(x, pts[segs[i][0]], pts[segs[i][1]]);
            return magSqr(x - c);
        },
        q,
        d2
    );
    return q;
}


namespace pmsh
{
namespace
{

//- A number as the log and pmshDict write it (6 significant digits).
std::string toString(double x)
{
    std::ostringstream os;
    os << x;
    return os.str();
}


//- The sizes of one try of Netgen's STL mesher.
struct stlMeshSizes
{
    double maxh;
    double curvatureRefinement;
};


//- The configured sizes, then the retries. Measured on a curved wall of
//  radius 1 and thickness 0.002 at maxCellSize 0.3 ("boundary mesh is
//  overlapping"): curvatureRefinement 10 or maxCellSize 0.1 cure it;
//  Netgen's close-edge restriction 5x stronger with its edge-angle
//  restriction does not, and makes curvatureRefinement 10 fail too.
std::vector<ladderAttempt<stlMeshSizes>> meshAttempts(double maxh, double curvatureRefinement)
{
    std::vector<ladderAttempt<stlMeshSizes>> attempts{{{maxh, curvatureRefinement}, ""}};

    // Smaller sizes on curved faces: a chord of a curved wall sags by
    // h^2/(8 radius) = radius/(8 curvatureRefinement^2), and crosses the
    // wall's other side where that exceeds its thickness. Each retry
    // divides the sag by 9.
    double curved = curvatureRefinement;
    for (double least : {10.0, 30.0})
    {
        curved = std::max(least, 3*curved);
        attempts.push_back
        (
            {{maxh, curved}, "curvatureRefinement " + toString(curved)}
        );
    }

    // Smaller sizes everywhere, for walls or gaps thinner than the
    // triangles on flat faces too
    attempts.push_back
    (
        {
            {maxh/2, curved},
            "maxCellSize " + toString(maxh/2) + " and curvatureRefinement "
          + toString(curved)
        }
    );
    return attempts;
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * Curvature sizing  * * * * * * * * * * * * * //

pmsh::stlGeometry::curvatureSizing pmsh::stlGeometry::curvatureSizes
(
    double curvatureRefinement,
    double minCellSize,
    double maxCellSize,
    double grading
) const
{
    const impl& d = *impl_;
    const stlSurface& s = d.surface;
    const label np = label(s.points.size());

    curvatureSizing result;
    result.solids.resize(s.solidNames.size());
    if (!(curvatureRefinement > 0))
    {
        return result;
    }

    // Each point's size from the curvature across its edges: the radius
    // over curvatureRefinement, never below the floor
    std::vector<double> h(np, maxCellSize);
    std::vector<char> atFloor(np, 0);
    for (const impl::curvedEdge& e : d.curvedEdges)
    {
        const double wanted = e.radius/curvatureRefinement;
        const double size = std::max(minCellSize, wanted);
        for (label v : {e.a, e.b})
        {
            if (size < h[v])
            {
                h[v] = size;
                atFloor[v] = wanted < minCellSize;
            }
        }
    }

    // Graded over the surface as `grading` lets sizes grow (Netgen's own
    // size tree grades STL sizes at 0.3 in space whatever grading says):
    // h(v) <= h(u) + grading |uv| along the STL's edges, smallest first
    std::vector<std::vector<label>> neighbours(np);
    for (const triVerts& f : s.triangles)
    {
        for (int k = 0; k < 3; ++k)
        {
            neighbours[f[k]].push_back(f[(k + 1) % 3]);
            neighbours[f[(k + 1) % 3]].push_back(f[k]);
        }
    }
    using sizeAt = std::pair<double, label>;
    std::priority_queue<sizeAt, std::vector<sizeAt>, std::greater<sizeAt>> front;
    for (label v = 0; v < np; ++v)
    {
        if (h[v] < maxCellSize)
        {
            front.push({h[v], v});
        }
    }
    while (!front.empty())
    {
        const sizeAt top = front.top();
        front.pop();
        if (top.first > h[top.second])
        {
            continue;
        }
        for (label u : neighbours[top.second])
        {
            const double graded =
                top.first
              + grading*std::sqrt(magSqr(s.points[u] - s.points[top.second]));
            if (graded < h[u])
            {
                h[u] = graded;
                atFloor[u] = 0;
                front.push({graded, u});
            }
        }
    }

    // Netgen's size is a tree over space: a point's size binds there
    std::vector<char> counted(np, 0);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const triVerts& f = s.triangles[t];
        curvatureSizing::solidSizes& solid = result.solids[s.solid[t]];
        double mean = 0;
        for (label v : f)
        {
            mean += h[v]/3;
            if (h[v] < maxCellSize && !counted[v])
            {
                counted[v] = 1;
                result.points.push_back({s.points[v], h[v]});
                ++solid.nPoints;
                solid.nAtFloor += atFloor[v];
                solid.smallest = std::min(solid.smallest, h[v]);
            }
        }
        // Equilateral triangles of edge h cover sqrt(3)/4 h^2 each
        const double area = 0.5*std::sqrt(magSqr(s.areaNormal(t)));
        solid.faces += area*(4/std::sqrt(3.0))/(mean*mean);
        solid.uniformFaces += area*(4/std::sqrt(3.0))/(maxCellSize*maxCellSize);
    }
    return result;
}


namespace pmsh
{
namespace
{

//- The stage-1 log's account of curvature sizing: how much it asked for
//  and where, so a user sees when it made most of the coarse mesh.
void logCurvatureSizing
(
    const stlGeometry::curvatureSizing& sizing,
    const std::vector<std::string>& solidNames,
    double curvatureRefinement,
    double minCellSize
)
{
    label nPoints = 0, nAtFloor = 0;
    for (const auto& solid : sizing.solids)
    {
        nPoints += solid.nPoints;
        nAtFloor += solid.nAtFloor;
    }
    Info()
        << "    curvature sizing (curvatureRefinement "
        << toString(curvatureRefinement) << ", minCellSize "
        << toString(minCellSize) << "): " << nPoints
        << " STL points below maxCellSize, " << nAtFloor
        << " held at minCellSize\n";
    for (std::size_t i = 0; i < sizing.solids.size(); ++i)
    {
        const auto& solid = sizing.solids[i];
        if (solid.nPoints)
        {
            Info()
                << "        " << solidNames[i] << ": " << solid.nPoints
                << " points, smallest size " << toString(solid.smallest)
                << ", about " << label(std::lround(solid.faces))
                << " boundary faces at these sizes, "
                << label(std::lround(solid.uniformFaces))
                << " at maxCellSize\n";
        }
    }
}


//- Seconds an attempt of Netgen's STL coarse mesh may take by default: ten
//  times what it is expected to take, at least two minutes. Measured here
//  (2 shared cores): about 2000 coarse cells and 500 boundary faces a
//  second, and the STL's analysis at 20000 triangles a second. The cells
//  are those of the domain at maxCellSize plus ten a boundary face (the
//  grading from the surface inwards: 3119 cells for 342 faces in the
//  cylinder's box).
double defaultTimeLimit
(
    const stlSurface& surface,
    const stlGeometry::curvatureSizing& sizing,
    double maxh
)
{
    double faces = 0;
    for (const auto& solid : sizing.solids)
    {
        faces += solid.faces;
    }
    const double cells =
        std::abs(enclosedVolume(surface))/(0.118*maxh*maxh*maxh) + 10*faces;
    const double expected =
        surface.nTriangles()/20000.0 + faces/500.0 + cells/2000.0;
    return std::max(120.0, std::ceil(10*expected));
}


//- What to change when Netgen's STL mesh took too long: fewer, larger
//  coarse triangles (every retry asks for smaller ones, which take
//  longer), or more time.
std::string coarserAdvice(const coarseMeshParameters& sizes, double attemptLimit)
{
    std::string advice =
        "In system/pmshDict, if Netgen was still getting on (its progress"
        " lines above), raise coarseTimeLimit (now "
      + toString(attemptLimit) + " s an attempt); else ask for fewer coarse"
        " triangles: maxCellSize " + toString(2*sizes.maxCellSize)
      + " (now " + toString(sizes.maxCellSize) + ")";
    if (sizes.curvatureRefinement > 0)
    {
        advice +=
            ", minCellSize " + toString(2*sizes.minCellSize) + " (now "
          + toString(sizes.minCellSize) + ") or curvatureRefinement 0 (now "
          + toString(sizes.curvatureRefinement) + ")";
    }
    return advice + "; or simplify the STL";
}


//- Netgen's coarse mesh of the STL surface, retried with smaller sizes
//  while Netgen's meshing steps fail, each attempt and all of them within
//  a time limit.
ng::volumeMesh retriedStlMesh
(
    const stlGeometry& geometry,
    const ng::meshParameters& configured,
    const coarseMeshParameters& sizes,
    const std::string& fileName
)
{
    const std::string what = "STL file \"" + fileName + "\"";
    const stlSurface& surface = geometry.surface();
    const std::vector<ladderAttempt<stlMeshSizes>> attempts =
        meshAttempts(sizes.maxCellSize, sizes.curvatureRefinement);

    // A surface Netgen cannot mesh well can keep it busy for tens of
    // minutes (a ship's hull: 25 at "Surface meshing, 99%")
    const double attemptLimit =
        sizes.coarseTimeLimit > 0
      ? sizes.coarseTimeLimit
      : defaultTimeLimit
        (
            surface,
            geometry.curvatureSizes
            (
                sizes.curvatureRefinement, sizes.minCellSize, sizes.maxCellSize,
                sizes.grading
            ),
            sizes.maxCellSize
        );
    const double ladderLimit = 2*attemptLimit;
    Info()
        << "    time limit: " << toString(attemptLimit) << " s an attempt, "
        << toString(ladderLimit) << " s for all (coarseTimeLimit"
        << (sizes.coarseTimeLimit > 0 ? "" : ", from the surface's size")
        << ")\n";
    const auto start = std::chrono::steady_clock::now();

    // Netgen's STL mesher fails on some valid surfaces where its triangles
    // are too large for the geometry, e.g. "boundary mesh is overlapping"
    // on a thin curved wall: each retry asks for smaller ones
    double remaining = ladderLimit;
    const auto withinLadderLimit = [&](std::size_t)
    {
        remaining = ladderLimit - std::chrono::duration<double>
        (
            std::chrono::steady_clock::now() - start
        ).count();
        return remaining > 0;
    };
    ladderFailures failed;
    std::optional<ng::volumeMesh> meshed = climbLadder
    (
        attempts,
        [&](const ladderAttempt<stlMeshSizes>& attempt, std::size_t i)
        {
            const stlMeshSizes& sizesTried = attempt.parameters;

            // Curvature sizes are pmshFoam's, not Netgen's (resthsurfcurvfac):
            // Netgen's have no floor and follow no grading
            const stlGeometry::curvatureSizing curvature = geometry.curvatureSizes
            (
                sizesTried.curvatureRefinement, sizes.minCellSize,
                sizesTried.maxh, sizes.grading
            );
            ng::meshParameters parameters = configured;
            parameters.maxh = sizesTried.maxh;
            parameters.timeLimit = std::min(attemptLimit, remaining);
            parameters.sizePoints.insert
            (
                parameters.sizePoints.end(),
                curvature.points.begin(), curvature.points.end()
            );
            try
            {
                ng::volumeMesh m = ng::stlVolumeMesh
                (
                    surface.points, surface.triangles, geometry.featureEdges(),
                    parameters, what
                );
                if (i > 0)
                {
                    Info()
                        << "    Netgen's STL mesh succeeded at attempt " << i + 1
                        << " (" << attempt.change << ")\n";
                }
                if (sizesTried.curvatureRefinement > 0)
                {
                    logCurvatureSizing
                    (
                        curvature, surface.solidNames,
                        sizesTried.curvatureRefinement, sizes.minCellSize
                    );
                }
                return m;
            }
            catch (const ng::stlMeshingTimeout& e)
            {
                // Every later attempt asks for smaller triangles: it would
                // take longer still
                throw attemptFailed{e.reason(), true};
            }
            catch (const ng::stlMeshingFailure& e)
            {
                if (i + 1 < attempts.size())
                {
                    Info()
                        << "    Netgen's STL mesh failed (" << e.reason()
                        << "); retrying with " << attempts[i + 1].change << '\n';
                }
                throw attemptFailed{e.reason()};
            }
        },
        failed,
        withinLadderLimit
    );
    if (meshed)
    {
        return std::move(*meshed);
    }

    const std::vector<std::string>& reasons = failed.reasons;
    const std::size_t nTried = failed.nTried();
    msg message;
    message
        << "Netgen could not mesh " << what << " in " << nTried
        << (nTried == 1 ? " attempt" : " attempts")
        << (nTried < attempts.size() ? " of " + std::to_string(attempts.size()) : "")
        << ":";
    for (std::size_t i = 0; i < nTried; ++i)
    {
        message
            << "\n    " << i + 1 << " ("
            << (i == 0 ? "as configured" : attempts[i].change) << "): "
            << reasons[i];
    }
    if (failed.stopped)
    {
        message
            << "\nEvery further attempt asks for smaller triangles and would"
            << " take longer: none was made. "
            << coarserAdvice(sizes, attemptLimit) << '.';
        throw FatalError(message, "pmsh::stlGeometry::netgenMesh");
    }

    const stlMeshSizes& last = attempts[nTried - 1].parameters;
    if (nTried < attempts.size())
    {
        message
            << "\nThe attempts together reached their time limit of "
            << toString(ladderLimit) << " s (twice coarseTimeLimit) before "
            << attempts[nTried].change << " could be tried.";
    }
    message
        << "\nNetgen's triangles are too large for some part of the surface"
        << " (often a wall thinner than the sag of its triangles on a curved"
        << " face, or two surfaces closer than maxCellSize). In system/pmshDict"
        << " set maxCellSize " << toString(last.maxh/2) << " (or smaller), or"
        << " curvatureRefinement " << toString(2*last.curvatureRefinement)
        << " with a smaller minCellSize (now " << toString(sizes.minCellSize)
        << "), or give the thin part's patch a smaller maxCellSize in"
        << " patches; also check the STL for self-intersections.";
    if (nTried < attempts.size())
    {
        message
            << " Each of these takes longer: raise coarseTimeLimit (now "
            << toString(attemptLimit) << " s) with it.";
    }
    throw FatalError(message, "pmsh::stlGeometry::netgenMesh");
}

} // End anonymous namespace
} // End namespace pmsh


pmsh::CoarseMesh pmsh::stlGeometry::netgenMesh
(
    const coarseMeshParameters& parameters,
    bool surfaceOnly
) const
{
    const char* function = "pmsh::stlGeometry::netgenMesh";
    const impl& d = *impl_;

    if (!(parameters.maxCellSize > 0))
    {
        throw FatalError
        (
            msg()
                << "maxCellSize " << parameters.maxCellSize << " for STL"
                << " geometry \"" << fileName_ << "\" must be positive",
            function
        );
    }

    ng::meshParameters mp;
    mp.grading = parameters.grading;
    mp.surfaceOnly = surfaceOnly;
    mp.regions = parameters.regions;
    mp.sizePoints = parameters.sizePoints;
    ng::volumeMesh m = retriedStlMesh(*this, mp, parameters, fileName_);

    // Netgen's boundary vertices lie on the STL up to rounding; a vertex is
    // "on" a region within this distance
    const double tol = 1e-8*d.diagonal;
    const double tol2 = tol*tol;

    // Regions within tol of a point (sorted, unique)
    auto regionsAt = [&d, tol2](const point3& p)
    {
        std::vector<label> r;
        d.allTriangles.near
        (
            p, tol2,
            [&](label t)
            {
                point3 q;
                if (d.triangleDistSqr(t, p, q) <= tol2)
                {
                    r.push_back(d.region[t]);
                }
            }
        );
        std::sort(r.begin(), r.end());
        r.erase(std::unique(r.begin(), r.end()), r.end());
        return r;
    };

    // Regions of every boundary point, computed once
    std::vector<std::vector<label>> pointRegions(m.points.size());
    std::vector<bool> done(m.points.size(), false);

    CoarseMesh coarse;
    coarse.boundary.reserve(m.boundary.size());
    label nOff = 0;
    double maxOff = 0;
    for (const ng::boundaryTriangle& b : m.boundary)
    {
        std::vector<label> common;
        for (int k = 0; k < 3; ++k)
        {
            const label v = b.v[k];
            if (!done[v])
            {
                pointRegions[v] = regionsAt(m.points[v]);
                done[v] = true;
            }
            if (k == 0)
            {
                common = pointRegions[v];
            }
            else
            {
                std::vector<label> c;
                std::set_intersection
                (
                    common.begin(), common.end(),
                    pointRegions[v].begin(), pointRegions[v].end(),
                    std::back_inserter(c)
                );
                common.swap(c);
            }
        }

        const point3 c = (1.0/3.0)
          * (m.points[b.v[0]] + m.points[b.v[1]] + m.points[b.v[2]]);

        label r = -1;
        if (common.size() == 1)
        {
            r = common[0];
        }
        else if (common.size() > 1)
        {
            // All three vertices on region boundaries: the region nearest
            // to the centroid (ties to the lower region)
            double best = std::numeric_limits<double>::infinity();
            for (label cr : common)
            {
                double d2;
                point3 q;
                d.regionTriangles[cr].nearest
                (
                    c,
                    [&d](label t, const point3& x, point3& y) { return d.triangleDistSqr(t, x, y); },
                    q,
                    d2
                );
                if (d2 < best)
                {
                    best = d2;
                    r = cr;
                }
            }
        }
        else
        {
            // No region holds all three vertices: Netgen's face crosses a
            // feature edge (or a vertex is off the STL)
            ++nOff;
            point3 q;
            r = d.region[nearestTriangle(c, q)];
            for (label v : b.v)
            {
                nearestTriangle(m.points[v], q);
                maxOff = std::max(maxOff, std::sqrt(magSqr(q - m.points[v])));
            }
        }

        coarse.boundary.push_back({b.v, d.regionSolid[r], r});
    }

    if (nOff)
    {
        throw FatalError
        (
            msg()
                << "Netgen's coarse mesh of STL file \"" << fileName_
                << "\" does not follow its feature edges: " << nOff
                << " boundary face(s) have vertices on different surfaces"
                << " (separated by edges sharper than " << featureAngle
                << " degrees or between solids), or off the STL (largest"
                << " distance of their vertices from the STL " << maxOff
                << ", tolerance " << tol << ").\nTry a smaller maxCellSize"
                << " (now " << parameters.maxCellSize << ")",
            function
        );
    }

    coarse.points = std::move(m.points);
    coarse.tets = std::move(m.tets);
    for (const std::string& name : d.surface.solidNames)
    {
        coarse.patches.push_back({name});
    }

    return coarse;
}


// ************************************************************************* //
