/*---------------------------------------------------------------------------*\
  pmshFoam: surface files read by OpenFOAM's triSurface (see
  surfaceFiles.H). The only file that includes triSurface.H: ESI has it in
  libsurfMesh, the Foundation in libtriSurface (Make/options picks one).

  Quirks handled here:
  - ESI lists the types it reads (triSurface::readTypes()); the Foundation's
    reader has them in an if-chain, so its list is written out below.
  - Triangles outside any named group get a default region name from the
    reader ("zone0" from ESI's OBJ reader, "patch0" from triSurface's
    default patches): such regions take the file's stem.
  - triSurface stops the process on a bad file (FatalError): here it
    throws, and the message names the file.
  - Given "body.obj.gz", triSurface reads "body.obj" when that exists
    (OpenFOAM's IFstream prefers the uncompressed copy), and it knows
    extensions in lower case only ("body.OBJ" is refused): such files are
    copied (decompressed) here into a scratch file that triSurface reads.
  - triSurface does not check that a triangle's points exist (an OBJ face
    "f 1 2 3" after one "v" line reads beyond the points): checked here.
\*---------------------------------------------------------------------------*/

#include "surfaceFiles.H"
#include "surfaceBuilder.H"
#include "pmshError.H"
#include "foamShims.H"

#include "triSurface.H"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- A region name a reader makes up for triangles outside any named group.
bool defaultRegionName(const std::string& name)
{
    static const std::regex made("(patch|zone|region)[0-9]+");
    return name.empty() || std::regex_match(name, made);
}

//- A file in a scratch directory of its own, removed with it.
class scratchCopy
{
    std::filesystem::path dir_;
    std::filesystem::path path_;

public:

    scratchCopy(const std::string& bytes, const std::string& name)
    {
        std::string dir =
            (std::filesystem::temp_directory_path() / "pmshFoam-surface-XXXXXX").string();
        if (!mkdtemp(dir.data()))
        {
            throw FatalError
            (
                "Cannot make a scratch directory in " + std::filesystem::temp_directory_path().string()
              + " to decompress \"" + name + "\" (set TMPDIR to a writable directory)",
                "pmsh::readFoamSurface"
            );
        }
        dir_ = dir;
        path_ = dir_ / name;
        std::ofstream os(path_, std::ios::binary);
        os.write(bytes.data(), std::streamsize(bytes.size()));
        if (!os.good())
        {
            std::error_code ec;
            std::filesystem::remove_all(dir_, ec);
            throw FatalError
            (
                "Cannot write the decompressed copy " + path_.string()
              + " (is the disk full? set TMPDIR elsewhere)",
                "pmsh::readFoamSurface"
            );
        }
    }

    ~scratchCopy()
    {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }

    scratchCopy(const scratchCopy&) = delete;
    scratchCopy& operator=(const scratchCopy&) = delete;

    std::string path() const { return path_.string(); }
};

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

std::vector<std::string> pmsh::foamSurfaceTypes()
{
    std::vector<std::string> types;
    #if PMSH_FOAM_ESI
    for (const Foam::word& t : Foam::triSurface::readTypes().sortedToc())
    {
        types.push_back(t);
    }
    #else
    types = {"ac", "ftr", "gts", "nas", "obj", "off", "stl", "stlb", "tri", "vtk"};
    #endif
    return types;
}


pmsh::stlSurface pmsh::readFoamSurface(const std::string& fileName)
{
    const std::string type = surfaceFileType(fileName);
    Foam::autoPtr<Foam::triSurface> read;
    try
    {
        const foamErrorsThrow throwing;
        const std::string ext = fileName.substr(fileName.find_last_of('.') + 1);
        if (isGzipped(fileName) || ext != type)
        {
            const scratchCopy copy(fileBytes(fileName, type), fileStem(fileName) + "." + type);
            read.reset(new Foam::triSurface(Foam::fileName(copy.path())));
        }
        else
        {
            read.reset(new Foam::triSurface(Foam::fileName(fileName)));
        }
    }
    catch (const Foam::error& e)
    {
        throw FatalError
        (
            msg() << "Cannot read " << type << " file \"" << fileName << "\" with"
                << " OpenFOAM's triSurface:\n" << FatalError::of(e).message(),
            "pmsh::readFoamSurface"
        );
    }
    const Foam::triSurface& surf = read();
    if (surf.empty())
    {
        throw FatalError
        (
            msg() << "Surface file \"" << fileName << "\" is empty: it contains"
                << " no triangles",
            "pmsh::readFoamSurface"
        );
    }

    std::string stem = sanitise(fileStem(fileName));
    if (stem.empty())
    {
        stem = type;
    }

    stlSurface s;
    surfaceBuilder builder(s, stem);
    const Foam::geometricSurfacePatchList& regions = surf.patches();
    std::vector<label> solidOf(regions.size(), -1);
    const Foam::pointField& points = surf.points();
    auto point = [&](Foam::label i)
    {
        return point3{points[i].x(), points[i].y(), points[i].z()};
    };
    for (const Foam::labelledTri& t : surf)
    {
        for (const Foam::label v : t)
        {
            if (v < 0 || v >= points.size())
            {
                throw FatalError
                (
                    msg() << "Surface file \"" << fileName << "\": triangle "
                        << s.nTriangles() << " names point " << v + 1 << " (counting"
                        << " from 1) but the file has " << points.size() << " points",
                    "pmsh::readFoamSurface"
                );
            }
        }
        const Foam::label r = t.region();
        if (r >= Foam::label(solidOf.size()))
        {
            solidOf.resize(r + 1, -1);
        }
        if (solidOf[r] < 0)
        {
            const std::string name =
                r < regions.size() ? std::string(regions[r].name()) : std::string();
            solidOf[r] = builder.addSolid(defaultRegionName(name) ? stem : name);
        }
        builder.addTriangle(point(t[0]), point(t[1]), point(t[2]), solidOf[r]);
    }
    return s;
}


// ************************************************************************* //
