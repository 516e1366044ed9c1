/*---------------------------------------------------------------------------*\
  pmshFoam: the coarse surface remeshed by CGAL (see surfaceRemesh.H).
\*---------------------------------------------------------------------------*/

#include "surfaceRemesh.H"
#include "cgalSurface.H"
#include "boxTree.H"
#include "triangleGeometry.H"
#include "pmshError.H"

#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <iterator>
#include <map>
#include <numeric>
#include <stdexcept>

namespace pmsh
{
namespace
{

using cgal::Mesh;
using cgal::toCgal;
using cgal::toPoint3;
using Face = Mesh::Face_index;
namespace PMP = CGAL::Polygon_mesh_processing;

//- Relaxation steps of each remeshing (CGAL's default is 1): 3 gave the
//  motorBike's wrap its coarse surface in 0.4 s, and rounder triangles.
constexpr unsigned remeshIterations = 3;

//- A coarse edge whose midpoint lies farther than this fraction of its
//  length from the surface spans a thin part or a sharp bend: stage 3
//  would project the midpoint across (the DTC hull's bow at 0.31).
constexpr double foldingSag = 0.25;


//- The shells of s (connected by shared points: the surface checks have
//  made sure shells neither touch nor cross), as lists of triangles.
std::vector<std::vector<label>> shellsOf(const stlSurface& s)
{
    std::vector<label> parent(s.points.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto root = [&](label p)
    {
        while (parent[p] != p)
        {
            p = parent[p] = parent[parent[p]];
        }
        return p;
    };
    for (const triVerts& t : s.triangles)
    {
        parent[root(t[1])] = root(t[0]);
        parent[root(t[2])] = root(t[0]);
    }
    std::map<label, label> shellOfRoot;
    std::vector<std::vector<label>> shells;
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        const auto it = shellOfRoot.emplace(root(s.triangles[t][0]), label(shells.size())).first;
        if (it->second == label(shells.size()))
        {
            shells.emplace_back();
        }
        shells[it->second].push_back(t);
    }
    return shells;
}


//- The coarse triangles of one shell, with each one's region and size.
struct remeshedShell
{
    std::vector<point3> points;
    std::vector<triVerts> triangles;
    std::vector<label> region;
    std::vector<double> size;
    label nBordersHeld = 0;         //!< sizes remeshed again, border held
    label nGradedBands = 0;         //!< gradeSizeBorders' bands
};


//- A triangle whose area is below this fraction of its longest edge
//  squared is flat: its three points (nearly) on a line.
constexpr double flatTriangle = 1e-6;

//- A triangle whose largest angle is above 160 degrees is a cap: a point
//  near the middle of its longest edge. The remeshing leaves them where
//  sizes change and along patch borders (the motorBike's wrap at 0.0156,
//  remeshed at 0.0625: 31 caps of up to 179.5 degrees), and stage 3
//  refines each into caps, on which the volume meshers put tets of faces
//  at up to 89.7 degrees from orthogonal.
constexpr double capCos = -0.9396926;   // cos(160 degrees)

//- Sweeps of a flip pass at most
constexpr int maxFlipSweeps = 10;


//- flipSweep() (one pass over the mesh, returning how many edges it
//  flipped) again until it flips none, at most maxFlipSweeps times: a flip
//  can leave a triangle next door to flip
template<class FlipSweep>
void sweepUntilNoneFlips(const FlipSweep& flipSweep)
{
    for (int sweep = 0; sweep < maxFlipSweeps; ++sweep)
    {
        if (flipSweep() == 0)
        {
            break;
        }
    }
}


//- Whether the flips may flip the edge of h: it lies between two
//  triangles of one region (of one size or two: the border of a
//  refinement region on the floor is no edge of the geometry), it is no
//  feature, and the edge the flip makes is not there already
template<class PatchMap, class EdgeMap>
bool flippableWithinRegion
(
    const Mesh& m,
    const Mesh::Halfedge_index h,
    const PatchMap& patch,
    const std::vector<label>& patchRegion,
    const EdgeMap& constrained
)
{
    const auto o = m.opposite(h);
    return !m.is_border(m.edge(h))
        && patchRegion[patch[m.face(h)]] == patchRegion[patch[m.face(o)]]
        && !constrained[m.edge(h)]
        && !CGAL::halfedge(m.target(m.next(h)), m.target(m.next(o)), m).second;
}


//- Whether flipping edge (a, b) of triangles (a, b, c) and (b, a, d)
//  makes the worse of the two better, with neither new triangle, (a, d, c)
//  and (d, b, c), turned against the old pair
bool flipImproves(const point3& a, const point3& b, const point3& c, const point3& d)
{
    const vector3 normal = cross(b - a, c - a) + cross(a - b, d - b);
    if (!(dot(cross(d - a, c - a), normal) > 0 && dot(cross(b - d, c - d), normal) > 0))
    {
        return false;
    }
    return std::min(triangleShapeQuality(a, d, c), triangleShapeQuality(d, b, c))
         > std::min(triangleShapeQuality(a, b, c), triangleShapeQuality(b, a, d));
}


//- Flip the longest edge of every flat triangle, and of every cap where
//  that makes the pair better, where both its triangles lie in one region
//  (of one size or two: the border of a refinement region on the floor
//  is no edge of the geometry, and OpenFOAM's motorBike had caps of 177
//  degrees along it, whose tets made potentialFoam's velocity 1e7) and
//  the edge is no feature. Isotropic remeshing can leave a triangle
//  whose third point is its longest edge's midpoint (the motorBike's wrap
//  at 0.05, after a round of halving: two), and neither HXT nor Netgen
//  fills a surface with one (HXT: a flat tet of aspect ratio 1e10, each
//  attempt; Netgen: minutes in RemoveIllegalElements).
template<class PatchMap, class EdgeMap>
void flipDegenerateTriangles
(
    Mesh& m,
    const PatchMap& patch,
    const std::vector<label>& patchRegion,
    const EdgeMap& constrained
)
{
    // A cap's flip makes its pair's worse triangle better, so the sweeps end
    sweepUntilNoneFlips([&]()
    {
        label nFlipped = 0;
        for (const Face f : m.faces())
        {
            Mesh::Halfedge_index longest;
            double longest2 = 0;
            for (const auto h : CGAL::halfedges_around_face(m.halfedge(f), m))
            {
                const double l2 = CGAL::to_double
                (
                    CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)))
                );
                if (l2 > longest2)
                {
                    longest2 = l2;
                    longest = h;
                }
            }
            const point3 a = toPoint3(m.point(m.source(longest)));
            const point3 b = toPoint3(m.point(m.target(longest)));
            const point3 c = toPoint3(m.point(m.target(m.next(longest))));
            const double area = 0.5*std::sqrt(magSqr(cross(b - a, c - a)));
            const bool flat = area < flatTriangle*longest2;
            const bool cap =
                dot(a - c, b - c) < capCos*std::sqrt(magSqr(a - c)*magSqr(b - c));
            if (!flat && !cap)
            {
                continue;
            }
            const auto otherApex = m.target(m.next(m.opposite(longest)));
            if
            (
                flippableWithinRegion(m, longest, patch, patchRegion, constrained)
             && (flat || flipImproves(a, b, c, toPoint3(m.point(otherApex))))
            )
            {
                CGAL::Euler::flip_edge(longest, m);
                ++nFlipped;
            }
        }
        return nFlipped;
    });
}


