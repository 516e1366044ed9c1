#include "meshSettings.H"
#include "dictEntries.H"
#include "foamShims.H"
#include "VolumeMesher.H"
#include "layerSpecification.H"
#include "surfaceFiles.H"
#include "Geometry.H"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <limits>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

namespace pmsh
{

namespace
{

using Foam::dictionary;
using Foam::entry;

const char* const where = "pmsh::readMeshSettings";

// Every entry is read and checked the one way (dictEntries.H)
const entryChecks check(where);


//- Stop at the first entry of sub (a sub-dictionary of d, of owner) not
//  among valid: "Unknown entry 'x' in <owner>. Did you mean ...?", then
//  validText, at the entry's line.
void rejectUnknownEntries
(
    const dictionary& d,
    const dictionary& sub,
    const std::vector<std::string>& valid,
    const std::string& owner,
    const std::string& validText
)
{
    for (const entry& x : sub)
    {
        if (!containsWord(valid, x.keyword()))
        {
            check.error(d, x)
                << "Unknown entry '" << x.keyword().c_str() << "' in " << owner.c_str()
                << '.' << didYouMean(x.keyword(), valid).c_str() << '\n'
                << validText.c_str() << Foam::exit(Foam::FatalIOError);
        }
    }
}


//- What is wrong with the geometry file at path, or "".
std::string geometryFileProblem(const std::string& path, const std::string& caseDir)
{
    const std::string type = surfaceFileType(path);
    std::error_code ec;
    if (type != "geo" && !canReadSurfaceFile(path))
    {
        return
            (type.empty()
           ? std::string("the file name has no extension")
           : "the file type '." + type + "' is not supported")
          + "\n" + validGeometryFiles();
    }
    if (!fs::exists(path, ec))
    {
        return
            "the file \"" + path + "\" does not exist\n"
            "Relative names are relative to the case directory \""
          + caseDir + "\"";
    }
    if (!fs::is_regular_file(path, ec))
    {
        return "\"" + path + "\" is not a regular file";
    }
    std::ifstream probe(path, std::ios::binary);
    if (!probe || probe.peek() == std::ifstream::traits_type::eof())
    {
        return
            "the file \"" + path + "\" "
          + (probe ? "is empty" : "cannot be read (check its permissions)");
    }
    return "";
}


//- The geometry: one file name, or a list of surface files, each checked
//  to exist and be of a type that can be read.
std::vector<std::string> readGeometry(const dictionary& d, const std::string& caseDir)
{
    const char* const validFiles =
        "Valid geometry: one .geo (Netgen CSG) file, or one or more surface files"
        " (STL, OBJ, VTK, ...), e.g.\n"
        "    geometry \"constant/geometry/body.stl\";\n"
        "    geometry (\"constant/geometry/box.stl\" \"constant/geometry/body.obj.gz\");";
    const entry* e = foam::findEntry(d, "geometry");
    if (!e)
    {
        check.error(d, "geometry")
            << "Entry 'geometry' not found\n"
            << "Set it to the geometry file, relative to the case directory\n"
            << validFiles << Foam::exit(Foam::FatalIOError);
    }

    // A string, or a list of strings in parentheses
    std::vector<std::string> names;
    if (!stringList(*e, names, true) || names.empty())
    {
        check.invalid
        (
            d, *e,
            "geometry must be a file name in quotes, or a list of them in"
            " parentheses, relative to the case directory\n"
          + std::string(validFiles)
        );
    }

    std::vector<std::string> paths;
    for (const std::string& name : names)
    {
        const std::string path = casePath(caseDir, name);
        std::string problem = geometryFileProblem(path, caseDir);
        if (problem.empty() && std::find(paths.begin(), paths.end(), path) != paths.end())
        {
            problem = "it is given twice";
        }
        if (problem.empty() && names.size() > 1 && surfaceFileType(path) == "geo")
        {
            problem =
                "a Netgen CSG geometry is one file: it cannot be meshed with"
                " other files";
        }
        if (!problem.empty())
        {
            check.error(d, *e)
                << "Entry 'geometry'"
                << (names.size() > 1 ? ": file \"" : " is \"") << name.c_str()
                << "\": " << problem.c_str() << Foam::exit(Foam::FatalIOError);
        }
        paths.push_back(path);
    }
    return paths;
}


//- A box's corners min and max of d (owned by owner), every component of
//  max above min's; context names the entry's owner in the message
//  (" of 'domain'").
void readBoxCorners
(
    const dictionary& d,
    const std::string& owner,
    point3& min,
    point3& max,
    const std::string& context = ""
)
{
    min = check.point(d, "min", owner);
    max = check.point(d, "max", owner);
    for (int k = 0; k < 3; ++k)
    {
        if (!(min[k] < max[k]))
        {
            check.invalid
            (
                d, *foam::findEntry(d, "max"),
                "Every component of 'max' of " + owner + " must be larger than"
                " that of 'min'", " (not above min)", context
            );
        }
    }
}


//- The domain box (domainBox.H): type box, min < max, patches naming
//  its sides (xMin, ..., default) with words, how dirty bodies are
//  wrapped (by default at the finest cell size).
domainBox readDomain
(
    const dictionary& d,
    const entry& e,
    const std::vector<std::string>& files,
    const double finestCellSize
)
{
    const std::string owner = "'domain'";
    const std::vector<std::string> entries
    {"type", "min", "max", "patches", "wrap", "wrapSize", "wrapOffset", "plinthHeight"};
    std::vector<std::string> sideKeys(domainBox::sides.begin(), domainBox::sides.end());
    sideKeys.push_back("default");
    const std::string example =
        "e.g. domain { type box; min (-5 -4 0); max (15 4 8);"
        " patches { xMin inlet; xMax outlet; default sides; } }";
    if (!e.isDict())
    {
        check.invalid(d, e, "domain must be a dictionary, " + example);
    }
    const dictionary& dd = e.dict();
    rejectUnknownEntries(d, dd, entries, owner, "Valid entries are: " + joinedWords(entries));
    const std::string csgFile = csgFileOf(files);
    if (!csgFile.empty())
    {
        check.error(d, e)
            << "Entry 'domain' is for surface files, not the Netgen CSG file \""
            << csgFile.c_str() << "\": a CSG geometry makes its own domain (box and not"
            << " body). Remove 'domain'" << Foam::exit(Foam::FatalIOError);
    }
    check.require(dd, "type", owner, "Valid types: box; " + example);
    const entry* t = foam::findEntry(dd, "type");
    const Foam::token* tok = singleToken(*t);
    if (!tok || !foam::isStringType(*tok) || foam::stringToken(*tok) != "box")
    {
        check.invalid(dd, *t, "Valid types: box", "", " of " + owner);
    }

    domainBox box;
    box.given = true;
    readBoxCorners(dd, owner, box.min, box.max, " of " + owner);
    box.wrap = check.choice
    (
        dd, "wrap", box.wrap,
        std::vector<std::string>(domainBox::wrapModes.begin(), domainBox::wrapModes.end())
    );
    box.wrapSize = check.bounded
    (
        dd, "wrapSize", finestCellSize, aboveZero, std::numeric_limits<double>::max(), false,
        "wrapSize of " + owner + " must be a number > 0: no gap narrower than it"
        " is kept when a body is wrapped (default: the finest cell size asked for)"
    );
    // Not CGAL's usual alpha/30: a thin part wraps into a slab 2 offsets
    // thick, whose rims Netgen's coarse surface cannot follow. OpenFOAM's
    // wigley hull (a half hull, wrapSize 0.0125): at /30 the coarse
    // surface overlapped itself, at /4 it meshed with 86.8 degrees, at /2
    // with 56.9
    box.wrapOffset = check.bounded
    (
        dd, "wrapOffset", box.wrapSize/2, aboveZero, std::numeric_limits<double>::max(), false,
        "wrapOffset of " + owner + " must be a number > 0: how far outside the"
        " body its wrap lies (default wrapSize/2)"
    );
    box.plinthHeight = check.bounded
    (
        dd, "plinthHeight", 0.0, 0.0, std::numeric_limits<double>::max(), false,
        "plinthHeight of " + owner + " must be a number >= 0: bodies reaching a side"
        " stand on their section this far from it (default 0: no plinths)"
    );

    if (const entry* p = foam::findEntry(dd, "patches"))
    {
        if (!p->isDict())
        {
            check.invalid(dd, *p, "patches of " + owner + " must be a dictionary, " + example);
        }
        std::string deflt;
        for (const entry& x : p->dict())
        {
            const Foam::token* name = singleToken(x);
            if (!containsWord(sideKeys, x.keyword()))
            {
                check.error(p->dict(), x)
                    << "Unknown side '" << x.keyword().c_str() << "' in patches of "
                    << owner.c_str() << '.' << didYouMean(x.keyword(), sideKeys).c_str()
                    << "\nValid sides are: " << joinedWords(sideKeys).c_str()
                    << Foam::exit(Foam::FatalIOError);
            }
            if (!name || !foam::isStringType(*name) || foam::stringToken(*name).empty())
            {
                check.invalid(p->dict(), x, "The side's patch name, a word: " + example);
            }
            const std::string patch = foam::stringToken(*name);
            if (x.keyword() == "default")
            {
                deflt = patch;
            }
            for (std::size_t side = 0; side < domainBox::sides.size(); ++side)
            {
                if (x.keyword() == domainBox::sides[side])
                {
                    box.sideNames[side] = patch;
                }
            }
        }
        if (!deflt.empty())
        {
            for (std::size_t side = 0; side < domainBox::sides.size(); ++side)
            {
                if (!foam::findEntry(p->dict(), domainBox::sides[side]))
                {
                    box.sideNames[side] = deflt;
                }
            }
        }
    }
    return box;
}


//- A local maxCellSize in sub-dictionary sub (of entry owner): optional
//  for a patch (0 when absent), required for a region.
double localSize
(
    const dictionary& d,
    const dictionary& sub,
    const std::string& owner,
    bool required = false
)
{
    const std::string valid =
        "maxCellSize of " + owner + " must be a number > 0: the largest"
        " coarse cell size there, in the units of the geometry (a size"
        " larger than the global maxCellSize does not refine)";
    if (required)
    {
        check.require(sub, "maxCellSize", owner, valid);
    }
    return check.bounded
    (
        sub, "maxCellSize", 0, aboveZero, std::numeric_limits<double>::max(), false, valid
    );
}


//- A required number > 0 of a region (its radius).
double readPositive
(
    const dictionary& region,
    const char* key,
    const std::string& owner
)
{
    const std::string valid =
        "Entry '" + std::string(key) + "' of " + owner + " must be a number > 0";
    check.require(region, key, owner, valid);
    return check.bounded
    (
        region, key, 0, aboveZero, std::numeric_limits<double>::max(), false, valid
    );
}


//- The refinementRegions sub-dictionary: one shape per entry.
std::vector<pmsh::sizeRegion> readRegions(const dictionary& d, const entry& regionsEntry)
{
    using pmsh::sizeRegion;
    const std::vector<std::string> shapes = sizeRegion::shapeNames();
    const std::string validTypes = "Valid region types are: " + joinedWords(shapes);
    const std::string example =
        "    refinementRegions\n    {\n"
        "        wake { type box; min (0 -1 -1); max (4 1 1); maxCellSize 0.05; }\n"
        "        nose { type sphere; centre (0 0 0); radius 0.5; maxCellSize 0.02; }\n"
        "        shaft { type cylinder; point1 (0 0 0); point2 (1 0 0);"
        " radius 0.1; maxCellSize 0.02; }\n    }";
    if (!regionsEntry.isDict())
    {
        check.invalid
        (
            d, regionsEntry,
            "Expected a sub-dictionary of named regions, e.g.\n" + example
        );
    }

    std::vector<sizeRegion> regions;
    for (const entry& r : regionsEntry.dict())
    {
        const std::string owner = "region '" + r.keyword() + "'";
        if (r.keyword().isPattern() || !r.isDict())
        {
            check.invalid(d, r, "Expected '" + r.keyword() + " { type T; ... }' with T"
                " one of: " + joinedWords(shapes) + ", e.g.\n" + example);
        }
        const dictionary& rd = r.dict();
        const entry* t = foam::findEntry(rd, "type");
        if (!t)
        {
            check.error(d, r)
                << "Entry 'type' not found in " << owner.c_str() << "\n"
                << validTypes.c_str() << Foam::exit(Foam::FatalIOError);
        }
        const Foam::token* tok = singleToken(*t);
        if (!tok || !foam::isStringType(*tok) || !containsWord(shapes, foam::stringToken(*tok)))
        {
            check.invalid(rd, *t, validTypes);
        }

        sizeRegion region;
        region.name = r.keyword();
        const std::string type = foam::stringToken(*tok);
        std::vector<std::string> entries{"type", "maxCellSize"};
        if (type == "box")
        {
            region.type = sizeRegion::shape::box;
            entries.insert(entries.end(), {"min", "max"});
        }
        else if (type == "sphere")
        {
            region.type = sizeRegion::shape::sphere;
            entries.insert(entries.end(), {"centre", "radius"});
        }
        else
        {
            region.type = sizeRegion::shape::cylinder;
            entries.insert(entries.end(), {"point1", "point2", "radius"});
        }
        rejectUnknownEntries
        (
            d, rd, entries, owner,
            "Valid entries of a " + type + " are: " + joinedWords(entries)
        );

        switch (region.type)
        {
            case sizeRegion::shape::box:
                readBoxCorners(rd, owner, region.min, region.max);
                break;
            case sizeRegion::shape::sphere:
                region.centre = check.point(rd, "centre", owner);
                region.radius = readPositive(rd, "radius", owner);
                break;
            case sizeRegion::shape::cylinder:
                region.point1 = check.point(rd, "point1", owner);
                region.point2 = check.point(rd, "point2", owner);
                region.radius = readPositive(rd, "radius", owner);
                if (!(magSqr(region.point2 - region.point1) > 0))
                {
                    check.invalid
                    (
                        rd, *foam::findEntry(rd, "point2"),
                        "point1 and point2 of " + owner + " are the ends of"
                        " its axis and must differ",
                        " (the same as point1)"
                    );
                }
                break;
        }
        region.size = localSize(d, rd, owner, true);

        // The samples that restrict the coarse size are about the coarse
        // cells the region will hold: refuse what no master could mesh
        const double nSamples = region.volume()/std::pow(region.size, 3);
        if (nSamples > 1e8)
        {
            check.error(d, r)
                << "Region '" << r.keyword().c_str() << "' would hold about "
                << nSamples << " coarse cells of size " << region.size
                << " (its volume is " << region.volume() << ")\n"
                << "Use a larger maxCellSize or a smaller region"
                << Foam::exit(Foam::FatalIOError);
        }
        regions.push_back(region);
    }
    return regions;
}


void checkPatches(const dictionary& d, const entry& patchesEntry)
{
    const std::vector<std::string> types = meshSettingsPatchTypes();
    const std::string validTypes = "Valid patch types are: " + joinedWords(types);

    if (!patchesEntry.isDict())
    {
        check.invalid
        (
            d, patchesEntry,
            "Expected a sub-dictionary of patch names (or \"regular"
            " expressions\") and their types, e.g.\n"
            "    patches\n    {\n        inlet { type patch; }\n"
            "        \".*\"  { type wall; }\n    }"
        );
    }
    for (const entry& p : patchesEntry.dict())
    {
        if (!p.isDict())
        {
            check.invalid
            (
                d, p,
                "Expected '" + p.keyword() + " { type T; }' with T one of: "
              + joinedWords(types)
            );
        }
        rejectUnknownEntries
        (
            d, p.dict(), meshSettingsPatchEntries(), "patch '" + p.keyword() + "'",
            "Valid entries of a patch are: 'type' (" + joinedWords(types) + "),"
            " 'maxCellSize' (the coarse cell size on the patch), 'inGroups' (its"
            " patch groups) and the prism layers' "
          + joinedWords(layerSpecificationEntries())
        );
        localSize(d, p.dict(), "patch '" + p.keyword() + "'");
        if (const entry* g = foam::findEntry(p.dict(), "inGroups"))
        {
            std::vector<std::string> groups;
            if (!stringList(*g, groups, false))
            {
                check.invalid
                (
                    d, *g,
                    "inGroups is a list of patch group names, as OpenFOAM's"
                    " boundary file has it, e.g. inGroups (motorBikeGroup);",
                    "", " of patch '" + p.keyword() + "'"
                );
            }
        }
        readLayerSpecification(p.dict(), p.keyword());
        const entry* t = foam::findEntry(p.dict(), "type");
        if (!t)
        {
            check.error(d, p)
                << "Entry 'type' not found in patch '" << p.keyword().c_str()
                << "'\n" << validTypes.c_str()
                << Foam::exit(Foam::FatalIOError);
        }
        const Foam::token* tok = singleToken(*t);
        if (!tok || !foam::isStringType(*tok) || !containsWord(types, foam::stringToken(*tok)))
        {
            check.invalid(d, *t, validTypes);
        }
    }
}

//- Who makes the coarse surface (coarseSurfaceRoutes). Netgen's STL
//  mesher stalls on alpha wraps (the motorBike: 432 s at its time limit);
//  the surface's own triangles remeshed take seconds (surfaceRemesh.H).
std::string readCoarseSurface
(
    const dictionary& dict,
    const std::vector<std::string>& geometryFiles
)
{
    const std::string route = check.choice
    (
        dict, "coarseSurface", "auto",
        std::vector<std::string>(coarseSurfaceRoutes.begin(), coarseSurfaceRoutes.end())
    );
    if (route == "remesh" && !csgFileOf(geometryFiles).empty())
    {
        check.error(dict, "coarseSurface")
            << "coarseSurface remesh is for surface files (STL, OBJ, ...):"
            << " Netgen makes the coarse surface of a CSG geometry.\n"
            << "Valid values here are auto and netgen"
            << Foam::exit(Foam::FatalIOError);
    }
    return route;
}


//- The entries that size the coarse surface of surface files (curvature,
//  its floor, gaps) and bound the time Netgen may take on it.
void readSurfaceSizing(const Foam::dictionary& dict, meshSettings& s)
{
    // Default 3: a ball of radius 0.5 at maxCellSize 1 then gets 120
    // coarse faces from its STL (mean edge 0.24), as from CSG, where
    // Netgen always sizes by curvature (128, 0.23); with 0 or 2 it gets 70
    // (0.31), whatever the global size
    s.curvatureRefinement = check.bounded
    (
        dict, "curvatureRefinement", 3, 0, 100, false,
        "Valid values are numbers 0 <= curvatureRefinement <= 100: coarse"
        " cells per radian of STL surface curvature (0 = off)"
    );

    // The floor of curvature sizing: without one a finely tessellated
    // fillet or tip asks for cells far below maxCellSize and the coarse
    // mesh (and every level after it) blows the budget. maxCellSize/8:
    // bench/results/curvature.md
    std::ostringstream validMinCellSize;
    validMinCellSize
        << "Valid values are numbers 0 < minCellSize <= maxCellSize ("
        << s.maxCellSize << "): the smallest coarse cell size that STL"
        << " curvature sizing may ask for (default maxCellSize/8)";
    s.minCellSize = check.bounded
    (
        dict, "minCellSize", s.maxCellSize/8, aboveZero,
        s.maxCellSize, false, validMinCellSize.str()
    );

    s.cellsAcrossGap = check.bounded
    (
        dict, "cellsAcrossGap", meshSettings().cellsAcrossGap, 0, 100, false,
        "Valid values are numbers 0 <= cellsAcrossGap <= 100: coarse cells"
        " across a gap of the domain narrower than the local size (0 = off)"
    );

    // 0 (absent): from the STL's size, when it is known (stlGeometry)
    s.coarseTimeLimit = check.bounded
    (
        dict, "coarseTimeLimit", 0, aboveZero, 1e7,
        false,
        "Valid values are numbers 0 < coarseTimeLimit <= 1e7: the seconds each"
        " attempt of Netgen's STL coarse mesh may take (all attempts together"
        " twice that); without the entry, from the surface's size"
    );
}


} // End anonymous namespace


// * * * * * * * * * * * * * * * * meshSettings  * * * * * * * * * * * * * //

std::vector<std::string> meshSettingsEntries()
{
    return
    {
        "geometry", "maxCellSize", "grading", "refinementLevels",
        "coarseMesher", "volumeMesher", "optimisationSteps",
        "volumeMesherThreads", "maxPieceCells", "curvatureRefinement", "minCellSize",
        "cellsAcrossGap",
        "coarseTimeLimit", "coarseSurface", "patches", "refinementRegions",
        "domain"
    };
}


std::vector<std::string> meshSettingsPatchTypes()
{
    return {"patch", "wall", "symmetry", "symmetryPlane"};
}


std::vector<std::string> meshSettingsPatchEntries()
{
    std::vector<std::string> entries{"type", "maxCellSize", "inGroups"};
    for (const std::string& e : layerSpecificationEntries())
    {
        entries.push_back(e);
    }
    return entries;
}


meshSettings readMeshSettings
(
    const Foam::dictionary& dict,
    const std::string& caseDir
)
{
    meshSettings s;
    s.dictFile = dict.name();

    // Typos first: an unknown entry would otherwise look like a missing one
    const std::vector<std::string> valid = meshSettingsEntries();
    for (const entry& e : dict)
    {
        const std::string key = e.keyword();
        if (key == "labelSize")
        {
            check.error(dict, e)
                << "Entry 'labelSize' is no longer supported: labels follow"
                << " the OpenFOAM build (WM_LABEL_SIZE; this build has "
                << int(8*sizeof(Foam::label)) << "-bit labels)\n"
                << "Remove the entry; for 64-bit labels use pmshFoam built"
                << " with an OpenFOAM of WM_LABEL_SIZE=64"
                << Foam::exit(Foam::FatalIOError);
        }
        if (key != "FoamFile" && (e.keyword().isPattern() || !containsWord(valid, key)))
        {
            check.error(dict, e)
                << "Unknown entry '" << key.c_str() << "'."
                << didYouMean(key, valid).c_str() << '\n'
                << "Valid entries are: " << joinedWords(valid).c_str()
                << Foam::exit(Foam::FatalIOError);
        }
    }

    s.geometryFiles = readGeometry(dict, caseDir);

    const std::string validSize =
        "maxCellSize must be a number > 0: the largest edge length of the"
        " coarse mesh, in the units of the geometry";
    if (!foam::findEntry(dict, "maxCellSize"))
    {
        check.error(dict, "maxCellSize")
            << "Entry 'maxCellSize' not found\n" << validSize.c_str()
            << Foam::exit(Foam::FatalIOError);
    }
    s.maxCellSize = check.bounded
    (
        dict, "maxCellSize", 0, aboveZero,
        std::numeric_limits<double>::max(), false, validSize
    );

    s.grading = check.bounded
    (
        dict, "grading", 0.3, 0, 1, false,
        "Valid values are numbers 0 <= grading <= 1 (0 uniform .. 1 aggressive)"
    );
    s.refinementLevels = check.bounded
    (
        dict, "refinementLevels", 1, 0, 10, true,
        "Valid values are integers 0 <= refinementLevels <= 10"
        " (each level multiplies the number of cells by about 8)"
    );
    if (const entry* e = foam::findEntry(dict, "refinementLevels"))
    {
        s.refinementLevelsLine = e->startLineNumber();
    }
    s.volumeMesher = check.choice(dict, "volumeMesher", "netgen", VolumeMesher::names());
    // By default the volume mesher fills the coarse surface too: HXT is
    // 4-27x faster per cell there at the fine quality HXT gives anyway, while
    // Netgen's fine meshes are up to 10 degrees better on a Netgen coarse
    // mesh (bench/results/coarse-stage.md)
    s.coarseMesher = check.choice(dict, "coarseMesher", s.volumeMesher, VolumeMesher::names());
    s.optimisationSteps = check.bounded
    (
        dict, "optimisationSteps",
        VolumeMesher::New(s.volumeMesher)->defaultOptimisationSteps(), 0, 100, true,
        "Valid values are integers 0 <= optimisationSteps <= 100"
    );
    s.volumeMesherThreads = check.bounded
    (
        dict, "volumeMesherThreads", 1, 1, 256, true,
        "Valid values are integers 1 <= volumeMesherThreads <= 256"
        " (threads per rank; 1 with one rank per core)"
    );
    s.maxPieceCells = check.bounded
    (
        dict, "maxPieceCells", meshSettings().maxPieceCells, 1000, 1e9, true,
        "Valid values are integers 1000 <= maxPieceCells <= 1e9: the fine"
        " cells one volume-mesher call meshes at most"
    );

    readSurfaceSizing(dict, s);
    s.coarseSurface = readCoarseSurface(dict, s.geometryFiles);

    if (const entry* e = foam::findEntry(dict, "patches"))
    {
        checkPatches(dict, *e);
        s.patches = e->dict();
    }

    if (const entry* e = foam::findEntry(dict, "refinementRegions"))
    {
        s.refinementRegions = readRegions(dict, *e);
    }

    if (const entry* e = foam::findEntry(dict, "domain"))
    {
        s.domain = readDomain(dict, *e, s.geometryFiles, s.finestCellSize());
    }

    return s;
}

} // End namespace pmsh


double pmsh::meshSettings::finestCellSize() const
{
    double finest = maxCellSize;
    for (const Foam::entry& e : patches)
    {
        if (e.isDict())
        {
            const double h = foam::getOrDefault<double>(e.dict(), "maxCellSize", 0.0);
            if (h > 0)
            {
                finest = std::min(finest, h);
            }
        }
    }
    return finest/double(1 << refinementLevels);
}


std::string pmsh::meshSettings::geometryText() const
{
    std::string text;
    for (const std::string& f : geometryFiles)
    {
        text += (text.empty() ? "\"" : " + \"") + f + "\"";
    }
    return text;
}


// ************************************************************************* //
