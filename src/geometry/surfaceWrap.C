#include "surfaceWrap.H"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/alpha_wrap_3.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <vector>

namespace
{

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Mesh = CGAL::Surface_mesh<Point>;

// The input's triangles in a tree: the nearest one to a wrap triangle
// gives it its solid
using TrianglePrimitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using TriangleTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, TrianglePrimitive>>;

Point cgal(const pmsh::point3& p)
{
    return Point(p[0], p[1], p[2]);
}

} // End anonymous namespace


pmsh::stlSurface pmsh::wrapSurface
(
    const stlSurface& s,
    const double size,
    const double offset,
    surfaceWrapReport& report
)
{
    const auto start = std::chrono::steady_clock::now();

    std::vector<Point> points;
    points.reserve(s.points.size());
    for (const point3& p : s.points)
    {
        points.push_back(cgal(p));
    }
    // alpha_wrap_3 takes a soup: repeated, crossing or open faces are all
    // fine, but a face is a range of point indices
    std::vector<std::array<std::size_t, 3>> faces;
    faces.reserve(s.triangles.size());
    for (const triVerts& t : s.triangles)
    {
        faces.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
    }

    Mesh wrap;
    CGAL::alpha_wrap_3(points, faces, size, offset, wrap);

    std::vector<Triangle> input;
    input.reserve(s.triangles.size());
    for (const triVerts& t : s.triangles)
    {
        input.emplace_back(points[t[0]], points[t[1]], points[t[2]]);
    }
    TriangleTree inputTree(input.begin(), input.end());
    inputTree.accelerate_distance_queries();

    stlSurface out;
    out.solidNames = s.solidNames;
    std::vector<label> index(wrap.number_of_vertices(), -1);
    for (const Mesh::Vertex_index v : wrap.vertices())
    {
        index[std::size_t(v)] = label(out.points.size());
        const Point& p = wrap.point(v);
        out.points.push_back({p.x(), p.y(), p.z()});
    }
    for (const Mesh::Face_index f : wrap.faces())
    {
        triVerts t{};
        int k = 0;
        for (const Mesh::Vertex_index v : CGAL::vertices_around_face(wrap.halfedge(f), wrap))
        {
            t[k++] = index[std::size_t(v)];
        }
        out.triangles.push_back(t);
        const Point centre = CGAL::centroid
        (
            wrap.point(CGAL::source(wrap.halfedge(f), wrap)),
            wrap.point(CGAL::target(wrap.halfedge(f), wrap)),
            wrap.point(CGAL::target(wrap.next(wrap.halfedge(f)), wrap))
        );
        const auto nearest = inputTree.closest_point_and_primitive(centre);
        out.solid.push_back(s.solid[std::size_t(nearest.second - input.begin())]);
    }

    // How far the mesh's boundary may lie from the CAD: the wrap's points
    // lie on the offset surface, its triangles' centres further where
    // they bridge a concave corner or a gap narrower than size
    double maxDistance2 = 0;
    for (const point3& p : out.points)
    {
        maxDistance2 = std::max(maxDistance2, inputTree.squared_distance(cgal(p)));
    }
    for (label t = 0; t < out.nTriangles(); ++t)
    {
        maxDistance2 = std::max(maxDistance2, inputTree.squared_distance(cgal(out.centroid(t))));
    }

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
