/*---------------------------------------------------------------------------*\
  pmshFoam: checking STL surfaces: closed, manifold, oriented out of the
  domain, shells apart (see stlReader.H).
\*---------------------------------------------------------------------------*/

#include "stlReader.H"
#include "surfaceTopology.H"
#include "pmshError.H"
#include "triangleGeometry.H"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <unordered_map>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

// STL coordinates in messages: enough digits to find the facet in the file
std::string stlPoint(const point3& p)
{
    return str(p, 10);
}


std::string edgeString(const stlSurface& s, label a, label b)
{
    return stlPoint(s.points[a]) + "-" + stlPoint(s.points[b]);
}


//- The solids of a set of triangles, for messages: "solid a" or
//  "solids a, b".
std::string solidsOf(const stlSurface& s, const std::vector<label>& triangles)
{
    std::vector<label> solids;
    for (label t : triangles)
    {
        solids.push_back(s.solid[t]);
    }
    std::sort(solids.begin(), solids.end());
    solids.erase(std::unique(solids.begin(), solids.end()), solids.end());
    std::string names;
    for (label solid : solids)
    {
        names += (names.empty() ? "" : ", ") + s.solidNames[solid];
    }
    return (solids.size() > 1 ? "solids " : "solid ") + names;
}


//- Where the surface is a body's, pmshFoam can mend it (domainBox.H).
const char* wrapAdvice =
    "A body in a domain box (domain in system/pmshDict: the box round the"
    " bodies, not in the files) is wrapped instead: a closed surface round"
    " it (wrap auto, the default there)";

//- What to do about surfaces that touch: Netgen cannot mesh a gap of zero
//  width, and stops with a message that names no solid.
const char* touchingAdvice =
    "Netgen needs the closed surfaces of a domain to be apart (it would stop"
    " with \"edgepoint does not exist\" or an overlapping boundary mesh)."
    " Either join the touching solids into one closed surface (their union,"
    " e.g. the desk's legs and top as one surface, or a leg and the floor it"
    " stands on with the shared part removed), or move them apart by at"
    " least a coarse cell (maxCellSize), e.g. lift the desk off the floor";


//- Sheets: the triangles connected across edges that exactly two
//  triangles share. On a closed manifold surface a sheet is a shell;
//  shells that touch at a point share it but stay separate sheets.
std::vector<label> manifoldSheets(const stlSurface& s, label& nSheets)
{
    const label nt = s.nTriangles();
    std::vector<label> parent(nt);
    for (label t = 0; t < nt; ++t)
    {
        parent[t] = t;
    }
    auto root = [&parent](label i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };

    // (lower point, higher point, triangle), grouped by edge
    std::vector<std::array<label, 3>> edges;
    edges.reserve(3*nt);
    for (label t = 0; t < nt; ++t)
    {
        const triVerts& f = s.triangles[t];
        for (int k = 0; k < 3; ++k)
        {
            const label a = f[k], b = f[(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), t});
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i + 1;
        while
        (
            j < edges.size() && edges[j][0] == edges[i][0]
         && edges[j][1] == edges[i][1]
        )
        {
            ++j;
        }
        if (j - i == 2)
        {
            const label a = root(edges[i][2]), b = root(edges[i + 1][2]);
            if (a != b)
            {
                parent[std::max(a, b)] = std::min(a, b);
            }
        }
        i = j;
    }

    std::unordered_map<label, label> sheetOfRoot;
    std::vector<label> sheet(nt);
    for (label t = 0; t < nt; ++t)
    {
        sheet[t] = sheetOfRoot.emplace(root(t), label(sheetOfRoot.size())).first->second;
    }
    nSheets = label(sheetOfRoot.size());
    return sheet;
}


//- Where two sheets touch: the first contact found, and how.
struct sheetContact
{
    label sheetA = -1, sheetB = -1;
    point3 where{0, 0, 0};
    std::string how;
};


//- Each triangle's bounding box grown by tol, and its largest extent.
struct triangleBoxes
{
    std::vector<point3> lo, hi;
    std::vector<double> extent;
};


