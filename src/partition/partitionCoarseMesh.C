#include "partitionCoarseMesh.H"
#include "pmshError.H"
#include "failTogether.H"
#include "foamShims.H"
#include "streamManip.H"

// OpenFOAM
#include "argList.H"
#include "decompositionMethod.H"
#include "dictionary.H"
#include "IFstream.H"
#include "OSspecific.H"
#include "UPstream.H"

#include <algorithm>
#include <iomanip>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

using Foam::Info;
using Foam::fixed;
using Foam::setprecision;

namespace
{

using namespace pmsh;

bool tetHas(const tetVerts& t, label p)
{
    return std::find(t.begin(), t.end(), p) != t.end();
}


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


// With zones, a part is meshed zone by zone (meshVolumeByZone), so every
// piece (part, zone) must be a manifold. The repair and the balance work
// on pieces: a cell's key is part*nZones + zone, and the faces between two
// zones count as boundary (the pieces on their two sides are meshed
// apart). Without zones a key is the part.
class zonePieces
{
public:

    explicit zonePieces(const CoarseMesh& coarse)
    :
        coarse_(coarse),
        nZones_(coarse.nZones())
    {}

    label key(label part, label cell) const
    {
        return part*nZones_ + coarse_.zoneOf(cell);
    }

    label part(label key) const { return key/nZones_; }

    //- The key of part(to) for cell c (in c's zone)
    label moved(label cell, label to) const { return key(part(to), cell); }

    std::vector<label> keys(const std::vector<label>& cellPart) const
    {
        std::vector<label> k(cellPart.size());
        for (std::size_t c = 0; c < k.size(); ++c)
        {
            k[c] = key(cellPart[c], label(c));
        }
        return k;
    }

    void toParts(const std::vector<label>& keys, std::vector<label>& cellPart) const
    {
        for (std::size_t c = 0; c < keys.size(); ++c)
        {
            cellPart[c] = part(keys[c]);
        }
    }

    //- The coarse face neighbours, a face between zones as boundary
    std::vector<faceNeighbours> neighbours() const
    {
        std::vector<faceNeighbours> n = coarseFaceNeighbours(coarse_);
        if (nZones_ > 1)
        {
            for (label c = 0; c < label(n.size()); ++c)
            {
                for (label& nbr : n[c])
                {
                    if (!isBoundaryNeighbour(nbr) && coarse_.zoneOf(nbr) != coarse_.zoneOf(c))
                    {
                        nbr = -1;
                    }
                }
            }
        }
        return n;
    }

private:

