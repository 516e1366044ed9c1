/*---------------------------------------------------------------------------*\
  pmshFoam: reading the geometry's surface files (see surfaceFiles.H).
\*---------------------------------------------------------------------------*/

#include "surfaceFiles.H"
#include "surfaceBuilder.H"
#include "pmshError.H"

#include <algorithm>
#include <cctype>

// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

std::string pmsh::surfaceFileType(const std::string& fileName)
{
    std::string name = fileName.substr(fileName.find_last_of('/') + 1);
    if (isGzipped(name))
    {
        name.resize(name.size() - 3);
    }
    const std::size_t dot = name.find_last_of('.');
    if (dot == std::string::npos || dot == 0)
    {
        return "";
    }
    std::string type = name.substr(dot + 1);
    for (char& c : type)
    {
        c = char(std::tolower(static_cast<unsigned char>(c)));
    }
    return type;
}


std::string pmsh::csgFileOf(const std::vector<std::string>& fileNames)
{
    for (const std::string& f : fileNames)
    {
        if (surfaceFileType(f) == "geo")
        {
            return f;
        }
    }
    return {};
}


bool pmsh::canReadSurfaceFile(const std::string& fileName)
{
    const std::string type = surfaceFileType(fileName);
    if (type == "stl")
    {
        return true;
    }
    const std::vector<std::string> types = foamSurfaceTypes();
    return !type.empty() && std::find(types.begin(), types.end(), type) != types.end();
}


std::string pmsh::readableSurfaceTypes()
{
    std::vector<std::string> types = foamSurfaceTypes();
    types.push_back("stl");
    std::sort(types.begin(), types.end());
    types.erase(std::unique(types.begin(), types.end()), types.end());
    std::string list;
    for (const std::string& t : types)
    {
        list += (list.empty() ? "." : ", .") + t;
    }
    return list;
}


std::string pmsh::validGeometryFiles()
{
    return
        "Valid geometry files are: .geo (Netgen CSG), or surface files "
      + readableSurfaceTypes() + ", in any letter case and gzip-compressed"
        " too (.stl.gz, .obj.gz, ...)";
}


pmsh::stlSurface pmsh::readSurfaceFile(const std::string& fileName)
{
    // STL by pmshFoam's own reader: triSurface's keeps single precision
    return surfaceFileType(fileName) == "stl" ? readStl(fileName) : readFoamSurface(fileName);
}


pmsh::stlSurface pmsh::readSurfaceFiles(const std::vector<std::string>& fileNames)
{
    if (fileNames.size() == 1)
    {
        return readSurfaceFile(fileNames[0]);
    }
    stlSurface merged;
    surfaceBuilder builder(merged, "");
    std::vector<std::size_t> fileOfSolid;       // per merged solid
    for (std::size_t f = 0; f < fileNames.size(); ++f)
    {
        const stlSurface s = readSurfaceFile(fileNames[f]);
        std::vector<label> solidIndex(s.solidNames.size());
        for (std::size_t i = 0; i < s.solidNames.size(); ++i)
        {
            const std::string& name = s.solidNames[i];
            const auto seen =
                std::find(merged.solidNames.begin(), merged.solidNames.end(), name);
            if (seen != merged.solidNames.end())
            {
                throw FatalError
                (
                    msg()
                        << "Surface files \""
                        << fileNames[fileOfSolid[seen - merged.solidNames.begin()]]
                        << "\" and \"" << fileNames[f] << "\" both have a patch named '"
                        << name << "'\nA patch name must come from one file: rename the"
                        << " solid, group or region in one of them, or rename a file"
                        << " whose patch takes its name",
                    "pmsh::readSurfaceFiles"
                );
            }
            solidIndex[i] = builder.addSolid(name);
            fileOfSolid.push_back(f);
        }
        for (label t = 0; t < s.nTriangles(); ++t)
        {
            const triVerts& v = s.triangles[t];
            builder.addTriangle
            (
                s.points[v[0]], s.points[v[1]], s.points[v[2]], solidIndex[s.solid[t]]
            );
        }
    }
    return merged;
}


std::string pmsh::describeSurfaceFiles(const std::vector<std::string>& fileNames)
{
    if (fileNames.size() == 1)
    {
        std::string type = surfaceFileType(fileNames[0]);
        for (char& c : type)
        {
            c = char(std::toupper(static_cast<unsigned char>(c)));
        }
        return (type.empty() ? "surface" : type) + " file \"" + fileNames[0] + "\"";
    }
    std::string text = "surface files";
    for (std::size_t f = 0; f < fileNames.size(); ++f)
    {
        text += f == 0 ? " " : f + 1 < fileNames.size() ? ", " : " and ";
        text += "\"" + fileNames[f] + "\"";
    }
    return text;
}


// ************************************************************************* //
