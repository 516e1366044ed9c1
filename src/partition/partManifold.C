#include "partManifold.H"

#include <algorithm>
#include <map>
#include <numeric>

namespace pmsh
{

namespace
{

// Does face f (outwardTetFaces order) of tet t contain all points of the
// entity (one vertex, or the two ends of an edge)?
bool faceContains(const tetVerts& t, int f, const std::vector<label>& entity)
{
    const triVerts face = outwardTetFaces(t)[f];
    for (label p : entity)
    {
        if (std::find(face.begin(), face.end(), p) == face.end())
        {
            return false;
        }
    }
    return true;
}

} // End anonymous namespace

} // End namespace pmsh


std::vector<pmsh::label> pmsh::components
(
    const CoarseMesh& coarse,
    const std::vector<faceNeighbours>& neighbours,
    const std::vector<label>& entity,
    const std::vector<label>& cells,
    const std::vector<bool>& inRegion,      // size cells.size() (+1 outside)
    label& nComponents
)
{
    const label n = label(inRegion.size());
    std::vector<label> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](label x)
    {
        while (parent[x] != x)
        {
            x = parent[x] = parent[parent[x]];
        }
        return x;
    };
    auto unite = [&](label a, label b) { parent[find(a)] = find(b); };

    const bool withOutside = n > label(cells.size());
    bool onBoundary = false;
    for (label i = 0; i < label(cells.size()); ++i)
    {
        const tetVerts& t = coarse.tets[cells[i]];
        for (int f = 0; f < 4; ++f)
        {
            if (!faceContains(t, f, entity))
            {
                continue;
            }
            const label nbr = neighbours[cells[i]][f];
            if (isBoundaryNeighbour(nbr))
            {
                onBoundary = true;
                if (withOutside && inRegion[i] && inRegion.back())
                {
                    unite(i, n - 1);
                }
                continue;
            }
            if (!inRegion[i])
            {
                continue;
            }
            auto it = std::find(cells.begin(), cells.end(), nbr);
            const label j = label(it - cells.begin());
            if (it != cells.end() && inRegion[j])
            {
                unite(i, j);
            }
        }
    }

    // The outside is a node only where the entity is on the boundary
    const label nNodes = (withOutside && !onBoundary) ? n - 1 : n;

    std::vector<label> comp(n, -1);
    std::map<label, label> rootIndex;
    for (label i = 0; i < nNodes; ++i)
    {
        if (inRegion[i])
        {
            comp[i] = rootIndex.emplace(find(i), label(rootIndex.size())).first->second;
        }
    }
    nComponents = label(rootIndex.size());
    return comp;
}


pmsh::label pmsh::neighbourPart
(
    const std::vector<faceNeighbours>& neighbours,
    const std::vector<label>& cellPart,
    const std::vector<label>& cells,
    label notPart
)
{
    std::map<label, label> count;
    for (label c : cells)
    {
        for (label nbr : neighbours[c])
        {
            if (!isBoundaryNeighbour(nbr) && cellPart[nbr] != notPart)
            {
                ++count[cellPart[nbr]];
            }
        }
    }
    label best = -1, bestCount = 0;
    for (const auto& [part, n] : count)
    {
        if (n > bestCount)
        {
            best = part;
            bestCount = n;
        }
    }
    return best;
}


bool pmsh::manifoldAt
(
    const CoarseMesh& coarse,
    const std::vector<faceNeighbours>& neighbours,
    const std::vector<label>& entity,
    const std::vector<label>& cells,
    const std::vector<label>& cellPart,
    label p
)
{
    std::vector<bool> inPart(cells.size());
    label nIn = 0;
    for (std::size_t i = 0; i < cells.size(); ++i)
    {
        inPart[i] = cellPart[cells[i]] == p;
        nIn += inPart[i];
    }
    if (nIn == 0 || nIn == label(cells.size()))
    {
        return true;
    }
    label nComp;
    components(coarse, neighbours, entity, cells, inPart, nComp);
    if (nComp > 1 || entity.size() > 1)
    {
        return nComp <= 1;
    }
    std::vector<bool> other(cells.size() + 1, true);
    for (std::size_t i = 0; i < cells.size(); ++i)
    {
        other[i] = !inPart[i];
    }
    components(coarse, neighbours, entity, cells, other, nComp);
    return nComp <= 1;
}


bool pmsh::moveIfManifold
(
    const CoarseMesh& coarse,
    const std::vector<faceNeighbours>& neighbours,
    const coarsePointCells& vc,
    label c,
    label to,
    std::vector<label>& cellPart
)
{
    const label from = cellPart[c];
    cellPart[c] = to;
    const tetVerts& t = coarse.tets[c];
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i)
    {
        const std::vector<label> around = vc.around(t[i]);
        ok = manifoldAt(coarse, neighbours, {t[i]}, around, cellPart, from)
          && manifoldAt(coarse, neighbours, {t[i]}, around, cellPart, to);
        for (int j = i + 1; j < 4 && ok; ++j)
        {
            std::vector<label> cells;
            for (label d : around)
            {
                if (tetHas(coarse.tets[d], t[j])) cells.push_back(d);
            }
            ok = manifoldAt(coarse, neighbours, {t[i], t[j]}, cells, cellPart, from)
              && manifoldAt(coarse, neighbours, {t[i], t[j]}, cells, cellPart, to);
        }
    }
    if (!ok)
    {
        cellPart[c] = from;
    }
    return ok;
}


// ************************************************************************* //
