/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen's local mesh size inside a closed surface, for the
  meshers that are not Netgen (see netgenInterface.H: sizeField).

  Netgen's volume mesher (surfaceVolumeMesh) sizes its cells by a local
  size tree (netgen::LocalH) that Mesh::CalcLocalH fills from the surface:
  at each triangle's centre the triangle's longest edge; then the regions'
  sizes (restrictLocalSizes). The tree grades every size it is given into
  its surroundings: LocalH::SetH(x, h) sets h on the box of x (a box no
  larger than h) and h + grading*b on the boxes b away along the axes, in
  turn, so that the size grows by about `grading` per unit of distance.
  This file builds the same tree the same way, so that a size asked of it
  is the size Netgen's volume mesher would aim at.

  Netgen quirks handled here:
  - LocalH's boxes come from one static block allocator (GradingBox::ball),
    not thread-safe: the tree is built and freed under Netgen's lock.
    GetH only reads, so sizes are asked without the lock (HXT's threads).
  - SetH ignores points outside the tree's root box: the root is the
    surface's bounding box, which LocalH's constructor enlarges by 10-26 %.
  - A size is set only where the tree has none below 1.2 times it (SetH's
    own test): the tree's size is within 1.2 times the smallest asked for.
\*---------------------------------------------------------------------------*/

#include "netgenSession.H"

struct pmsh::ng::sizeField::impl
{
    std::unique_ptr<netgen::LocalH> tree;
    double maxh = 1e300;
};


pmsh::ng::sizeField::sizeField
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const meshParameters& parameters
)
:
    impl_(new impl)
{
    impl_->maxh = parameters.maxh;
    if (points.empty())
    {
        return;
    }

    const auto [lo, hi] = boundingBox(points);

    std::lock_guard<std::mutex> lock(netgenMutex);
    impl_->tree.reset
    (
        new netgen::LocalH
        (
            netgen::Point<3>(lo[0], lo[1], lo[2]),
            netgen::Point<3>(hi[0], hi[1], hi[2]),
            parameters.grading
        )
    );
    netgen::LocalH& tree = *impl_->tree;

    // Mesh::CalcLocalH's rule: the longest edge of each triangle at its
    // centre
    for (const triVerts& t : triangles)
    {
        const point3& a = points[t[0]];
        const point3& b = points[t[1]];
        const point3& c = points[t[2]];
        const double longest = std::sqrt
        (
            std::max({magSqr(b - a), magSqr(c - b), magSqr(a - c)})
        );
        if (longest > 0)
        {
            const point3 centre = (1.0/3.0)*(a + b + c);
            tree.SetH(netgen::Point<3>(centre[0], centre[1], centre[2]), longest);
        }
    }
    restrictLocalSizes(tree, parameters);
}


pmsh::ng::sizeField::~sizeField()
{
    if (impl_ && impl_->tree)
    {
        std::lock_guard<std::mutex> lock(netgenMutex);
        impl_->tree.reset();
    }
}


pmsh::ng::sizeField::sizeField(sizeField&&) noexcept = default;


double pmsh::ng::sizeField::operator()(const point3& x) const
{
    if (!impl_->tree)
    {
        return impl_->maxh;
    }
    return std::min
    (
        impl_->maxh,
        impl_->tree->GetH(netgen::Point<3>(x[0], x[1], x[2]))
    );
}


// ************************************************************************* //
