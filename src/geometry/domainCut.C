/*---------------------------------------------------------------------------*\
  pmshFoam: bodies that reach the domain box, cut by it (see domainCut.H).
\*---------------------------------------------------------------------------*/

#include "domainCut.H"
#include "cgalSurface.H"
#include "pmshError.H"
#include "surfaceBuilder.H"

#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/boost/graph/Euler_operations.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <unordered_set>
#include <vector>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

using Mesh = pmsh::cgal::Mesh;
using pmsh::cgal::toCgal;
namespace PMP = CGAL::Polygon_mesh_processing;


//- Squares a side's shortest edge is split into (the longest edge into no
//  more than longestSquares): the cut fans a side's triangles out from
//  their corners to the bodies' footprints, and the remesher sizes and
//  halves each input triangle whole, so a triangle across a large part of
//  a side carries the footprint's size over it. OpenFOAM's motorBike on
//  its floor (r = 1): with two triangles a side the coarse surface took
//  624 s; with 8 squares across the floor 612k cells, 1,444 faces above
//  70 degrees along the squares' edges round the tyres; with 32 squares
//  360k cells (as with the floor below the tyres) and 170, at the tyres.
constexpr int squaresAcrossSide = 32;
constexpr int longestSquares = 256;


//- The number of squares along each edge of the domain box's sides.
std::array<int, 3> squaresAlongEdges(const pmsh::point3& min, const pmsh::point3& max)
{
    using namespace pmsh;
    const vector3 extent = max - min;
    const double spacing = std::max
    (
        std::min({extent[0], extent[1], extent[2]})/squaresAcrossSide,
        std::max({extent[0], extent[1], extent[2]})/longestSquares
    );
    std::array<int, 3> n;
    for (int k = 0; k < 3; ++k)
    {
        n[k] = std::max(1, int(std::lround(extent[k]/spacing)));
    }
    return n;
}


