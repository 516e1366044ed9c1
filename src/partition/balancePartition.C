#include "partitionCoarseMesh.H"
#include "partManifold.H"
#include "pmshError.H"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

pmsh::label pmsh::balancePartition
(
    const CoarseMesh& coarse,
    label nParts,
    const std::vector<double>& weights,
    std::vector<label>& cellPart,
    double tolerance
)
{
    const label nCells = coarse.nCells();
    if (nParts < 2 || label(weights.size()) != nCells)
    {
        return 0;
    }
    // Loads are the parts'; cells move between pieces of one zone
    const zonePieces pieces(coarse);
    const std::vector<faceNeighbours> neighbours = pieces.neighbours();
    const coarsePointCells vc(coarse);
    std::vector<label> keys = pieces.keys(cellPart);

    std::vector<double> load(nParts, 0);
    std::vector<label> size(nParts, 0);
    std::vector<std::vector<label>> members(nParts);
    for (label c = 0; c < nCells; ++c)
    {
        load[cellPart[c]] += weights[c];
        ++size[cellPart[c]];
        members[cellPart[c]].push_back(c);
    }
    double total = 0;
    for (double l : load) total += l;
    const double target = (1 + tolerance)*total/nParts;

    // The heaviest part gives boundary cells to lighter neighbours. A move
    // is made only when the receiver stays lighter than the giver was, so
    // the sum of squared loads falls with every move and this ends
    label moved = 0;
    std::vector<bool> stuck(nParts, false);
    for (label iter = 0; iter < 10*nCells; ++iter)
    {
        label p = -1;
        for (label q = 0; q < nParts; ++q)
        {
            if (!stuck[q] && (p < 0 || load[q] > load[p])) p = q;
        }
        if (p < 0 || load[p] <= target)
        {
            break;
        }

        // Candidates: (cell, receiving part), most faces towards the
        // receiver and fewest towards the giver first (compact parts, few
        // new interface faces), then the lightest receiver
        struct move { label cell, to; int gain; };
        std::vector<move> moves;
        for (label c : members[p])
        {
            if (cellPart[c] != p) continue;
            int toP = 0;
            std::map<label, int> toOther;
            for (label nbr : neighbours[c])
            {
                if (isBoundaryNeighbour(nbr)) continue;
                if (cellPart[nbr] == p) ++toP;
                else ++toOther[cellPart[nbr]];
            }
            for (const auto& [q, n] : toOther)
            {
                moves.push_back({c, q, n - toP});
            }
        }
        std::stable_sort(moves.begin(), moves.end(), [&](const move& a, const move& b)
        {
            return a.gain != b.gain ? a.gain > b.gain : load[a.to] < load[b.to];
        });

        label movedNow = 0;
        for (const move& m : moves)
        {
            if (load[p] <= target || size[p] <= 1) break;
            const double w = weights[m.cell];
            if (cellPart[m.cell] != p || load[m.to] + w >= load[p]) continue;
            if (moveIfManifold(coarse, neighbours, vc, m.cell, pieces.key(m.to, m.cell), keys))
            {
                cellPart[m.cell] = m.to;
                load[p] -= w;
                load[m.to] += w;
                --size[p];
                ++size[m.to];
                members[m.to].push_back(m.cell);
                ++movedNow;
            }
        }
        if (movedNow)
        {
            auto& list = members[p];
            list.erase
            (
                std::remove_if(list.begin(), list.end(), [&](label c) { return cellPart[c] != p; }),
                list.end()
            );
            moved += movedNow;
            std::fill(stuck.begin(), stuck.end(), false);
        }
        else
        {
            // Nothing to give: the other parts may still come down
            stuck[p] = true;
        }
    }
    return moved;
}


double pmsh::weightImbalance
(
    const std::vector<double>& weights,
    label nParts,
    const std::vector<label>& cellPart
)
{
    std::vector<double> load(nParts, 0);
    double total = 0;
    for (std::size_t c = 0; c < cellPart.size(); ++c)
    {
        const double w = weights.empty() ? 1.0 : weights[c];
        load[cellPart[c]] += w;
        total += w;
    }
    return total > 0 ? *std::max_element(load.begin(), load.end())*nParts/total : 1.0;
}


// ************************************************************************* //
