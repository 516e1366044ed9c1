#include "mixedFaceMatching.H"
#include "matchByPoints.H"

#include <sstream>

namespace
{

using namespace pmsh;

//- +1 when b is a's cycle (a rotation of it), -1 when it is the reversed
//  cycle, 0 otherwise (the same points in another cyclic order: a twisted
//  quad). a and b have the same n points.
int orientationOf(const quadVerts& a, const quadVerts& b, int n)
{
    int k = 0;
    while (k < n && b[k] != a[0]) ++k;
    if (k == n) return 0;
    bool same = true, reversed = true;
    for (int i = 1; i < n; ++i)
    {
        same = same && b[(k + i) % n] == a[i];
        reversed = reversed && b[(k - i + n) % n] == a[i];
    }
    return same ? 1 : (reversed ? -1 : 0);
}


void report(std::ostream& os, const problemCount& p, const char* what)
{
    if (p.count)
    {
        os  << "\n    " << p.count << ' ' << what << " (first: " << p.first << ')';
    }
}

} // End anonymous namespace


std::string pmsh::mixedFaces::name(faceId id) const
{
    quadVerts f;
    const int n = pointsOf(id, f);
    std::ostringstream os;
    if (id < nCellFaces)
    {
        const label c = cellOf(id);
        os  << (c < nTets() ? "tet " : "prism ")
            << (c < nTets() ? c : c - nTets()) << " face";
    }
    else
    {
        os  << (id < quadsStart ? "boundary triangle " : "boundary quad ")
            << (id < quadsStart ? id - nCellFaces : id - quadsStart);
    }
    os  << " (";
    for (int k = 0; k < n; ++k)
    {
        os  << (k ? " " : "") << f[k];
    }
    os  << ')';
    return os.str();
}


std::vector<pmsh::faceId> pmsh::matchMixedFaces
(
    std::size_t nPoints,
    const mixedFaces& m
)
{
    std::vector<faceId> across(m.nCellFaces, noFace);
    problemCount open, notCellFace, internalInBoundary, nonManifold;
    problemCount wrongSide, overlapping;

    // Keyed by the three smallest points; the fourth splits the group
    auto key3 = [&](faceId id) -> std::array<label, 3>
    {
        quadVerts f;
        const int n = m.pointsOf(id, f);
        // The three smallest, sorted (insertion sort of 3 or 4)
        for (int i = 1; i < n; ++i)
        {
            for (int k = i; k > 0 && f[k] < f[k - 1]; --k) std::swap(f[k], f[k - 1]);
        }
        return {f[0], f[1], f[2]};
    };
    std::vector<std::pair<label, faceId>> group;
    auto classify = [&](const std::pair<label, faceId>* g, std::size_t n)
    {
        std::size_t nCell = 0;
        while (nCell < n && g[nCell].second < m.nCellFaces) ++nCell;
        const std::size_t nBoundary = n - nCell;
        const faceId a = g[0].second;
        quadVerts fa, fb;
        const int np = m.pointsOf(a, fa);
        if (nCell == 2 && nBoundary == 0)
        {
            const faceId b = g[1].second;
            m.pointsOf(b, fb);
            if (orientationOf(fa, fb, np) != -1)
            {
                overlapping.add([&] { return m.name(a) + " and " + m.name(b); });
            }
            across[a] = b;
            across[b] = a;
        }
        else if (nCell == 1 && nBoundary == 1)
        {
            const faceId b = g[1].second;
            m.pointsOf(b, fb);
            if (orientationOf(fa, fb, np) != 1)
            {
                wrongSide.add([&] { return m.name(b) + " of " + m.name(a); });
            }
            across[a] = b;
        }
        else if (nCell == 1 && nBoundary == 0)
        {
            open.add([&] { return m.name(a); });
        }
        else if (nCell == 0 || nCell == 2)
        {
            problemCount& p = nCell ? internalInBoundary : notCellFace;
            for (std::size_t k = nCell; k < n; ++k)
            {
                p.add([&] { return m.name(g[k].second); });
            }
        }
        else
        {
            nonManifold.add([&]
            {
                return std::to_string(nCell) + " cells and "
                    + std::to_string(nBoundary) + " boundary faces share "
                    + m.name(a);
            });
        }
    };

    forEachSamePointsGroup
    (
        nPoints, m.nAll, key3,
        [&](const faceId* ids, std::size_t n)
        {
            // Split by the fourth point (-1: a triangle), ids ascending
            group.clear();
            for (std::size_t i = 0; i < n; ++i)
            {
                quadVerts f;
                const int np = m.pointsOf(ids[i], f);
                group.push_back
                (
                    {np == 3 ? -1 : *std::max_element(f.begin(), f.end()), ids[i]}
                );
            }
            std::sort(group.begin(), group.end());
            for (std::size_t i = 0; i < group.size(); )
            {
                std::size_t j = i + 1;
                while (j < group.size() && group[j].first == group[i].first) ++j;
                // Cell faces first within the sub-group (ids ascend)
                classify(group.data() + i, j - i);
                i = j;
            }
        }
    );

    std::ostringstream os;
    report(os, open, "cell faces are on no other cell and in no boundary"
        " list (boundary face missing)");
    report(os, notCellFace, "boundary triangles or quads are no cell face");
    report(os, internalInBoundary, "boundary triangles or quads lie on a"
        " face between two cells");
    report(os, nonManifold, "faces are shared by more than two cells or"
        " boundary faces (duplicates)");
    report(os, wrongSide, "boundary triangles or quads are not oriented"
        " outward from their cell (orientation mismatch)");
    report(os, overlapping, "faces are shared by two cells on the same side"
        " or in another point order (overlapping cells)");
    if (!os.str().empty())
    {
        throw FatalError
        (
            msg() << "The cells (" << m.tets.size() << " tets, "
                << m.prisms.size() << " prisms) and the boundary ("
                << m.tris.size() << " triangles, " << m.quads.size()
                << " quads) do not match:" << os.str(),
            m.function
        );
    }
    return across;
}


// ************************************************************************* //
