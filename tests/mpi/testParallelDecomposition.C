// Stage 2 in a parallel run: OpenFOAM's decomposition methods gather the
// cells of every rank when Pstream runs parallel, but pmshFoam's coarse
// mesh is whole on the master, which decomposes it alone. partitionCells
// switches parallel off around the method, and back on after it.

#include "mpiTestMain.H"
#include "partitionCoarseMesh.H"
#include "cubeMesh.H"
#include "pmshError.H"

// OpenFOAM
#include "dictionary.H"
#include "IStringStream.H"
#include "UPstream.H"

using namespace pmsh;

namespace
{

Foam::dictionary dictOf(const std::string& text)
{
    return Foam::dictionary(Foam::IStringStream(text)());
}

} // End anonymous namespace


TEST(parallelDecomposition, eachRanksMeshIsDecomposedAsInASerialRun)
{
    // Each rank decomposes a mesh of its own at the same time: were the
    // method to run parallel, it would decompose the ranks' cells together
    const bool parRun = test::world().parallel();
    ASSERT_EQ(Foam::UPstream::parRun(), parRun);
    const CoarseMesh m = test::cubeMesh(3 + test::world().rank());
    for (const char* method :
    {
        "method simple; coeffs { n (2 1 1); }",
        "method metis;"
    })
    {
        Foam::UPstream::parRun() = false;
        const std::vector<label> serial = partitionCells(m, 2, dictOf(method));
        Foam::UPstream::parRun() = parRun;

        EXPECT_EQ(partitionCells(m, 2, dictOf(method)), serial) << method;
        EXPECT_EQ(Foam::UPstream::parRun(), parRun) << method;
    }
}


TEST(parallelDecomposition, parallelIsBackOnAfterAMethodFails)
{
    const bool parRun = test::world().parallel();
    const CoarseMesh m = test::cubeMesh(3);
    // simple's n must multiply to the number of parts: the method throws
    EXPECT_THROW
    (
        partitionCells(m, 3, dictOf("method simple; coeffs { n (2 1 1); }")),
        FatalError
    );
    EXPECT_EQ(Foam::UPstream::parRun(), parRun);
}
