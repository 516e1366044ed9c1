/*---------------------------------------------------------------------------*\
  pmshFoam: the geometry surfaces of coarse boundary edges (see
  boundaryEdgeSurfaces.H).
\*---------------------------------------------------------------------------*/

#include "boundaryEdgeSurfaces.H"
#include "Geometry.H"
#include "pmshError.H"
#include "matchByPoints.H"

#include <algorithm>
#include <cmath>
#include <tuple>

// * * * * * * * * * * * * * * boundaryEdgeSurfaces  * * * * * * * * * * * * //

pmsh::boundaryEdgeSurfaces::boundaryEdgeSurfaces
(
    const CoarseMesh& coarse,
    const Geometry* geometry
)
{
    // Edge k of face b is 3*b + k, boundary faces first, then the faces
    // between zones. A boundary edge away from zones has exactly two
    // faces. Groups come in (p, q) order.
    const matchId nBoundary = matchId(coarse.boundary.size());
    auto faceOf = [&](matchId face) -> const triVerts&
    {
        return face < nBoundary
            ? coarse.boundary[face].v : coarse.zoneFaces[face - nBoundary].v;
    };
    auto surfaceOf = [&](matchId face)
    {
        return face < nBoundary
            ? coarse.boundary[face].surface
            : coarse.zoneFaces[face - nBoundary].surface;
    };
    auto edgeOf = [&](matchId id)
    {
        const triVerts& f = faceOf(id/3);
        return std::array<label, 2>{f[id % 3], f[(id + 1) % 3]};
    };
    edges_.reserve(3*coarse.boundary.size()/2);
    forEachSamePointsGroup
    (
        coarse.points.size(),
        matchId(3*(coarse.boundary.size() + coarse.zoneFaces.size())),
        edgeOf,
        [&](const matchId* ids, std::size_t n)
        {
            const auto e = sortedPoints(edgeOf(ids[0]));
            std::vector<label> surfaces;
            std::size_t nBoundaryFaces = 0;
            for (std::size_t i = 0; i < n; ++i)
            {
                nBoundaryFaces += ids[i]/3 < nBoundary;
                surfaces.push_back(surfaceOf(ids[i]/3));
            }
            if (nBoundaryFaces == n && n != 2)
            {
                throw FatalError
                (
                    msg() << "The coarse boundary is not a closed manifold: edge "
                        << e[0] << '-' << e[1] << " is used by " << n
                        << " boundary faces instead of 2",
                    "boundaryEdgeSurfaces"
                );
            }
            std::sort(surfaces.begin(), surfaces.end());
            surfaces.erase(std::unique(surfaces.begin(), surfaces.end()), surfaces.end());
            label s1 = surfaces.front();
            label s2 = surfaces.size() > 1 ? surfaces[1] : s1;
            if (surfaces.size() > 2 && geometry)
            {
                // The first pair whose curve lies on all the surfaces here
                // (two of them may be one plane, given twice)
                const point3 mid = midPoint(coarse.points[e[0]], coarse.points[e[1]]);
                const double tolerance =
                    1e-6*std::sqrt(magSqr(coarse.points[e[1]] - coarse.points[e[0]]));
                s1 = s2 = -1;
                for (std::size_t i = 0; i < surfaces.size() && s1 < 0; ++i)
                {
                    for (std::size_t j = i + 1; j < surfaces.size() && s1 < 0; ++j)
                    {
                        const point3 q = geometry->projectToEdge(mid, surfaces[i], surfaces[j]);
                        double off = 0;
                        for (label s : surfaces)
                        {
                            off = std::max
                            (
                                off, std::sqrt(magSqr(q - geometry->projectToSurface(q, s)))
                            );
                        }
                        if (off < tolerance)
                        {
                            s1 = surfaces[i];
                            s2 = surfaces[j];
                        }
                    }
                }
            }
            edges_.push_back({e[0], e[1], s1, s2});
        }
    );
}


bool pmsh::boundaryEdgeSurfaces::find(label p, label q, label& s1, label& s2) const
{
    const edge key{std::min(p, q), std::max(p, q), 0, 0};
    auto it = std::lower_bound
    (
        edges_.begin(), edges_.end(), key,
        [](const edge& x, const edge& y) { return std::tie(x.p, x.q) < std::tie(y.p, y.q); }
    );
    if (it == edges_.end() || it->p != key.p || it->q != key.q)
    {
        return false;
    }
    s1 = it->s1;
    s2 = it->s2;
    return true;
}


// ************************************************************************* //