//- Two triangles sharing an edge are coplanar when their normals are
//  within 0.1 degrees: a side of the domain box, a plinth's wall, a CAD
//  body's flat face. A curved surface's triangles at the coarse sizes are
//  degrees apart, and are left as the remesher made them.
constexpr double coplanarCos = 0.9999985;   // cos(0.1 degrees)

//- Lawson's Delaunay flips on the flat parts of one region: the edge
//  between two coplanar triangles is flipped where the angles opposite it
//  add up to more than 180 degrees (and 0.06 more, so that points on one
//  circle do not flip back and forth). The remesher keeps the border of
//  every size it meshes at, and leaves obtuse triangles along those
//  borders; the side faces of a prism layer on them are as far from
//  orthogonal as the triangles are obtuse (OpenFOAM's motorBike with a
//  layer on its floor: 155 faces above 70 degrees, all on the floor).
template<class PatchMap, class EdgeMap>
void delaunayFlipFlatParts
(
    Mesh& m,
    const PatchMap& patch,
    const std::vector<label>& patchRegion,
    const EdgeMap& constrained
)
{
    const double delaunayTolerance = 1e-3;
    const auto angle = [](const vector3& u, const vector3& v)
    {
        return std::atan2(std::sqrt(magSqr(cross(u, v))), dot(u, v));
    };
    sweepUntilNoneFlips([&]()
    {
        label nFlipped = 0;
        for (const auto e : m.edges())
        {
            const auto h = m.halfedge(e);
            if (!flippableWithinRegion(m, h, patch, patchRegion, constrained))
            {
                continue;
            }
            const point3 a = toPoint3(m.point(m.source(h)));
            const point3 b = toPoint3(m.point(m.target(h)));
            const point3 c = toPoint3(m.point(m.target(m.next(h))));
            const point3 d = toPoint3(m.point(m.target(m.next(m.opposite(h)))));
            const vector3 n1 = cross(b - a, c - a);
            const vector3 n2 = cross(a - b, d - b);
            if
            (
                dot(n1, n2) >= coplanarCos*std::sqrt(magSqr(n1)*magSqr(n2))
             && angle(a - c, b - c) + angle(a - d, b - d) > M_PI + delaunayTolerance
            )
            {
                CGAL::Euler::flip_edge(h, m);
                ++nFlipped;
            }
        }
        return nFlipped;
    });
}


