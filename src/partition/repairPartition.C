#include "partitionCoarseMesh.H"
#include "partManifold.H"
#include "pmshError.H"

#include <algorithm>

namespace
{

using namespace pmsh;

// The repair at one entity (a vertex, or the two ends of an edge) and the
// cells around it: where a part's cells around it are not one
// face-connected group, or (at a vertex) the other cells and the outside
// are not, the smaller groups move (with doMove).
class entityRepair
{
public:

    entityRepair
    (
        const CoarseMesh& coarse,
        const zonePieces& pieces,
        const std::vector<faceNeighbours>& neighbours,
        std::vector<label>& cellPart,
        bool doMove,
        bool absorb,
        label& moved
    )
    :
        coarse_(coarse),
        pieces_(pieces),
        neighbours_(neighbours),
        cellPart_(cellPart),
        doMove_(doMove),
        absorb_(absorb),
        moved_(moved)
    {}

    //- Is some part not a manifold at the entity? Only the first such
    //  part is repaired: the cells changed, the next pass looks again.
    bool defect(const std::vector<label>& entity, const std::vector<label>& cells)
    {
        std::vector<label> parts;
        for (label c : cells)
        {
            parts.push_back(cellPart_[c]);
        }
        std::sort(parts.begin(), parts.end());
        parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
        if (parts.size() < 2)
        {
            return false;   // inside one part: nothing to check
        }
        for (label p : parts)
        {
            // The part's own cells around the entity
            std::vector<bool> inPart(cells.size());
            for (std::size_t i = 0; i < cells.size(); ++i)
            {
                inPart[i] = cellPart_[cells[i]] == p;
            }
            label nComp;
            const std::vector<label> comp =
                components(coarse_, neighbours_, entity, cells, inPart, nComp);
            if (nComp > 1)
            {
                repair(cells, p, [&] { splitOff(cells, parts, comp, nComp, p); });
                return true;
            }
            if (entity.size() > 1)
            {
                continue;   // on an edge's ring one group means an arc
            }

            // Around a vertex the part must also not surround a hole: the
            // other cells plus the outside must be one group
            std::vector<bool> other(cells.size() + 1, true);
            for (std::size_t i = 0; i < cells.size(); ++i)
            {
                other[i] = !inPart[i];
            }
            const std::vector<label> otherComp =
                components(coarse_, neighbours_, entity, cells, other, nComp);
            if (nComp > 1)
            {
                repair(cells, p, [&] { fillHoles(cells, otherComp, nComp, p); });
                return true;
            }
        }
        return false;
    }

private:

    template<class Move>
    void repair(const std::vector<label>& cells, label p, const Move& move)
    {
        if (doMove_ && absorb_)
        {
            absorbAround(cells, p);
        }
        else if (doMove_)
        {
            move();
        }
    }

    // A defect the usual moves took back and forth (two places each
    // wanting the same cells): the cells of p's zone around the entity all
    // go to the lowest part among them. Cells only ever move to lower
    // parts here, so this ends.
    void absorbAround(const std::vector<label>& cells, label p)
    {
        label lowest = pieces_.part(p);
        for (label c : cells)
        {
            if (pieces_.moved(c, p) == p)
            {
                lowest = std::min(lowest, pieces_.part(cellPart_[c]));
            }
        }
        for (label c : cells)
        {
            if (pieces_.moved(c, p) == p && pieces_.part(cellPart_[c]) != lowest)
            {
                cellPart_[c] = pieces_.key(lowest, c);
                ++moved_;
            }
        }
    }

    // Keep part p's largest group around the entity, hand the others to a
    // neighbour
    void splitOff
    (
        const std::vector<label>& cells,
        const std::vector<label>& parts,
        const std::vector<label>& comp,
        label nComp,
        label p
    )
    {
        std::vector<label> size(nComp, 0);
        for (label c : comp) if (c >= 0) ++size[c];
        const label keep = label(std::max_element(size.begin(), size.end()) - size.begin());
        for (label k = 0; k < nComp; ++k)
        {
            if (k == keep) continue;
            std::vector<label> group;
            for (std::size_t i = 0; i < cells.size(); ++i)
            {
                if (comp[i] == k) group.push_back(cells[i]);
            }
            label to = neighbourPart(neighbours_, cellPart_, group, p);
            if (to < 0) to = (parts[0] == p ? parts[1] : parts[0]);
            for (label c : group)
            {
                cellPart_[c] = pieces_.moved(c, to);
                ++moved_;
            }
        }
    }

    // Fill the holes around a vertex (the other cells' groups not reaching
    // the outside, all but the largest if none does) with part p's cells
    void fillHoles
    (
        const std::vector<label>& cells,
        const std::vector<label>& otherComp,
        label nComp,
        label p
    )
    {
        const label outsideComp = otherComp.back();
        std::vector<label> size(nComp, 0);
        for (std::size_t i = 0; i < cells.size(); ++i)
        {
            if (otherComp[i] >= 0) ++size[otherComp[i]];
        }
        const label keep = outsideComp >= 0
            ? outsideComp
            : label(std::max_element(size.begin(), size.end()) - size.begin());
        for (std::size_t i = 0; i < cells.size(); ++i)
        {
            if (otherComp[i] >= 0 && otherComp[i] != keep)
            {
                cellPart_[cells[i]] = pieces_.moved(cells[i], p);
                ++moved_;
            }
        }
    }

