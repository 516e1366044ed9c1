/*---------------------------------------------------------------------------*\
  pmshFoam: Geometry::New, dispatch on the file extension.
\*---------------------------------------------------------------------------*/

#include "Geometry.H"
#include "csgGeometry.H"
#include "stlGeometry.H"
#include "pmshError.H"

#include <algorithm>
#include <cctype>
#include <cmath>

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

    if (ext == "geo")
    {
        return std::unique_ptr<Geometry>(new csgGeometry(fileName));
    }
    if (ext == "stl")
    {
        return std::unique_ptr<Geometry>(new stlGeometry(fileName));
    }

    throw FatalError
    (
        msg()
            << "Unknown geometry file type \"" << fileName << "\""
            << (ext.empty() ? " (no extension)" : "") << ".\nValid extensions:"
            << "\n    .geo    Netgen CSG (algebraic3d)"
            << "\n    .stl    STL, ascii or binary (case-insensitive)",
        "pmsh::Geometry::New"
    );
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
