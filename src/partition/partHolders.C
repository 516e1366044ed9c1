/*---------------------------------------------------------------------------*\
  pmshFoam: which ranks hold a surface vertex (partHolders.H).
\*---------------------------------------------------------------------------*/

#include "partHolders.H"

#include <algorithm>
#include <iterator>


std::vector<int> pmsh::holderRanks
(
    const barycentricId& id,
    const coarsePointCells& pointCells,
    const std::vector<label>& cellPart
)
{
    if (cellPart.empty())
    {
        return {0};
    }

    // Cells holding every coarse vertex of the id (1-based; 0 = padding)
    std::vector<label> cells;
    bool first = true;
    for (int n = 0; n < 3; ++n)
    {
        if (id.vertex[n] == 0)
        {
            continue;
        }
        const std::vector<label> around = pointCells.around(id.vertex[n] - 1);
        if (first)
        {
            cells = around;
            first = false;
        }
        else
        {
            std::vector<label> common;
            std::set_intersection
            (
                cells.begin(), cells.end(), around.begin(), around.end(),
                std::back_inserter(common)
            );
            cells.swap(common);
        }
    }

    std::vector<int> holders;
    for (label c : cells)
    {
        holders.push_back(cellPart[c]);
    }
    std::sort(holders.begin(), holders.end());
    holders.erase(std::unique(holders.begin(), holders.end()), holders.end());
    return holders;
}


// ************************************************************************* //
