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


// Decompose a graph with OpenFOAM's decompositionMethod; the part of every
// node in [0, nParts). `nodes` names them in messages ("coarse cells")
std::vector<label> decomposeGraph
(
    const Foam::labelListList& nodeNodes,
    const Foam::pointField& centres,
    const Foam::scalarField& weights,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::string& nodes
)
{
    const label nNodes = label(nodeNodes.size());
    Foam::dictionary dict(decompositionDict);
    dict.set("numberOfSubdomains", Foam::label(nParts));

    checkDecompositionMethod(dict);

    Foam::labelList decomp;
    try
    {
        const foamErrorsThrow throwing;
        const serialSection serial;
        Foam::autoPtr<Foam::decompositionMethod> decomposer =
            foam::newDecompositionMethod(dict);
        decomp = decomposer->decompose(nodeNodes, centres, weights);
    }
    catch (const Foam::error& e)
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " failed for "
                << nNodes << " " << nodes << " into " << nParts << " parts:\n"
                << FatalError::of(e).message() << "\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }

    // Trust no method blindly: a stub library or a bad manual file gives
    // nonsense that would crash the later stages
    std::string problem;
    if (decomp.size() != nNodes)
    {
        problem = "gave " + std::to_string(decomp.size()) + " parts for "
            + std::to_string(nNodes) + " " + nodes;
    }
    else
    {
        for (label c = 0; c < nNodes && problem.empty(); ++c)
        {
            if (decomp[c] < 0 || decomp[c] >= nParts)
            {
                problem = "put node " + std::to_string(c) + " of the " + nodes
                    + " in part " + std::to_string(decomp[c]) + ", not one of 0.."
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


point3 centroidOf(const CoarseMesh& coarse, label c)
{
    const tetVerts& t = coarse.tets[c];
    return 0.25*
    (
        (coarse.points[t[0]] + coarse.points[t[1]])
      + (coarse.points[t[2]] + coarse.points[t[3]])
    );
}


// Decompose the coarse cells with OpenFOAM's decompositionMethod; the
// graph: the face neighbours of every coarse tet; the points: the tet
// centroids; the weights: the expected fine cells (else 1)
std::vector<label> decomposeCells
(
    const CoarseMesh& coarse,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& cellWeights
)
{
    const label nCells = coarse.nCells();
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    Foam::labelListList cellCells(nCells);
    Foam::pointField centres(nCells);
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
        const point3 centroid = centroidOf(coarse, c);
        centres[c] = Foam::point(centroid[0], centroid[1], centroid[2]);
    }
    return decomposeGraph
    (
        cellCells, centres, methodWeights(cellWeights, nCells), nParts,
        decompositionDict, "coarse cells"
    );
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


std::vector<pmsh::label> pmsh::groupPieces
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPiece,
    label nPieces,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& weights
)
{
    if (nParts == 1)
    {
        return std::vector<label>(nPieces, 0);
    }

    // The pieces' graph: two pieces are neighbours where they share a
    // coarse face; a piece stands at its cells' weighted centroid
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    std::vector<std::vector<label>> adjacent(nPieces);
    std::vector<double> pieceWeight(nPieces, 0);
    std::vector<point3> centre(nPieces, point3{0, 0, 0});
    for (label c = 0; c < coarse.nCells(); ++c)
    {
        const label p = cellPiece[c];
        const double w = weights.empty() ? 1.0 : weights[c];
        pieceWeight[p] += w;
        centre[p] = centre[p] + w*centroidOf(coarse, c);
        for (label nbr : neighbours[c])
        {
            if (!isBoundaryNeighbour(nbr) && cellPiece[nbr] != p)
            {
                adjacent[p].push_back(cellPiece[nbr]);
            }
        }
    }
    Foam::labelListList pieceNeighbours(nPieces);
    Foam::pointField centres(nPieces);
    for (label p = 0; p < nPieces; ++p)
    {
        std::vector<label>& a = adjacent[p];
        std::sort(a.begin(), a.end());
        a.erase(std::unique(a.begin(), a.end()), a.end());
        // ESI's List (v2506) takes no pair of std iterators
        Foam::labelList& nbrs = pieceNeighbours[p];
        nbrs.setSize(label(a.size()));
        std::copy(a.begin(), a.end(), nbrs.begin());
        const point3 x = (1/std::max(pieceWeight[p], 1e-300))*centre[p];
        centres[p] = Foam::point(x[0], x[1], x[2]);
    }
    std::vector<label> pieceRank = decomposeGraph
    (
        pieceNeighbours, centres, methodWeights(pieceWeight, nPieces), nParts,
        decompositionDict, "pieces"
    );

    // A method may leave a part without pieces (metis on few nodes): give
    // it the lightest piece of the part with most, which keeps one at least
    std::vector<label> nOf(nParts, 0);
    for (label r : pieceRank)
    {
        ++nOf[r];
    }
    for (label empty = 0; empty < nParts; ++empty)
    {
        if (nOf[empty] > 0)
        {
            continue;
        }
        const label from = label(std::max_element(nOf.begin(), nOf.end()) - nOf.begin());
        label lightest = -1;
        for (label p = 0; p < nPieces; ++p)
        {
            if (pieceRank[p] == from && (lightest < 0 || pieceWeight[p] < pieceWeight[lightest]))
            {
                lightest = p;
            }
        }
        pieceRank[lightest] = empty;
        --nOf[from];
        ++nOf[empty];
    }
    const label moved = balancePieceGroups(pieceWeight, adjacent, nParts, pieceRank);
    if (moved > 0)
    {
        Info<< "    " << moved << " piece(s) moved between parts to balance them\n";
    }
    return pieceRank;
}


pmsh::label pmsh::balancePieceGroups
(
    const std::vector<double>& pieceWeight,
    const std::vector<std::vector<label>>& adjacent,
    label nParts,
    std::vector<label>& pieceRank
)
{
    const label nPieces = label(pieceRank.size());
    std::vector<double> partWeight(nParts, 0);
    std::vector<label> nOf(nParts, 0);
    for (label p = 0; p < nPieces; ++p)
    {
        partWeight[pieceRank[p]] += pieceWeight[p];
        ++nOf[pieceRank[p]];
    }
    label moved = 0;
    // Each move lowers the heaviest part or the number of parts that
    // heavy: nPieces*nParts moves bound it well above what it takes
    for (label step = 0; step < nPieces*nParts; ++step)
    {
        const label heaviest =
            label(std::max_element(partWeight.begin(), partWeight.end()) - partWeight.begin());
        if (nOf[heaviest] < 2)
        {
            break;
        }
        label bestPiece = -1, bestPart = -1;
        double bestMax = partWeight[heaviest];
        for (label p = 0; p < nPieces; ++p)
        {
            if (pieceRank[p] != heaviest) continue;
            for (const label n : adjacent[p])
            {
                const label q = pieceRank[n];
                if (q == heaviest) continue;
                const double after = std::max
                (
                    partWeight[heaviest] - pieceWeight[p], partWeight[q] + pieceWeight[p]
                );
                if
                (
                    after < bestMax
                 || (after == bestMax && bestPiece == p && q < bestPart)
                )
                {
                    bestMax = after;
                    bestPiece = p;
                    bestPart = q;
                }
            }
        }
        if (bestPiece < 0)
        {
            break;
        }
        partWeight[heaviest] -= pieceWeight[bestPiece];
        partWeight[bestPart] += pieceWeight[bestPiece];
        --nOf[heaviest];
        ++nOf[bestPart];
        pieceRank[bestPiece] = bestPart;
        ++moved;
    }
    return moved;
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
