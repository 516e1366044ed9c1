/*---------------------------------------------------------------------------*\
  pmshFoam: Geometry::New, selection by the files' types (OpenFOAM's
  run-time selection table, which each geometry type adds itself to).
\*---------------------------------------------------------------------------*/

#include "Geometry.H"
#include "pmshError.H"
#include "surfaceFiles.H"

#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    defineTypeNameAndDebug(Geometry, 0);
    defineRunTimeSelectionTable(Geometry, extension);
}


// * * * * * * * * * * * * * * * * Selectors  * * * * * * * * * * * * * * * //

std::unique_ptr<pmsh::Geometry> pmsh::Geometry::New
(
    const std::vector<std::string>& fileNames,
    const domainBox& domain
)
{
    const char* function = "pmsh::Geometry::New";
    const std::string valid = validGeometryFiles();
    if (fileNames.empty())
    {
        throw FatalError("No geometry file given.\n" + valid, function);
    }
    const std::string csgFile = csgFileOf(fileNames);
    for (const std::string& f : fileNames)
    {
        if (surfaceFileType(f) != "geo" && !canReadSurfaceFile(f))
        {
            throw FatalError
            (
                msg() << "Unknown geometry file type \"" << f << "\""
                    << (surfaceFileType(f).empty() ? " (no extension)" : "")
                    << ".\n" << valid,
                function
            );
        }
    }
    if (!csgFile.empty() && fileNames.size() > 1)
    {
        throw FatalError
        (
            msg() << "The Netgen CSG file \"" << csgFile << "\" cannot be meshed"
                << " with other files: a CSG geometry is one file.\n" << valid,
            function
        );
    }
    if (!csgFile.empty() && domain.given)
    {
        throw FatalError
        (
            msg() << "A domain box cannot be given with the Netgen CSG file \""
                << csgFile << "\": a CSG geometry makes its own domain (box and"
                << " not body)",
            function
        );
    }
    const word key(csgFile.empty() ? "surface" : "geo");
    if (!extensionConstructorTablePtr_ || !extensionConstructorTablePtr_->found(key))
    {
        throw FatalError("No geometry type '" + key + "' is linked in", function);
    }
    return (*extensionConstructorTablePtr_)[key](fileNames, domain);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::CoarseMesh pmsh::Geometry::localSizedMesh
(
    const coarseMeshParameters& parameters,
    bool surfaceOnly
) const
{
    if (!parameters.patchMaxCellSize)
    {
        return netgenMesh(parameters, surfaceOnly);
    }

    // The first surface mesh needs no patch or gap sizes, only the patches
    coarseMeshParameters first = parameters;
    first.patchMaxCellSize = nullptr;
    first.sizePoints.clear();
    first.cellsAcrossGap = 0;
    const CoarseMesh surface = netgenMesh(first, true);

    std::vector<double> patchSize(surface.patches.size());
    for (std::size_t p = 0; p < patchSize.size(); ++p)
    {
        patchSize[p] = parameters.patchMaxCellSize(surface.patches[p].name);
    }

    coarseMeshParameters sized = parameters;
    for (const coarseBoundaryFace& f : surface.boundary)
    {
        const double h = patchSize[f.patch];
        if (!(h > 0 && h < parameters.maxCellSize))
        {
            continue;
        }
        // Netgen's triangles are chords of curved surfaces: their
        // subdivision is projected back onto the face's surface
        sampleTriangle
        (
            surface.points[f.v[0]], surface.points[f.v[1]],
            surface.points[f.v[2]], h,
            [&](const point3& x)
            {
                sized.sizePoints.push_back({projectToSurface(x, f.surface), h});
            }
        );
    }
    return netgenMesh(sized, surfaceOnly);
}


pmsh::CoarseMesh pmsh::Geometry::remeshedSurface(const coarseMeshParameters&) const
{
    throw FatalError
    (
        "coarseSurface remesh is for surface files: Netgen makes the coarse"
        " surface of a CSG geometry",
        "pmsh::Geometry::remeshedSurface"
    );
}


// ************************************************************************* //