//- The faces of the patches of size h remeshed at h; the others, and the
//  feature edges, kept. The points on the border with the finer sizes,
//  remeshed before, are held where that border is no feature: CGAL
//  collapses edges along the border of the faces it remeshes up to their
//  size, so a coarser size took such a border (a refinement box's on the
//  floor) back to its own spacing, and left the finer triangles along it
//  with one long edge each (gradeSizeBorders then grades from it). A
//  feature's points are left free: a plinth's foot on the floor comes
//  with segments of 0.0005, which held made floor triangles of 160
//  degrees.
//
//  Whether the border with the coarser sizes had to be held as well:
//  CGAL 5.5's remesher, when a collapse leaves a face whose points are
//  exactly on a line, flips that face's longest edge even where it is
//  the border of the faces it remeshes (fix_degenerate_faces checks no
//  status), so a face outside them gets an edge inside; check_normals
//  then asks for that face's patch, which it never listed, and throws
//  std::out_of_range ("map::at"). Exactly collinear points come from the
//  domain box's sides, whose edges along the axes split into points on
//  one line: OpenFOAM's motorBike with the tutorial's refinementBox
//  (0.0625 fine) stopped so on its floor. The same size is then remeshed
//  again from before, with its whole border held, so that no collapse
//  reaches it.
bool remeshAtSize
(
    Mesh& m,
    const double h,
    const std::vector<double>& patchSize,
    Mesh::Property_map<Face, std::size_t>& patch,
    Mesh::Property_map<Mesh::Edge_index, bool>& constrained
)
{
    const auto remesh = [&](const bool wholeBorder)
    {
        // held: the points remeshing may not move
        auto held = m.add_property_map<Mesh::Vertex_index, bool>("v:held", false).first;
        for (const auto e : m.edges())
        {
            const double size0 = patchSize[patch[m.face(m.halfedge(e, 0))]];
            const double size1 = patchSize[patch[m.face(m.halfedge(e, 1))]];
            if
            (
                (size0 == h) != (size1 == h)
             && (wholeBorder || (std::min(size0, size1) < h && !constrained[e]))
            )
            {
                held[m.vertex(e, 0)] = true;
                held[m.vertex(e, 1)] = true;
            }
        }
        std::vector<Face> faces;
        for (const Face f : m.faces())
        {
            if (patchSize[patch[f]] == h) faces.push_back(f);
        }
        PMP::isotropic_remeshing
        (
            faces, h, m,
            PMP::parameters::number_of_iterations(remeshIterations)
           .edge_is_constrained_map(constrained)
           .vertex_is_constrained_map(held)
           .face_patch_map(patch)
        );
        m.remove_property_map(held);
    };
    const Mesh before(m);
    try
    {
        remesh(false);
        return false;
    }
    catch (const std::out_of_range&)
    {}

    // A copy's property maps are its own
    m = before;
    patch = m.property_map<Face, std::size_t>("f:patch").first;
    constrained = m.property_map<Mesh::Edge_index, bool>("e:feature").first;
    try
    {
        remesh(true);
    }
    catch (const std::out_of_range&)
    {
        throw FatalError
        (
            msg()
                << "CGAL's isotropic remeshing failed on the coarse surface's"
                << " triangles of size " << h << ", with their border held"
                << " as well (a face whose points are exactly on a line,"
                << " by the border of that size).\nIn system/pmshDict change"
                << " that maxCellSize a little, or set coarseSurface netgen",
            "pmsh::remeshSurface"
        );
    }
    return true;
}