    const CoarseMesh& coarse_;
    const zonePieces& pieces_;
    const std::vector<faceNeighbours>& neighbours_;
    std::vector<label>& cellPart_;
    const bool doMove_;
    const bool absorb_;
    label& moved_;
};


// One pass over the entities (vertices, then edges), repairing each (see
// entityRepair). Returns the number of defects found; `moved` counts cell
// moves.
label repairPass
(
    const CoarseMesh& coarse,
    const zonePieces& pieces,
    const std::vector<faceNeighbours>& neighbours,
    const coarsePointCells& vc,
    std::vector<label>& cellPart,
    bool doMove,
    bool absorb,
    label& moved
)
{
    entityRepair repair(coarse, pieces, neighbours, cellPart, doMove, absorb, moved);
    label nDefects = 0;
    for (label v = 0; v < coarse.nPoints(); ++v)
    {
        nDefects += repair.defect({v}, vc.around(v));
    }

    // Edges: the cells around (a, b) are the cells around a that hold b
    for (label a = 0; a < coarse.nPoints(); ++a)
    {
        const std::vector<label> aroundA = vc.around(a);
        std::vector<label> others;
        for (label c : aroundA)
        {
            for (label b : coarse.tets[c])
            {
                if (b > a) others.push_back(b);
            }
        }
        std::sort(others.begin(), others.end());
        others.erase(std::unique(others.begin(), others.end()), others.end());
        for (label b : others)
        {
            std::vector<label> cells;
            for (label c : aroundA)
            {
                if (tetHas(coarse.tets[c], b)) cells.push_back(c);
            }
            nDefects += repair.defect({a, b}, cells);
        }
    }
    return nDefects;
}


// Give every empty part one cell of the largest part, taken from where
// that part touches another (so the rest of it stays in one piece).
// cellPart holds the pieces' keys.
label fillEmptyParts
(
    const zonePieces& pieces,
    const std::vector<faceNeighbours>& neighbours,
    label nParts,
    std::vector<label>& cellPart
)
{
    label moved = 0;
    for (label q = 0; q < nParts; ++q)
    {
        std::vector<label> size(nParts, 0);
        for (label k : cellPart) ++size[pieces.part(k)];
        if (size[q] > 0)
        {
            continue;
        }
        const label largest = label(std::max_element(size.begin(), size.end()) - size.begin());
        label pick = -1;
        for (label c = 0; c < label(cellPart.size()) && pick < 0; ++c)
        {
            if (pieces.part(cellPart[c]) != largest) continue;
            for (label nbr : neighbours[c])
            {
                if (isBoundaryNeighbour(nbr) || cellPart[nbr] != cellPart[c])
                {
                    pick = c;
                    break;
                }
            }
        }
        pick = pick < 0 ? 0 : pick;
        cellPart[pick] = pieces.key(q, pick);
        ++moved;
    }
    return moved;
}

} // End anonymous namespace


pmsh::label pmsh::repairPartition
(
    const CoarseMesh& coarse,
    label nParts,
    std::vector<label>& cellPart
)
{
    const zonePieces pieces(coarse);
    const std::vector<faceNeighbours> neighbours = pieces.neighbours();
    const coarsePointCells vc(coarse);
    std::vector<label> keys = pieces.keys(cellPart);

    // After absorbAfter passes a part takes the cells around a place where
    // it falls apart, instead of giving its smaller pieces away: a defect
    // left by then is one the moves took back and forth
    const int absorbAfter = 20;
    label moved = 0;
    const int maxPasses = 50;
    for (int pass = 0; pass < maxPasses; ++pass)
    {
        const label filled = fillEmptyParts(pieces, neighbours, nParts, keys);
        moved += filled;
        label passMoved = 0;
        const label nDefects = repairPass
        (
            coarse, pieces, neighbours, vc, keys, true, pass >= absorbAfter, passMoved
        );
        moved += passMoved;
        if (nDefects == 0 && filled == 0)
        {
            pieces.toParts(keys, cellPart);
            return moved;
        }
    }
    throw FatalError
    (
        msg() << "Could not make every part of the " << nParts << "-way partition"
            << " of the coarse mesh (" << coarse.nCells() << " cells) a closed"
            << " manifold in " << maxPasses << " passes.\n"
            << "Use fewer ranks or a smaller maxCellSize (more coarse cells"
            << " per rank).",
        "repairPartition"
    );
}


pmsh::label pmsh::countNonManifoldParts
(
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart
)
{
    const zonePieces pieces(coarse);
    std::vector<label> keys = pieces.keys(cellPart);
    label moved = 0;
    return repairPass
    (
        coarse, pieces, pieces.neighbours(), coarsePointCells(coarse), keys,
        false, false, moved
    );
}


// ************************************************************************* //
