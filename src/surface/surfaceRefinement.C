#include "surfaceRefinement.H"
#include "Geometry.H"
#include "pmshError.H"
#include "partitionSurface.H"
#include "matchByPoints.H"

#include <algorithm>
#include <tuple>
#include <unordered_map>

// * * * * * * * * * * * * * * boundaryEdgeSurfaces  * * * * * * * * * * * * //

pmsh::boundaryEdgeSurfaces::boundaryEdgeSurfaces(const CoarseMesh& coarse)
{
    // Edge k of boundary face b is 3*b + k; each appears twice, once per
    // face of the closed boundary. Groups come in (p, q) order.
    auto edgeOf = [&](matchId id)
    {
        const triFace& f = coarse.boundary[id/3].v;
        return std::array<label, 2>{f[id % 3], f[(id + 1) % 3]};
    };
    edges_.reserve(3*coarse.boundary.size()/2);
    forEachSamePointsGroup
    (
        coarse.points.size(), matchId(3*coarse.boundary.size()), edgeOf,
        [&](const matchId* ids, std::size_t n)
        {
            const auto e = sortedPoints(edgeOf(ids[0]));
            if (n != 2)
            {
                throw FatalError
                (
                    msg() << "The coarse boundary is not a closed manifold: edge "
                        << e[0] << '-' << e[1] << " is used by " << n
                        << " boundary faces instead of 2",
                    "boundaryEdgeSurfaces"
                );
            }
            const label s1 = coarse.boundary[ids[0]/3].surface;
            const label s2 = coarse.boundary[ids[1]/3].surface;
            edges_.push_back({e[0], e[1], std::min(s1, s2), std::max(s1, s2)});
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


// * * * * * * * * * * * * * * * * refineSurface  * * * * * * * * * * * * * //

namespace
{

using namespace pmsh;

// The lattice of one coarse face refined r times: point (i, j) has integer
// barycentric coordinates (n - i - j, i, j) on the face's points sorted by
// index (v0 < v1 < v2), so both ranks that hold an interface face walk it
// identically.
class faceLattice
{
public:

    explicit faceLattice(int levels)
    :
        levels_(levels),
        n_(1 << levels),
        pos_((n_ + 1)*(n_ + 1))
    {}

    int n() const { return n_; }
    point& at(int i, int j) { return pos_[j*(n_ + 1) + i]; }

    // Fill positions level by level: each new point is the midpoint of the
    // coarser edge it splits, projected through `project(i, j, p)`.
    template<class Projector>
    void fill(const point& x0, const point& x1, const point& x2, Projector project)
    {
        at(0, 0) = x0;
        at(n_, 0) = x1;
        at(0, n_) = x2;
        for (int level = 1; level <= levels_; ++level)
        {
            const int s = n_ >> level;
            for (int j = 0; j <= n_; j += s)
            {
                for (int i = 0; i + j <= n_; i += s)
                {
                    const bool oddI = (i/s) % 2;
                    const bool oddJ = (j/s) % 2;
                    const bool oddK = ((n_ - i - j)/s) % 2;
                    if (!oddI && !oddJ && !oddK)
                    {
                        continue;       // exists at a coarser level
                    }
                    point mid;
                    if (oddI && oddJ)
                    {
                        mid = midPoint(at(i + s, j - s), at(i - s, j + s));
                    }
                    else if (oddI)
                    {
                        mid = midPoint(at(i + s, j), at(i - s, j));
                    }
                    else
                    {
                        mid = midPoint(at(i, j + s), at(i, j - s));
                    }
                    at(i, j) = project(i, j, mid);
                }
            }
        }
    }

private:

    int levels_;
    int n_;
    std::vector<point> pos_;
};


} // End anonymous namespace


pmsh::FineSurface pmsh::refineSurface
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const boundaryEdgeSurfaces& edgeSurfaces,
    const Geometry* geometry,
    int levels
)
{
    if (levels < 0 || levels > 15)
    {
        throw FatalError
        (
            msg() << "refinementLevels " << levels << " is outside 0..15",
            "refineSurface"
        );
    }

    const label nCoarseFaces = label(partSurface.faces.size());
    const int n = 1 << levels;
    const std::size_t trianglesPerFace = std::size_t(n)*n;

    FineSurface fine;
    fine.triangles.reserve(nCoarseFaces*trianglesPerFace);
    fine.region.reserve(nCoarseFaces*trianglesPerFace);
    // Points: about half the triangles for a closed surface
    fine.points.reserve(nCoarseFaces*trianglesPerFace/2 + 4);
    fine.ids.reserve(fine.points.capacity());

    // Points on coarse vertices and edges are shared by several faces and
    // are looked up by id; points inside a face belong to that face alone.
    std::unordered_map<barycentricId, label, barycentricIdHash> sharedPoints;
    sharedPoints.reserve(nCoarseFaces*(3*n/2 + 1));

    faceLattice lattice(levels);
    std::vector<label> latticePoint((n + 1)*(n + 1));

    for (label facei = 0; facei < nCoarseFaces; ++facei)
    {
        const triFace& f = partSurface.faces[facei];
        triFace v = f;
        std::sort(v.begin(), v.end());
        const label faceSurface = partSurface.surface[facei];

        // Projection of the point at lattice (i, j): by the coarse entity
        // the point lies on (the zero coordinates say which)
        auto project = [&](int i, int j, const point& p) -> point
        {
            if (!geometry)
            {
                return p;
            }
            const int k = n - i - j;
            if (i != 0 && j != 0 && k != 0)
            {
                return faceSurface >= 0 ? geometry->projectToSurface(p, faceSurface) : p;
            }
            const label a = (k == 0) ? v[1] : v[0];
            const label b = (j == 0) ? v[1] : v[2];
            label s1, s2;
            if (!edgeSurfaces.find(a, b, s1, s2))
            {
                return p;   // an edge inside the domain
            }
            return s1 == s2
                ? geometry->projectToSurface(p, s1)
                : geometry->projectToEdge(p, s1, s2);
        };
        lattice.fill(coarse.points[v[0]], coarse.points[v[1]], coarse.points[v[2]], project);

        for (int j = 0; j <= n; ++j)
        {
            for (int i = 0; i + j <= n; ++i)
            {
                const barycentricId id
                (
                    std::uint32_t(v[0] + 1), std::uint32_t(n - i - j),
                    std::uint32_t(v[1] + 1), std::uint32_t(i),
                    std::uint32_t(v[2] + 1), std::uint32_t(j)
                );
                label pointi = label(fine.points.size());
                if (id.nNonZero() < 3)
                {
                    auto inserted = sharedPoints.emplace(id, pointi);
                    if (!inserted.second)
                    {
                        latticePoint[j*(n + 1) + i] = inserted.first->second;
                        continue;
                    }
                }
                fine.points.push_back(lattice.at(i, j));
                fine.ids.push_back(id);
                latticePoint[j*(n + 1) + i] = pointi;
            }
        }

        // Triangles of the lattice, oriented like (v0, v1, v2); flipped to
        // the coarse face's outward orientation where that differs
        const bool flip = !sameOrientation(v, f);
        auto P = [&](int i, int j) { return latticePoint[j*(n + 1) + i]; };
        auto addTriangle = [&](label a, label b, label c)
        {
            fine.triangles.push_back(flip ? triFace{a, c, b} : triFace{a, b, c});
            fine.region.push_back(partSurface.region[facei]);
        };
        for (int j = 0; j < n; ++j)
        {
            for (int i = 0; i + j < n; ++i)
            {
                addTriangle(P(i, j), P(i + 1, j), P(i, j + 1));
                if (i + j + 1 < n)
                {
                    addTriangle(P(i + 1, j), P(i + 1, j + 1), P(i, j + 1));
                }
            }
        }
    }
    return fine;
}


pmsh::label pmsh::countFoldedTriangles
(
    const CoarseMesh& coarse,
    const coarsePartSurface& partSurface,
    const FineSurface& fine,
    int levels
)
{
    const std::size_t trianglesPerFace = std::size_t(1) << (2*levels);
    label nFolded = 0;
    for (std::size_t facei = 0; facei < partSurface.faces.size(); ++facei)
    {
        const triFace& f = partSurface.faces[facei];
        const vector coarseNormal = cross
        (
            coarse.points[f[1]] - coarse.points[f[0]],
            coarse.points[f[2]] - coarse.points[f[0]]
        );
        for (std::size_t t = 0; t < trianglesPerFace; ++t)
        {
            const triFace& tri = fine.triangles[facei*trianglesPerFace + t];
            const vector normal = cross
            (
                fine.points[tri[1]] - fine.points[tri[0]],
                fine.points[tri[2]] - fine.points[tri[0]]
            );
            if (dot(normal, coarseNormal) <= 0)
            {
                ++nFolded;
            }
        }
    }
    return nFolded;
}


pmsh::FineSurface pmsh::refinePartSurface
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    label part,
    const Geometry* geometry,
    int levels
)
{
    const coarsePartSurface partSurface = partitionSurface(coarse, cellPart, part);
    FineSurface fine = refineSurface
    (
        coarse, partSurface, boundaryEdgeSurfaces(coarse), geometry, levels
    );
    const label nFolded = countFoldedTriangles(coarse, partSurface, fine, levels);
    if (nFolded > 0)
    {
        throw FatalError
        (
            msg() << nFolded << " refined surface triangles of part " << part
                << " folded over when projected onto the geometry: the coarse"
                << " mesh is too coarse for the curvature of the geometry.\n"
                << "Reduce maxCellSize in system/pmshDict.",
            "refinePartSurface"
        );
    }
    return fine;
}
