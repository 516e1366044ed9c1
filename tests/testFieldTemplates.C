/*---------------------------------------------------------------------------*\
  Tests of the processor-directory fields and decomposeParDict
  (src/io/fieldTemplates).
\*---------------------------------------------------------------------------*/

#include "fieldTemplates.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace pmsh;
using namespace pmsh::test;
namespace fs = std::filesystem;

namespace
{

const std::string dataDir = std::string(PMSH_TEST_DATA) + "/io";

//- Text without blanks and newlines: OpenFOAM writes "( 1 0 0 )" where we
//  write "(1 0 0)", and lays out dictionaries its own way.
std::string noBlanks(std::string s)
{
    s.erase
    (
        std::remove_if(s.begin(), s.end(), [](char c){ return c == ' ' || c == '\n'; }),
        s.end()
    );
    return s;
}

//- Run an OpenFOAM command; its output (and a failure if it fails).
std::string runOpenFOAM(const std::string& command)
{
    const auto [out, status] = runFoam(command);
    EXPECT_EQ(status, 0) << command << "\n" << out;
    return out;
}

//- The test case (a copy of tests/data/io/fieldCase) in a temporary
//  directory, with OpenFOAM's etc directory replaced by the test stand-in.
class fieldCase
:
    public ::testing::Test
{
protected:

    const tempDir tmp{"fields"};
    const std::string dir = tmp.path();
    const scopedEnv etc{"WM_PROJECT_DIR", (dataDir + "/fakeOpenFOAM").c_str()};

    void SetUp() override
    {
        fs::copy(dataDir + "/fieldCase", dir, fs::copy_options::recursive);
    }

    const fieldTemplate& field(const std::vector<fieldTemplate>& fields, const std::string& name)
    {
        for (const fieldTemplate& f : fields)
        {
            if (f.name == name) return f;
        }
        ADD_FAILURE() << "no field " << name;
        return fields.front();
    }

    //- Patches of processor 0 of 3: physical ones, then processor ones.
    static std::vector<patchNameType> patches()
    {
        return
        {
            {"inlet", "patch"},
            {"outlet", "patch"},
            {"hull", "wall"},
            {"sym", "symmetryPlane"},
            {"procBoundary0to1", "processor"},
            {"procBoundary0to2", "processor"}
        };
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Templates * * * * * * * * * * * * * * * //

TEST_F(fieldCase, onlyFieldFilesAreTemplates)
{
    // Backups and hidden files beside the real ones
    fs::copy_file(dir + "/0/p", dir + "/0/p.orig");
    fs::copy_file(dir + "/0/p", dir + "/0/p~");
    fs::copy_file(dir + "/0/p", dir + "/0/.p.swp");
    fs::copy_file(dir + "/0/p", dir + "/0/p.bak");

    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    ASSERT_EQ(fields.size(), 2u);
    EXPECT_EQ(fields[0].name, "U");
    EXPECT_EQ(fields[1].name, "p");
    EXPECT_EQ(fields[0].className, "volVectorField");
    EXPECT_EQ(fields[1].className, "volScalarField");
    EXPECT_EQ(fields[0].file, dir + "/0/U");
}

TEST_F(fieldCase, missingTimeDirectoryGivesNoTemplates)
{
    EXPECT_TRUE(readFieldTemplates(dir + "/0.5").empty());
}

TEST_F(fieldCase, internalValueHasVariablesExpanded)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    EXPECT_EQ(field(fields, "U").internalValue, "(1 0 0)");
    EXPECT_EQ(field(fields, "p").internalValue, "0");
}

TEST(fieldTemplate, nonuniformInternalFieldIsAnError)
{
    const std::string file = dataDir + "/nonuniformCase/0/T";
    const std::string err = errorOf([]{ readFieldTemplates(dataDir + "/nonuniformCase/0"); });
    EXPECT_HAS(err, fs::absolute(file).lexically_normal().string());
    EXPECT_HAS(err, "line 11");
    EXPECT_HAS(err, "nonuniform");
    EXPECT_HAS(err, "only maps uniform initial fields");
}

TEST(fieldTemplate, internalAndBoundaryValuesMustBeUniform)
{
    const tempDir tmp("field");
    const std::string dir = tmp.path();
    const std::string head =
        "FoamFile { version 2.0; format ascii; class volScalarField; object T; }\n";

    writeFile(dir + "/T", head + "internalField 300;\nboundaryField { }\n");
    std::string err = errorOf([&]{ readFieldTemplate(dir + "/T"); });
    EXPECT_HAS(err, "Entry 'internalField'");
    EXPECT_HAS(err, "(line 2)");
    EXPECT_HAS(err, "internalField uniform <value>");

    writeFile(dir + "/T", head + "boundaryField { }\n");
    err = errorOf([&]{ readFieldTemplate(dir + "/T"); });
    EXPECT_HAS(err, "'internalField' not found");
    EXPECT_HAS(err, dir + "/T");

    writeFile(dir + "/T", head + "internalField uniform 1;\n");
    err = errorOf([&]{ readFieldTemplate(dir + "/T"); });
    EXPECT_HAS(err, "boundaryField");

    writeFile
    (
        dir + "/T",
        head + "internalField uniform 1;\nboundaryField\n{\n"
        "    inlet { type fixedValue; value nonuniform List<scalar> 2(1 2); }\n}\n"
    );
    err = errorOf([&]{ readFieldTemplate(dir + "/T"); });
    EXPECT_HAS(err, dir + "/T\" line 5");
    EXPECT_HAS(err, "entry 'value'");
    EXPECT_HAS(err, "only maps uniform values");
}


// * * * * * * * * * * * * * * * Patch matching  * * * * * * * * * * * * * //

TEST_F(fieldCase, patchesMatchByNameThenGroupThenRegex)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const fieldTemplate& U = field(fields, "U");

    EXPECT_EQ(matchingPatchEntry(U, "inlet", "patch"), "inlet");
    EXPECT_EQ(matchingPatchEntry(U, "hull", "wall"), "wall");
    EXPECT_EQ(matchingPatchEntry(U, "outlet", "patch"), "out.*");
    // From #includeEtc "caseDicts/setConstraintTypes"
    EXPECT_EQ(matchingPatchEntry(U, "sym", "symmetryPlane"), "symmetryPlane");
    EXPECT_EQ(matchingPatchEntry(U, "procBoundary0to1", "processor"), "processor");
    // A plain patch is in no group
    EXPECT_EQ(matchingPatchEntry(U, "hull", "patch"), "");

    // The group beats a regex, wherever it is written
    writeFile
    (
        dir + "/1/k",
        "FoamFile { version 2.0; format ascii; class volScalarField; object k; }\n"
        "internalField uniform 1;\n"
        "boundaryField { wall { type a; } \".*\" { type b; } \"h.*\" { type c; } }\n"
    );
    const fieldTemplate k = readFieldTemplate(dir + "/1/k");
    EXPECT_EQ(matchingPatchEntry(k, "hull", "wall"), "wall");
    EXPECT_EQ(matchingPatchEntry(k, "hull", "patch"), "h.*");
    EXPECT_EQ(matchingPatchEntry(k, "other", "patch"), ".*");
}

TEST_F(fieldCase, uncoveredPatchNamesFieldPatchAndKeys)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const fieldTemplate& U = field(fields, "U");
    std::vector<patchNameType> p = patches();
    p.push_back({"body", "patch"});