//- The box's sides, outward, as grids of n squares of two triangles along
//  each axis.
Mesh boxMesh(const pmsh::point3& min, const pmsh::point3& max, const std::array<int, 3>& n)
{
    using namespace pmsh;
    const vector3 extent = max - min;
    Mesh m;
    std::map<std::array<int, 3>, Mesh::Vertex_index> vertex;
    auto at = [&](const std::array<int, 3>& ijk)
    {
        const auto found = vertex.find(ijk);
        if (found != vertex.end())
        {
            return found->second;
        }
        // The box's own coordinates on its sides: no rounding there
        std::array<double, 3> x;
        for (int k = 0; k < 3; ++k)
        {
            x[k] = ijk[k] == 0 ? min[k]
                 : ijk[k] == n[k] ? max[k]
                 : min[k] + extent[k]*ijk[k]/n[k];
        }
        const Mesh::Vertex_index v = m.add_vertex(toCgal(x));
        vertex.emplace(ijk, v);
        return v;
    };
    for (int side = 0; side < 6; ++side)
    {
        const int axis = side/2;
        const bool high = side % 2;
        // The side's two other axes, ordered so that u x v points out
        int u = (axis + 1) % 3, v = (axis + 2) % 3;
        if (!high)
        {
            std::swap(u, v);
        }
        for (int i = 0; i < n[u]; ++i)
        {
            for (int j = 0; j < n[v]; ++j)
            {
                std::array<std::array<int, 3>, 4> c;
                const int corner[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                for (int q = 0; q < 4; ++q)
                {
                    c[q][axis] = high ? n[axis] : 0;
                    c[q][u] = corner[q][0];
                    c[q][v] = corner[q][1];
                }
                m.add_face(at(c[0]), at(c[1]), at(c[2]));
                m.add_face(at(c[0]), at(c[2]), at(c[3]));
            }
        }
    }
    return m;
}


//- The bodies as one CGAL mesh bounding their volume (outward); FatalError
//  where they are not closed 2-manifolds.
Mesh bodyMesh(const pmsh::stlSurface& s, const std::string& what)
{
    Mesh m;
    std::vector<Mesh::Vertex_index> v;
    v.reserve(s.points.size());
    for (const pmsh::point3& p : s.points)
    {
        v.push_back(m.add_vertex(toCgal(p)));
    }
    bool manifold = true;
    for (const pmsh::triVerts& t : s.triangles)
    {
        manifold = manifold && m.add_face(v[t[0]], v[t[1]], v[t[2]]) != Mesh::null_face();
    }
    if (!manifold || !CGAL::is_closed(m))
    {
        throw pmsh::FatalError
        (
            pmsh::msg() << "The bodies of " << what << " reach the domain box, and to cut"
                << " them by it they must be closed 2-manifolds, which they are not.\n"
                << "Set 'wrap on;' in 'domain' of system/pmshDict to wrap them first",
            "pmsh::boxMinusBodies"
        );
    }
    PMP::orient_to_bound_a_volume(m);
    return m;
}

//- Whether a point of m lies on or beyond the side at `wall` of axis.
bool reachesSide(const Mesh& m, const int axis, const bool high, const double wall)
{
    for (const Mesh::Vertex_index v : m.vertices())
    {
        const double x = m.point(v)[axis];
        if (high ? x >= wall : x <= wall)
        {
            return true;
        }
    }
    return false;
}


//- p with its coordinate along axis set to x.
pmsh::cgal::Point withCoordinate(const pmsh::cgal::Point& p, const int axis, const double x)
{
    std::array<double, 3> c{p.x(), p.y(), p.z()};
    c[axis] = x;
    return pmsh::cgal::Point(c[0], c[1], c[2]);
}


//- body (closed, connected, reaching the side at `wall` of axis) with its
//  part within `height` of the side replaced by its section at that
//  height drawn out `height` beyond the side: a plinth, as wind tunnels
//  and road-car CFD put under tyres. The fluid then meets the body at
//  right angles on the side, not in the wedge a tyre makes with the road
//  (7 degrees where a tyre of radius 0.3 dips 2 mm into it), in which
//  no tetrahedron is good. False, body unchanged, where no section is
//  left (the body lies within height of the side) or the section pinches
//  (a point of it on two of its loops).
bool plinthed(Mesh& body, const int axis, const bool high, const double wall, const double height)
{
    using Vector = pmsh::cgal::Kernel::Vector_3;
    const double level = high ? wall - height : wall + height;
    const double beyond = high ? wall + height : wall - height;
    Vector towardsWall(axis == 0, axis == 1, axis == 2);
    if (!high)
    {
        towardsWall = -towardsWall;
    }
    // The body's part away from the wall, closed by faces on the level:
    // its intersection with a box ending there. Not PMP::clip by a plane,
    // which does the same but doubled this file's compile time (100 s
    // against 57): it instantiates the corefinement again, which the cut
    // by the domain box instantiates already.
    const CGAL::Bbox_3 bounds = PMP::bbox(body);
    const double margin = 1 + bounds.xmax() - bounds.xmin() + bounds.ymax() - bounds.ymin()
        + bounds.zmax() - bounds.zmin();
    pmsh::point3 boxMin{bounds.xmin() - margin, bounds.ymin() - margin, bounds.zmin() - margin};
    pmsh::point3 boxMax{bounds.xmax() + margin, bounds.ymax() + margin, bounds.zmax() + margin};
    (high ? boxMax : boxMin)[axis] = level;
    Mesh awayFromWall = boxMesh(boxMin, boxMax, {1, 1, 1});
    Mesh whole = body;
    Mesh clipped;
    if
    (
        !PMP::corefine_and_compute_intersection(whole, awayFromWall, clipped)
     || clipped.is_empty()
    )
    {
        return false;
    }

    const double tolerance = 1e-9*std::max(1.0, std::abs(level));
    const auto onSection = [&](const Mesh::Face_index f)
    {
        for (const Mesh::Vertex_index v : CGAL::vertices_around_face(clipped.halfedge(f), clipped))
        {
            if (std::abs(clipped.point(v)[axis] - level) > tolerance)
            {
                return false;
            }
        }
        return PMP::compute_face_normal(f, clipped)*towardsWall > 0;
    };
    std::vector<bool> section(clipped.number_of_faces(), false);
    bool any = false;
    for (const Mesh::Face_index f : clipped.faces())
    {
        section[f] = onSection(f);
        any = any || section[f];
    }
    if (!any)
    {
        return false;
    }

    // The body above the section, the section moved beyond the wall and
    // a wall from each of its edges down to there
    Mesh out;
    const Mesh::Vertex_index none = Mesh::null_vertex();
    std::vector<Mesh::Vertex_index> kept(clipped.number_of_vertices(), none);
    std::vector<Mesh::Vertex_index> moved(clipped.number_of_vertices(), none);
    const auto keptOf = [&](const Mesh::Vertex_index v)
    {
        if (kept[v] == none)
        {
            kept[v] = out.add_vertex(clipped.point(v));
        }
        return kept[v];
    };
    const auto movedOf = [&](const Mesh::Vertex_index v)
    {
        if (moved[v] == none)
        {
            moved[v] = out.add_vertex(withCoordinate(clipped.point(v), axis, beyond));
        }
        return moved[v];
    };
    bool manifold = true;
    const auto add = [&](Mesh::Vertex_index a, Mesh::Vertex_index b, Mesh::Vertex_index c)
    {
        manifold = manifold && out.add_face(a, b, c) != Mesh::null_face();
    };
    for (const Mesh::Face_index f : clipped.faces())
    {
        const Mesh::Halfedge_index h = clipped.halfedge(f);
        std::array<Mesh::Vertex_index, 3> v
        {
            clipped.source(h), clipped.target(h), clipped.target(clipped.next(h))
        };
        if (!section[f])
        {
            add(keptOf(v[0]), keptOf(v[1]), keptOf(v[2]));
            continue;
        }
        add(movedOf(v[0]), movedOf(v[1]), movedOf(v[2]));
        for (const Mesh::Halfedge_index e : CGAL::halfedges_around_face(h, clipped))
        {
            if (!section[clipped.face(clipped.opposite(e))])
            {
                // The removed section face's edge u -> v, as it ran
                const Mesh::Vertex_index u = clipped.source(e), w = clipped.target(e);
                add(keptOf(u), keptOf(w), movedOf(w));
                add(keptOf(u), movedOf(w), movedOf(u));
            }
        }
    }
    if (!manifold || !CGAL::is_closed(out))
    {
        return false;
    }
    body = std::move(out);
    return true;
}


//- The bodies of solid that reach a side, each with a plinth there
//  (plinthed) of the given height: the report counts the plinths made and
//  the bodies left as they were.
void addPlinths
(
    Mesh& solid,
    const pmsh::point3& min,
    const pmsh::point3& max,
    const double height,
    pmsh::domainCutReport& report
)
{
    for (int side = 0; side < 6; ++side)
    {
        const int axis = side/2;
        const bool high = side % 2;
        const double wall = (high ? max : min)[axis];
        if (!reachesSide(solid, axis, high, wall))
        {
            continue;
        }
        std::vector<Mesh> bodies;
        PMP::split_connected_components(solid, bodies);
        Mesh joined;
        for (Mesh& body : bodies)
        {
            if (reachesSide(body, axis, high, wall))
            {
                ++(plinthed(body, axis, high, wall, height) ? report.nPlinths : report.nNoPlinth);
            }
            CGAL::copy_face_graph(body, joined);
        }
        solid = std::move(joined);
    }
}


//- The fluid's pockets removed from m (the box less the bodies, oriented
//  out of the fluid): closed parts of the fluid apart from the rest,
//  which the cut makes where a body's cavity is open only beyond a side
//  (OpenFOAM's motorBike on its floor: the inside of its rear wheel's
//  wrap, 8,599 cells that no face joined to the rest, on which simpleFoam's
//  pressure solver could not converge and the solution blew up). The rest
//  is the shell of the largest volume; a shell of positive volume
//  besides it bounds a pocket, a body wholly inside the box bounds a
//  negative one. As snappyHexMesh keeps only the cells reachable from
//  locationInMesh, the report counts the pockets, their volume and a
//  point of the largest.
void removeFluidPockets(Mesh& m, pmsh::domainCutReport& report)
{
    auto component = m.add_property_map<Mesh::Face_index, std::size_t>("f:pocket").first;
    const std::size_t nComponents = PMP::connected_components(m, component);
    std::vector<double> volume(nComponents, 0);
    std::vector<pmsh::point3> somePoint(nComponents);
    for (const Mesh::Face_index f : m.faces())
    {
        std::array<pmsh::point3, 3> x;
        int k = 0;
        for (const Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m))
        {
            x[k++] = pmsh::cgal::toPoint3(m.point(v));
        }
        volume[component[f]] += pmsh::dot(x[0], pmsh::cross(x[1], x[2]))/6;
        somePoint[component[f]] = x[0];
    }
    const std::size_t rest =
        std::max_element(volume.begin(), volume.end()) - volume.begin();
    std::vector<std::size_t> pockets;
    double largest = 0;
    for (std::size_t c = 0; c < nComponents; ++c)
    {
        if (c != rest && volume[c] > 0)
        {
            pockets.push_back(c);
            report.pocketVolume += volume[c];
            if (volume[c] > largest)
            {
                largest = volume[c];
                report.pocketAt = somePoint[c];
            }
        }
    }
    if (!pockets.empty())
    {
        PMP::remove_connected_components(m, pockets, component);
    }
    report.nPockets = pockets.size();
    m.remove_property_map(component);
}


