/*---------------------------------------------------------------------------*\
  Tests of system/pmshDict and system/controlDict reading and validation
  (src/io/meshSettings).
\*---------------------------------------------------------------------------*/

#include "meshSettings.H"
#include "VolumeMesher.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

using namespace pmsh;
using namespace pmsh::test;
namespace fs = std::filesystem;

namespace
{

const char* const header =
    "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class dictionary;\n"
    "    object pmshDict;\n}\n";     // 7 lines

//- A case directory with a geometry file; removed at the end of the test.
class caseDir
:
    public ::testing::Test
{
protected:

    const tempDir tmp{"case"};
    const std::string dir = tmp.path();
    const std::string dict = dir + "/system/pmshDict";

    void SetUp() override
    {
        writeFile(dir + "/constant/geometry/body.stl", "solid body\nendsolid body\n");
        writeFile(dir + "/constant/geometry/Shape.GEO", "algebraic3d\n");
    }

    //- pmshDict = header (7 lines) + entries; the first entry is line 8.
    void writeDict(const std::string& entries)
    {
        writeFile(dict, header + entries);
    }

    //- The error of reading a pmshDict with these entries.
    std::string errorFor(const std::string& entries)
    {
        writeDict(entries);
        return errorOf([&]{ readMeshSettings(dir); });
    }

    std::string minimal() const
    {
        return "geometry \"constant/geometry/body.stl\";\nmaxCellSize 0.1;\n";
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * pmshDict  * * * * * * * * * * * * * * * //

TEST_F(caseDir, readsEveryEntry)
{
    writeDict
    (
        "geometry          \"constant/geometry/Shape.GEO\";\n"
        "maxCellSize       0.25;\n"
        "grading           0.5;\n"
        "refinementLevels  3;\n"
        "volumeMesher      netgen;\n"
        "optimisationSteps 7;\n"
        "volumeMesherThreads 2;\n"
        "labelSize         64;\n"
        "patches\n{\n    inlet { type patch; }\n}\n"
    );
    const meshSettings s = readMeshSettings(dir);
    EXPECT_EQ(s.geometryFile, fs::absolute(dir + "/constant/geometry/Shape.GEO").lexically_normal().string());
    EXPECT_TRUE(fs::path(s.geometryFile).is_absolute());
    EXPECT_DOUBLE_EQ(s.maxCellSize, 0.25);
    EXPECT_DOUBLE_EQ(s.grading, 0.5);
    EXPECT_EQ(s.refinementLevels, 3);
    EXPECT_EQ(s.volumeMesher, "netgen");
    EXPECT_EQ(s.optimisationSteps, 7);
    EXPECT_EQ(s.volumeMesherThreads, 2);
    EXPECT_EQ(s.labelBits, 64);
    EXPECT_EQ(s.patchType("inlet"), "patch");
}

TEST_F(caseDir, optionalEntriesHaveTheirDefaults)
{
    const scopedEnv env("WM_LABEL_SIZE", nullptr);
    writeDict(minimal());
    const meshSettings s = readMeshSettings(dir);
    EXPECT_DOUBLE_EQ(s.grading, 0.3);
    EXPECT_EQ(s.refinementLevels, 1);
    EXPECT_EQ(s.volumeMesher, "netgen");
    EXPECT_EQ(s.optimisationSteps, 3);
    EXPECT_EQ(s.volumeMesherThreads, 1);
    EXPECT_EQ(s.labelBits, 32);
    EXPECT_EQ(s.patchType("anything"), "wall");
}

TEST_F(caseDir, labelSizeDefaultsToTheEnvironment)
{
    writeDict(minimal());
    {
        const scopedEnv env("WM_LABEL_SIZE", "64");
        EXPECT_EQ(readMeshSettings(dir).labelBits, 64);
    }
    {
        const scopedEnv env("WM_LABEL_SIZE", "32");
        EXPECT_EQ(readMeshSettings(dir).labelBits, 32);
    }
    {
        // The dictionary wins over the environment
        const scopedEnv env("WM_LABEL_SIZE", "64");
        writeDict(minimal() + "labelSize 32;\n");
        EXPECT_EQ(readMeshSettings(dir).labelBits, 32);
    }
}

TEST_F(caseDir, dictFileMayBeRelativeToTheCaseOrAbsolute)
{
    writeFile(dir + "/system/otherDict", header + minimal() + "refinementLevels 4;\n");
    EXPECT_EQ(readMeshSettings(dir, "system/otherDict").refinementLevels, 4);
    EXPECT_EQ(readMeshSettings(dir, dir + "/system/otherDict").refinementLevels, 4);
    EXPECT_NE(errorOf([&]{ readMeshSettings(dir, "system/noSuchDict"); }), "");
}

TEST_F(caseDir, missingDictionaryNamesThePath)
{
    const std::string err = errorOf([&]{ readMeshSettings(dir); });
    EXPECT_HAS(err, fs::absolute(dict).lexically_normal().string());
}

TEST_F(caseDir, gradingOutOfRangeGivesTheDocumentedMessage)
{
    const std::string err = errorFor(minimal() + "grading 1.7;\n");
    EXPECT_EQ
    (
        err,
        "Entry 'grading' in dictionary \""
      + fs::absolute(dict).lexically_normal().string()
      + "\" (line 10) is 1.7\n"
        "Valid values are 0 <= grading <= 1 (0 uniform .. 1 aggressive)"
    );
    EXPECT_HAS(errorFor(minimal() + "grading -0.1;\n"), "0 <= grading <= 1");
    EXPECT_HAS(errorFor(minimal() + "grading steep;\n"), "0 <= grading <= 1");
}

TEST_F(caseDir, geometryErrorsNameTheEntryAndTheValidFiles)
{
    std::string err = errorFor("maxCellSize 0.1;\n");
    EXPECT_HAS(err, "Entry 'geometry' not found in dictionary");
    EXPECT_HAS(err, ".geo");
    EXPECT_HAS(err, ".stl");

    err = errorFor("geometry \"constant/geometry/missing.stl\";\nmaxCellSize 0.1;\n");
    EXPECT_HAS(err, "Entry 'geometry'");
    EXPECT_HAS(err, "(line 8)");
    EXPECT_HAS(err, dir + "/constant/geometry/missing.stl");
    EXPECT_HAS(err, "does not exist");

    writeFile(dir + "/constant/geometry/body.obj", "v 0 0 0\n");
    err = errorFor("geometry \"constant/geometry/body.obj\";\nmaxCellSize 0.1;\n");
    EXPECT_HAS(err, "(line 8)");
    EXPECT_HAS(err, "'.obj'");
    EXPECT_HAS(err, "Valid geometry file extensions are: .geo");
    EXPECT_HAS(err, ".stl");

    err = errorFor("geometry constant/geometry/body.stl;\nmaxCellSize 0.1;\n");
    EXPECT_HAS(err, "(line 8)");
    EXPECT_HAS(err, "must be quoted");

    fs::create_directories(dir + "/constant/dir.stl");
    err = errorFor("geometry \"constant/dir.stl\";\nmaxCellSize 0.1;\n");
    EXPECT_HAS(err, "not a regular file");

    writeFile(dir + "/constant/geometry/empty.stl", "");
    err = errorFor("geometry \"constant/geometry/empty.stl\";\nmaxCellSize 0.1;\n");
    EXPECT_HAS(err, "is empty");
}

TEST_F(caseDir, unreadableGeometryIsAnError)
{
    const std::string stl = dir + "/constant/geometry/body.stl";
    fs::permissions(stl, fs::perms::none);

    // Root reads any file: check as an unprivileged user in a child process
    writeDict(minimal());
    auto check = [&]
    {
        const std::string err = errorOf([&]{ readMeshSettings(dir); });
        return err.find("cannot be read") != std::string::npos
            && err.find("Entry 'geometry'") != std::string::npos;
    };
    bool ok = false;
    if (::geteuid() == 0)
    {
        // mkdtemp made the case private to root: let the user in
        fs::permissions(dir, fs::perms::others_read | fs::perms::others_exec, fs::perm_options::add);
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0)
        {
            const bool dropped = ::setgid(65534) == 0 && ::setuid(65534) == 0;
            std::_Exit(dropped && check() ? 0 : 1);
        }
        int status = 0;
        ::waitpid(child, &status, 0);
        ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    }
    else
    {
        ok = check();
    }
    fs::permissions(stl, fs::perms::owner_read | fs::perms::owner_write);
    EXPECT_TRUE(ok) << "no 'cannot be read' error naming Entry 'geometry'";
}

TEST_F(caseDir, geometryMayUseTheCaseTag)
{
    writeDict("geometry \"<case>/constant/geometry/body.stl\";\nmaxCellSize 1;\n");
    EXPECT_EQ
    (
        readMeshSettings(dir).geometryFile,
        fs::absolute(dir + "/constant/geometry/body.stl").lexically_normal().string()
    );
}

TEST_F(caseDir, maxCellSizeMustBeAPositiveNumber)
{
    std::string err = errorFor("geometry \"constant/geometry/body.stl\";\n");
    EXPECT_HAS(err, "Entry 'maxCellSize' not found");
    EXPECT_HAS(err, "numbers > 0");

    for (const char* bad : {"0", "-1", "small", "(1 2)"})
    {
        err = errorFor
        (
            "geometry \"constant/geometry/body.stl\";\nmaxCellSize "
          + std::string(bad) + ";\n"
        );
        EXPECT_HAS(err, "Entry 'maxCellSize'");
        EXPECT_HAS(err, "(line 9)");
        EXPECT_HAS(err, "numbers > 0");
    }
}

TEST_F(caseDir, integerEntriesMustBeIntegersInRange)
{
    for (const char* bad : {"11", "-1", "2.5", "two"})
    {
        const std::string err = errorFor(minimal() + "refinementLevels " + bad + ";\n");
        EXPECT_HAS(err, "Entry 'refinementLevels'");
        EXPECT_HAS(err, "(line 10)");
        EXPECT_HAS(err, "0 <= refinementLevels <= 10");
    }
    for (const char* bad : {"101", "-3", "1.5"})
    {
        const std::string err = errorFor(minimal() + "optimisationSteps " + bad + ";\n");
        EXPECT_HAS(err, "Entry 'optimisationSteps'");
        EXPECT_HAS(err, "0 <= optimisationSteps <= 100");
    }
    for (const char* bad : {"0", "257", "1.5"})
    {
        const std::string err = errorFor(minimal() + "volumeMesherThreads " + bad + ";\n");
        EXPECT_HAS(err, "Entry 'volumeMesherThreads'");
        EXPECT_HAS(err, "1 <= volumeMesherThreads <= 256");
    }
    const std::string err = errorFor(minimal() + "labelSize 48;\n");
    EXPECT_HAS(err, "Entry 'labelSize'");
    EXPECT_HAS(err, "(line 10) is 48");
    EXPECT_HAS(err, "32 or 64");
}

TEST_F(caseDir, volumeMesherMustBeAKnownBackend)
{
    const std::string err = errorFor(minimal() + "volumeMesher tetgen;\n");
    EXPECT_HAS(err, "Entry 'volumeMesher'");
    EXPECT_HAS(err, "(line 10) is tetgen");
    for (const std::string& name : VolumeMesher::names())
    {
        EXPECT_HAS(err, name);
    }
}

TEST_F(caseDir, unknownEntryIsAnErrorWithASuggestion)
{
    const std::string err = errorFor(minimal() + "gradng 0.3;\n");
    EXPECT_HAS(err, "Unknown entry 'gradng'");
    EXPECT_HAS(err, "(line 10)");
    EXPECT_HAS(err, "did you mean 'grading'?");
    EXPECT_HAS(err, "Valid entries are: geometry, maxCellSize, grading");

    // A regex key at top level is not a setting either
    EXPECT_HAS(errorFor(minimal() + "\".*\" 1;\n"), "Unknown entry '.*'");
}

TEST_F(caseDir, patchesAreValidated)
{
    std::string err = errorFor(minimal() + "patches wall;\n");
    EXPECT_HAS(err, "Entry 'patches'");
    EXPECT_HAS(err, "sub-dictionary");

    err = errorFor(minimal() + "patches\n{\n    inlet { type inflow; }\n}\n");
    EXPECT_HAS(err, "Entry 'type'");
    EXPECT_HAS(err, "(line 12) is inflow");
    EXPECT_HAS(err, "Valid patch types are: patch, wall, symmetry, symmetryPlane");

    err = errorFor(minimal() + "patches\n{\n    inlet patch;\n}\n");
    EXPECT_HAS(err, "Entry 'inlet'");
    EXPECT_HAS(err, "(line 12)");
    EXPECT_HAS(err, "{ type T; }");

    err = errorFor(minimal() + "patches\n{\n    inlet { }\n}\n");
    EXPECT_HAS(err, "Entry 'type' not found");
    EXPECT_HAS(err, "patches/inlet");
    EXPECT_HAS(err, "Valid patch types are");

    err = errorFor(minimal() + "patches\n{\n    inlet { type patch; tpye wall; }\n}\n");
    EXPECT_HAS(err, "Unknown entry 'tpye'");
    EXPECT_HAS(err, "(line 12)");
}

TEST_F(caseDir, patchTypeUsesExactNameThenLastMatchingRegex)
{
    writeDict
    (
        minimal()
      + "patches\n{\n"
        "    \".*\"        { type symmetryPlane; }\n"
        "    \"in.*\"      { type symmetry; }\n"
        "    inlet       { type patch; }\n"
        "}\n"
    );
    const meshSettings s = readMeshSettings(dir);
    EXPECT_EQ(s.patchType("inlet"), "patch");
    EXPECT_EQ(s.patchType("inside"), "symmetry");
    EXPECT_EQ(s.patchType("outlet"), "symmetryPlane");

    // A copy (as the application keeps it) still matches
    const meshSettings copy = s;
    EXPECT_EQ(copy.patchType("inside"), "symmetry");
}

TEST_F(caseDir, foamFileHeaderIsNotAnUnknownEntry)
{
    writeDict(minimal());
    EXPECT_NO_THROW(readMeshSettings(dir));
}


// * * * * * * * * * * * * * * * * controlDict * * * * * * * * * * * * * * //

TEST_F(caseDir, writeSettingsDefaults)
{
    writeFile(dir + "/system/controlDict", "application simpleFoam;\n");
    const writeSettings w = readWriteSettings(dir);
    EXPECT_FALSE(w.binary);
    EXPECT_EQ(w.writePrecision, 6);
    EXPECT_EQ(w.startTime, "0");
}

TEST_F(caseDir, writeSettingsAreRead)
{
    writeFile
    (
        dir + "/system/controlDict",
        "startTime 0.5;\nwriteFormat binary;\nwritePrecision 12;\n"
    );
    const writeSettings w = readWriteSettings(dir);
    EXPECT_TRUE(w.binary);
    EXPECT_EQ(w.writePrecision, 12);
    EXPECT_EQ(w.startTime, "0.5");

    writeFile(dir + "/system/controlDict", "startTime 100;\nwriteFormat ascii;\n");
    EXPECT_EQ(readWriteSettings(dir).startTime, "100");
    EXPECT_FALSE(readWriteSettings(dir).binary);

    writeFile(dir + "/system/controlDict", "startTime 0.0;\n");
    EXPECT_EQ(readWriteSettings(dir).startTime, "0");
}

TEST_F(caseDir, writeSettingsErrorsListValidValues)
{
    writeFile(dir + "/system/controlDict", "application simpleFoam;\nwriteFormat binar;\n");
    std::string err = errorOf([&]{ readWriteSettings(dir); });
    EXPECT_HAS(err, "Entry 'writeFormat'");
    EXPECT_HAS(err, "controlDict\" (line 2) is binar");
    EXPECT_HAS(err, "Valid values are: ascii, binary");

    for (const char* bad : {"0", "31", "high"})
    {
        writeFile(dir + "/system/controlDict", std::string("writePrecision ") + bad + ";\n");
        err = errorOf([&]{ readWriteSettings(dir); });
        EXPECT_HAS(err, "Entry 'writePrecision'");
        EXPECT_HAS(err, "1 <= writePrecision <= 30");
    }

    writeFile(dir + "/system/controlDict", "startTime latestTime;\n");
    err = errorOf([&]{ readWriteSettings(dir); });
    EXPECT_HAS(err, "Entry 'startTime'");
    EXPECT_HAS(err, "latestTime");
}

TEST_F(caseDir, missingControlDictNamesThePath)
{
    const std::string err = errorOf([&]{ readWriteSettings(dir); });
    EXPECT_HAS(err, dir + "/system/controlDict");
}

TEST(timeName, formatsAsOpenFOAMTimeDirectories)
{
    EXPECT_EQ(timeName(0), "0");
    EXPECT_EQ(timeName(0.5), "0.5");
    EXPECT_EQ(timeName(100), "100");
    EXPECT_EQ(timeName(1e-5), "1e-05");
    EXPECT_EQ(timeName(0.1 + 0.2), "0.3");
}
