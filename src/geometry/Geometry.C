/*---------------------------------------------------------------------------*\
  pmshFoam: Geometry::New, dispatch on the file extension.
\*---------------------------------------------------------------------------*/

#include "Geometry.H"
#include "csgGeometry.H"
#include "stlGeometry.H"
#include "pmshError.H"

#include <algorithm>
#include <cctype>

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


// ************************************************************************* //
