#include "meshSettings.H"
#include "error.H"
#include "VolumeMesher.H"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pmsh
{

namespace
{

const char* const where = "pmsh::readMeshSettings";

std::string joined(const std::vector<std::string>& words, const std::string& sep = ", ")
{
    std::string s;
    for (std::size_t i = 0; i < words.size(); ++i)
    {
        if (i) s += sep;
        s += words[i];
    }
    return s;
}


std::string lowerCase(std::string s)
{
    for (char& c : s)
    {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return s;
}


//- Edit distance, to suggest the entry a typo meant.
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const std::size_t subst =
                prev[j - 1]
              + (std::tolower(static_cast<unsigned char>(a[i - 1]))
              != std::tolower(static_cast<unsigned char>(b[j - 1])));
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, subst});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}


//- " (did you mean 'grading'?)" when a valid name is close to key.
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
    return best.empty() ? "" : " (did you mean '" + best + "'?)";
}


//- The dictionary's own error, with what would be valid appended.
template<class T>
T valueOf(const dictionary& d, const entry& e, const std::string& valid)
{
    try
    {
        return d.value<T>(e);
    }
    catch (const FatalError& err)
    {
        throw FatalError(err.message() + "\n" + valid, where);
    }
}


//- "Unknown entry 'x' in dictionary ... (line N)".
std::string unknownEntry(const dictionary& d, const entry& e)
{
    // entryInfo() starts with "Entry"
    return "Unknown entry" + d.entryInfo(e).substr(5);
}


[[noreturn]] void invalid
(
    const dictionary& d,
    const entry& e,
    const std::string& valid
)
{
    throw FatalError
    (
        msg() << d.entryInfo(e) << " is " << e.text() << '\n' << valid,
        where
    );
}


//- An optional number within [lo, hi].
double boundedNumber
(
    const dictionary& d,
    const std::string& key,
    double deflt,
    double lo,
    double hi,
    const std::string& valid
)
{
    const entry* e = d.findEntry(key, false);
    if (!e) return deflt;
    const double v = valueOf<double>(d, *e, valid);
    if (!(v >= lo && v <= hi)) invalid(d, *e, valid);
    return v;
}


//- An optional integer within [lo, hi].
int boundedInteger
(
    const dictionary& d,
    const std::string& key,
    int deflt,
    int lo,
    int hi,
    const std::string& valid
)
{
    const entry* e = d.findEntry(key, false);
    if (!e) return deflt;
    const int v = valueOf<int>(d, *e, valid);
    if (v < lo || v > hi) invalid(d, *e, valid);
    return v;
}


//- An optional word from a list of choices.
std::string choice
(
    const dictionary& d,
    const std::string& key,
    const std::string& deflt,
    const std::vector<std::string>& choices
)
{
    const std::string valid = "Valid values are: " + joined(choices);
    const entry* e = d.findEntry(key, false);
    if (!e) return deflt;
    const std::string v = valueOf<std::string>(d, *e, valid);
    if (std::find(choices.begin(), choices.end(), v) == choices.end())
    {
        invalid(d, *e, valid);
    }
    return v;
}


