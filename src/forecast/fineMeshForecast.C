#include "fineMeshForecast.H"
#include "failTogether.H"
#include "fineCellWeights.H"
#include "sizeFieldCells.H"

#include <cmath>

pmsh::fineMeshForecast pmsh::forecastFineMesh
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const meshSettings& settings,
    const std::map<label, layerSpecification>& layerSpecs,
    bool checkMemory
)
{
    fineMeshForecast forecast;
    sizeFieldTerms terms;
    failTogether(comm, [&]
    {
        if (comm.master())
        {
            forecast.fineWeights = fineCellWeights
            (
                coarse, settings.maxCellSize, settings.refinementLevels,
                settings.refinementRegions
            );
            terms = sizeFieldCells
            (
                coarse, settings.maxCellSize, settings.grading,
                settings.refinementLevels, settings.refinementRegions, layerSpecs
            );
        }
    });
    failTogether(comm, [&]
    {
        // Stop before the expensive stages if the fine mesh cannot fit
        const double weighted = comm.sum(terms.weighted());
        memoryEstimate& estimate = forecast.estimate;
        estimate = estimateAndCheckMemory
        (
            comm, settings, coarse.nCells(), weighted,
            expectedPrisms(coarse, layerSpecs, settings.refinementLevels), checkMemory
        );
        if (weighted > 0)
        {
            estimate.interfaceShare = comm.sum(terms.coarseShare*terms.coarse)/weighted;
            estimate.sizeFieldShare = 1 - estimate.interfaceShare;
        }
    });
    return forecast;
}


double pmsh::expectedPrisms
(
    const CoarseMesh& coarse,
    const std::map<label, layerSpecification>& layerSpecs,
    const int refinementLevels
)
{
    double prisms = 0;
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        const auto spec = layerSpecs.find(f.patch);
        if (spec != layerSpecs.end()) prisms += spec->second.nLayers;
    }
    return prisms*std::pow(4.0, refinementLevels);
}


// ************************************************************************* //
