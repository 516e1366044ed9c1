#include "tetFaceMatching.H"
#include "pmshError.H"

#include <sstream>

namespace
{

using namespace pmsh;

std::string facePoints(const triVerts& f)
{
    std::ostringstream os;
    os  << '(' << f[0] << ' ' << f[1] << ' ' << f[2] << ')';
    return os.str();
}


//- "\n    <count> <what> (first: <example>)" when there is a problem.
void report(std::ostream& os, const problemCount& p, const char* what)
{
    if (p.count)
    {
        os  << "\n    " << p.count << ' ' << what << " (first: " << p.first << ')';
    }
}

} // End anonymous namespace


pmsh::tetFaceMatch pmsh::matchTetFaces
(
    std::size_t nPoints,
    const std::vector<tetVerts>& tets,
    const std::vector<triVerts>& boundaryTriangles
)
{
    const std::size_t nTets = tets.size();
    const std::size_t nTris = boundaryTriangles.size();
    if (4*nTets + nTris >= std::size_t(noFace))
    {
        throw FatalError
        (
            msg() << "Too many faces for one rank: " << nTets << " tets, "
                << nTris << " boundary triangles.\nUse more ranks",
            "pmsh::matchTetFaces"
        );
    }
    const faceId nTetFaces = faceId(4*nTets);

    auto faceOf = [&](faceId id) -> triVerts
    {
        return id < nTetFaces
            ? tetFace(tets[id/4], int(id % 4))
            : boundaryTriangles[id - nTetFaces];
    };
    auto triangleName = [&](faceId id)
    {
        return "triangle " + std::to_string(id - nTetFaces) + ' ' + facePoints(faceOf(id));
    };

    tetFaceMatch match;
    match.across.assign(nTetFaces, noFace);
    match.nTetFaces = nTetFaces;
    problemCount open, notTetFace, internalInSurface, nonManifold, wrongSide, overlapping;

    forEachSamePointsGroup
    (
        nPoints, faceId(nTetFaces + nTris), faceOf,
        [&](const faceId* ids, std::size_t n)
        {
            // Ids ascend: tet faces come before triangles
            std::size_t nTet = 0;
            while (nTet < n && ids[nTet] < nTetFaces)
            {
                ++nTet;
            }
            const std::size_t nTri = n - nTet;
            const faceId a = ids[0];

            if (nTet == 2 && nTri == 0)
            {
                const faceId b = ids[1];
                if (sameOrientation(faceOf(a), faceOf(b)))
                {
                    overlapping.add([&]
                    {
                        return "tets " + std::to_string(a/4) + " and "
                            + std::to_string(b/4) + " at face " + facePoints(faceOf(a));
                    });
                }
                match.across[a] = b;
                match.across[b] = a;
            }
            else if (nTet == 1 && nTri == 1)
            {
                const faceId b = ids[1];
                if (!sameOrientation(faceOf(a), faceOf(b)))
                {
                    wrongSide.add([&]
                    {
                        return triangleName(b) + " of tet " + std::to_string(a/4);
                    });
                }
                match.across[a] = b;
            }
            else if (nTet == 1 && nTri == 0)
            {
                open.add([&]
                {
                    return "tet " + std::to_string(a/4) + " face " + facePoints(faceOf(a));
                });
            }
            else if (nTet == 0 || nTet == 2)
            {
                problemCount& p = nTet ? internalInSurface : notTetFace;
                for (std::size_t k = nTet; k < n; ++k)
                {
                    p.add([&] { return triangleName(ids[k]); });
                }
            }
            else
            {
                nonManifold.add([&]
                {
                    return std::to_string(nTet) + " tets and " + std::to_string(nTri)
                        + " triangles share face " + facePoints(faceOf(a));
                });
            }
        }
    );

    std::ostringstream os;
    report(os, open, "tet faces are on no other tet and not in the boundary"
        " surface (boundary face not in the surface)");
    report(os, notTetFace, "boundary surface triangles are not a tet face");
    report(os, internalInSurface, "boundary surface triangles lie on a face"
        " between two tets");
    report(os, nonManifold, "faces are shared by more than two tets or"
        " surface triangles (duplicates)");
    report(os, wrongSide, "boundary surface triangles are not oriented"
        " outward from their tet (orientation mismatch)");
    report(os, overlapping, "faces are shared by two tets on the same side"
        " (overlapping tets)");
    match.problems = os.str();
    return match;
}


pmsh::tetFaceMatch pmsh::fittingTetFaces
(
    std::size_t nPoints,
    const std::vector<tetVerts>& tets,
    const std::vector<triVerts>& boundaryTriangles,
    const std::string& mismatch,
    const std::string& function
)
{
    tetFaceMatch match = matchTetFaces(nPoints, tets, boundaryTriangles);
    if (!match.fits())
    {
        throw FatalError(msg() << mismatch << ':' << match.problems, function);
    }
    return match;
}


// ************************************************************************* //
