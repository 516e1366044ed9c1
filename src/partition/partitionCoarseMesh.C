#include "partitionCoarseMesh.H"
#include "coarseMesh.H"
#include "error.H"
#include "failTogether.H"

#include <metis.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <tuple>

namespace
{

using namespace pmsh;

bool tetHas(const tetCell& t, label p)
{
    return std::find(t.begin(), t.end(), p) != t.end();
}


// Does face f (outwardTetFaces order) of tet t contain all points of the
// entity (one vertex, or the two ends of an edge)?
bool faceContains(const tetCell& t, int f, const std::vector<label>& entity)
{
    const triFace face = outwardTetFaces(t)[f];
    for (label p : entity)
    {
        if (std::find(face.begin(), face.end(), p) == face.end())
        {
            return false;
        }
    }
    return true;
}


// Face-connected components among `cells` (the cells around an entity)
// restricted to those with inRegion; returns the component of each cell
// (-1 when not in the region). Cells around an entity that share a face
// share a face containing the entity, so the tet neighbours suffice. An
// optional extra node (index cells.size(), the space outside the domain)
// joins every cell with a boundary face containing the entity.
std::vector<label> components
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
        const tetCell& t = coarse.tets[cells[i]];
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


// The part across a face most of `cells` share, other than `notPart`
label neighbourPart
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


// One pass over the entities (vertices, then edges): where a part's cells
// around an entity are not one face-connected group, or (at a vertex) the
// other cells and the outside are not, move the smaller groups. Returns the
// number of defects found; `moved` counts cell moves.
label repairPass
(
    const CoarseMesh& coarse,
    const std::vector<faceNeighbours>& neighbours,
    const coarsePointCells& vc,
    std::vector<label>& cellPart,
    bool doMove,
    label& moved
)
{
    label nDefects = 0;

    auto checkEntity = [&](const std::vector<label>& entity, const std::vector<label>& cells)
    {
        std::vector<label> parts;
        for (label c : cells)
        {
            parts.push_back(cellPart[c]);
        }
        std::sort(parts.begin(), parts.end());
        parts.erase(std::unique(parts.begin(), parts.end()), parts.end());
        if (parts.size() < 2)
        {
            return;     // inside one part: nothing to check
        }
        const bool isVertex = entity.size() == 1;

        for (label p : parts)
        {
            // The part's own cells around the entity
            std::vector<bool> inPart(cells.size());
            for (std::size_t i = 0; i < cells.size(); ++i)
            {
                inPart[i] = cellPart[cells[i]] == p;
            }
            label nComp;
            const std::vector<label> comp =
                components(coarse, neighbours, entity, cells, inPart, nComp);
            if (nComp > 1)
            {
                ++nDefects;
                if (doMove)
                {
                    // Keep the largest group, hand the others to a neighbour
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
                        label to = neighbourPart(neighbours, cellPart, group, p);
                        if (to < 0) to = (parts[0] == p ? parts[1] : parts[0]);
                        for (label c : group)
                        {
                            cellPart[c] = to;
                            ++moved;
                        }
                    }
                }
                return;     // the cells changed: look again next pass
            }

            if (!isVertex)
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
                components(coarse, neighbours, entity, cells, other, nComp);
            if (nComp > 1)
            {
                ++nDefects;
                if (doMove)
                {
                    // Fill the holes (groups not reaching the outside, all
                    // but the largest if none does) with the part's cells
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
                            cellPart[cells[i]] = p;
                            ++moved;
                        }
                    }
                }
                return;
            }
        }
    };

    for (label v = 0; v < coarse.nPoints(); ++v)
    {
        checkEntity({v}, vc.around(v));
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
            checkEntity({a, b}, cells);
        }
    }
    return nDefects;
}


