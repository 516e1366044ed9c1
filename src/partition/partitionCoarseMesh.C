#include "partitionCoarseMesh.H"
#include "decompositionMethodCheck.H"
#include "failTogether.H"
#include "foamShims.H"
#include "pmshError.H"
#include "streamManip.H"

// OpenFOAM
#include "decompositionMethod.H"
#include "dictionary.H"
#include "UPstream.H"

#include <algorithm>

using Foam::Info;
using Foam::fixed;
using Foam::setprecision;

namespace
{

using namespace pmsh;

// While one lives, OpenFOAM runs serial: the decomposition is the master's
// alone (the others do not take part in its reductions), as OpenFOAM's own
// utilities do it (renumberMesh)
class serialSection
{
    const bool oldParRun_;
public:
    serialSection()
    :
        oldParRun_(Foam::UPstream::parRun())
    {
        Foam::UPstream::parRun() = false;
    }
    ~serialSection()
    {
        Foam::UPstream::parRun() = oldParRun_;
    }
    serialSection(const serialSection&) = delete;
    serialSection& operator=(const serialSection&) = delete;
};


// The weights as a decompositionMethod takes them. metis turns them into
// integers, weight/min(weights) rounded down: the lightest cell is set to
// 1/50 of the mean, which makes the unit 2% of a mean cell (the others keep
// theirs, and the sum stays below 2^31 up to 40M coarse cells)
Foam::scalarField methodWeights(const std::vector<double>& weights, label nCells)
{
    if (label(weights.size()) != nCells || nCells == 0)
    {
        return Foam::scalarField(nCells, 1.0);
    }
    Foam::scalarField w(nCells);
    double mean = 0;
    for (label c = 0; c < nCells; ++c)
    {
        w[c] = weights[c];
        mean += weights[c];
    }
    mean /= nCells;
    const label lightest = label
    (
        std::min_element(weights.begin(), weights.end()) - weights.begin()
    );
    w[lightest] = std::min(w[lightest], mean/50);
    for (label c = 0; c < nCells; ++c)
    {
        w[c] = std::max(w[c], mean/50);
    }
    return w;
}


// Decompose with OpenFOAM's decompositionMethod; cellPart[c] in [0, nParts)
std::vector<label> decomposeCells
(
    const CoarseMesh& coarse,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& cellWeights
)
{
    const label nCells = coarse.nCells();

    Foam::dictionary dict(decompositionDict);
    dict.set("numberOfSubdomains", Foam::label(nParts));

    checkDecompositionMethod(dict);

    // The graph: the face neighbours of every coarse tet; the points: the
    // tet centroids; the weights: the expected fine cells (else 1)
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    Foam::labelListList cellCells(nCells);
    Foam::pointField centres(nCells);
    const Foam::scalarField weights = methodWeights(cellWeights, nCells);
    for (label c = 0; c < nCells; ++c)
    {
        Foam::labelList& nbrs = cellCells[c];
        nbrs.setSize(4);
        label n = 0;
        for (label nbr : neighbours[c])
        {
            if (!isBoundaryNeighbour(nbr))
            {
                nbrs[n++] = nbr;
            }
        }
        nbrs.setSize(n);

        const tetVerts& t = coarse.tets[c];
        const point3 centroid = 0.25*
        (
            (coarse.points[t[0]] + coarse.points[t[1]])
          + (coarse.points[t[2]] + coarse.points[t[3]])
        );
        centres[c] = Foam::point(centroid[0], centroid[1], centroid[2]);
    }

    Foam::labelList decomp;
    try
    {
        const foamErrorsThrow throwing;
        const serialSection serial;
        Foam::autoPtr<Foam::decompositionMethod> decomposer =
            foam::newDecompositionMethod(dict);
        decomp = decomposer->decompose(cellCells, centres, weights);
    }
    catch (const Foam::error& e)
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " failed for "
                << nCells << " coarse cells into " << nParts << " parts:\n"
                << FatalError::of(e).message() << "\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }

    // Trust no method blindly: a stub library or a bad manual file gives
    // nonsense that would crash the later stages
    std::string problem;
    if (decomp.size() != nCells)
    {
        problem = "gave " + std::to_string(decomp.size()) + " parts for "
            + std::to_string(nCells) + " cells";
    }
    else
    {
        for (label c = 0; c < nCells && problem.empty(); ++c)
        {
            if (decomp[c] < 0 || decomp[c] >= nParts)
            {
                problem = "put cell " + std::to_string(c) + " in part "
                    + std::to_string(decomp[c]) + ", not one of 0.."
                    + std::to_string(nParts - 1);
            }
        }
    }
    if (!problem.empty())
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " " << problem << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    return std::vector<label>(decomp.begin(), decomp.end());
}

} // End anonymous namespace


std::vector<pmsh::label> pmsh::partitionCells
(
    const CoarseMesh& coarse,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& weights
)
{
    const label nCells = coarse.nCells();
    if (nParts > nCells)
    {
        throw FatalError
        (
            msg() << "Cannot split a coarse mesh of " << nCells << " cells into "
                << nParts << " parts: every rank needs at least one coarse cell.\n"
                << "Reduce maxCellSize in system/pmshDict for a finer coarse mesh"
                << (nCells > 1 ? ", or run on at most " + std::to_string(nCells) + " ranks." : "."),
            "partitionCells"
        );
    }
    if (nParts == 1)
    {
        return std::vector<label>(nCells, 0);
    }

    std::vector<label> cellPart =
        decomposeCells(coarse, nParts, decompositionDict, weights);
    repairPartition(coarse, nParts, cellPart);
    if (weights.empty())
    {
        return cellPart;
    }

    // The method balances its (integer) weights within a few per cent, and
    // the repair moves cells without looking at them: balance the parts'
    // expected fine cells now, keeping every part a manifold
    const double before = weightImbalance(weights, nParts, cellPart);
    const label moved = balancePartition(coarse, nParts, weights, cellPart);
    Info
        << fixed << setprecision(3)
        << "    expected fine cells per part max/mean: " << before
        << " from the method, "
        << weightImbalance(weights, nParts, cellPart)
        << " after moving " << moved << " coarse cells\n"
        << defaultfloat;
    return cellPart;
}


std::vector<pmsh::label> pmsh::partitionCoarseMesh
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& fineWeights
)
{
    std::vector<label> cellPart;
    failTogether(comm, [&]
    {
        comm.masterWorksOthersSleep([&]
        {
            cellPart = partitionCells(coarse, comm.size(), decompositionDict, fineWeights);
        });
    });
    comm.broadcast(cellPart);
    return cellPart;
}


// ************************************************************************* //
