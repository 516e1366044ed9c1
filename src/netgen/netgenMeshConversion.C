/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen's meshes as pmshFoam's volumeMesh (see
  netgenMeshConversion.H).
\*---------------------------------------------------------------------------*/

#include "netgenMeshConversion.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <cmath>

namespace pmsh
{
namespace ng
{

double boundingBoxDiagonal(const std::vector<pmsh::point3>& points)
{
    const auto [lo, hi] = pmsh::boundingBox(points);
    return std::sqrt(pmsh::magSqr(hi - lo));
}


void makeTetsPositive(pmsh::ng::volumeMesh& m, const std::string& what)
{
    using namespace pmsh;
    for (std::size_t i = 0; i < m.tets.size(); ++i)
    {
        tetVerts& t = m.tets[i];
        const double v6 = tetVolume6
        (
            m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]
        );
        if (v6 < 0)
        {
            std::swap(t[1], t[2]);
        }
        else if (!(v6 > 0))
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a flat tetrahedron (zero volume) when"
                    << " meshing " << what << ": tet " << i << " with points "
                    << str(m.points[t[0]]) << ' ' << str(m.points[t[1]]) << ' '
                    << str(m.points[t[2]]) << ' ' << str(m.points[t[3]]),
                "pmsh::ng::makeTetsPositive"
            );
        }
    }
}


void checkBoundary(const pmsh::ng::volumeMesh& m, const std::string& what)
{
    using namespace pmsh;
    std::vector<triVerts> boundary(m.boundary.size());
    for (std::size_t b = 0; b < boundary.size(); ++b)
    {
        boundary[b] = m.boundary[b].v;
    }
    fittingTetFaces
    (
        m.points.size(), m.tets, boundary,
        "Netgen's mesh of " + what + " is inconsistent", "pmsh::ng::checkBoundary"
    );
}


void compactPoints(pmsh::ng::volumeMesh& m)
{
    using namespace pmsh;
    std::vector<label> newIndex(m.points.size(), -1);
    for (const auto& t : m.tets)
    {
        for (label p : t)
        {
            newIndex[p] = 0;
        }
    }
    for (const auto* triangles : {&m.boundary, &m.interfaces})
    {
        for (const auto& b : *triangles)
        {
            for (label p : b.v)
            {
                newIndex[p] = 0;
            }
        }
    }
    label n = 0;
    std::vector<point3> points;
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
        if (newIndex[i] == 0)
        {
            newIndex[i] = n++;
            points.push_back(m.points[i]);
        }
    }
    if (std::size_t(n) == m.points.size())
    {
        return;
    }
    for (auto& t : m.tets)
    {
        for (label& p : t)
        {
            p = newIndex[p];
        }
    }
    for (auto* triangles : {&m.boundary, &m.interfaces})
    {
        for (auto& b : *triangles)
        {
            for (label& p : b.v)
            {
                p = newIndex[p];
            }
        }
    }
    for (auto& identification : m.periodic)
    {
        for (auto& pair : identification.points)
        {
            pair = {newIndex[pair[0]], newIndex[pair[1]]};
        }
    }
    m.points = std::move(points);
}


pmsh::ng::volumeMesh convertMesh(const netgen::Mesh& mesh, const std::string& what)
{
    using namespace pmsh;
    ng::volumeMesh m;

    const int np = int(mesh.GetNP());
    m.points.resize(np);
    for (int i = 1; i <= np; ++i)
    {
        const netgen::Point<3>& p = mesh.Point(netgen::PointIndex(i));
        m.points[i - 1] = {p(0), p(1), p(2)};
    }

    const int ne = int(mesh.GetNE());
    m.tets.reserve(ne);
    for (int i = 1; i <= ne; ++i)
    {
        const netgen::Element& el = mesh.VolumeElement(i);
        if (el.IsDeleted())
        {
            continue;
        }
        if (el.GetNP() != 4)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced an element with " << el.GetNP()
                    << " points when meshing " << what
                    << "; only linear tetrahedra are supported",
                "pmsh::ng::convertMesh"
            );
        }
        m.tets.push_back
        ({
            label(int(el.PNum(1))) - 1, label(int(el.PNum(2))) - 1,
            label(int(el.PNum(3))) - 1, label(int(el.PNum(4))) - 1
        });
        m.tetDomain.push_back(label(el.GetIndex()));
    }

    const int nse = int(mesh.GetNSE());
    for (int i = 1; i <= nse; ++i)
    {
        const netgen::Element2d& el = mesh.SurfaceElement(i);
        if (el.IsDeleted())
        {
            continue;
        }
        if (el.GetNP() != 3)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a surface element with " << el.GetNP()
                    << " points when meshing " << what
                    << "; only triangles are supported",
                "pmsh::ng::convertMesh"
            );
        }
        const netgen::FaceDescriptor& fd = mesh.GetFaceDescriptor(el.GetIndex());
        const bool inside = fd.DomainIn() > 0;
        const bool outside = fd.DomainOut() > 0;
        if (!inside && !outside)
        {
            continue;   // bounding no domain
        }
        ng::boundaryTriangle b;
        b.v =
        {
            label(int(el.PNum(1))) - 1,
            label(int(el.PNum(2))) - 1,
            label(int(el.PNum(3))) - 1
        };
        if (inside && outside)
        {
            // Between two domains
            b.bc = fd.BCProperty();
            b.surface = fd.SurfNr();
            b.domain = fd.DomainIn();
            b.otherDomain = fd.DomainOut();
            m.interfaces.push_back(b);
            continue;
        }
        if (outside)
        {
            // Normal points into the domain: flip
            std::swap(b.v[1], b.v[2]);
        }
        b.bc = fd.BCProperty();
        b.surface = fd.SurfNr();
        b.domain = inside ? fd.DomainIn() : fd.DomainOut();
        m.boundary.push_back(b);
        m.bcNames.emplace(b.bc, fd.GetBCName());
    }

    return m;
}


void readNglibMesh
(
    nglib::Ng_Mesh* mesh,
    pmsh::ng::volumeMesh& m,
    const std::string& what
)
{
    using namespace pmsh;
    const int np = nglib::Ng_GetNP(mesh);
    m.points.resize(np);
    for (int i = 1; i <= np; ++i)
    {
        double x[3];
        nglib::Ng_GetPoint(mesh, i, x);
        m.points[i - 1] = {x[0], x[1], x[2]};
    }

    const int ne = nglib::Ng_GetNE(mesh);
    m.tets.resize(ne);
    for (int i = 1; i <= ne; ++i)
    {
        int pi[NG_VOLUME_ELEMENT_MAXPOINTS];
        if (nglib::Ng_GetVolumeElement(mesh, i, pi) != nglib::NG_TET)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a volume element that is not a linear"
                    << " tetrahedron when meshing " << what,
                "pmsh::ng::readNglibMesh"
            );
        }
        m.tets[i - 1] = {pi[0] - 1, pi[1] - 1, pi[2] - 1, pi[3] - 1};
    }
}

} // End namespace ng
} // End namespace pmsh

// ************************************************************************* //
