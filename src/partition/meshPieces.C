#include "meshPieces.H"
#include "failTogether.H"
#include "partitionCoarseMesh.H"

#include "dictionary.H"

#include <algorithm>
#include <cmath>

using Foam::Info;


pmsh::label pmsh::numberOfPieces
(
    double expectedTets,
    label nRanks,
    double maxPieceCells
)
{
    const double pieces = maxPieceCells > 0 ? std::ceil(expectedTets/maxPieceCells) : 0;
    return pieces < 2 || pieces < double(nRanks) ? 0 : label(pieces);
}


pmsh::meshPieces pmsh::partitionIntoPieces
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& fineWeights,
    label nPieces
)
{
    meshPieces pieces;
    if (nPieces == 0)
    {
        pieces.cellPart =
            partitionCoarseMesh(comm, coarse, decompositionDict, fineWeights);
        return pieces;
    }

    Info<< "    " << nPieces << " pieces, meshed one volume-mesher call each,"
        << " grouped into " << comm.size() << " part(s)\n";
    std::vector<label> pieceRank;
    failTogether(comm, [&]
    {
        comm.masterWorksOthersSleep([&]
        {
            // Always metis: the pieces must not depend on the ranks, and a
            // method's coefficients (hierarchical's n) are for the ranks
            pieces.cellPiece =
                partitionCells(coarse, nPieces, defaultDecompositionDict(), fineWeights);
            pieceRank = groupPieces
            (
                coarse, pieces.cellPiece, nPieces, comm.size(),
                decompositionDict, fineWeights
            );
        });
    });
    comm.broadcast(pieces.cellPiece);
    comm.broadcast(pieceRank);
    pieces.cellPart.resize(pieces.cellPiece.size());
    for (std::size_t c = 0; c < pieces.cellPiece.size(); ++c)
    {
        pieces.cellPart[c] = pieceRank[pieces.cellPiece[c]];
    }
    return pieces;
}


// ************************************************************************* //