//- Rounds of grading at most: each halves the jump of size at a border
constexpr int maxGradingRounds = 8;

//- Where a size meets one more than twice finer (a refinement box's
//  border on the floor: 0.125 against 1), the triangles of the coarser
//  size that touch the border are remeshed at twice the finer size, and
//  so on outwards, round after round, until no size meets one more than
//  twice finer. CGAL's remesher has one size a call: next to a border of
//  points eight times closer than its size, it leaves triangles with one
//  short edge on the border and long ones away from it, up to 160
//  degrees, and no flip can mend them, the points are not there. The
//  side faces of a prism layer on such triangles are as far from
//  orthogonal as they are obtuse: OpenFOAM's motorBike with its
//  refinementBox at the tutorial's level 4 had floor prisms' faces at 86
//  degrees, and simpleFoam blew up by them. The new sizes are patches
//  of their triangles' regions. Returns the bands remeshed.
label gradeSizeBorders
(
    Mesh& m,
    std::vector<double>& patchSize,
    std::vector<label>& patchRegion,
    Mesh::Property_map<Face, std::size_t>& patch,
    Mesh::Property_map<Mesh::Edge_index, bool>& constrained,
    label& nBordersHeld
)
{
    std::map<std::pair<label, double>, std::size_t> patchOf;
    for (std::size_t i = 0; i < patchSize.size(); ++i)
    {
        patchOf.emplace(std::make_pair(patchRegion[i], patchSize[i]), i);
    }
    label nBands = 0;
    for (int round = 0; round < maxGradingRounds; ++round)
    {
        // The finest size round each point
        auto finest = m.add_property_map<Mesh::Vertex_index, double>("v:finest", 0).first;
        for (const auto v : m.vertices())
        {
            double size = std::numeric_limits<double>::max();
            for (const Face f : CGAL::faces_around_target(m.halfedge(v), m))
            {
                if (f != Mesh::null_face()) size = std::min(size, patchSize[patch[f]]);
            }
            finest[v] = size;
        }
        std::set<double> bandSizes;
        std::map<Face, std::size_t> bandOrigin;
        for (const Face f : m.faces())
        {
            double near = std::numeric_limits<double>::max();
            for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m))
            {
                near = std::min(near, finest[v]);
            }
            const double size = patchSize[patch[f]];
            // 1.01: sizes of one grading, twice one another, are no jump
            if (size > 2.01*near)
            {
                const auto key = std::make_pair(patchRegion[patch[f]], 2*near);
                const auto it = patchOf.emplace(key, patchSize.size()).first;
                if (it->second == patchSize.size())
                {
                    patchSize.push_back(key.second);
                    patchRegion.push_back(key.first);
                }
                bandOrigin[f] = patch[f];
                patch[f] = it->second;
                bandSizes.insert(key.second);
            }
        }
        m.remove_property_map(finest);
        if (bandSizes.empty())
        {
            break;
        }
        // A band CGAL fails on even with its border held (exactly
        // collinear points, as remeshAtSize says; the motorBike's floor at
        // level 4 had one) is left as it was, and the grading ends there:
        // the surface is valid without it
        const Mesh before(m);
        try
        {
            for (const double h : bandSizes)
            {
                nBordersHeld += remeshAtSize(m, h, patchSize, patch, constrained);
            }
        }
        catch (const FatalError&)
        {
            m = before;
            patch = m.property_map<Face, std::size_t>("f:patch").first;
            constrained = m.property_map<Mesh::Edge_index, bool>("e:feature").first;
            for (const auto& fp : bandOrigin)
            {
                patch[fp.first] = fp.second;
            }
            break;
        }
        nBands += label(bandSizes.size());
    }
    return nBands;
}


