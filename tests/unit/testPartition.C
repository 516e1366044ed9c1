// Stage 2: the partition by OpenFOAM's decompositionMethod (the methods of
// decomposeParDict), and its repair into parts with closed, manifold
// surfaces, which the volume mesher needs.

#include "partitionCoarseMesh.H"
#include "fineCellWeights.H"
#include "partitionSurface.H"
#include "Geometry.H"
#include "cubeMesh.H"
#include "quietFoamInfo.H"
#include "surfaceChecks.H"
#include "testPaths.H"
#include "testUtilities.H"
#include "pmshError.H"

// OpenFOAM
#include "argList.H"
#include "dictionary.H"
#include "fileName.H"
#include "IStringStream.H"
#include "foamShims.H"
#include "messageStream.H"
#include "UPstream.H"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <unistd.h>

using namespace pmsh;

namespace
{

Foam::dictionary dictOf(const std::string& text)
{
    return Foam::dictionary(Foam::IStringStream(text)());
}


bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}


// Every part in [0, nParts), non-empty, with a closed manifold surface
void expectGoodPartition
(
    const CoarseMesh& m,
    const std::vector<label>& part,
    label nParts,
    const std::string& what
)
{
    ASSERT_EQ(part.size(), m.tets.size()) << what;
    std::vector<int> size(nParts, 0);
    for (label p : part)
    {
        ASSERT_GE(p, 0) << what;
        ASSERT_LT(p, nParts) << what;
        ++size[p];
    }
    for (label p = 0; p < nParts; ++p)
    {
        EXPECT_GT(size[p], 0) << what << ": part " << p;
        EXPECT_TRUE(test::closedManifold(partitionSurface(m, part, p).faces))
            << what << ": part " << p;
    }
    EXPECT_EQ(countNonManifoldParts(m, part), 0) << what;
}


// Quiet OpenFOAM's Info ("Selecting decompositionMethod ...") in the tests
// of this file
class decomposition : public test::quietFoamInfo {};


// The tests of the repair (and of the default method): quiet as well
class partition : public decomposition {};


