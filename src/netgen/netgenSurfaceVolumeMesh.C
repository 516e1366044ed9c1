/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen's volume mesh of a closed triangulated surface, the
  per-partition mesher of stage 4 (see netgenInterface.H).

  Netgen quirk handled here: when the advancing front fails after the
  Delaunay fill ("Call remove problem"), MeshVolume leaves nearly every tet
  flagged fixed, and the volume optimisation then removes no cells
  (1.2-1.8x as many; which surfaces take that path depends on the point
  order: 1 of 7 partition surfaces at r = 3 and 3 of 96 at r = 2 in the
  tutorials): the flags are cleared before it.

  smoothInteriorPoints gives Netgen another mesher's tets; quirks there:
  Netgen's tets turn the other way (a positive tet is negative to Netgen,
  whose optimiser would take every one for inverted), and every point
  added is an inner point, yet ImproveMesh moves none of a surface
  element's points.
\*---------------------------------------------------------------------------*/

#include "netgenMeshConversion.H"
#include "pmshError.H"

namespace
{

//- Netgen's mesh of the closed surface (outward triangles) and its
//  parameters: the points in order, 1-based
void addSurface
(
    nglib::Ng_Mesh* mesh,
    const std::vector<pmsh::point3>& points,
    const std::vector<pmsh::triVerts>& triangles
)
{
    for (const pmsh::point3& x : points)
    {
        double xyz[3] = {x[0], x[1], x[2]};
        nglib::Ng_AddPoint(mesh, xyz);
    }
    for (const pmsh::triVerts& t : triangles)
    {
        // Ng_NewMesh's face descriptor has DomainIn 1, DomainOut 0:
        // triangles must point outward (right-hand rule)
        int pi[3] = {int(t[0] + 1), int(t[1] + 1), int(t[2] + 1)};
        nglib::Ng_AddSurfaceElement(mesh, nglib::NG_TRIG, pi);
    }
}


//- An element larger than the domain is meaningless, and Netgen's local
//  size tree does not need 1e300
pmsh::ng::meshParameters withinDomain
(
    const pmsh::ng::meshParameters& parameters,
    const std::vector<pmsh::point3>& points
)
{
    const double diagonal = pmsh::ng::boundingBoxDiagonal(points);
    pmsh::ng::meshParameters p = parameters;
    if (!(p.maxh < diagonal))
    {
        p.maxh = diagonal;
    }
    return p;
}

} // End anonymous namespace


// * * * * * * * * * * * * * Volume of a closed surface  * * * * * * * * * * //

pmsh::ng::volumeMesh pmsh::ng::surfaceVolumeMesh
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const meshParameters& parameters,
    const std::string& what
)
{
    const char* function = "pmsh::ng::surfaceVolumeMesh";
    const label nPoints = label(points.size());
    const meshParameters p = withinDomain(parameters, points);

    netgenSession session;

    nglibMeshGuard guard(nglib::Ng_NewMesh());
    nglib::Ng_Mesh* mesh = guard.mesh;
    addSurface(mesh, points, triangles);

    // Transfer_Parameters copies these into the global netgen::mparam;
    // fineness, closeedge*, minedgelen* and opt*meshenable are ignored
    nglib::Ng_Meshing_Parameters mp;
    mp.maxh = p.maxh;
    mp.grading = p.grading;
    mp.optsteps_3d = p.optimisationSteps;

    try
    {
        // Ng_GenerateVolumeMesh's steps, with the fixed flags cleared
        // before the optimisation. Failures are exceptions, e.g. "Stop
        // meshing since surface mesh not consistent" (open or badly
        // oriented) or "Stop meshing since too many attempts" (inverted)
        mp.Transfer_Parameters();
        netgen::Mesh& volume = *reinterpret_cast<netgen::Mesh*>(mesh);
        volume.CalcLocalH(netgen::mparam.grading);
        restrictLocalSizes(volume, p);
        netgen::MeshVolume(netgen::mparam, volume);
        netgen::RemoveIllegalElements(volume);
        for (netgen::Element& tet : volume.VolumeElements())
        {
            // Quirk: left set by MeshVolume's failure path ("Call remove
            // problem": FreeOpenElementsEnvironment), they stop the
            // optimiser from touching the tet
            tet.flags.fixed = false;
        }
        netgen::OptimizeVolume(netgen::mparam, volume);
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what << " ("
                << nPoints << " points, " << triangles.size()
                << " triangles): " << exceptionText(e) << session.tail(),
            function
        );
    }
    catch (...)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what
                << " with an unknown exception" << session.tail(),
            function
        );
    }

    // Ng_GenerateVolumeMesh's steps report no failure but an empty mesh
    if (nglib::Ng_GetNE(mesh) == 0)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what << ": no tets"
                << session.tail(),
            function
        );
    }

    // The contract (surface points kept in place and in order, the surface
    // triangles faces of the tets) is VolumeMesher::mesh's to check
    volumeMesh m;
    readNglibMesh(mesh, m, what);
    makeTetsPositive(m, what);

    return m;
}

