/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: regions, feature edges and projection (see
  stlGeometry.H). Curvature sizing is in stlCurvatureSizing.C, the coarse
  mesh in stlNetgenMesh.C.
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "stlGeometryImpl.H"
#include "surfaceFiles.H"
#include "pmshError.H"
#include "matchByPoints.H"

#include <algorithm>
#include <cmath>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- The length of the diagonal of the points' bounding box.
double boundingBoxDiagonal(const std::vector<point3>& points)
{
    const auto [lo, hi] = boundingBox(points);
    return std::sqrt(magSqr(hi - lo));
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * * //

void pmsh::stlGeometryImpl::buildTriangleTrees()
{
    const label nt = surface.nTriangles();
    std::vector<boxTree::entry> all(nt);
    std::vector<std::vector<boxTree::entry>> perRegion(nRegions);
    for (label t = 0; t < nt; ++t)
    {
        all[t] = triangleEntry(t);
        perRegion[region[t]].push_back(all[t]);
    }
    allTriangles = boxTree(std::move(all));
    regionTriangles.resize(nRegions);
    for (label r = 0; r < nRegions; ++r)
    {
        regionTriangles[r] = boxTree(std::move(perRegion[r]));
    }
}


void pmsh::stlGeometryImpl::buildRegionEdges
(
    const std::vector<std::array<label, 2>>& featureEdgeTriangles
)
{
    const stlSurface& s = surface;
    for (std::size_t i = 0; i < featureEdges.size(); ++i)
    {
        const label r1 = region[featureEdgeTriangles[i][0]];
        const label r2 = region[featureEdgeTriangles[i][1]];
        if (r1 != r2)
        {
            regionEdges[{std::min(r1, r2), std::max(r1, r2)}]
                .segments.push_back(featureEdges[i]);
        }
    }
    for (auto& re : regionEdges)
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


// Surface files of every format (Geometry::New)
namespace pmsh
{
    addNamedToRunTimeSelectionTable(Geometry, stlGeometry, extension, surface);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

pmsh::stlGeometry::stlGeometry
(
    const std::vector<std::string>& fileNames,
    const domainBox& domain
)
:
    what_(describeSurfaceFiles(fileNames)),
    impl_(new impl)
{
    impl& d = *impl_;
    d.surface = readSurfaceFiles(fileNames);
    if (domain.given)
    {
        wrap_ = wrapBodies(d.surface, domain, what_);
        putBodiesInDomain(d.surface, domain, what_);
    }
    checkStl(d.surface, what_);

    const stlSurface& s = d.surface;
    const label nt = s.nTriangles();

    d.diagonal = boundingBoxDiagonal(s.points);

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
    auto edgeOf = [&](matchId id) { return triangleEdge(s.triangles, id); };
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

    d.buildTriangleTrees();
    d.buildRegionEdges(featureEdgeTriangles);
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
                << "Surface " << s << " does not exist in " << what_
                << ": valid surfaces are 0.." << d.nRegions - 1,
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


std::vector<double> pmsh::stlGeometry::localTriangleSizes
(
    const coarseMeshParameters& parameters
) const
{
    const stlSurface& s = impl_->surface;
    std::vector<double> patchSize(s.solidNames.size(), parameters.maxCellSize);
    if (parameters.patchMaxCellSize)
    {
        for (std::size_t p = 0; p < patchSize.size(); ++p)
        {
            const double h = parameters.patchMaxCellSize(s.solidNames[p]);
            if (h > 0)
            {
                patchSize[p] = std::min(patchSize[p], h);
            }
        }
    }
    std::vector<double> size(s.nTriangles());
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        size[t] = regionSizeAt(parameters.regions, s.centroid(t), patchSize[s.solid[t]]);
    }
    return size;
}


// ************************************************************************* //