//- One shell's triangles remeshed at their sizes, from the input itself.
//  Each (region, size) pair is a patch whose borders CGAL keeps, so every
//  coarse triangle knows its region and size. One CGAL mesh a shell: CGAL
//  5.5 takes a face range with no border (a whole shell) for the whole
//  mesh and projects every other shell's points onto it (remesh_impl.h,
//  is_on_patch: "if (!has_border_) return true"); a ball in a box lost its
//  box so.
remeshedShell remeshShell
(
    const stlSurface& s,
    const std::vector<label>& shell,
    const std::vector<label>& region,
    const std::vector<std::array<label, 2>>& featureEdges,
    const std::vector<double>& size
)
{
    Mesh m;
    std::map<label, Mesh::Vertex_index> vertex;
    for (const label t : shell)
    {
        for (const label p : s.triangles[t])
        {
            if (!vertex.count(p))
            {
                const point3& x = s.points[p];
                vertex[p] = m.add_vertex(toCgal(x));
            }
        }
    }

    std::map<std::pair<label, double>, std::size_t> patchOf;
    std::vector<double> patchSize;
    std::vector<label> patchRegion;
    auto patch = m.add_property_map<Face, std::size_t>("f:patch", 0).first;
    for (const label t : shell)
    {
        const triVerts& f = s.triangles[t];
        // The surface checks have made it a closed 2-manifold
        const Face face = m.add_face(vertex[f[0]], vertex[f[1]], vertex[f[2]]);
        const auto it = patchOf.emplace(std::make_pair(region[t], size[t]), patchSize.size()).first;
        if (it->second == patchSize.size())
        {
            patchSize.push_back(size[t]);
            patchRegion.push_back(region[t]);
        }
        patch[face] = it->second;
    }

    auto constrained = m.add_property_map<Mesh::Edge_index, bool>("e:feature", false).first;
    for (const auto& e : featureEdges)
    {
        const auto a = vertex.find(e[0]), b = vertex.find(e[1]);
        if (a == vertex.end() || b == vertex.end()) continue;
        const auto h = CGAL::halfedge(a->second, b->second, m);
        if (h.second)
        {
            constrained[m.edge(h.first)] = true;
        }
    }

    // The finest sizes first: the coarser patches' borders then follow them
    std::vector<double> sizes(patchSize);
    std::sort(sizes.begin(), sizes.end());
    sizes.erase(std::unique(sizes.begin(), sizes.end()), sizes.end());
    label nBordersHeld = 0;
    for (const double h : sizes)
    {
        nBordersHeld += remeshAtSize(m, h, patchSize, patch, constrained);
    }
    const label nGradedBands =
        gradeSizeBorders(m, patchSize, patchRegion, patch, constrained, nBordersHeld);
    flipDegenerateTriangles(m, patch, patchRegion, constrained);
    delaunayFlipFlatParts(m, patch, patchRegion, constrained);
    m.collect_garbage();

    remeshedShell r;
    for (const auto v : m.vertices())
    {
        r.points.push_back(toPoint3(m.point(v)));
    }
    for (const Face f : m.faces())
    {
        r.triangles.push_back(cgal::triangleOf(m, f));
        r.region.push_back(patchRegion[patch[f]]);
        r.size.push_back(patchSize[patch[f]]);
    }
    r.nBordersHeld = nBordersHeld;
    r.nGradedBands = nGradedBands;
    return r;
}


//- The pairs of triangles that cross (CGAL's exact predicates), as
//  indices into `triangles`.
std::vector<std::pair<label, label>> crossingPairs
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles
)
{
    Mesh m;
    for (const point3& x : points)
    {
        m.add_vertex(toCgal(x));
    }
    for (const triVerts& t : triangles)
    {
        m.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
    }
    std::vector<std::pair<Face, Face>> crossing;
    PMP::self_intersections(m.faces(), m, std::back_inserter(crossing));
    std::vector<std::pair<label, label>> pairs;
    for (const auto& [a, b] : crossing)
    {
        pairs.push_back({label(a), label(b)});
    }
    return pairs;
}


} // End anonymous namespace
} // End namespace pmsh


