#include "labelLimit.H"
#include "pmshError.H"

void pmsh::checkFitsLabel(std::int64_t count, const std::string& what)
{
    if (count <= labelLimit)
    {
        return;
    }
    throw FatalError
    (
        msg() << "The mesh is too large for this OpenFOAM's " << labelBits
            << "-bit labels (largest label " << labelLimit << "): it has "
            << count << ' ' << what << ".\n"
            << "Use pmshFoam built with an OpenFOAM of WM_LABEL_SIZE=64 (see"
            << " pmshFoam's README, Building), or fewer cells (a larger"
            << " maxCellSize or fewer refinementLevels)",
        "pmsh::checkFitsLabel"
    );
}