    const std::string err = errorOf([&]{ checkPatchCoverage(U, p); });
    EXPECT_HAS(err, dir + "/0/U");
    EXPECT_HAS(err, "patch 'body'");
    EXPECT_HAS(err, "#includeEtc \"caseDicts/setConstraintTypes\", inlet, wall, \"out.*\"");

    // Nothing is written for an uncovered patch
    EXPECT_NE(errorOf([&]{ writeProcessorField(U, dir + "/processor0/0/U", p); }), "");
    EXPECT_FALSE(fs::exists(dir + "/processor0/0/U"));
}


TEST_F(fieldCase, constraintPatchNeedsItsOwnPatchFieldType)
{
    const std::string head =
        "FoamFile { version 2.0; format ascii; class volScalarField; object k; }\n"
        "internalField uniform 1;\n";

    // A regex gives the symmetryPlane patch a fixedValue: OpenFOAM refuses
    writeFile(dir + "/0/k", head + "boundaryField\n{\n    \".*\" { type fixedValue; value uniform 1; }\n}\n");
    std::string err = errorOf([&]{ checkPatchCoverage(readFieldTemplate(dir + "/0/k"), patches()); });
    EXPECT_HAS(err, dir + "/0/k");
    EXPECT_HAS(err, "patch 'sym' (type symmetryPlane)");
    EXPECT_HAS(err, "\".*\" (line 5) of type fixedValue");
    EXPECT_HAS(err, "setConstraintTypes");

    // A constraint type on an ordinary patch is refused too
    writeFile(dir + "/0/k", head + "boundaryField\n{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n    \".*\" { type symmetryPlane; }\n}\n");
    err = errorOf([&]{ checkPatchCoverage(readFieldTemplate(dir + "/0/k"), patches()); });
    EXPECT_HAS(err, "patch 'inlet' (type patch)");
    EXPECT_HAS(err, "cannot take the constraint type symmetryPlane");

    // setConstraintTypes' group entry wins over the regex: accepted
    writeFile(dir + "/0/k", head + "boundaryField\n{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n    \".*\" { type fixedValue; value uniform 1; }\n}\n");
    EXPECT_EQ(errorOf([&]{ checkPatchCoverage(readFieldTemplate(dir + "/0/k"), patches()); }), "");
}