pmsh::remeshedTriangulation pmsh::remeshSurface
(
    const stlSurface& s,
    const boxTree& inputTriangles,
    const std::vector<label>& region,
    const std::vector<std::array<label, 2>>& featureEdges,
    const std::vector<double>& triangleSize,
    const double sagFraction,
    const double minSize,
    const std::string& what
)
{
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::vector<label>> shells = shellsOf(s);

    std::vector<double> size(triangleSize);
    std::vector<bool> refined(size.size(), false);
    remeshedTriangulation result;
    std::vector<double> coarseSize;
    for (label round = 1; ; ++round)
    {
        result = remeshedTriangulation();
        coarseSize.clear();
        for (const std::vector<label>& shell : shells)
        {
            const remeshedShell r = remeshShell(s, shell, region, featureEdges, size);
            const label offset = label(result.points.size());
            result.points.insert(result.points.end(), r.points.begin(), r.points.end());
            for (const triVerts& t : r.triangles)
            {
                result.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
            }
            result.region.insert(result.region.end(), r.region.begin(), r.region.end());
            coarseSize.insert(coarseSize.end(), r.size.begin(), r.size.end());
            result.nBordersHeld += r.nBordersHeld;
            result.nGradedBands += r.nGradedBands;
        }
        result.nRounds = round;

        // Where a coarse edge's midpoint lies farther from the surface than
        // sagFraction of the edge (a curved or thin part), and round every
        // crossing, the input triangles get half the size
        std::vector<std::pair<label, double>> tooLarge;     // coarse triangle, new size
        for (label c = 0; c < label(result.triangles.size()); ++c)
        {
            const double h = coarseSize[c];
            // Curvature sizing stops at minSize; a midpoint a quarter of
            // its edge away is no curvature but a chord across a thin part
            // or a sharp bend, where stage 3 would fold the surface: always
            const double curved = h/2 >= minSize ? sagFraction : 0;
            const triVerts& t = result.triangles[c];
            for (int k = 0; k < 3; ++k)
            {
                const point3& a = result.points[t[k]];
                const point3& b = result.points[t[(k + 1) % 3]];
                const point3 mid = 0.5*(a + b);
                point3 q;
                double d2;
                inputTriangles.nearest
                (
                    mid,
                    [&s](label i, const point3& x, point3& y) { return triangleDistSqr(s, i, x, y); },
                    q, d2
                );
                const double limit = curved > 0 ? std::min(curved, foldingSag) : foldingSag;
                if (d2 > limit*limit*magSqr(b - a))
                {
                    tooLarge.push_back({c, h/2});
                    break;
                }
            }
        }
        const std::vector<std::pair<label, label>> crossing =
            crossingPairs(result.points, result.triangles);
        for (const auto& pair : crossing)
        {
            tooLarge.push_back({pair.first, coarseSize[pair.first]/2});
            tooLarge.push_back({pair.second, coarseSize[pair.second]/2});
        }
        if (tooLarge.empty())
        {
            break;
        }
        if (round == maxRemeshRounds)
        {
            if (crossing.empty())
            {
                // Sagging edges are only coarser than asked for
                break;
            }
            const triVerts& t = result.triangles[crossing.front().first];
            const point3 where = (1.0/3.0)
              * (result.points[t[0]] + result.points[t[1]] + result.points[t[2]]);
            throw FatalError
            (
                msg()
                    << "The coarse surface remeshed from " << what << " still"
                    << " crosses itself after " << round << " rounds, each"
                    << " halving the size round the crossings: "
                    << crossing.size() << " pair(s) of triangles, one near ("
                    << where[0] << ' ' << where[1] << ' ' << where[2] << ").\n"
                    << "The surface has parts thinner than its smallest"
                    << " triangles there. In system/pmshDict give that patch a"
                    << " smaller maxCellSize, or set coarseSurface netgen;"
                    << " where the bodies were wrapped, a larger wrapOffset"
                    << " makes the thin parts thicker",
                "pmsh::remeshSurface"
            );
        }

        // The input triangles within two sizes of such a coarse triangle
        for (const auto& [c, h] : tooLarge)
        {
            const triVerts& t = result.triangles[c];
            const point3 centre = (1.0/3.0)
              * (result.points[t[0]] + result.points[t[1]] + result.points[t[2]]);
            const double r2 = 16*h*h;
            inputTriangles.near
            (
                centre, r2,
                [&](label i)
                {
                    point3 q;
                    if (triangleDistSqr(s, i, centre, q) <= r2 && size[i] > h)
                    {
                        size[i] = h;
                        refined[i] = true;
                    }
                }
            );
        }
    }
    result.nRefined = label(std::count(refined.begin(), refined.end(), true));
    result.seconds = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    return result;
}


// ************************************************************************* //