//- Edges of m shorter than `tolerance` collapsed, where that keeps m a
//  2-manifold (the link condition). The cut's constructed points are
//  rounded, so where an input point lies on a grid line of a side the cut
//  makes a point a rounding away from it: OpenFOAM's bullet standing on
//  a side gave four triangles of height 2e-18 (checkStl: degenerate).
//  Returns the edges collapsed.
std::size_t collapseShortEdges(Mesh& m, const double tolerance)
{
    std::vector<Mesh::Halfedge_index> shortEdges;
    for (const Mesh::Edge_index e : m.edges())
    {
        const Mesh::Halfedge_index h = m.halfedge(e);
        if (CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)))
          < tolerance*tolerance)
        {
            shortEdges.push_back(h);
        }
    }
    std::size_t nCollapsed = 0;
    for (const Mesh::Halfedge_index h : shortEdges)
    {
        if
        (
            !m.is_removed(h)
         && CGAL::squared_distance(m.point(m.source(h)), m.point(m.target(h)))
          < tolerance*tolerance
         && CGAL::Euler::does_satisfy_link_condition(m.edge(h), m)
        )
        {
            CGAL::Euler::collapse_edge(m.edge(h), m);
            ++nCollapsed;
        }
    }
    m.collect_garbage();
    return nCollapsed;
}

