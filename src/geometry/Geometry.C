/*---------------------------------------------------------------------------*\
  pmshFoam: Geometry::New, selection by the file extension (OpenFOAM's
  run-time selection table, which each geometry type adds itself to).
\*---------------------------------------------------------------------------*/

#include "Geometry.H"
#include "pmshError.H"

#include <algorithm>
#include <cctype>
#include <cmath>

// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    defineTypeNameAndDebug(Geometry, 0);
    defineRunTimeSelectionTable(Geometry, extension);
}


// * * * * * * * * * * * * * * * * Selectors  * * * * * * * * * * * * * * * //

std::unique_ptr<pmsh::Geometry> pmsh::Geometry::New(const std::string& fileName)
{
    // Extension of the file name (not of a directory), lower case
    const std::size_t slash = fileName.find_last_of('/');
    const std::size_t dot = fileName.find_last_of('.');
    std::string ext;
    if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
    {
        ext = fileName.substr(dot + 1);
    }
    std::transform
    (
        ext.begin(), ext.end(), ext.begin(),
        [](unsigned char c) { return char(std::tolower(c)); }
    );

    const word key(ext, false);
    if (!extensionConstructorTablePtr_ || !extensionConstructorTablePtr_->found(key))
    {
        msg m;
        m   << "Unknown geometry file type \"" << fileName << "\""
            << (ext.empty() ? " (no extension)" : "") << ".\nValid extensions:";
        if (extensionConstructorTablePtr_)
        {
            for (const word& valid : extensionConstructorTablePtr_->sortedToc())
            {
                m   << "\n    ." << valid;
            }
        }
        throw FatalError(m, "pmsh::Geometry::New");
    }
    return (*extensionConstructorTablePtr_)[key](fileName);
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

    // The first surface mesh needs no patch sizes, only the patches
    coarseMeshParameters first = parameters;
    first.patchMaxCellSize = nullptr;
    first.sizePoints.clear();
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


// ************************************************************************* //
