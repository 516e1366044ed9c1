#include "meshSettings.H"
#include "foamShims.H"
#include "VolumeMesher.H"
#include "layerSpecification.H"

#include <algorithm>
#include <sstream>
#include <cctype>
#include <cmath>
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

std::string joined(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words)
    {
        s += (s.empty() ? "" : ", ") + w;
    }
    return s;
}


bool contains(const std::vector<std::string>& words, const std::string& w)
{
    return std::find(words.begin(), words.end(), w) != words.end();
}


//- Edit distance (ignoring case), to suggest the entry a typo meant.
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const bool same =
                std::tolower(static_cast<unsigned char>(a[i - 1]))
             == std::tolower(static_cast<unsigned char>(b[j - 1]));
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + !same});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}


//- " Did you mean 'grading'?" when a valid name is close to key.
std::string suggestion(const std::string& key, const std::vector<std::string>& valid)
{
    std::string best;
    std::size_t bestDist = 3;
    for (const std::string& v : valid)
    {
        const std::size_t d = editDistance(key, v);
        if (d < bestDist)
        {
            bestDist = d;
            best = v;
        }
    }
    return best.empty() ? "" : " Did you mean '" + best + "'?";
}


//- FatalIOError located at an entry of d: the file and the entry's lines.
Foam::OSstream& entryError(const dictionary& d, const entry& e)
{
    return foam::ioError
    (
        Foam::FatalIOError, where, __FILE__, __LINE__,
        d.topDict().name(), e.startLineNumber(), e.endLineNumber()
    );
}


//- "Entry 'key' is <value><note>" and what is valid, at the entry's line.
void invalid
(
    const dictionary& d,
    const entry& e,
    const std::string& valid,
    const std::string& note = ""
)
{
    const std::string value =
        e.isStream() ? foam::tokensString(e.stream()) : "a sub-dictionary";
    entryError(d, e)
        << "Entry '" << e.keyword().c_str() << "' is " << value.c_str()
        << note.c_str() << '\n' << valid.c_str()
        << Foam::exit(Foam::FatalIOError);
}


//- The value of an entry of exactly one token, else nullptr.
const Foam::token* single(const entry& e)
{
    return e.isStream() && e.stream().size() == 1 ? &e.stream()[0] : nullptr;
}


//- An optional number (an integer if integral) within [lo, hi]. Not
//  getCheckOrDefault (none in Foundation 13): its error names neither the
//  value, the entry's line nor the valid values, as these messages do.
double bounded
(
    const dictionary& d,
    const char* key,
    double deflt,
    double lo,
    double hi,
    bool integral,
    const std::string& valid
)
{
    const entry* e = foam::findEntry(d, key);
    if (!e) return deflt;
    const Foam::token* t = single(*e);
    if
    (
        !t || !(integral ? t->isLabel() : t->isNumber())
     || !(t->number() >= lo && t->number() <= hi)
    )
    {
        // 1e1 is written back as 10, and "is fine" reads as a verdict:
        // say why the value is wrong
        const bool real = integral && t && t->isScalar();
        const bool number = t && t->isNumber();
        invalid
        (
            d, *e, valid,
            real ? " (not an integer)" : t && !number ? " (not a number)" : ""
        );
    }
    return t->number();
}


//- An optional word from a list of choices (known at run time: no Foam::Enum).
std::string choice
(
    const dictionary& d,
    const char* key,
    const std::string& deflt,
    const std::vector<std::string>& choices
)
{
    const entry* e = foam::findEntry(d, key);
    if (!e) return deflt;
    const Foam::token* t = single(*e);
    if (!t || !foam::isStringType(*t) || !contains(choices, foam::stringToken(*t)))
    {
        invalid(d, *e, "Valid values are: " + joined(choices));
    }
    return foam::stringToken(*t);
}


//- <case>/x, $FOAM_CASE/x and relative names are relative to the case
//  (fileName::expand would take it from $FOAM_CASE, not from caseDir).
std::string casePath(const std::string& caseDir, const std::string& name)
{
    std::string rest = name;
    bool caseRelative = false;
    for (const std::string tag : {"<case>", "${FOAM_CASE}", "$FOAM_CASE"})
    {
        if (rest.compare(0, tag.size(), tag) == 0)
        {
            rest.erase(0, tag.size());
            rest.erase(0, rest.find_first_not_of('/'));
            caseRelative = true;
            break;
        }
    }
    fs::path p(rest);
    if (caseRelative || p.is_relative())
    {
        p = fs::path(caseDir)/p;
    }
    std::error_code ec;
    const fs::path abs = fs::absolute(p, ec);
    return (ec ? p : abs).lexically_normal().string();
}