// * * * * * * * * * * * * * * * Writing fields  * * * * * * * * * * * * * //

TEST_F(fieldCase, processorFieldHasAnEntryForEveryPatch)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    for (const fieldTemplate& f : fields)
    {
        const std::string out = dir + "/processor0/0/" + f.name;
        writeProcessorField(f, out, patches());

        const fieldTemplate back = readFieldTemplate(out);
        EXPECT_EQ(back.className, f.className);
        EXPECT_EQ(back.internalValue, f.internalValue);
        const dictionary& header = back.dict.subDict("FoamFile");
        EXPECT_EQ(header.get<std::string>("location"), "0");
        EXPECT_EQ(header.get<std::string>("format"), "ascii");
        EXPECT_EQ(header.get<std::string>("object"), f.name);

        for (const patchNameType& p : patches())
        {
            EXPECT_NE(matchingPatchEntry(back, p.first, p.second), "")
                << f.name << " " << p.first;
        }

        // Processor patches: explicit entries, whatever a regex says
        const dictionary& bf = back.dict.subDict("boundaryField");
        for (const char* proc : {"procBoundary0to1", "procBoundary0to2"})
        {
            ASSERT_TRUE(bf.found(proc, false)) << f.name;
            EXPECT_EQ(bf.subDict(proc).get<std::string>("type"), "processor");
            EXPECT_EQ(bf.subDict(proc).text("value"), "uniform " + f.internalValue);
        }
    }
}

TEST_F(fieldCase, processorFieldKeepsTemplateEntriesAsWritten)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const std::string out = dir + "/processor0/0/U";
    writeProcessorField(field(fields, "U"), out, patches());
    const std::string text = readFile(out);

    EXPECT_HAS(text, "    #includeEtc \"caseDicts/setConstraintTypes\"\n");
    EXPECT_HAS(text, "    \"out.*\"\n    {\n        type            zeroGradient;\n");
    EXPECT_HAS(text, "internalField   uniform $flowVelocity;\n");
    EXPECT_HAS(text, "dimensions      [0 1 -1 0 0 0 0];\n");
    // The case-relative #include is read in: processor0/0 has no include/
    EXPECT_HAS(text, "flowVelocity    (1 0 0);\n");
    EXPECT_EQ(text.find("#include \""), std::string::npos) << text;
}

TEST_F(fieldCase, explicitTimeNameSetsTheLocation)
{
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const std::string out = dir + "/staging/processor0/fields/p";
    writeProcessorField(field(fields, "p"), out, patches(), "0.5");
    const dictionary back = dictionary::read(out);
    EXPECT_EQ(back.subDict("FoamFile").get<std::string>("location"), "0.5");
}

TEST_F(fieldCase, templateProcessorEntryIsKept)
{
    writeFile
    (
        dir + "/0/q",
        "FoamFile { version 2.0; format ascii; class volScalarField; object q; }\n"
        "internalField uniform 2;\n"
        "boundaryField { #includeEtc \"caseDicts/setConstraintTypes\"\n"
        " \".*\" { type zeroGradient; }"
        " procBoundary0to1 { type processor; value uniform 7; } }\n"
    );
    const fieldTemplate q = readFieldTemplate(dir + "/0/q");
    writeProcessorField(q, dir + "/processor0/0/q", patches());
    const dictionary back = dictionary::read(dir + "/processor0/0/q");
    const dictionary& bf = back.subDict("boundaryField");
    EXPECT_EQ(bf.subDict("procBoundary0to1").text("value"), "uniform 7");
    EXPECT_EQ(bf.subDict("procBoundary0to2").text("value"), "uniform 2");
}