//- The points of m (nothing removed: in vertex index order): nullptr, or
//  the first point m gives twice. CGAL keeps the result of a cut manifold
//  where a body touches a side along a line or at a point by giving the
//  touching points twice.
const pmsh::point3* pointsOf(const Mesh& m, std::vector<pmsh::point3>& points)
{
    using namespace pmsh;
    points.clear();
    points.reserve(m.number_of_vertices());
    std::unordered_set<pointKey, pointKeyHash> seen;
    for (const Mesh::Vertex_index v : m.vertices())
    {
        points.push_back(cgal::toPoint3(m.point(v)));
        if (!seen.insert(pointKey(points.back())).second)
        {
            return &points.back();
        }
    }
    return nullptr;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

pmsh::stlSurface pmsh::boxMinusBodies
(
    const stlSurface& bodies,
    const point3& min,
    const point3& max,
    const std::array<std::string, 6>& sideNames,
    const double plinthHeight,
    const std::string& what,
    domainCutReport& report
)
{
    const char* function = "pmsh::boxMinusBodies";
    const auto start = std::chrono::steady_clock::now();

    Mesh fluid = boxMesh(min, max, squaresAlongEdges(min, max));
    Mesh solid = bodyMesh(bodies, what);
    if (plinthHeight > 0)
    {
        addPlinths(solid, min, max, plinthHeight, report);
    }
    Mesh out;
    bool manifold = false;
    try
    {
        manifold = PMP::corefine_and_compute_difference
        (
            fluid, solid, out, CGAL::parameters::throw_on_self_intersection(true)
        );
    }
    catch (const PMP::Corefinement::Self_intersection_exception&)
    {
        throw FatalError
        (
            msg() << "The bodies of " << what << " reach the domain box, and cutting"
                << " them by it found a body crossing itself or another.\nSet"
                << " 'wrap on;' in 'domain' of system/pmshDict to wrap them first",
            function
        );
    }
    removeFluidPockets(out, report);
    const double tolerance = 1e-9*std::sqrt(magSqr(max - min));
    collapseShortEdges(out, tolerance);     // and collects the garbage

    std::vector<point3> points;
    const point3* touching = pointsOf(out, points);
    if (!manifold || touching)
    {
        throw FatalError
        (
            msg() << "The bodies of " << what << " touch the domain box from "
                << str(min, 10) << " to " << str(max, 10) << " along a line"
                << " or at a point" << (touching ? " " + str(*touching, 10) : "")
                << ": the fluid between them and the side would end in a wedge of"
                << " zero angle.\nMove the box's side (min, max of 'domain' in"
                << " system/pmshDict) so that the bodies cross it or stay apart"
                << " from it, or stand them on plinths (plinthHeight in 'domain')",
            function
        );
    }

    // Each body triangle's solid, found from the nearest input triangle:
    // the cut's triangles inside a body triangle lie on it
    const cgal::triangleTree inputTree(bodies);

    stlSurface s;
    s.solidNames = bodies.solidNames;
    // Sides of one name are one solid (patch); none is a body's
    // (putBodiesInDomain)
    std::array<label, 6> sideSolid{};
    {
        surfaceBuilder builder(s, "");
        for (std::size_t side = 0; side < sideSolid.size(); ++side)
        {
            sideSolid[side] = builder.addSolid(sideNames[side]);
        }
    }

    s.points = std::move(points);
    // Points the cut made on a side lie on it to rounding (the exact
    // predicates decide, the constructions round)
    for (const Mesh::Face_index f : out.faces())
    {
        const triVerts t = cgal::triangleOf(out, f);
        label solid = -1;
        for (int side = 0; side < 6 && solid < 0; ++side)
        {
            const int axis = side/2;
            const double plane = (side % 2 ? max : min)[axis];
            bool onSide = true;
            for (label p : t)
            {
                onSide = onSide && std::abs(s.points[p][axis] - plane) <= tolerance;
            }
            if (onSide)
            {
                solid = sideSolid[side];
            }
        }
        s.triangles.push_back(t);
        if (solid < 0)
        {
            solid = bodies.solid[inputTree.nearest(s.centroid(s.nTriangles() - 1))];
        }
        s.solid.push_back(solid);
    }

    report.nTriangles = s.nTriangles();
    report.seconds = std::chrono::duration<double>
    (
        std::chrono::steady_clock::now() - start
    ).count();
    return s;
}


// ************************************************************************* //
