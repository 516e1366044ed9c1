#include "fineMeshForecast.H"
#include "failTogether.H"
#include "fineCellWeights.H"

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
    fineCellWeightTerms weightTerms;
    failTogether(comm, [&]
    {
        if (comm.master())
        {
            forecast.fineWeights = fineCellWeights
            (
                coarse, settings.maxCellSize, settings.refinementLevels,
                settings.refinementRegions, &weightTerms
            );
        }
    });
    failTogether(comm, [&]
    {
        // The sizes of the cells graded from a small body to
        // maxCellSize count more than the partition's weights say
        const double weightSum = comm.sum
        (
            weightTerms.volumeGraded + weightTerms.regionsGraded
          + weightTerms.boundary
        );

        // Stop before the expensive stages if the fine mesh cannot fit
        memoryEstimate& estimate = forecast.estimate;
        estimate = estimateAndCheckMemory
        (
            comm, settings, coarse.nCells(),
            weightSum*std::pow(8.0, settings.refinementLevels),
            expectedPrisms(coarse, layerSpecs, settings.refinementLevels), checkMemory
        );
        const double termSum =
            weightTerms.volumeGraded + weightTerms.regionsGraded
          + weightTerms.boundary;
        if (termSum > 0)
        {
            estimate.volumeShare = weightTerms.volumeGraded/termSum;
            estimate.regionShare = weightTerms.regionsGraded/termSum;
            estimate.boundaryShare = weightTerms.boundary/termSum;
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
