#include "stageParameters.H"

pmsh::volumeMeshParameters pmsh::volumeParameters
(
    const meshSettings& settings,
    const FineSurface& surface,
    int rank
)
{
    volumeMeshParameters p;
    p.interfaceTriangles.resize(surface.region.size());
    for (std::size_t t = 0; t < surface.region.size(); ++t)
    {
        // Cells lie behind processor faces and faces between zones
        p.interfaceTriangles[t] =
            isInterfaceRegion(surface.region[t]) || isBetweenZones(surface.region[t]);
    }
    p.what = "partition " + std::to_string(rank);
    const double toFine = double(1 << settings.refinementLevels);
    p.maxCellSize = settings.maxCellSize/toFine;
    for (const sizeRegion& r : settings.refinementRegions)
    {
        p.regions.push_back(r.scaled(toFine));
    }
    p.grading = settings.grading;
    p.optimisationSteps = settings.optimisationSteps;
    p.netgenSmoothing = settings.optimisationSteps >= netgenSmoothingFromSteps;
    p.mendGradients = true;
    p.threads = settings.volumeMesherThreads;
    return p;
}


std::string pmsh::failedSurfaceFile(const std::string& caseDir, int rank)
{
    return caseDir + "/postProcessing/pmshFoam/failedPartition" + std::to_string(rank) + ".stl";
}


pmsh::coarseMeshParameters pmsh::coarseParameters
(
    const meshSettings& settings,
    const std::string& caseDir
)
{
    coarseMeshParameters p;
    p.maxCellSize = settings.maxCellSize;
    p.grading = settings.grading;
    p.mesher = settings.coarseMesher;
    p.failedSurfaceFile = caseDir + "/postProcessing/pmshFoam/failedCoarseSurface.stl";
    p.regions = settings.refinementRegions;
    p.curvatureRefinement = settings.curvatureRefinement;
    p.minCellSize = settings.minCellSize;
    p.cellsAcrossGap = settings.cellsAcrossGap;
    p.coarseTimeLimit = settings.coarseTimeLimit;
    p.coarseSurface = settings.coarseSurface;
    if (settings.hasPatchSizes())
    {
        p.patchMaxCellSize = [settings](const std::string& patch)
        {
            return settings.patchMaxCellSize(patch);
        };
    }
    return p;
}


// ************************************************************************* //
