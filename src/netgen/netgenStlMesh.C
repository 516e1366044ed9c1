/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen's coarse volume mesh of an STL triangulation (see
  netgenInterface.H).

  Netgen quirks handled here, each commented where it is handled:
  - nglib has no Ng_STL_DeleteGeometry: the STLGeometry is deleted here;
  - Ng_STL_AddTriangle's buffer is emptied only by Ng_STL_InitSTLGeometry;
  - Ng_STL_AddEdge's buffer is never emptied (only Ng_STL_LoadGeometry
    resets it): edges go straight to STLGeometry::AddEdges instead;
  - without those edges Netgen's STL mesh ignores boundaries it sees no
    angle at (two coplanar solids);
  - Ng_STL_MakeEdges creates the local size tree (always with grading 0.3)
    before lines and surface are meshed in Ng_STL_GenerateSurfaceMesh: it
    is restricted in between;
  - STL curvature sizing (stlparam.resthsurfcurvenable) is off by default
    and has no floor: pmshFoam's own (stlGeometry) comes as size points;
  - Netgen told to stop at the time limit returns as if it had finished.
\*---------------------------------------------------------------------------*/

#include "netgenMeshConversion.H"
#include "pmshError.H"

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

using namespace pmsh::ng;

//- Where errors of stlVolumeMesh come from.
const char* const stlFunction = "pmsh::ng::stlVolumeMesh";


//- Netgen's STL geometry of the triangles, checked by Netgen. Quirk: nglib
//  has no Ng_STL_DeleteGeometry; the object is a netgen::STLGeometry.
std::unique_ptr<netgen::STLGeometry> newStlGeometry
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const netgenSession& session,
    const std::string& what
)
{
    const char* function = stlFunction;
    std::unique_ptr<netgen::STLGeometry> geometry
    (
        reinterpret_cast<netgen::STLGeometry*>(nglib::Ng_STL_NewGeometry())
    );
    nglib::Ng_STL_Geometry* geo =
        reinterpret_cast<nglib::Ng_STL_Geometry*>(geometry.get());

    // Ng_STL_AddTriangle appends to a file-global buffer that only
    // Ng_STL_InitSTLGeometry empties: nothing in between may throw.
    // Triangles are expected with positive (outward) orientation.
    for (const triVerts& t : triangles)
    {
        double p[3][3];
        for (int k = 0; k < 3; ++k)
        {
            for (int j = 0; j < 3; ++j)
            {
                p[k][j] = points[t[k]][j];
            }
        }
        const vector3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        double nv[3] = {n[0], n[1], n[2]};
        nglib::Ng_STL_AddTriangle(geo, p[0], p[1], p[2], nv);
    }

    nglib::Ng_Result rc = nglib::NG_OK;
    try
    {
        rc = nglib::Ng_STL_InitSTLGeometry(geo);
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg()
                << "Netgen cannot read " << what << ": " << exceptionText(e)
                << session.tail(),
            function
        );
    }
    if (rc != nglib::NG_OK)
    {
        throw FatalError
        (
            msg()
                << "Netgen rejects " << what << " (its STL check failed,"
                << " code " << int(rc) << ")" << session.tail(),
            function
        );
    }
    return geometry;
}


//- Add feature edges, as edges Netgen's surface mesh must follow
//  (without them it ignores, e.g., the boundary between two coplanar
//  solids). Quirk: not through Ng_STL_AddEdge: its file-global buffer is
//  never emptied, so every later geometry would get this one's edges too,
//  fail to find their points and then drop all of its own edges. Init
//  does exactly this call with that buffer.
void addFeatureEdges
(
    netgen::STLGeometry& geometry,
    const std::vector<point3>& points,
    const std::vector<std::array<label, 2>>& featureEdges,
    const netgenSession& session,
    const std::string& what
)
{
    const char* function = stlFunction;
    netgen::Array<netgen::Point<3>> ends;
    for (const auto& e : featureEdges)
    {
        for (label v : e)
        {
            ends.Append(netgen::Point<3>(points[v][0], points[v][1], points[v][2]));
        }
    }
    geometry.AddEdges(ends);

    // AddEdges reports unmatched end points only by printing, and then
    // adds no edge at all
    const std::string out = session.output();
    if
    (
        out.find("edgepoint does not exist") != std::string::npos
     || out.find("too much points") != std::string::npos
    )
    {
        throw FatalError
        (
            msg()
                << "Netgen did not accept the feature edges of " << what
                << " (points closer than 1e-10 of its size?)"
                << session.tail(),
            function
        );
    }
}