    const CoarseMesh& coarse_;
    const label nZones_;
};


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
    const zonePieces& pieces,
    const std::vector<faceNeighbours>& neighbours,
    const coarsePointCells& vc,
    std::vector<label>& cellPart,
    bool doMove,
    bool absorb,
    label& moved
)
{
    label nDefects = 0;

    // A defect the usual moves took back and forth (two places each
    // wanting the same cells): the cells of p's zone around the entity all
    // go to the lowest part among them. Cells only ever move to lower
    // parts here, so this ends.
    auto absorbAround = [&](const std::vector<label>& cells, label p)
    {
        label lowest = pieces.part(p);
        for (label c : cells)
        {
            if (pieces.moved(c, p) == p)
            {
                lowest = std::min(lowest, pieces.part(cellPart[c]));
            }
        }
        for (label c : cells)
        {
            if (pieces.moved(c, p) == p && pieces.part(cellPart[c]) != lowest)
            {
                cellPart[c] = pieces.key(lowest, c);
                ++moved;
            }
        }
    };

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
                if (doMove && absorb)
                {
                    absorbAround(cells, p);
                }
                else if (doMove)
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
                            cellPart[c] = pieces.moved(c, to);
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
                if (doMove && absorb)
                {
                    absorbAround(cells, p);
                }
                else if (doMove)
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
                            cellPart[cells[i]] = pieces.moved(cells[i], p);
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


// Is part p a manifold at the entity (as repairPass judges it): its cells
// around the entity one face-connected group and, at a vertex, the other
// cells with the outside one group too?
bool manifoldAt
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


// Move cell c to part `to` if parts from and to stay manifolds at every
// vertex and edge of c (the only entities the move changes); else leave it
bool moveIfManifold
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

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Functions * * * * * * * * * * * * * * * //

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


namespace
{

using namespace pmsh;

// While one lives, OpenFOAM runs serial: the decomposition is the master's
// alone (the others do not take part in its reductions), as OpenFOAM's own
// utilities do it (renumberMesh)
class serialSection
{
    const bool oldParRun_;
public:
    serialSection()
    :
        oldParRun_(Foam::UPstream::parRun())
    {
        Foam::UPstream::parRun() = false;
    }
    ~serialSection()
    {
        Foam::UPstream::parRun() = oldParRun_;
    }
    serialSection(const serialSection&) = delete;
    serialSection& operator=(const serialSection&) = delete;
};


// Methods whose decompose(globalCellCells, ...) is NotImplemented: they need
// an OpenFOAM polyMesh, which the coarse mesh is not
const std::set<std::string> meshOnlyMethods{"manual", "structured"};

std::vector<std::string> knownMethods()
{
    std::vector<std::string> methods;
    for (const Foam::word& name : foam::decompositionMethodNames())
    {
        if (!meshOnlyMethods.count(name))
        {
            methods.push_back(name);
        }
    }
    return methods;
}


// The method's name ("" when the dictionary has none)
std::string methodName(const Foam::dictionary& dict)
{
    const foamErrorsThrow throwing;
    Foam::word method;
    try
    {
        dict.readIfPresent("method", method);
    }
    catch (const Foam::error&)
    {
        return "(not a word)";
    }
    return method;
}


// The name of the default dictionary (a valid fileName: no spaces)
const char* const defaultName = "defaultDecomposition";

// Where the dictionary comes from, for messages
std::string dictSource(const Foam::dictionary& dict)
{
    if (dict.name() == defaultName)
    {
        return "the default, as the case has no decomposeParDict";
    }
    if (dict.name().empty())
    {
        return "the decomposition dictionary";
    }
    return dict.name();
}


// "decomposition method 'x' (from <dict>)": the start of every message
std::string methodFrom(const Foam::dictionary& dict)
{
    return "decomposition method '" + methodName(dict) + "' (from "
        + dictSource(dict) + ")";
}


// Stop unless dict names a method this executable can use on a tet mesh
void checkDecompositionMethod(const Foam::dictionary& dict)
{
    const std::string method = methodName(dict);
    const std::vector<std::string> known = knownMethods();
    if (method.empty())
    {
        throw FatalError
        (
            msg() << "No decomposition 'method' in " << dictSource(dict) << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    if (meshOnlyMethods.count(method))
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " needs an OpenFOAM"
                << " polyMesh: it cannot split the coarse tet mesh.\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    if (std::find(known.begin(), known.end(), method) == known.end())
    {
        throw FatalError
        (
            msg() << "Unknown " << methodFrom(dict) << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
}


// The weights as a decompositionMethod takes them. metis turns them into
// integers, weight/min(weights) rounded down: the lightest cell is set to
// 1/50 of the mean, which makes the unit 2% of a mean cell (the others keep
// theirs, and the sum stays below 2^31 up to 40M coarse cells)
Foam::scalarField methodWeights(const std::vector<double>& weights, label nCells)
{
    if (label(weights.size()) != nCells || nCells == 0)
    {
        return Foam::scalarField(nCells, 1.0);
    }
    Foam::scalarField w(nCells);
    double mean = 0;
    for (label c = 0; c < nCells; ++c)
    {
        w[c] = weights[c];
        mean += weights[c];
    }
    mean /= nCells;
    const label lightest = label
    (
        std::min_element(weights.begin(), weights.end()) - weights.begin()
    );
    w[lightest] = std::min(w[lightest], mean/50);
    for (label c = 0; c < nCells; ++c)
    {
        w[c] = std::max(w[c], mean/50);
    }
    return w;
}


// Decompose with OpenFOAM's decompositionMethod; cellPart[c] in [0, nParts)
std::vector<label> decomposeCells
(
    const CoarseMesh& coarse,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& cellWeights
)
{
    const label nCells = coarse.nCells();

    Foam::dictionary dict(decompositionDict);
    dict.set("numberOfSubdomains", Foam::label(nParts));

    checkDecompositionMethod(dict);

    // The graph: the face neighbours of every coarse tet; the points: the
    // tet centroids; the weights: the expected fine cells (else 1)
    const std::vector<faceNeighbours> neighbours = coarseFaceNeighbours(coarse);
    Foam::labelListList cellCells(nCells);
    Foam::pointField centres(nCells);
    const Foam::scalarField weights = methodWeights(cellWeights, nCells);
    for (label c = 0; c < nCells; ++c)
    {
        Foam::labelList& nbrs = cellCells[c];
        nbrs.setSize(4);
        label n = 0;
        for (label nbr : neighbours[c])
        {
            if (!isBoundaryNeighbour(nbr))
            {
                nbrs[n++] = nbr;
            }
        }
        nbrs.setSize(n);

        const tetVerts& t = coarse.tets[c];
        const point3 centroid = 0.25*
        (
            (coarse.points[t[0]] + coarse.points[t[1]])
          + (coarse.points[t[2]] + coarse.points[t[3]])
        );
        centres[c] = Foam::point(centroid[0], centroid[1], centroid[2]);
    }

    Foam::labelList decomp;
    try
    {
        const foamErrorsThrow throwing;
        const serialSection serial;
        Foam::autoPtr<Foam::decompositionMethod> decomposer =
            foam::newDecompositionMethod(dict);
        decomp = decomposer->decompose(cellCells, centres, weights);
    }
    catch (const Foam::error& e)
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " failed for "
                << nCells << " coarse cells into " << nParts << " parts:\n"
                << FatalError::of(e).message() << "\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }

    // Trust no method blindly: a stub library or a bad manual file gives
    // nonsense that would crash the later stages
    std::string problem;
    if (decomp.size() != nCells)
    {
        problem = "gave " + std::to_string(decomp.size()) + " parts for "
            + std::to_string(nCells) + " cells";
    }
    else
    {
        for (label c = 0; c < nCells && problem.empty(); ++c)
        {
            if (decomp[c] < 0 || decomp[c] >= nParts)
            {
                problem = "put cell " + std::to_string(c) + " in part "
                    + std::to_string(decomp[c]) + ", not one of 0.."
                    + std::to_string(nParts - 1);
            }
        }
    }
    if (!problem.empty())
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " " << problem << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    return std::vector<label>(decomp.begin(), decomp.end());
}

} // End anonymous namespace


Foam::fileName pmsh::decompositionDictFile(const Foam::argList& args)
{
    Foam::fileName file;
    if (foam::readIfPresent(args, "decomposeParDict", file))
    {
        // As argList resolves it for a parallel run (it leaves it as given
        // in a serial one)
        if (Foam::isDir(file))
        {
            file /= "decomposeParDict";
        }
        if (!file.isAbsolute() && file.compare(0, 1, ".") != 0)
        {
            file = foam::globalPath(args)/file;
        }
        file.expand();
        file.clean();
        return file;
    }
    return foam::globalPath(args)/"system"/"decomposeParDict";
}


Foam::dictionary pmsh::decompositionDict
(
    const Foam::fileName& dictFile,
    int nParts,
    bool required
)
{
    Foam::dictionary dict;
    if (Foam::isFile(dictFile))
    {
        try
        {
            const foamErrorsThrow throwing;
            Foam::IFstream is(dictFile);
            if (!is.good())
            {
                throw FatalError
                (
                    msg() << "Cannot open the decomposition dictionary " << dictFile,
                    "decompositionDict"
                );
            }
            dict = Foam::dictionary(is);
            dict.name() = dictFile;
        }
        catch (const Foam::error& e)
        {
            throw FatalError
            (
                msg() << "Cannot read the decomposition dictionary " << dictFile
                    << ":\n" << FatalError::of(e).message(),
                "decompositionDict"
            );
        }
        if (!dict.found("method"))
        {
            throw FatalError
            (
                msg() << "No 'method' in " << dictFile << ".\n"
                    << "Valid decomposition methods: " << validDecompositionMethods(),
                "decompositionDict"
            );
        }
    }
    else if (required)
    {
        throw FatalError
        (
            msg() << "The decomposition dictionary " << dictFile
                << " (-decomposeParDict) does not exist.\n"
                << "Name an existing file, or leave -decomposeParDict out to use"
                << " system/decomposeParDict (method metis when there is none)",
            "decompositionDict"
        );
    }
    else
    {
        dict = defaultDecompositionDict();
    }

    // numberOfSubdomains is the number of ranks, whatever the file says
    if (dict.found("numberOfSubdomains"))
    {
        std::string inFile = "?";
        Foam::label n = -1;
        try
        {
            const foamErrorsThrow throwing;
            inFile = foam::tokensString(dict.lookup("numberOfSubdomains"));
            n = foam::get<Foam::label>(dict, "numberOfSubdomains");
        }
        catch (const Foam::error&)
        {
            n = -1;     // not a number: replaced all the same
        }
        if (n != nParts)
        {
            Info
                << "Note: numberOfSubdomains " << inFile.c_str() << " in " << dictFile.c_str()
                << " is replaced by the number of ranks, " << nParts << "\n";
        }
    }
    dict.set("numberOfSubdomains", Foam::label(nParts));

    // A wrong method stops now, before the coarse mesh is made
    checkDecompositionMethod(dict);
    return dict;
}


Foam::dictionary pmsh::decompositionDict(const Foam::argList& args, int nParts)
{
    return decompositionDict
    (
        decompositionDictFile(args),
        nParts,
        foam::found(args, "decomposeParDict")
    );
}


const Foam::dictionary& pmsh::defaultDecompositionDict()
{
    static const Foam::dictionary dict = []
    {
        Foam::dictionary d;
        d.name() = defaultName;
        d.add("method", Foam::word("metis"));

        // k-way, not OpenFOAM's default recursive bisection: on the sphere
        // at r = 4 the recursive parts gave HXT a surface it filled with a
        // flat cell (checkMesh: aspect ratio 6e9); k-way parts did not
        Foam::dictionary coeffs;
        coeffs.add("method", Foam::word("k-way"));
        d.add("metisCoeffs", coeffs);
        return d;
    }();
    return dict;
}


std::string pmsh::validDecompositionMethods()
{
    std::string list = "(";
    for (const std::string& method : knownMethods())
    {
        list += (list.size() > 1 ? " " : "") + method;
    }
    return list + ")";
}


std::vector<pmsh::label> pmsh::partitionCells
(
    const CoarseMesh& coarse,
    label nParts,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& weights
)
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
    if (nParts == 1)
    {
        return std::vector<label>(nCells, 0);
    }

    std::vector<label> cellPart =
        decomposeCells(coarse, nParts, decompositionDict, weights);
    repairPartition(coarse, nParts, cellPart);
    if (weights.empty())
    {
        return cellPart;
    }

    // The method balances its (integer) weights within a few per cent, and
    // the repair moves cells without looking at them: balance the parts'
    // expected fine cells now, keeping every part a manifold
    const double before = weightImbalance(weights, nParts, cellPart);
    const label moved = balancePartition(coarse, nParts, weights, cellPart);
    Info
        << fixed << setprecision(3)
        << "    expected fine cells per part max/mean: " << before
        << " from the method, "
        << weightImbalance(weights, nParts, cellPart)
        << " after moving " << moved << " coarse cells\n"
        << defaultfloat;
    return cellPart;
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


std::vector<pmsh::label> pmsh::partitionCoarseMesh
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const Foam::dictionary& decompositionDict,
    const std::vector<double>& fineWeights
)
{
    std::vector<label> cellPart;
    failTogether(comm, [&]
    {
        comm.masterWorksOthersSleep([&]
        {
            cellPart = partitionCells(coarse, comm.size(), decompositionDict, fineWeights);
        });
    });
    comm.broadcast(cellPart);
    return cellPart;
}