//- <case>/x, $FOAM_CASE/x and relative names are relative to the case.
std::string casePath(const std::string& caseDir, const std::string& name)
{
    std::string rest = name;
    bool caseRelative = false;
    for (const char* tag : {"<case>", "${FOAM_CASE}", "$FOAM_CASE"})
    {
        const std::string t(tag);
        if (rest.compare(0, t.size(), t) == 0)
        {
            rest = rest.substr(t.size());
            while (!rest.empty() && rest[0] == '/') rest.erase(0, 1);
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


void checkGeometry(const dictionary& d, const std::string& caseDir, meshSettings& s)
{
    const entry* e = d.findEntry("geometry", false);
    if (!e)
    {
        throw FatalError
        (
            msg() << "Entry 'geometry' not found in dictionary \""
                << d.name() << "\"\n"
                << "Set it to the geometry file, relative to the case"
                << " directory, e.g.\n"
                << "    geometry \"constant/geometry/body.stl\";\n"
                << "Valid geometry files: .geo (Netgen CSG), .stl (ascii or"
                << " binary STL)",
            where
        );
    }
    const std::string valid =
        "Expected the geometry file name in quotes, relative to the case"
        " directory, e.g. \"constant/geometry/body.stl\"; valid files are .geo"
        " (Netgen CSG) and .stl (ascii or binary STL)";
    const std::string name = valueOf<std::string>(d, *e, valid);
    const std::string path = casePath(caseDir, name);

    const std::string ext = lowerCase(fs::path(path).extension().string());
    if (ext != ".geo" && ext != ".stl")
    {
        const std::string given = fs::path(path).extension().string();
        throw FatalError
        (
            msg() << d.entryInfo(*e) << " is \"" << name << "\": "
                << (
                       given.empty()
                     ? std::string("the file name has no extension")
                     : "the file extension '" + given + "' is not supported"
                   ) << '\n'
                << "Valid geometry file extensions are: .geo (Netgen CSG),"
                << " .stl (ascii or binary STL), in any letter case",
            where
        );
    }

    std::error_code ec;
    if (!fs::exists(path, ec))
    {
        throw FatalError
        (
            msg() << d.entryInfo(*e) << " is \"" << name << "\": the file \""
                << path << "\" does not exist\n"
                << "Relative names are relative to the case directory \""
                << caseDir << "\"",
            where
        );
    }
    if (!fs::is_regular_file(path, ec))
    {
        throw FatalError
        (
            msg() << d.entryInfo(*e) << " is \"" << name << "\": \""
                << path << "\" is not a regular file\n"
                << "Expected a .geo or .stl file",
            where
        );
    }
    std::ifstream probe(path, std::ios::binary);
    if (!probe || probe.peek() == std::ifstream::traits_type::eof())
    {
        throw FatalError
        (
            msg() << d.entryInfo(*e) << " is \"" << name << "\": the file \""
                << path << "\" "
                << (probe ? "is empty" : "cannot be read (check its permissions)"),
            where
        );
    }
    s.geometryFile = path;
}


void checkPatches(const dictionary& d, meshSettings& s)
{
    const entry* e = d.findEntry("patches", false);
    if (!e) return;

    const std::vector<std::string> types = meshSettingsPatchTypes();
    const std::string validTypes = "Valid patch types are: " + joined(types);

    if (!e->isDict())
    {
        invalid
        (
            d, *e,
            "Expected a sub-dictionary of patch names (or \"regular"
            " expressions\") and their types, e.g.\n"
            "    patches\n    {\n        inlet { type patch; }\n"
            "        \".*\"  { type wall; }\n    }"
        );
    }
    const dictionary& patches = e->dict();

    for (const entry& p : patches.entries())
    {
        if (p.isDirective()) continue;
        if (!p.isDict())
        {
            invalid
            (
                patches, p,
                "Expected '" + p.keyword() + " { type T; }' with T one of: "
              + joined(types)
            );
        }
        const dictionary& pd = p.dict();
        for (const entry& x : pd.entries())
        {
            if (x.isDirective() || x.keyword() == "type") continue;
            throw FatalError
            (
                msg() << unknownEntry(pd, x) << '\n'
                    << "The only valid entry of a patch is 'type' ("
                    << joined(types) << ")",
                where
            );
        }
        const entry* t = pd.findEntry("type", false);
        if (!t)
        {
            throw FatalError
            (
                msg() << "Entry 'type' not found in dictionary \""
                    << pd.name() << "\" (line " << p.line() << ")\n"
                    << validTypes,
                where
            );
        }
        const std::string type = valueOf<std::string>(pd, *t, validTypes);
        if (std::find(types.begin(), types.end(), type) == types.end())
        {
            invalid(pd, *t, validTypes);
        }
    }
    s.patches = patches;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * meshSettings  * * * * * * * * * * * * * //

std::vector<std::string> meshSettingsEntries()
{
    return
    {
        "geometry", "maxCellSize", "grading", "refinementLevels",
        "volumeMesher", "optimisationSteps", "volumeMesherThreads", "patches",
        "labelSize"
    };
}


std::vector<std::string> meshSettingsPatchTypes()
{
    return {"patch", "wall", "symmetry", "symmetryPlane"};
}


std::string meshSettings::patchType(const std::string& patchName) const
{
    const entry* e = patches.findEntry(patchName);
    if (e && e->isDict())
    {
        const entry* t = e->dict().findEntry("type", false);
        if (t) return e->dict().value<std::string>(*t);
    }
    return "wall";
}


meshSettings readMeshSettings
(
    const std::string& caseDir,
    const std::string& dictFile
)
{
    const std::string path = casePath(caseDir, dictFile);
    std::error_code ec;
    if (!fs::exists(path, ec))
    {
        throw FatalError
        (
            msg() << "Cannot find the mesh dictionary \"" << path << "\"\n"
                << "pmshFoam reads what to mesh and how fine from it"
                << " (geometry, maxCellSize, ...): create it, or name another"
                << " file with -dict",
            where
        );
    }

    const dictionary d = dictionary::read(path);
    meshSettings s;
    s.dictFile = d.name();

    // Typos first: an unknown entry would otherwise look like a missing one
    const std::vector<std::string> valid = meshSettingsEntries();
    for (const entry& e : d.entries())
    {
        if (e.isDirective() || e.keyword() == "FoamFile") continue;
        if (std::find(valid.begin(), valid.end(), e.keyword()) == valid.end())
        {
            throw FatalError
            (
                msg() << unknownEntry(d, e)
                    << suggestion(e.keyword(), valid) << '\n'
                    << "Valid entries are: " << joined(valid),
                where
            );
        }
    }

    checkGeometry(d, caseDir, s);

    {
        const std::string validSize =
            "Valid values are numbers > 0: the largest edge length of the"
            " coarse mesh, in the units of the geometry";
        const entry* e = d.findEntry("maxCellSize", false);
        if (!e)
        {
            throw FatalError
            (
                msg() << "Entry 'maxCellSize' not found in dictionary \""
                    << d.name() << "\"\n" << validSize,
                where
            );
        }
        s.maxCellSize = valueOf<double>(d, *e, validSize);
        if (!(s.maxCellSize > 0) || !std::isfinite(s.maxCellSize))
        {
            invalid(d, *e, validSize);
        }
    }

    s.grading = boundedNumber
    (
        d, "grading", 0.3, 0, 1,
        "Valid values are 0 <= grading <= 1 (0 uniform .. 1 aggressive)"
    );
    s.refinementLevels = boundedInteger
    (
        d, "refinementLevels", 1, 0, 10,
        "Valid values are integers 0 <= refinementLevels <= 10"
        " (each level multiplies the number of cells by about 8)"
    );
    if (const entry* e = d.findEntry("refinementLevels", false))
    {
        s.refinementLevelsLine = e->line();
    }
    s.volumeMesher = choice(d, "volumeMesher", "netgen", VolumeMesher::names());
    s.optimisationSteps = boundedInteger
    (
        d, "optimisationSteps", 3, 0, 100,
        "Valid values are integers 0 <= optimisationSteps <= 100"
    );
    s.volumeMesherThreads = boundedInteger
    (
        d, "volumeMesherThreads", 1, 1, 256,
        "Valid values are integers 1 <= volumeMesherThreads <= 256"
        " (threads per rank; 1 with one rank per core)"
    );

    {
        int deflt = 32;
        if (const char* env = std::getenv("WM_LABEL_SIZE"))
        {
            if (std::string(env) == "64") deflt = 64;
        }
        const std::string validLabel =
            "Valid values are 32 or 64 (bits per label in the polyMesh"
            " files; 64 for meshes beyond 2 billion faces)";
        s.labelBits = deflt;
        if (const entry* e = d.findEntry("labelSize", false))
        {
            s.labelBits = valueOf<int>(d, *e, validLabel);
            if (s.labelBits != 32 && s.labelBits != 64)
            {
                invalid(d, *e, validLabel);
            }
        }
    }

    checkPatches(d, s);

    return s;
}


// * * * * * * * * * * * * * * * * writeSettings * * * * * * * * * * * * * //

std::string timeName(double t, int precision)
{
    std::ostringstream os;
    os.imbue(std::locale::classic());
    os.precision(precision);
    os << t;
    return os.str();
}


writeSettings readWriteSettings(const std::string& caseDir)
{
    const std::string path =
        (fs::path(caseDir)/"system"/"controlDict").lexically_normal().string();
    std::error_code ec;
    if (!fs::exists(path, ec))
    {
        throw FatalError
        (
            msg() << "Cannot find \"" << fs::absolute(path, ec).string()
                << "\"\n"
                << "pmshFoam reads writeFormat, writePrecision and startTime"
                << " from system/controlDict, as every OpenFOAM application"
                << " does: is \"" << caseDir << "\" an OpenFOAM case?",
            "pmsh::readWriteSettings"
        );
    }

    const dictionary d = dictionary::read(path);
    writeSettings w;

    w.binary = (choice(d, "writeFormat", "ascii", {"ascii", "binary"}) == "binary");
    w.writePrecision = boundedInteger
    (
        d, "writePrecision", 6, 1, 30,
        "Valid values are integers 1 <= writePrecision <= 30"
    );

    // The time directory name as OpenFOAM forms it
    const std::string format =
        choice(d, "timeFormat", "general", {"general", "fixed", "scientific"});
    const int precision = boundedInteger
    (
        d, "timePrecision", 6, 1, 30,
        "Valid values are integers 1 <= timePrecision <= 30"
    );
    double start = 0;
    if (const entry* e = d.findEntry("startTime", false))
    {
        start = valueOf<double>
        (
            d, *e, "Valid values are numbers: the start time (e.g. 0)"
        );
    }
    std::ostringstream os;
    os.imbue(std::locale::classic());
    if (format == "fixed") os << std::fixed;
    if (format == "scientific") os << std::scientific;
    os.precision(precision);
    os << start;
    w.startTime = os.str();

    return w;
}

} // End namespace pmsh


// ************************************************************************* //