std::string readGeometry(const dictionary& d, const std::string& caseDir)
{
    const char* const validFiles =
        "Valid geometry files: .geo (Netgen CSG), .stl (ascii or binary STL)";
    const entry* e = foam::findEntry(d, "geometry");
    if (!e)
    {
        FatalIOErrorInFunction(d)
            << "Entry 'geometry' not found\n"
            << "Set it to the geometry file, relative to the case directory,"
            << " e.g.\n    geometry \"constant/geometry/body.stl\";\n"
            << validFiles << Foam::exit(Foam::FatalIOError);
    }
    const Foam::token* t = single(*e);
    if (!t || !foam::isStringType(*t))
    {
        invalid
        (
            d, *e,
            "geometry must be a file name in quotes, relative to the case"
            " directory, e.g. \"constant/geometry/body.stl\"\n"
          + std::string(validFiles)
        );
    }
    const std::string name = foam::stringToken(*t);
    const std::string path = casePath(caseDir, name);

    std::string ext = fs::path(path).extension().string();
    const std::string given = ext;
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));

    std::string problem;
    std::error_code ec;
    if (ext != ".geo" && ext != ".stl")
    {
        problem =
            given.empty()
          ? "the file name has no extension"
          : "the file extension '" + given + "' is not supported";
        problem +=
            "\nValid geometry file extensions are: .geo (Netgen CSG),"
            " .stl (ascii or binary STL), in any letter case";
    }
    else if (!fs::exists(path, ec))
    {
        problem =
            "the file \"" + path + "\" does not exist\n"
            "Relative names are relative to the case directory \""
          + caseDir + "\"";
    }
    else if (!fs::is_regular_file(path, ec))
    {
        problem = "\"" + path + "\" is not a regular file\n" + validFiles;
    }
    else
    {
        std::ifstream probe(path, std::ios::binary);
        if (!probe || probe.peek() == std::ifstream::traits_type::eof())
        {
            problem =
                "the file \"" + path + "\" "
              + (probe ? "is empty" : "cannot be read (check its permissions)");
        }
    }
    if (!problem.empty())
    {
        entryError(d, *e)
            << "Entry 'geometry' is \"" << name.c_str() << "\": "
            << problem.c_str() << Foam::exit(Foam::FatalIOError);
    }
    return path;
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
    const entry* e = foam::findEntry(sub, "maxCellSize");
    if (!e)
    {
        if (required)
        {
            FatalIOErrorInFunction(sub)
                << "Entry 'maxCellSize' not found in " << owner.c_str()
                << '\n' << valid.c_str() << Foam::exit(Foam::FatalIOError);
        }
        return 0;
    }
    return bounded
    (
        sub, "maxCellSize", 0, std::numeric_limits<double>::min(),
        std::numeric_limits<double>::max(), false, valid
    );
}


//- A required point entry "(x y z)" of a region.
pmsh::point3 readPoint
(
    const dictionary& region,
    const char* key,
    const std::string& owner
)
{
    const std::string valid =
        "Entry '" + std::string(key) + "' of " + owner
      + " must be a point (x y z), e.g. " + key + " (0 0 0);";
    const entry* e = foam::findEntry(region, key);
    if (!e)
    {
        FatalIOErrorInFunction(region)
            << "Entry '" << key << "' not found in " << owner.c_str() << '\n'
            << valid.c_str() << Foam::exit(Foam::FatalIOError);
    }
    const bool stream = e->isStream();
    Foam::ITstream* is = stream ? &e->stream() : nullptr;
    bool ok =
        stream && is->size() == 5
     && (*is)[0].isPunctuation() && (*is)[0].pToken() == Foam::token::BEGIN_LIST
     && (*is)[4].isPunctuation() && (*is)[4].pToken() == Foam::token::END_LIST;
    pmsh::point3 p{};
    for (int k = 0; ok && k < 3; ++k)
    {
        ok = (*is)[k + 1].isNumber() && std::isfinite((*is)[k + 1].number());
        if (ok) p[k] = (*is)[k + 1].number();
    }
    if (!ok)
    {
        invalid(region, *e, valid);
    }
    return p;
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
    if (!foam::findEntry(region, key))
    {
        FatalIOErrorInFunction(region)
            << "Entry '" << key << "' not found in " << owner.c_str() << '\n'
            << valid.c_str() << Foam::exit(Foam::FatalIOError);
    }
    return bounded
    (
        region, key, 0, std::numeric_limits<double>::min(),
        std::numeric_limits<double>::max(), false, valid
    );
}