triangleBoxes grownBoxes(const stlSurface& s, double tol)
{
    const label nt = s.nTriangles();
    triangleBoxes boxes;
    std::vector<point3>& lo = boxes.lo;
    std::vector<point3>& hi = boxes.hi;
    lo.resize(nt);
    hi.resize(nt);
    boxes.extent.resize(nt);
    for (label t = 0; t < nt; ++t)
    {
        const triVerts& f = s.triangles[t];
        lo[t] = hi[t] = s.points[f[0]];
        for (label v : f)
        {
            for (int k = 0; k < 3; ++k)
            {
                lo[t][k] = std::min(lo[t][k], s.points[v][k] - tol);
                hi[t][k] = std::max(hi[t][k], s.points[v][k] + tol);
            }
        }
        boxes.extent[t] = std::max({hi[t][0] - lo[t][0], hi[t][1] - lo[t][1], hi[t][2] - lo[t][2]});
    }
    return boxes;
}


//- Triangles of different sheets that share a point or come within tol of
//  each other (overlapping coplanar faces, a leg on a floor, crossing
//  surfaces): candidates from a grid of about twice the typical triangle
//  size, each pair tested once, in the cell of its boxes' lower corner.
//  Calls found(contact) for each pair of sheets that touch, once.
template<class Found>
void findSheetContacts
(
    const stlSurface& s,
    const std::vector<label>& sheet,
    double tol,
    const Found& found
)
{
    const label nt = s.nTriangles();
    std::set<std::pair<label, label>> reported;
    auto report = [&](label a, label b, const point3& x, const std::string& how)
    {
        const std::pair<label, label> key{std::min(a, b), std::max(a, b)};
        if (reported.insert(key).second)
        {
            found(sheetContact{key.first, key.second, x, how});
        }
    };

    // A point used by two sheets
    std::vector<label> pointSheet(s.points.size(), -1);
    for (label t = 0; t < nt; ++t)
    {
        for (label v : s.triangles[t])
        {
            if (pointSheet[v] < 0)
            {
                pointSheet[v] = sheet[t];
            }
            else if (pointSheet[v] != sheet[t])
            {
                report(pointSheet[v], sheet[t], s.points[v], "share the point");
            }
        }
    }

    const triangleBoxes boxes = grownBoxes(s, tol);
    const std::vector<point3>& lo = boxes.lo;
    const std::vector<point3>& hi = boxes.hi;
    if (nt < 2)
    {
        return;
    }
    std::vector<double> sorted(boxes.extent);
    std::nth_element(sorted.begin(), sorted.begin() + nt/2, sorted.end());
    const double cell = 2*sorted[nt/2];

    auto overlap = [&](label a, label b)
    {
        for (int k = 0; k < 3; ++k)
        {
            if (lo[a][k] > hi[b][k] || lo[b][k] > hi[a][k])
            {
                return false;
            }
        }
        return true;
    };
    auto test = [&](label a, label b)
    {
        if (sheet[a] == sheet[b] || !overlap(a, b))
        {
            return;
        }
        const std::pair<label, label> key
        {
            std::min(sheet[a], sheet[b]), std::max(sheet[a], sheet[b])
        };
        if (reported.count(key))
        {
            return;
        }
        point3 ta[3], tb[3];
        for (int k = 0; k < 3; ++k)
        {
            ta[k] = s.points[s.triangles[a][k]];
            tb[k] = s.points[s.triangles[b][k]];
        }
        point3 where;
        if (trianglesTouch(ta, tb, tol, where))
        {
            report(sheet[a], sheet[b], where, "touch or overlap");
        }
    };

    // Triangles far larger than the cells (a box's faces) are tested
    // against every other triangle whose box meets theirs
    using cellKey = std::array<long long, 3>;
    auto cellOf = [cell](const point3& p)
    {
        return cellKey
        {
            static_cast<long long>(std::floor(p[0]/cell)),
            static_cast<long long>(std::floor(p[1]/cell)),
            static_cast<long long>(std::floor(p[2]/cell))
        };
    };
    constexpr long long maxCells = 512;
    std::map<cellKey, std::vector<label>> grid;
    std::vector<label> large;
    for (label t = 0; t < nt; ++t)
    {
        const cellKey a = cellOf(lo[t]), b = cellOf(hi[t]);
        const long long n =
            (b[0] - a[0] + 1)*(b[1] - a[1] + 1)*(b[2] - a[2] + 1);
        if (!(cell > 0) || n > maxCells)
        {
            large.push_back(t);
            continue;
        }
        for (long long i = a[0]; i <= b[0]; ++i)
            for (long long j = a[1]; j <= b[1]; ++j)
                for (long long k = a[2]; k <= b[2]; ++k)
                    grid[{i, j, k}].push_back(t);
    }
    std::vector<char> isLarge(nt, 0);
    for (label t : large)
    {
        isLarge[t] = 1;
        for (label u = 0; u < nt; ++u)
        {
            if (u != t && !(isLarge[u] && u < t))
            {
                test(t, u);
            }
        }
    }
    for (const auto& c : grid)
    {
        const std::vector<label>& in = c.second;
        for (std::size_t i = 0; i < in.size(); ++i)
        {
            for (std::size_t j = i + 1; j < in.size(); ++j)
            {
                const label a = in[i], b = in[j];
                // Once per pair: in the cell of their common box's lower corner
                point3 corner;
                for (int k = 0; k < 3; ++k)
                {
                    corner[k] = std::max(lo[a][k], lo[b][k]);
                }
                if (cellOf(corner) == c.first)
                {
                    test(a, b);
                }
            }
        }
    }
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

double pmsh::enclosedVolume(const stlSurface& s)
{
    // About a point near the surface, for accuracy far from the origin
    const point3 o = s.points.empty() ? point3{0, 0, 0} : s.points[0];
    double v6 = 0;
    for (const triVerts& f : s.triangles)
    {
        v6 += tetVolume6(o, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
    }
    return v6/6;
}


void pmsh::checkStl(const stlSurface& s, const std::string& what)
{
    checkStlTopology(s, what);
    checkShellOrientation(s, what);
}


void pmsh::checkStlTopology(const stlSurface& s, const std::string& what)
{
    const char* function = "pmsh::checkStl";
    const label nt = s.nTriangles();

    // Degenerate triangles: repeated vertices or (numerically) zero area,
    // relative to the triangle's longest edge
    {
        label nBad = 0;
        label first = -1;
        for (label t = 0; t < nt; ++t)
        {
            const triVerts& f = s.triangles[t];
            double l2 = 0;
            for (int k = 0; k < 3; ++k)
            {
                l2 = std::max(l2, magSqr(s.points[f[(k + 1) % 3]] - s.points[f[k]]));
            }
            const double a2 = magSqr(s.areaNormal(t));
            if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || !(a2 > 1e-24*l2*l2))
            {
                if (first < 0)
                {
                    first = t;
                }
                ++nBad;
            }
        }
        if (nBad)
        {
            const triVerts& f = s.triangles[first];
            throw FatalError
            (
                msg()
                    << what << " has " << nBad
                    << " degenerate (zero-area) triangle(s), e.g. triangle "
                    << first << " of solid " << s.solidNames[s.solid[first]]
                    << ": " << stlPoint(s.points[f[0]]) << ' ' << stlPoint(s.points[f[1]])
                    << ' ' << stlPoint(s.points[f[2]]) << ".\nRemove them (or"
                    << " repair the surface) before meshing",
                function
            );
        }
    }

    const surfaceEdgeDefects defects = findSurfaceEdgeDefects(s.triangles);
    auto edge = [&](const std::pair<label, label>& e) { return edgeString(s, e.first, e.second); };
    const label nOpen = defects.nOpen;
    const label nNonManifold = defects.nNonManifold;
    const label nFlipped = defects.nInconsistent;

    if (nNonManifold)
    {
        // Solids that share faces or edges (two cubes sharing a face) are
        // touching shells: say which and what to do
        std::vector<label> atEdge;
        const auto e = defects.firstNonManifold;
        for (label t = 0; t < nt; ++t)
        {
            const triVerts& f = s.triangles[t];
            for (int k = 0; k < 3; ++k)
            {
                if
                (
                    std::min(f[k], f[(k + 1) % 3]) == std::min(e.first, e.second)
                 && std::max(f[k], f[(k + 1) % 3]) == std::max(e.first, e.second)
                )
                {
                    atEdge.push_back(t);
                }
            }
        }
        const std::string solids = solidsOf(s, atEdge);
        const bool severalSolids = solids.compare(0, 7, "solids ") == 0;
        throw FatalError
        (
            msg()
                << what << " is not manifold: "
                << nNonManifold << " edge(s) are used by more than two"
                << " triangles, e.g. the edge " << edge(e) << " by "
                << atEdge.size() << " triangles of " << solids
                << ".\nEvery edge of a closed surface must be shared by"
                << " exactly two triangles"
                << (
                       severalSolids
                     ? ": the closed surfaces of these solids share faces or"
                       " edges (touching shells). " + std::string(touchingAdvice)
                     : std::string(" (closed surfaces sharing faces or edges,"
                       " or a stray triangle)")
                   )
                << ". " << wrapAdvice,
            function
        );
    }
    if (nOpen)
    {
        throw FatalError
        (
            msg()
                << what << " is not closed: " << nOpen
                << " edge(s) are used by only one triangle, e.g. the edge "
                << edge(defects.firstOpen) << ".\nThe surface must enclose a volume: fill"
                << " the holes (vertices of neighbouring triangles must match"
                << " exactly). " << wrapAdvice,
            function
        );
    }
    if (nFlipped)
    {
        throw FatalError
        (
            msg()
                << what << " is inconsistently"
                << " oriented: " << nFlipped << " edge(s) are traversed in the"
                << " same direction by both their triangles (one of the two"
                << " normals is flipped), e.g. the edge " << edge(defects.firstInconsistent)
                << ".\nOrient all triangles consistently (normals outward)",
            function
        );
    }

    checkShellContacts(s, what);
}


void pmsh::checkShellContacts(const stlSurface& s, const std::string& what)
{
    label nSheets = 0;
    const std::vector<label> sheet = manifoldSheets(s, nSheets);
    if (nSheets < 2)
    {
        return;
    }

    std::vector<std::vector<label>> triangles(nSheets);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        triangles[sheet[t]].push_back(t);
    }

    // The outer boundary is the shell whose box is the whole surface's
    point3 lo = s.points[0], hi = s.points[0];
    for (const point3& p : s.points)
    {
        for (int k = 0; k < 3; ++k)
        {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    const double diagonal = std::sqrt(magSqr(hi - lo));
    const double tol = 1e-8*diagonal;
    auto describe = [&](label sh)
    {
        point3 slo = s.points[s.triangles[triangles[sh][0]][0]], shi = slo;
        for (label t : triangles[sh])
        {
            for (label v : s.triangles[t])
            {
                for (int k = 0; k < 3; ++k)
                {
                    slo[k] = std::min(slo[k], s.points[v][k]);
                    shi[k] = std::max(shi[k], s.points[v][k]);
                }
            }
        }
        const bool outer =
            magSqr(slo - lo) <= tol*tol && magSqr(shi - hi) <= tol*tol;
        return
            "the closed surface of " + solidsOf(s, triangles[sh])
          + (outer ? " (the outer boundary)" : "") + " ("
          + std::to_string(triangles[sh].size()) + " triangles between "
          + stlPoint(slo) + " and " + stlPoint(shi) + ")";
    };

    std::vector<sheetContact> contacts;
    findSheetContacts
    (
        s, sheet, tol,
        [&contacts](const sheetContact& c) { contacts.push_back(c); }
    );
    if (contacts.empty())
    {
        return;
    }

    msg message;
    message
        << what << ": " << contacts.size()
        << " pair(s) of closed surfaces touch or overlap:";
    constexpr std::size_t shown = 5;
    for (std::size_t i = 0; i < contacts.size() && i < shown; ++i)
    {
        const sheetContact& c = contacts[i];
        message
            << "\n    " << describe(c.sheetA) << "\n    and "
            << describe(c.sheetB) << "\n        " << c.how << " at "
            << stlPoint(c.where);
    }
    if (contacts.size() > shown)
    {
        message << "\n    ... and " << contacts.size() - shown << " more";
    }
    message << ".\n" << touchingAdvice << ". " << wrapAdvice;
    throw FatalError(message, "pmsh::checkShellContacts");
}


pmsh::shellNesting pmsh::nestShells(const stlSurface& s)
{
    shellNesting n;
    label nShells = 0;
    const std::vector<label> shell = surfaceShells(label(s.points.size()), s.triangles, nShells);
    n.triangles.resize(nShells);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        n.triangles[shell[t]].push_back(t);
    }
    n.volume6.resize(nShells, 0);
    n.depth.resize(nShells, 0);
    n.around.resize(nShells, -1);
    for (label sh = 0; sh < nShells; ++sh)
    {
        // Volume about a point of the shell, for accuracy far from the origin
        const point3 o = s.points[s.triangles[n.triangles[sh][0]][0]];
        for (label t : n.triangles[sh])
        {
            const triVerts& f = s.triangles[t];
            n.volume6[sh] += tetVolume6(o, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
        }

        // Nesting depth: the other shells around this one (shells do not
        // cross, so any of its points tells)
        const triVerts& f = s.triangles[n.triangles[sh][0]];
        const point3 x =
            (1.0/3.0)*(s.points[f[0]] + s.points[f[1]] + s.points[f[2]]);
        for (label other = 0; other < nShells; ++other)
        {
            if
            (
                other != sh
             && std::abs(windingNumber(s.points, s.triangles, n.triangles[other], x)) > 0.5
            )
            {
                ++n.depth[sh];
                n.around[sh] = other;
            }
        }
    }
    return n;
}


void pmsh::orientShellsOutOfTheFluid(stlSurface& s)
{
    const shellNesting n = nestShells(s);
    for (std::size_t sh = 0; sh < n.triangles.size(); ++sh)
    {
        // Outward at even depth, inward at odd
        if ((n.volume6[sh] < 0) != (n.depth[sh] % 2 == 1))
        {
            for (label t : n.triangles[sh])
            {
                std::swap(s.triangles[t][1], s.triangles[t][2]);
            }
        }
    }
}


void pmsh::checkShellOrientation(const stlSurface& s, const std::string& what)
{
    const char* function = "pmsh::checkShellOrientation";

    const shellNesting n = nestShells(s);
    const std::vector<std::vector<label>>& triangles = n.triangles;
    const label nShells = label(triangles.size());

    // The solids a shell is made of, for messages
    auto solidsOfShell = [&](label sh) { return solidsOf(s, triangles[sh]); };
    // Where a shell is: a solid may hold several
    auto extentOf = [&](label sh)
    {
        point3 lo = s.points[s.triangles[triangles[sh][0]][0]];
        point3 hi = lo;
        for (label t : triangles[sh])
        {
            for (label p : s.triangles[t])
            {
                for (int k = 0; k < 3; ++k)
                {
                    lo[k] = std::min(lo[k], s.points[p][k]);
                    hi[k] = std::max(hi[k], s.points[p][k]);
                }
            }
        }
        return " (" + std::to_string(triangles[sh].size()) + " triangles between "
            + stlPoint(lo) + " and " + stlPoint(hi) + ")";
    };

    for (label sh = 0; sh < nShells; ++sh)
    {
        const double v6 = n.volume6[sh];
        if (!(v6 != 0))
        {
            throw FatalError
            (
                msg()
                    << what << ": the closed surface of "
                    << solidsOfShell(sh) << " encloses no volume",
                function
            );
        }
        const label depth = n.depth[sh];
        const std::string around = n.around[sh] < 0 ? "" : solidsOfShell(n.around[sh]);

        // The fluid lies inside the outermost shell and outside a shell
        // nested in it: normals point out of the fluid
        const bool inward = v6 < 0;
        if (depth % 2 == 0 && inward)
        {
            throw FatalError
            (
                msg()
                    << what << " is oriented inward: the"
                    << " closed surface of " << solidsOfShell(sh) << extentOf(sh)
                    << " encloses a negative volume (" << v6/6 << ").\nIts triangle normals"
                    << " point into the solid: flip the normals (reverse the"
                    << " vertex order of every triangle of "
                    << solidsOfShell(sh) << ")",
                function
            );
        }
        if (depth % 2 == 1 && !inward)
        {
            throw FatalError
            (
                msg()
                    << what << ": the closed surface of "
                    << solidsOfShell(sh) << extentOf(sh) << " lies inside that of " << around
                    << " but its normals point out of it, into the fluid"
                    << " around it.\nA body in the flow is a hole in the"
                    << " domain: its normals must point out of the fluid, into"
                    << " the body. Flip the normals of " << solidsOfShell(sh)
                    << " (reverse the vertex order of each of its triangles)",
                function
            );
        }
    }
}


// ************************************************************************* //