//- Netgen's edges, surface and (unless surfaceOnly) volume mesh of geo in
//  mesh, reported while it works and stopped at the time limit.
void meshStl
(
    nglib::Ng_STL_Geometry* geo,
    nglib::Ng_Mesh* mesh,
    const meshParameters& parameters,
    const netgenSession& session,
    const std::string& what
)
{
    const char* function = stlFunction;

    nglib::Ng_Meshing_Parameters mp;
    mp.maxh = parameters.maxh;
    mp.grading = parameters.grading;
    mp.optsteps_3d = parameters.optimisationSteps;

    const char* step = "finding edges";
    progressReport progress
    (
        session.console(), coarseProgressInterval,
        reinterpret_cast<const netgen::Mesh*>(mesh), parameters.timeLimit
    );
    // Netgen stopped by the time limit returns as if it had finished
    auto checkTime = [&]()
    {
        if (progress.timedOut())
        {
            throw stlMeshingTimeout
            (
                msg()
                    << "Netgen did not finish " << step << " of " << what
                    << " within " << parameters.timeLimit << " s",
                function,
                "stopped at the time limit of " + secondsString(parameters.timeLimit)
              + " while " + progress.taskAtTimeout()
            );
        }
    };
    try
    {
        progress.step(step);
        nglib::Ng_STL_MakeEdges(geo, mesh, &mp);
        checkTime();

        // Ng_STL_MakeEdges creates the local size tree (with grading 0.3,
        // whatever mp.grading says) and builds the charts; lines and
        // surface are meshed in Ng_STL_GenerateSurfaceMesh, from the tree
        // as restricted here
        restrictLocalSizes(*reinterpret_cast<netgen::Mesh*>(mesh), parameters);

        step = "meshing the surface";
        progress.step(step);
        nglib::Ng_STL_GenerateSurfaceMesh(geo, mesh, &mp);
        checkTime();

        // Always NG_OK: count the triangles instead
        if (nglib::Ng_GetNSE(mesh) == 0)
        {
            throw stlMeshingFailure
            (
                msg()
                    << "Netgen failed to mesh the surface of " << what
                    << " (maxCellSize " << parameters.maxh << "): no surface"
                    << " triangles" << session.tail(),
                function,
                "meshing the surface: no surface triangles"
            );
        }

        if (!parameters.surfaceOnly)
        {
            step = "meshing the volume";
            progress.step(step);
            nglib::Ng_GenerateVolumeMesh(mesh, &mp);
            checkTime();
        }
    }
    catch (const FatalError&)
    {
        throw;
    }
    catch (const std::exception& e)
    {
        // What Netgen throws once told to stop is not the reason
        checkTime();
        // E.g. "Stop meshing since boundary mesh is overlapping": the
        // surface mesh's chords of a thin curved wall cross the other side
        // (stlGeometry retries with smaller sizes)
        throw stlMeshingFailure
        (
            msg()
                << "Netgen failed " << step << " of " << what
                << " (maxCellSize " << parameters.maxh << "): "
                << exceptionText(e) << session.tail(),
            function,
            std::string(step) + ": " + exceptionText(e)
        );
    }
}


//- The mesh Netgen made, as a checked volumeMesh.
volumeMesh readStlMesh
(
    nglib::Ng_Mesh* mesh,
    const meshParameters& parameters,
    const netgenSession& session,
    const std::string& what
)
{
    const char* function = stlFunction;

    // Always NG_OK: count the tets instead
    if (!parameters.surfaceOnly && nglib::Ng_GetNE(mesh) == 0)
    {
        throw stlMeshingFailure
        (
            msg()
                << "Netgen failed to mesh the volume of " << what
                << " (maxCellSize " << parameters.maxh << "): no tets"
                << session.tail(),
            function,
            "meshing the volume: no tets"
        );
    }

    volumeMesh m;
    readNglibMesh(mesh, m, what);

    // Every STL face descriptor has DomainIn 1 and DomainOut 0, so the
    // surface triangles already point out of the domain (checkBoundary
    // below verifies it against the tets)
    const int nse = nglib::Ng_GetNSE(mesh);
    m.boundary.resize(nse);
    for (int i = 1; i <= nse; ++i)
    {
        int pi[NG_SURFACE_ELEMENT_MAXPOINTS];
        if (nglib::Ng_GetSurfaceElement(mesh, i, pi) != nglib::NG_TRIG)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a surface element that is not a"
                    << " triangle when meshing " << what,
                function
            );
        }
        m.boundary[i - 1] = {{pi[0] - 1, pi[1] - 1, pi[2] - 1}, 1, -1};
    }
    m.bcNames[1] = "default";

    compactPoints(m);
    if (!parameters.surfaceOnly)
    {
        makeTetsPositive(m, what);
        checkBoundary(m, what);
    }

    return m;
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * STL coarse mesh  * * * * * * * * * * * * * //

pmsh::ng::volumeMesh pmsh::ng::stlVolumeMesh
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<std::array<label, 2>>& featureEdges,
    const meshParameters& parameters,
    const std::string& what
)
{
    netgenSession session;

    // stlparam (edge angles, curvature-based size restrictions) is at its
    // defaults (netgenSession): yangle 30 degrees, as stlGeometry's
    // featureAngle; our feature edges are passed as user edges anyway
    std::unique_ptr<netgen::STLGeometry> geometry =
        newStlGeometry(points, triangles, session, what);
    if (!featureEdges.empty())
    {
        addFeatureEdges(*geometry, points, featureEdges, session, what);
    }

    nglibMeshGuard guard(nglib::Ng_NewMesh());
    meshStl
    (
        reinterpret_cast<nglib::Ng_STL_Geometry*>(geometry.get()),
        guard.mesh, parameters, session, what
    );
    return readStlMesh(guard.mesh, parameters, session, what);
}


// ************************************************************************* //