//- The refinementRegions sub-dictionary: one shape per entry.
std::vector<pmsh::sizeRegion> readRegions(const dictionary& d, const entry& regionsEntry)
{
    using pmsh::sizeRegion;
    const std::vector<std::string> shapes = sizeRegion::shapeNames();
    const std::string validTypes = "Valid region types are: " + joined(shapes);
    const std::string example =
        "    refinementRegions\n    {\n"
        "        wake { type box; min (0 -1 -1); max (4 1 1); maxCellSize 0.05; }\n"
        "        nose { type sphere; centre (0 0 0); radius 0.5; maxCellSize 0.02; }\n"
        "        shaft { type cylinder; point1 (0 0 0); point2 (1 0 0);"
        " radius 0.1; maxCellSize 0.02; }\n    }";
    if (!regionsEntry.isDict())
    {
        invalid
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
            invalid(d, r, "Expected '" + r.keyword() + " { type T; ... }' with T"
                " one of: " + joined(shapes) + ", e.g.\n" + example);
        }
        const dictionary& rd = r.dict();
        const entry* t = foam::findEntry(rd, "type");
        if (!t)
        {
            entryError(d, r)
                << "Entry 'type' not found in " << owner.c_str() << "\n"
                << validTypes.c_str() << Foam::exit(Foam::FatalIOError);
        }
        const Foam::token* tok = single(*t);
        if (!tok || !foam::isStringType(*tok) || !contains(shapes, foam::stringToken(*tok)))
        {
            invalid(rd, *t, validTypes);
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
        for (const entry& x : rd)
        {
            if (!contains(entries, x.keyword()))
            {
                entryError(d, x)
                    << "Unknown entry '" << x.keyword().c_str() << "' in "
                    << owner.c_str() << '.'
                    << suggestion(x.keyword(), entries).c_str() << '\n'
                    << "Valid entries of a " << type.c_str() << " are: "
                    << joined(entries).c_str() << Foam::exit(Foam::FatalIOError);
            }
        }

        switch (region.type)
        {
            case sizeRegion::shape::box:
                region.min = readPoint(rd, "min", owner);
                region.max = readPoint(rd, "max", owner);
                for (int k = 0; k < 3; ++k)
                {
                    if (!(region.min[k] < region.max[k]))
                    {
                        invalid
                        (
                            rd, *foam::findEntry(rd, "max"),
                            "Every component of 'max' of " + owner
                          + " must be larger than that of 'min'",
                            " (not above min)"
                        );
                    }
                }
                break;
            case sizeRegion::shape::sphere:
                region.centre = readPoint(rd, "centre", owner);
                region.radius = readPositive(rd, "radius", owner);
                break;
            case sizeRegion::shape::cylinder:
                region.point1 = readPoint(rd, "point1", owner);
                region.point2 = readPoint(rd, "point2", owner);
                region.radius = readPositive(rd, "radius", owner);
                if (!(magSqr(region.point2 - region.point1) > 0))
                {
                    invalid
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
            entryError(d, r)
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
    const std::string validTypes = "Valid patch types are: " + joined(types);

    if (!patchesEntry.isDict())
    {
        invalid
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
            invalid
            (
                d, p,
                "Expected '" + p.keyword() + " { type T; }' with T one of: "
              + joined(types)
            );
        }
        const std::vector<std::string> entries = meshSettingsPatchEntries();
        for (const entry& x : p.dict())
        {
            if (!contains(entries, x.keyword()))
            {
                entryError(d, x)
                    << "Unknown entry '" << x.keyword().c_str()
                    << "' in patch '" << p.keyword().c_str() << "'."
                    << suggestion(x.keyword(), entries).c_str() << '\n'
                    << "Valid entries of a patch are: 'type' ("
                    << joined(types).c_str() << "), 'maxCellSize' (the"
                    << " coarse cell size on the patch) and the prism layers' "
                    << joined(layerSpecificationEntries()).c_str()
                    << Foam::exit(Foam::FatalIOError);
            }
        }
        localSize(d, p.dict(), "patch '" + p.keyword() + "'");
        readLayerSpecification(p.dict(), p.keyword());
        const entry* t = foam::findEntry(p.dict(), "type");
        if (!t)
        {
            entryError(d, p)
                << "Entry 'type' not found in patch '" << p.keyword().c_str()
                << "'\n" << validTypes.c_str()
                << Foam::exit(Foam::FatalIOError);
        }
        const Foam::token* tok = single(*t);
        if (!tok || !foam::isStringType(*tok) || !contains(types, foam::stringToken(*tok)))
        {
            invalid(d, *t, validTypes);
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * meshSettings  * * * * * * * * * * * * * //

std::vector<std::string> meshSettingsEntries()
{
    return
    {
        "geometry", "maxCellSize", "grading", "refinementLevels",
        "coarseMesher", "volumeMesher", "optimisationSteps",
        "volumeMesherThreads", "curvatureRefinement", "minCellSize",
        "coarseTimeLimit", "patches", "refinementRegions"
    };
}


std::vector<std::string> meshSettingsPatchTypes()
{
    return {"patch", "wall", "symmetry", "symmetryPlane"};
}


std::vector<std::string> meshSettingsPatchEntries()
{
    std::vector<std::string> entries{"type", "maxCellSize"};
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
            entryError(dict, e)
                << "Entry 'labelSize' is no longer supported: labels follow"
                << " the OpenFOAM build (WM_LABEL_SIZE; this build has "
                << int(8*sizeof(Foam::label)) << "-bit labels)\n"
                << "Remove the entry; for 64-bit labels use pmshFoam built"
                << " with an OpenFOAM of WM_LABEL_SIZE=64"
                << Foam::exit(Foam::FatalIOError);
        }
        if (key != "FoamFile" && (e.keyword().isPattern() || !contains(valid, key)))
        {
            entryError(dict, e)
                << "Unknown entry '" << key.c_str() << "'."
                << suggestion(key, valid).c_str() << '\n'
                << "Valid entries are: " << joined(valid).c_str()
                << Foam::exit(Foam::FatalIOError);
        }
    }

    s.geometryFile = readGeometry(dict, caseDir);

    const std::string validSize =
        "maxCellSize must be a number > 0: the largest edge length of the"
        " coarse mesh, in the units of the geometry";
    if (!foam::findEntry(dict, "maxCellSize"))
    {
        FatalIOErrorInFunction(dict)
            << "Entry 'maxCellSize' not found\n" << validSize.c_str()
            << Foam::exit(Foam::FatalIOError);
    }
    s.maxCellSize = bounded
    (
        dict, "maxCellSize", 0, std::numeric_limits<double>::min(),
        std::numeric_limits<double>::max(), false, validSize
    );

    s.grading = bounded
    (
        dict, "grading", 0.3, 0, 1, false,
        "Valid values are numbers 0 <= grading <= 1 (0 uniform .. 1 aggressive)"
    );
    s.refinementLevels = bounded
    (
        dict, "refinementLevels", 1, 0, 10, true,
        "Valid values are integers 0 <= refinementLevels <= 10"
        " (each level multiplies the number of cells by about 8)"
    );
    if (const entry* e = foam::findEntry(dict, "refinementLevels"))
    {
        s.refinementLevelsLine = e->startLineNumber();
    }
    s.volumeMesher = choice(dict, "volumeMesher", "netgen", VolumeMesher::names());
    // By default the volume mesher fills the coarse surface too: HXT is
    // 4-27x faster per cell there at the fine quality HXT gives anyway, while
    // Netgen's fine meshes are up to 10 degrees better on a Netgen coarse
    // mesh (bench/results/coarse-stage.md)
    s.coarseMesher = choice(dict, "coarseMesher", s.volumeMesher, VolumeMesher::names());
    s.optimisationSteps = bounded
    (
        dict, "optimisationSteps",
        VolumeMesher::New(s.volumeMesher)->defaultOptimisationSteps(), 0, 100, true,
        "Valid values are integers 0 <= optimisationSteps <= 100"
    );
    s.volumeMesherThreads = bounded
    (
        dict, "volumeMesherThreads", 1, 1, 256, true,
        "Valid values are integers 1 <= volumeMesherThreads <= 256"
        " (threads per rank; 1 with one rank per core)"
    );

    // Default 3: a ball of radius 0.5 at maxCellSize 1 then gets 120
    // coarse faces from its STL (mean edge 0.24), as from CSG, where
    // Netgen always sizes by curvature (128, 0.23); with 0 or 2 it gets 70
    // (0.31), whatever the global size
    s.curvatureRefinement = bounded
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
    s.minCellSize = bounded
    (
        dict, "minCellSize", s.maxCellSize/8, std::numeric_limits<double>::min(),
        s.maxCellSize, false, validMinCellSize.str()
    );

    // 0 (absent): from the STL's size, when it is known (stlGeometry)
    s.coarseTimeLimit = bounded
    (
        dict, "coarseTimeLimit", 0, std::numeric_limits<double>::min(), 1e7,
        false,
        "Valid values are numbers 0 < coarseTimeLimit <= 1e7: the seconds each"
        " attempt of Netgen's STL coarse mesh may take (all attempts together"
        " twice that); without the entry, from the surface's size"
    );

    if (const entry* e = foam::findEntry(dict, "patches"))
    {
        checkPatches(dict, *e);
        s.patches = e->dict();
    }

    if (const entry* e = foam::findEntry(dict, "refinementRegions"))
    {
        s.refinementRegions = readRegions(dict, *e);
    }

    return s;
}

} // End namespace pmsh


// ************************************************************************* //