// A scratch directory, removed with its files at the end of the test
struct scratchDir
{
    std::string path;
    scratchDir()
    {
        char tmpl[] = "/tmp/pmshTestPartitionXXXXXX";
        path = mkdtemp(tmpl);
    }
    ~scratchDir()
    {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string write(const std::string& name, const std::string& text) const
    {
        const std::string file = path + "/" + name;
        std::ofstream(file) << text;
        return file;
    }
};

const char* foamHeader =
    "FoamFile\n{\n    version 2.0;\n    format ascii;\n"
    "    class dictionary;\n    object decomposeParDict;\n}\n";

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Methods  * * * * * * * * * * * * * * * * //

TEST_F(decomposition, metisGivesNonEmptyClosedManifoldParts)
{
    const CoarseMesh m = test::cubeMesh(6);
    const Foam::dictionary dict = dictOf("method metis;");
    for (label nParts : {2, 3, 4, 7, 16})
    {
        expectGoodPartition(m, partitionCells(m, nParts, dict), nParts,
            "metis, " + std::to_string(nParts) + " parts");
    }
}


TEST_F(decomposition, kWayMetisIsTheDefault)
{
    const CoarseMesh m = test::cubeMesh(5);
    EXPECT_EQ
    (
        partitionCells(m, 4),
        partitionCells(m, 4, dictOf("method metis; metisCoeffs { method k-way; }"))
    );
    EXPECT_EQ
    (
        Foam::word(foam::get<Foam::word>(defaultDecompositionDict(), "method")),
        Foam::word("metis")
    );
}


TEST_F(decomposition, metisIsTheSameOnEveryCall)
{
    const CoarseMesh m = test::cubeMesh(5);
    const Foam::dictionary dict = dictOf("method metis;");
    const std::vector<label> first = partitionCells(m, 4, dict);
    for (int i = 0; i < 3; ++i)
    {
        EXPECT_EQ(partitionCells(m, 4, dict), first);
    }
}


TEST_F(decomposition, metisCoeffsAreUsed)
{
    const CoarseMesh m = test::cubeMesh(6);
    const std::vector<label> kway =
        partitionCells(m, 5, dictOf("method metis; metisCoeffs { method k-way; }"));
    expectGoodPartition(m, kway, 5, "metis k-way");
    EXPECT_EQ
    (
        kway,
        partitionCells(m, 5, dictOf("method metis; metisCoeffs { method k-way; }"))
    );
}


TEST_F(decomposition, simpleGivesNonEmptyClosedManifoldParts)
{
    const CoarseMesh m = test::cubeMesh(6);
    const std::vector<label> coeffs =
        partitionCells(m, 4, dictOf("method simple; coeffs { n (2 2 1); }"));
    expectGoodPartition(m, coeffs, 4, "simple, coeffs");

    // The older name of the coefficients, which v1912 also reads
    const std::vector<label> simpleCoeffs =
        partitionCells(m, 4, dictOf("method simple; simpleCoeffs { n (2 2 1); delta 0.001; }"));
    expectGoodPartition(m, simpleCoeffs, 4, "simple, simpleCoeffs");
    EXPECT_EQ(coeffs, simpleCoeffs);

    // Split in x and y only: the parts are the four columns of cubes
    for (std::size_t c = 0; c < m.tets.size(); ++c)
    {
        const int cube = int(c/6);
        const int i = cube % 6, j = (cube/6) % 6;
        EXPECT_EQ(coeffs[c], coeffs[6*(i + 6*j)]) << "cell " << c;
    }
    std::set<label> columns;
    for (int i : {0, 5}) for (int j : {0, 5}) columns.insert(coeffs[6*(i + 6*j)]);
    EXPECT_EQ(columns.size(), 4u);

    expectGoodPartition(m, partitionCells(m, 8, dictOf("method simple; coeffs { n (2 2 2); }")), 8,
        "simple (2 2 2)");
}


TEST_F(decomposition, hierarchicalGivesNonEmptyClosedManifoldParts)
{
    const CoarseMesh m = test::cubeMesh(6);
    expectGoodPartition
    (
        m,
        partitionCells(m, 4, dictOf("method hierarchical; coeffs { n (2 2 1); order xyz; }")),
        4, "hierarchical, coeffs"
    );
    expectGoodPartition
    (
        m,
        partitionCells
        (
            m, 6,
            dictOf("method hierarchical; hierarchicalCoeffs { n (1 2 3); delta 0.001; order zyx; }")
        ),
        6, "hierarchical, hierarchicalCoeffs"
    );
}


TEST_F(decomposition, multiLevelGivesNonEmptyClosedManifoldParts)
{
    const CoarseMesh m = test::cubeMesh(6);
    const Foam::dictionary dict = dictOf
    (
        "method multiLevel;"
        "multiLevelCoeffs"
        "{"
        "    level0 { numberOfSubdomains 2; method simple; coeffs { n (2 1 1); } }"
        "    level1 { numberOfSubdomains 2; method metis; }"
        "}"
    );
    expectGoodPartition(m, partitionCells(m, 4, dict), 4, "multiLevel");
}


TEST_F(decomposition, scotchGivesClosedManifoldPartsWhereThisOpenFOAMHasIt)
{
    // Debian's libscotchDecomp is a stub: scotch is one of this OpenFOAM's
    // methods only where the real library is built and linked. Where it is
    // listed, it must work: pmshFoam offers every listed method.
    if (!contains(validDecompositionMethods(), " scotch") && !contains(validDecompositionMethods(), "(scotch"))
    {
        GTEST_SKIP() << "scotch is not a decomposition method of this OpenFOAM: "
            << validDecompositionMethods();
    }
    const CoarseMesh m = test::cubeMesh(6);
    expectGoodPartition(m, partitionCells(m, 4, dictOf("method scotch;")), 4, "scotch");
}


TEST_F(decomposition, worksOnANetgenCoarseMesh)
{
    // An unstructured coarse mesh, as pmshFoam's stage 1 makes it
    auto g = Geometry::New(test::testDataDir() + "/geometry/sphere.geo");
    const CoarseMesh m = g->coarseMesh({0.3, 0.3});
    ASSERT_GT(m.nCells(), 100);
    for (const char* method :
    {
        "method metis;",
        "method metis; metisCoeffs { method k-way; }",
        "method simple; coeffs { n (2 2 1); }",
        "method hierarchical; coeffs { n (2 2 1); order xyz; }"
    })
    {
        expectGoodPartition(m, partitionCells(m, 4, dictOf(method)), 4, method);
    }
    expectGoodPartition(m, partitionCells(m, 3, dictOf("method metis;")), 3, "metis 3");
}


// * * * * * * * * * * * * * * numberOfSubdomains * * * * * * * * * * * * * //

TEST_F(decomposition, numberOfSubdomainsIsReplacedByTheNumberOfParts)
{
    const CoarseMesh m = test::cubeMesh(6);
    const std::vector<label> part =
        partitionCells(m, 4, dictOf("method metis; numberOfSubdomains 2;"));
    expectGoodPartition(m, part, 4, "metis, numberOfSubdomains 2");
    EXPECT_EQ(std::set<label>(part.begin(), part.end()).size(), 4u);

    // simple checks that n multiplies to numberOfSubdomains: it must see 4
    EXPECT_NO_THROW
    (
        partitionCells(m, 4, dictOf("method simple; numberOfSubdomains 9; coeffs { n (2 2 1); }"))
    );
}


TEST_F(decomposition, decompositionDictReadsTheFileAndSetsNumberOfSubdomains)
{
    const scratchDir dir;
    const std::string file = dir.write
    (
        "decomposeParDict",
        std::string(foamHeader)
      + "numberOfSubdomains 8;\nmethod simple;\ncoeffs\n{\n    n (2 2 1);\n}\n"
    );

    // The note is Info, which this fixture quiets for the methods' own
    Foam::messageStream::level = 1;
    testing::internal::CaptureStdout();
    const Foam::dictionary dict = decompositionDict(Foam::fileName(file), 4);
    const std::string log = testing::internal::GetCapturedStdout();

    EXPECT_EQ(foam::get<Foam::label>(dict, "numberOfSubdomains"), 4);
    EXPECT_EQ(foam::get<Foam::word>(dict, "method"), Foam::word("simple"));
    EXPECT_FALSE(dict.found("FoamFile"));
    EXPECT_TRUE(contains(log, "numberOfSubdomains 8")) << log;
    EXPECT_TRUE(contains(log, file)) << log;

    const CoarseMesh m = test::cubeMesh(4);
    expectGoodPartition(m, partitionCells(m, 4, dict), 4, "simple from the file");
}


TEST_F(decomposition, decompositionDictSaysNothingWhenNumberOfSubdomainsAgrees)
{
    const scratchDir dir;
    const std::string file = dir.write
    (
        "decomposeParDict", std::string(foamHeader) + "numberOfSubdomains 4;\nmethod metis;\n"
    );
    // The note is Info, which this fixture quiets for the methods' own
    Foam::messageStream::level = 1;
    testing::internal::CaptureStdout();
    const Foam::dictionary dict = decompositionDict(Foam::fileName(file), 4);
    const std::string log = testing::internal::GetCapturedStdout();
    EXPECT_FALSE(contains(log, "numberOfSubdomains")) << log;
    EXPECT_EQ(foam::get<Foam::label>(dict, "numberOfSubdomains"), 4);
}


TEST_F(decomposition, decompositionDictWithoutAFileIsMetis)
{
    const scratchDir dir;
    const Foam::dictionary dict =
        decompositionDict(Foam::fileName(dir.path + "/system/decomposeParDict"), 3);
    EXPECT_EQ(foam::get<Foam::word>(dict, "method"), Foam::word("metis"));
    EXPECT_EQ(foam::get<Foam::label>(dict, "numberOfSubdomains"), 3);
}


TEST_F(decomposition, aMissingRequiredDictionaryIsAFatalError)
{
    const scratchDir dir;
    const std::string file = dir.path + "/myDecomposeParDict";
    const std::string what = test::errorOf([&]
    {
        decompositionDict(Foam::fileName(file), 2, true);
    });
    EXPECT_TRUE(contains(what, file)) << what;
    EXPECT_TRUE(contains(what, "does not exist")) << what;
}


TEST_F(decomposition, aBrokenDictionaryIsAFatalErrorNamingTheFile)
{
    const scratchDir dir;
    const std::string file = dir.write
    (
        "decomposeParDict", std::string(foamHeader) + "method metis;\ncoeffs { n (2 2 1;\n"
    );
    const std::string what = test::errorOf([&]
    {
        decompositionDict(Foam::fileName(file), 2);
    });
    EXPECT_TRUE(contains(what, file)) << what;
}


TEST_F(decomposition, theDictionaryComesFromTheCaseOrTheDecomposeParDictOption)
{
    const scratchDir dir;
    std::filesystem::create_directories(dir.path + "/system");
    std::filesystem::create_directories(dir.path + "/other");
    dir.write("system/decomposeParDict", std::string(foamHeader) + "method hierarchical;\n");
    dir.write("other/myDict", std::string(foamHeader) + "method simple;\n");
    dir.write("other/decomposeParDict", std::string(foamHeader) + "method random;\n");

    // argList as pmshFoam makes it, without its initialisation (banner,
    // signal handlers, libraries). Never destroyed: ~argList ends the
    // process (UPstream::exit)
    auto argsOf = [](const std::vector<std::string>& words) -> const Foam::argList*
    {
        static std::vector<std::unique_ptr<std::vector<std::string>>> keep;
        static std::vector<std::unique_ptr<std::vector<char*>>> argvs;
        keep.push_back(std::make_unique<std::vector<std::string>>(words));
        argvs.push_back(std::make_unique<std::vector<char*>>());
        for (std::string& w : *keep.back())
        {
            argvs.back()->push_back(&w[0]);
        }
        argvs.back()->push_back(nullptr);
        int argc = int(words.size());
        char** argv = argvs.back()->data();
        return new Foam::argList(argc, argv, true, true, false);
    };

    const auto plain = argsOf({"Test-pmshUnit", "-case", dir.path});
    EXPECT_EQ(std::string(decompositionDictFile(*plain)), dir.path + "/system/decomposeParDict");
    EXPECT_EQ(foam::get<Foam::word>(decompositionDict(*plain, 2), "method"), Foam::word("hierarchical"));

    // A relative file is relative to the case, as argList resolves it in a
    // parallel run
    const auto file = argsOf({"Test-pmshUnit", "-case", dir.path, "-decomposeParDict", "other/myDict"});
    EXPECT_EQ(std::string(decompositionDictFile(*file)), dir.path + "/other/myDict");
    const Foam::dictionary dict = decompositionDict(*file, 2);
    EXPECT_EQ(foam::get<Foam::word>(dict, "method"), Foam::word("simple"));
    EXPECT_EQ(foam::get<Foam::label>(dict, "numberOfSubdomains"), 2);

    // A directory holds a decomposeParDict
    const auto directory =
        argsOf({"Test-pmshUnit", "-case", dir.path, "-decomposeParDict", dir.path + "/other"});
    EXPECT_EQ(std::string(decompositionDictFile(*directory)), dir.path + "/other/decomposeParDict");

    // A file asked for must exist
    const auto missing = argsOf({"Test-pmshUnit", "-case", dir.path, "-decomposeParDict", "other/none"});
    EXPECT_THROW(decompositionDict(*missing, 2), FatalError);
}


// * * * * * * * * * * * * * * * * * Errors  * * * * * * * * * * * * * * * * //

TEST_F(decomposition, anUnknownMethodIsAFatalErrorNamingTheValidOnes)
{
    const CoarseMesh m = test::cubeMesh(2);
    const std::string what = test::errorOf([&]
    {
        partitionCells(m, 2, dictOf("method fooBar;"));
    });
    EXPECT_TRUE(contains(what, "'fooBar'")) << what;
    EXPECT_TRUE(contains(what, "Valid decomposition methods")) << what;
    for (const char* valid : {"metis", "simple", "hierarchical"})
    {
        EXPECT_TRUE(contains(what, valid)) << what;
    }
    EXPECT_FALSE(contains(what, "manual")) << what;
}


TEST_F(decomposition, aFailingMethodIsAFatalErrorNamingItAndTheValidOnes)
{
    // n (2 2 1) makes 4 parts, not 3: OpenFOAM's FatalError, as ours
    const CoarseMesh m = test::cubeMesh(3);
    const std::string what = test::errorOf([&]
    {
        partitionCells(m, 3, dictOf("method simple; coeffs { n (2 2 1); }"));
    });
    EXPECT_TRUE(contains(what, "'simple'")) << what;
    EXPECT_TRUE(contains(what, "failed")) << what;
    EXPECT_TRUE(contains(what, "Valid decomposition methods")) << what;
    EXPECT_TRUE(contains(what, "metis")) << what;

    // A method without its coefficients
    const std::string noCoefficients = test::errorOf([&]
    {
        partitionCells(m, 4, dictOf("method hierarchical;"));
    });
    EXPECT_TRUE(contains(noCoefficients, "'hierarchical'")) << noCoefficients;
}


TEST_F(decomposition, aMethodThatNeedsAPolyMeshIsAFatalError)
{
    const CoarseMesh m = test::cubeMesh(2);
    const std::string what = test::errorOf([&]
    {
        partitionCells(m, 2, dictOf("method manual; coeffs { dataFile \"decomp\"; }"));
    });
    EXPECT_TRUE(contains(what, "'manual'")) << what;
    EXPECT_TRUE(contains(what, "Valid decomposition methods")) << what;
}


TEST_F(decomposition, noMethodIsAFatalError)
{
    const CoarseMesh m = test::cubeMesh(2);
    const std::string what = test::errorOf([&]
    {
        partitionCells(m, 2, dictOf("numberOfSubdomains 2;"));
    });
    EXPECT_TRUE(contains(what, "method")) << what;
    EXPECT_TRUE(contains(what, "Valid decomposition methods")) << what;
}


TEST_F(decomposition, foamErrorsAreLeftAsTheCallerSetThem)
{
    const bool oldThrow = foam::throwExceptions(Foam::FatalError, false);
    const bool oldIOThrow = foam::throwExceptions(Foam::FatalIOError, false);
    const CoarseMesh m = test::cubeMesh(2);
    EXPECT_THROW(partitionCells(m, 2, dictOf("method simple; coeffs { n (3 1 1); }")), FatalError);
    EXPECT_FALSE(foam::throwing(Foam::FatalError));
    EXPECT_FALSE(foam::throwing(Foam::FatalIOError));
    foam::throwExceptions(Foam::FatalError, oldThrow);
    foam::throwExceptions(Foam::FatalIOError, oldIOThrow);
}


// * * * * * * * * * * * * * * * * * Repair  * * * * * * * * * * * * * * * * //

TEST_F(partition, everyPartIsNonEmptyWithAClosedManifoldSurface)
{
    const CoarseMesh m = test::cubeMesh(6);
    for (label nParts : {2, 3, 4, 7, 16})
    {
        const std::vector<label> part = partitionCells(m, nParts);
        ASSERT_EQ(part.size(), m.tets.size());
        std::vector<int> size(nParts, 0);
        for (label p : part)
        {
            ASSERT_GE(p, 0);
            ASSERT_LT(p, nParts);
            ++size[p];
        }
        for (label p = 0; p < nParts; ++p)
        {
            EXPECT_GT(size[p], 0) << nParts << " parts";
            EXPECT_TRUE(test::closedManifold(partitionSurface(m, part, p).faces))
                << "part " << p << " of " << nParts;
        }
        EXPECT_EQ(countNonManifoldParts(m, part), 0) << nParts << " parts";
    }
}


TEST_F(partition, repairTurnsACheckerboardIntoManifoldParts)
{
    // Alternating cubes touch each other only along edges and at corners
    const int n = 4;
    const CoarseMesh m = test::cubeMesh(n);
    std::vector<label> part(m.tets.size());
    for (std::size_t c = 0; c < part.size(); ++c)
    {
        const int cube = int(c/6);
        const int i = cube % n, j = (cube/n) % n, k = cube/(n*n);
        part[c] = (i + j + k) % 2;
    }
    ASSERT_GT(countNonManifoldParts(m, part), 0);

    const label moved = repairPartition(m, 2, part);
    EXPECT_GT(moved, 0);
    EXPECT_EQ(countNonManifoldParts(m, part), 0);
    for (label p : {0, 1})
    {
        EXPECT_TRUE(test::closedManifold(partitionSurface(m, part, p).faces)) << "part " << p;
    }
}


TEST_F(partition, repairGivesEveryEmptyPartACell)
{
    const CoarseMesh m = test::cubeMesh(2);
    std::vector<label> part(m.tets.size(), 0);
    repairPartition(m, 3, part);
    std::set<label> used(part.begin(), part.end());
    EXPECT_EQ(used.size(), 3u);
    EXPECT_EQ(countNonManifoldParts(m, part), 0);
}


TEST_F(partition, isTheSameOnEveryCall)
{
    const CoarseMesh m = test::cubeMesh(5);
    EXPECT_EQ(partitionCells(m, 4), partitionCells(m, 4));
}


TEST_F(partition, onePartIsAllZeroWhateverTheMethod)
{
    const CoarseMesh m = test::cubeMesh(2);
    EXPECT_EQ(partitionCells(m, 1, dictOf("method fooBar;")), std::vector<label>(m.tets.size(), 0));
}


TEST_F(partition, moreRanksThanCoarseCellsIsAFatalErrorSayingWhatToDo)
{
    const CoarseMesh m = test::cubeMesh(1);    // 6 cells
    const std::string what = test::errorOf([&]
    {
        partitionCells(m, 7, dictOf("method metis;"));
    });
    EXPECT_NE(what.find("6 cells into 7 parts"), std::string::npos) << what;
    EXPECT_NE(what.find("maxCellSize"), std::string::npos);
}


// * * * * * * * * * * * * * * * * * Balance * * * * * * * * * * * * * * * * //

TEST_F(partition, fineCellWeightsFollowVolumeOverLocalSizeAndTheGeometry)
{
    // Scaled by 2, an inner cell's weight V/(H^2 h) grows 8/2 = 4 times;
    // cells on the geometry weigh more than inner cells of the same shape
    const CoarseMesh m = test::cubeMesh(4);
    CoarseMesh big = m;
    for (point3& p : big.points) p = 2.0*p;
    const std::vector<double> w = fineCellWeights(m, 1.0, 2);
    const std::vector<double> wBig = fineCellWeights(big, 1.0, 2);
    const std::vector<faceNeighbours> nbrs = coarseFaceNeighbours(m);
    double inner = 0, outer = 0;
    label nInner = 0, nOuter = 0;
    for (std::size_t c = 0; c < w.size(); ++c)
    {
        EXPECT_GT(w[c], 0);
        const bool onGeometry = std::any_of(nbrs[c].begin(), nbrs[c].end(), isBoundaryNeighbour);
        if (onGeometry)
        {
            outer += w[c];
            ++nOuter;
        }
        else
        {
            inner += w[c];
            ++nInner;
            EXPECT_NEAR(wBig[c]/w[c], 4.0, 1e-9) << "cell " << c;
        }
    }
    ASSERT_GT(nInner, 0);
    EXPECT_GT(outer/nOuter, 1.2*inner/nInner);
}


TEST_F(partition, fineCellWeightsInsideARefinementRegionFollowOneOverSizeCubed)
{
    // The unit cube's cells (edges about 1/4) in a mesh of H = 1: inside a
    // region the volume mesher is held to the region's size, so the cells
    // there weigh 2 V/h^3 instead of V/(H^2 h), 2 H^2/h^2 (~32) times more;
    // a region that does not refine (size >= H) changes nothing
    const CoarseMesh m = test::cubeMesh(4);
    sizeRegion lower;
    lower.type = sizeRegion::shape::box;
    lower.min = {-1, -1, -1};
    lower.max = {2, 2, 0.5};
    lower.size = 0.25;
    sizeRegion coarse = lower;
    coarse.size = 1.0;

    const std::vector<double> w = fineCellWeights(m, 1.0, 2);
    const std::vector<double> wRegion = fineCellWeights(m, 1.0, 2, {lower});
    EXPECT_EQ(fineCellWeights(m, 1.0, 2, {coarse}), w);
    const std::vector<faceNeighbours> nbrs = coarseFaceNeighbours(m);
    label nInside = 0;
    for (std::size_t c = 0; c < w.size(); ++c)
    {
        const tetVerts& t = m.tets[c];
        const double z =
            0.25*(m.points[t[0]][2] + m.points[t[1]][2] + m.points[t[2]][2] + m.points[t[3]][2]);
        const bool onGeometry = std::any_of(nbrs[c].begin(), nbrs[c].end(), isBoundaryNeighbour);
        if (z <= 0.5)
        {
            // (the geometry's term, which dominates cells on it, stays)
            ++nInside;
            EXPECT_GT(wRegion[c], (onGeometry ? 1.5 : 10)*w[c]) << "cell " << c;
        }
        else
        {
            EXPECT_EQ(wRegion[c], w[c]) << "cell " << c;
        }
    }
    EXPECT_GT(nInside, 0);
}


TEST_F(partition, balancedPartsCarryEqualWeightAndStayManifolds)
{
    // Cells in the half x < 0.5 weigh 3: unit weights would give parts of
    // equal cell counts and unequal weight
    const CoarseMesh m = test::cubeMesh(6);
    std::vector<double> w(m.tets.size(), 1.0);
    for (std::size_t c = 0; c < w.size(); ++c)
    {
        const tetVerts& t = m.tets[c];
        const double x = 0.25*(m.points[t[0]][0] + m.points[t[1]][0] + m.points[t[2]][0] + m.points[t[3]][0]);
        if (x < 0.5) w[c] = 3;
    }
    for (label nParts : {2, 4, 7})
    {
        const std::vector<label> unit = partitionCells(m, nParts, dictOf("method simple; coeffs { n (" + std::to_string(nParts) + " 1 1); }"));
        std::vector<label> part = unit;
        ASSERT_GT(weightImbalance(w, nParts, part), 1.2) << nParts;
        const label moved = balancePartition(m, nParts, w, part);
        EXPECT_GT(moved, 0);
        EXPECT_LT(weightImbalance(w, nParts, part), 1.05) << nParts << " parts";
        expectGoodPartition(m, part, nParts, "balanced, " + std::to_string(nParts) + " parts");
    }
}


TEST_F(partition, weightsGoThroughTheMethodAndTheBalance)
{
    const CoarseMesh m = test::cubeMesh(6);
    std::vector<double> w(m.tets.size(), 1.0);
    for (std::size_t c = 0; c < w.size(); c += 3) w[c] = 5;
    const std::vector<label> part = partitionCells(m, 4, dictOf("method metis;"), w);
    EXPECT_LT(weightImbalance(w, 4, part), 1.02);
    expectGoodPartition(m, part, 4, "weighted metis");
}