// Give every empty part one cell of the largest part, taken from where
// that part touches another (so the rest of it stays in one piece)
label fillEmptyParts
(
    const std::vector<faceNeighbours>& neighbours,
    label nParts,
    std::vector<label>& cellPart
)
{
    label moved = 0;
    for (label q = 0; q < nParts; ++q)
    {
        std::vector<label> size(nParts, 0);
        for (label p : cellPart) ++size[p];
        if (size[q] > 0)
        {
            continue;
        }
        const label largest = label(std::max_element(size.begin(), size.end()) - size.begin());
        label pick = -1;
        for (label c = 0; c < label(cellPart.size()) && pick < 0; ++c)
        {
            if (cellPart[c] != largest) continue;
            for (label nbr : neighbours[c])
            {
                if (isBoundaryNeighbour(nbr) || cellPart[nbr] != largest)
                {
                    pick = c;
                    break;
                }
            }
        }
        cellPart[pick < 0 ? 0 : pick] = q;
        ++moved;
    }
    return moved;
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions * * * * * * * * * * * * * * * //

pmsh::label pmsh::repairPartition
(
    const CoarseMesh& coarse,
    label nParts,
    std::vector<label>& cellPart
)
{
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    const coarsePointCells vc(coarse);

    label moved = 0;
    const int maxPasses = 50;
    for (int pass = 0; pass < maxPasses; ++pass)
    {
        const label filled = fillEmptyParts(neighbours, nParts, cellPart);
        moved += filled;
        label passMoved = 0;
        const label nDefects = repairPass(coarse, neighbours, vc, cellPart, true, passMoved);
        moved += passMoved;
        if (nDefects == 0 && filled == 0)
        {
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
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    std::vector<label> parts = cellPart;
    label moved = 0;
    return repairPass(coarse, neighbours, coarsePointCells(coarse), parts, false, moved);
}


std::vector<pmsh::label> pmsh::partitionCells(const CoarseMesh& coarse, label nParts)
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
    std::vector<label> cellPart(nCells, 0);
    if (nParts == 1)
    {
        return cellPart;
    }

    idx_t ne = nCells;
    idx_t nn = coarse.nPoints();
    std::vector<idx_t> eptr(nCells + 1), eind(4*std::size_t(nCells));
    for (label c = 0; c < nCells; ++c)
    {
        eptr[c] = 4*c;
        for (int k = 0; k < 4; ++k) eind[4*c + k] = coarse.tets[c][k];
    }
    eptr[nCells] = 4*nCells;

    idx_t ncommon = 3;          // dual graph edges through faces
    idx_t np = nParts;
    idx_t objval = 0;
    std::vector<idx_t> epart(nCells), npart(nn);
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    options[METIS_OPTION_CONTIG] = 1;
    options[METIS_OPTION_SEED] = 1;     // same partition on every run

    int status = METIS_PartMeshDual
    (
        &ne, &nn, eptr.data(), eind.data(), nullptr, nullptr,
        &ncommon, &np, nullptr, options, &objval, epart.data(), npart.data()
    );
    if (status == METIS_ERROR_INPUT)
    {
        // Contiguous parts are impossible for a domain in several pieces
        options[METIS_OPTION_CONTIG] = 0;
        status = METIS_PartMeshDual
        (
            &ne, &nn, eptr.data(), eind.data(), nullptr, nullptr,
            &ncommon, &np, nullptr, options, &objval, epart.data(), npart.data()
        );
    }
    if (status != METIS_OK)
    {
        throw FatalError
        (
            msg() << "METIS_PartMeshDual failed (status " << status << ") for "
                << nCells << " cells into " << nParts << " parts",
            "partitionCells"
        );
    }
    std::copy(epart.begin(), epart.end(), cellPart.begin());
    repairPartition(coarse, nParts, cellPart);
    return cellPart;
}


std::vector<pmsh::label> pmsh::partitionCoarseMesh
(
    const Communicator& comm,
    const CoarseMesh& coarse
)
{
    std::vector<label> cellPart;
    failTogether(comm, [&]
    {
        if (comm.master())
        {
            cellPart = partitionCells(coarse, comm.size());
        }
    });
    comm.broadcast(cellPart);
    return cellPart;
}