// * * * * * * * * * * * Another mesher's tets smoothed  * * * * * * * * * * //

void pmsh::ng::smoothInteriorPoints
(
    std::vector<point3>& points,
    const std::vector<tetVerts>& tets,
    const std::vector<triVerts>& triangles,
    const meshParameters& parameters,
    const std::string& what
)
{
    const meshParameters p = withinDomain(parameters, points);

    netgenSession session;

    nglibMeshGuard guard(nglib::Ng_NewMesh());
    nglib::Ng_Mesh* mesh = guard.mesh;
    addSurface(mesh, points, triangles);
    for (const tetVerts& t : tets)
    {
        // Quirk: turned for Netgen (a positive tet is inverted to it)
        int pi[4] = {int(t[0] + 1), int(t[2] + 1), int(t[1] + 1), int(t[3] + 1)};
        nglib::Ng_AddVolumeElement(mesh, nglib::NG_TET, pi);
    }

    nglib::Ng_Meshing_Parameters mp;
    mp.maxh = p.maxh;
    mp.grading = p.grading;
    try
    {
        mp.Transfer_Parameters();
        netgen::Mesh& volume = *reinterpret_cast<netgen::Mesh*>(mesh);
        volume.CalcLocalH(netgen::mparam.grading);
        restrictLocalSizes(volume, p);
        // What OptimizeVolume does for optimize3d "m" and one step, less
        // its quality report: ImproveMesh's OPT_QUALITY goal only adds
        // three sums of every tet's badness for its log (the points move
        // alike), and MeshQuality3d a histogram of them
        volume.CalcSurfacesOfNode();
        volume.ImproveMesh(netgen::mparam, netgen::OPT_REST);
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg() << "Netgen failed to smooth the volume mesh of " << what << ": "
                << exceptionText(e) << session.tail(),
            "pmsh::ng::smoothInteriorPoints"
        );
    }

    // Netgen keeps the points in order and the tets as they were: only
    // the points come back
    const std::vector<point3> before = points;
    for (std::size_t i = 0; i < points.size(); ++i)
    {
        double xyz[3];
        nglib::Ng_GetPoint(mesh, int(i) + 1, xyz);
        points[i] = point3{xyz[0], xyz[1], xyz[2]};
    }

    // ImproveMesh's badness is infinite on an inverted tet, so it should
    // invert none; the points of one that it did go back, until none is
    for (bool reverted = true; reverted; )
    {
        reverted = false;
        for (const tetVerts& t : tets)
        {
            if (!(tetVolume6(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) > 0))
            {
                for (const label v : t)
                {
                    reverted = reverted || points[v] != before[v];
                    points[v] = before[v];
                }
            }
        }
    }
}

// ************************************************************************* //