TEST_F(fieldCase, pointFieldProcessorEntriesHaveNoValue)
{
    writeFile
    (
        dir + "/0/pointDisplacement",
        "FoamFile { version 2.0; format ascii; class pointVectorField;"
        " object pointDisplacement; }\n"
        "dimensions [0 1 0 0 0 0 0];\n"
        "internalField uniform (0 0 0);\n"
        "boundaryField { #includeEtc \"caseDicts/setConstraintTypes\"\n"
        " \".*\" { type fixedValue; value uniform (0 0 0); } }\n"
    );
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const fieldTemplate& pd = field(fields, "pointDisplacement");
    writeProcessorField(pd, dir + "/processor0/0/pointDisplacement", patches());
    const dictionary back = dictionary::read(dir + "/processor0/0/pointDisplacement");
    const dictionary& proc = back.subDict("boundaryField").subDict("procBoundary0to1");
    EXPECT_EQ(proc.get<std::string>("type"), "processor");
    EXPECT_FALSE(proc.found("value"));
}

TEST_F(fieldCase, processorFieldIsReadableByOpenFOAM)
{
    if (!fs::exists("/usr/bin/foamDictionary"))
    {
        GTEST_SKIP() << "OpenFOAM's foamDictionary is not installed";
    }
    const std::vector<fieldTemplate> fields = readFieldTemplates(dir + "/0");
    const std::string out = dir + "/processor0/0/U";
    writeProcessorField(field(fields, "U"), out, patches());

    // foamDictionary -expand resolves #includeEtc (the real one) and $vars
    EXPECT_EQ
    (
        noBlanks(runOpenFOAM("foamDictionary -entry boundaryField/procBoundary0to2/value -value " + out)),
        "uniform(100)"
    );
    const std::string expanded =
        noBlanks(runOpenFOAM("foamDictionary -expand " + out));
    EXPECT_HAS(expanded, "internalFielduniform(100);");
    EXPECT_HAS(expanded, "procBoundary0to1{typeprocessor;valueuniform(100);}");
    EXPECT_HAS(expanded, "symmetryPlane{typesymmetryPlane;}");
}


// * * * * * * * * * * * * * * * decomposeParDict  * * * * * * * * * * * * //

TEST_F(fieldCase, decomposeParDictIsCreated)
{
    writeDecomposeParDict(dir, 4);
    const dictionary d = dictionary::read(dir + "/system/decomposeParDict");
    EXPECT_EQ(d.get<int>("numberOfSubdomains"), 4);
    EXPECT_EQ(d.get<std::string>("method"), "scotch");
    EXPECT_EQ(d.subDict("FoamFile").get<std::string>("class"), "dictionary");
    EXPECT_EQ(d.subDict("FoamFile").get<std::string>("object"), "decomposeParDict");

    if (fs::exists("/usr/bin/foamDictionary"))
    {
        EXPECT_EQ
        (
            runOpenFOAM
            (
                "foamDictionary -entry numberOfSubdomains -value "
              + dir + "/system/decomposeParDict"
            ),
            "4\n"
        );
    }
}

TEST_F(fieldCase, decomposeParDictUpdateChangesOnlyTheNumber)
{
    const std::string before =
        "/* the user's decomposeParDict */\n"
        "FoamFile { version 2.0; format ascii; class dictionary;"
        " object decomposeParDict; }\n"
        "numberOfSubdomains  2;   // was two\n"
        "method          hierarchical;\n"
        "coeffs\n{\n    n (2 1 1);\n}\n";
    writeFile(dir + "/system/decomposeParDict", before);

    writeDecomposeParDict(dir, 16);
    const std::string after = readFile(dir + "/system/decomposeParDict");
    std::string expected = before;
    expected.replace(expected.find("2;   // was"), 1, "16");
    EXPECT_EQ(after, expected);
}

TEST_F(fieldCase, decomposeParDictWithoutTheNumberGainsIt)
{
    const std::string before =
        "FoamFile { version 2.0; format ascii; class dictionary;"
        " object decomposeParDict; }\n"
        "method          simple;  // keep\n"
        "coeffs { n (2 1 1); }\n";
    writeFile(dir + "/system/decomposeParDict", before);

    writeDecomposeParDict(dir, 3);
    const std::string after = readFile(dir + "/system/decomposeParDict");
    EXPECT_HAS(after, "method          simple;  // keep\n");
    const dictionary d = dictionary::read(dir + "/system/decomposeParDict");
    EXPECT_EQ(d.get<int>("numberOfSubdomains"), 3);
    EXPECT_EQ(d.text("coeffs"), dictionary::parse(before, "x").text("coeffs"));
}

TEST_F(fieldCase, decomposeParDictNeedsAPositiveNumber)
{
    EXPECT_HAS(errorOf([&]{ writeDecomposeParDict(dir, 0); }), "at least 1");
    EXPECT_FALSE(fs::exists(dir + "/system/decomposeParDict"));
}
