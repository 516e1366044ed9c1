/*---------------------------------------------------------------------------*\
  pmshFoam: STL geometry: Netgen's coarse mesh, retried with smaller sizes
  within a time limit, and its boundary faces' regions (see stlGeometry.H).
  Netgen itself is behind netgenInterface.
\*---------------------------------------------------------------------------*/

#include "stlGeometry.H"
#include "stlGeometryImpl.H"
#include "netgenInterface.H"
#include "pmshError.H"
#include "streamManip.H"
#include "retryLadder.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <optional>
#include <sstream>

using Foam::Info;

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- A number as the log and pmshDict write it (6 significant digits).
std::string toString(double x)
{
    std::ostringstream os;
    os << x;
    return os.str();
}


//- The sizes of one try of Netgen's STL mesher.
struct stlMeshSizes
{
    double maxh;
    double curvatureRefinement;
};


//- The configured sizes, then the retries. Measured on a curved wall of
//  radius 1 and thickness 0.002 at maxCellSize 0.3 ("boundary mesh is
//  overlapping"): curvatureRefinement 10 or maxCellSize 0.1 cure it;
//  Netgen's close-edge restriction 5x stronger with its edge-angle
//  restriction does not, and makes curvatureRefinement 10 fail too.
std::vector<ladderAttempt<stlMeshSizes>> meshAttempts(double maxh, double curvatureRefinement)
{
    std::vector<ladderAttempt<stlMeshSizes>> attempts{{{maxh, curvatureRefinement}, ""}};

    // Smaller sizes on curved faces: a chord of a curved wall sags by
    // h^2/(8 radius) = radius/(8 curvatureRefinement^2), and crosses the
    // wall's other side where that exceeds its thickness. Each retry
    // divides the sag by 9.
    double curved = curvatureRefinement;
    for (double least : {10.0, 30.0})
    {
        curved = std::max(least, 3*curved);
        attempts.push_back
        (
            {{maxh, curved}, "curvatureRefinement " + toString(curved)}
        );
    }

    // Smaller sizes everywhere, for walls or gaps thinner than the
    // triangles on flat faces too
    attempts.push_back
    (
        {
            {maxh/2, curved},
            "maxCellSize " + toString(maxh/2) + " and curvatureRefinement "
          + toString(curved)
        }
    );
    return attempts;
}

} // End anonymous namespace
} // End namespace pmsh


namespace pmsh
{
namespace
{

//- The stage-1 log's account of curvature sizing: how much it asked for
//  and where, so a user sees when it made most of the coarse mesh.
void logCurvatureSizing
(
    const stlGeometry::curvatureSizing& sizing,
    const std::vector<std::string>& solidNames,
    double curvatureRefinement,
    double minCellSize
)
{
    label nPoints = 0, nAtFloor = 0;
    for (const auto& solid : sizing.solids)
    {
        nPoints += solid.nPoints;
        nAtFloor += solid.nAtFloor;
    }
    Info
        << "    curvature sizing (curvatureRefinement "
        << toString(curvatureRefinement).c_str() << ", minCellSize "
        << toString(minCellSize).c_str() << "): " << nPoints
        << " STL points below maxCellSize, " << nAtFloor
        << " held at minCellSize\n";
    for (std::size_t i = 0; i < sizing.solids.size(); ++i)
    {
        const auto& solid = sizing.solids[i];
        if (solid.nPoints)
        {
            Info
                << "        " << solidNames[i].c_str() << ": " << solid.nPoints
                << " points, smallest size " << toString(solid.smallest).c_str()
                << ", about " << label(std::lround(solid.faces))
                << " boundary faces at these sizes, "
                << label(std::lround(solid.uniformFaces))
                << " at maxCellSize\n";
        }
    }
}


//- Seconds an attempt of Netgen's STL coarse mesh may take by default: ten
//  times what it is expected to take, at least two minutes. Measured here
//  (2 shared cores): about 2000 coarse cells and 500 boundary faces a
//  second, and the STL's analysis at 20000 triangles a second. The cells
//  are those of the domain at maxCellSize plus ten a boundary face (the
//  grading from the surface inwards: 3119 cells for 342 faces in the
//  cylinder's box).
double defaultTimeLimit
(
    const stlSurface& surface,
    const stlGeometry::curvatureSizing& sizing,
    double maxh
)
{
    double faces = 0;
    for (const auto& solid : sizing.solids)
    {
        faces += solid.faces;
    }
    const double cells =
        std::abs(enclosedVolume(surface))/(0.118*maxh*maxh*maxh) + 10*faces;
    const double expected =
        surface.nTriangles()/20000.0 + faces/500.0 + cells/2000.0;
    return std::max(120.0, std::ceil(10*expected));
}


//- What to change when Netgen's STL mesh took too long: fewer, larger
//  coarse triangles (every retry asks for smaller ones, which take
//  longer), or more time.
std::string coarserAdvice(const coarseMeshParameters& sizes, double attemptLimit)
{
    std::string advice =
        "In system/pmshDict, if Netgen was still getting on (its progress"
        " lines above), raise coarseTimeLimit (now "
      + toString(attemptLimit) + " s an attempt); else ask for fewer coarse"
        " triangles: maxCellSize " + toString(2*sizes.maxCellSize)
      + " (now " + toString(sizes.maxCellSize) + ")";
    if (sizes.curvatureRefinement > 0)
    {
        advice +=
            ", minCellSize " + toString(2*sizes.minCellSize) + " (now "
          + toString(sizes.minCellSize) + ") or curvatureRefinement 0 (now "
          + toString(sizes.curvatureRefinement) + ")";
    }
    return
        advice + "; or set coarseSurface remesh (the surface's own triangles"
        " remeshed, without Netgen's STL mesher); or simplify the STL";
}


//- The error when every attempt failed (or the time limit came first):
//  each attempt's reason, and what to change in system/pmshDict.
[[noreturn]] void throwLadderFailure
(
    const std::string& what,
    const std::vector<ladderAttempt<stlMeshSizes>>& attempts,
    const ladderFailures& failed,
    const coarseMeshParameters& sizes,
    double attemptLimit,
    double ladderLimit
)
{
    const std::vector<std::string>& reasons = failed.reasons;
    const std::size_t nTried = failed.nTried();
    msg message;
    message
        << "Netgen could not mesh " << what << " in " << nTried
        << (nTried == 1 ? " attempt" : " attempts")
        << (nTried < attempts.size() ? " of " + std::to_string(attempts.size()) : "")
        << ":";
    for (std::size_t i = 0; i < nTried; ++i)
    {
        message
            << "\n    " << i + 1 << " ("
            << (i == 0 ? "as configured" : attempts[i].change) << "): "
            << reasons[i];
    }
    if (failed.stopped)
    {
        message
            << "\nEvery further attempt asks for smaller triangles and would"
            << " take longer: none was made. "
            << coarserAdvice(sizes, attemptLimit) << '.';
        throw FatalError(message, "pmsh::stlGeometry::netgenMesh");
    }

    const stlMeshSizes& last = attempts[nTried - 1].parameters;
    if (nTried < attempts.size())
    {
        message
            << "\nThe attempts together reached their time limit of "
            << toString(ladderLimit) << " s (twice coarseTimeLimit) before "
            << attempts[nTried].change << " could be tried.";
    }
    message
        << "\nNetgen's triangles are too large for some part of the surface"
        << " (often a wall thinner than the sag of its triangles on a curved"
        << " face, or two surfaces closer than maxCellSize). In system/pmshDict"
        << " set maxCellSize " << toString(last.maxh/2) << " (or smaller), or"
        << " curvatureRefinement " << toString(2*last.curvatureRefinement)
        << " with a smaller minCellSize (now " << toString(sizes.minCellSize)
        << "), or give the thin part's patch a smaller maxCellSize in"
        << " patches; also check the STL for self-intersections.";
    if (nTried < attempts.size())
    {
        message
            << " Each of these takes longer: raise coarseTimeLimit (now "
            << toString(attemptLimit) << " s) with it.";
    }
    throw FatalError(message, "pmsh::stlGeometry::netgenMesh");
}


//- Netgen's coarse mesh of the STL surface, retried with smaller sizes
//  while Netgen's meshing steps fail, each attempt and all of them within
//  a time limit.
ng::volumeMesh retriedStlMesh
(
    const stlGeometry& geometry,
    const ng::meshParameters& configured,
    const coarseMeshParameters& sizes,
    const std::string& what
)
{
    const stlSurface& surface = geometry.surface();
    const std::vector<ladderAttempt<stlMeshSizes>> attempts =
        meshAttempts(sizes.maxCellSize, sizes.curvatureRefinement);

    // A surface Netgen cannot mesh well can keep it busy for tens of
    // minutes (a ship's hull: 25 at "Surface meshing, 99%")
    const double attemptLimit =
        sizes.coarseTimeLimit > 0
      ? sizes.coarseTimeLimit
      : defaultTimeLimit
        (
            surface,
            geometry.curvatureSizes
            (
                sizes.curvatureRefinement, sizes.minCellSize, sizes.maxCellSize,
                sizes.grading
            ),
            sizes.maxCellSize
        );
    const double ladderLimit = 2*attemptLimit;
    Info
        << "    time limit: " << toString(attemptLimit).c_str() << " s an attempt, "
        << toString(ladderLimit).c_str() << " s for all (coarseTimeLimit"
        << (sizes.coarseTimeLimit > 0 ? "" : ", from the surface's size")
        << ")\n";
    const auto start = std::chrono::steady_clock::now();

    // Netgen's STL mesher fails on some valid surfaces where its triangles
    // are too large for the geometry, e.g. "boundary mesh is overlapping"
    // on a thin curved wall: each retry asks for smaller ones
    double remaining = ladderLimit;
    const auto withinLadderLimit = [&](std::size_t)
    {
        remaining = ladderLimit - std::chrono::duration<double>
        (
            std::chrono::steady_clock::now() - start
        ).count();
        return remaining > 0;
    };
    ladderFailures failed;
    std::optional<ng::volumeMesh> meshed = climbLadder
    (
        attempts,
        [&](const ladderAttempt<stlMeshSizes>& attempt, std::size_t i)
        {
            const stlMeshSizes& sizesTried = attempt.parameters;

            // Curvature sizes are pmshFoam's, not Netgen's (resthsurfcurvfac):
            // Netgen's have no floor and follow no grading
            const stlGeometry::curvatureSizing curvature = geometry.curvatureSizes
            (
                sizesTried.curvatureRefinement, sizes.minCellSize,
                sizesTried.maxh, sizes.grading
            );
            ng::meshParameters parameters = configured;
            parameters.maxh = sizesTried.maxh;
            parameters.timeLimit = std::min(attemptLimit, remaining);
            parameters.sizePoints.insert
            (
                parameters.sizePoints.end(),
                curvature.points.begin(), curvature.points.end()
            );
            try
            {
                ng::volumeMesh m = ng::stlVolumeMesh
                (
                    surface.points, surface.triangles, geometry.featureEdges(),
                    parameters, what
                );
                if (i > 0)
                {
                    Info
                        << "    Netgen's STL mesh succeeded at attempt " << i + 1
                        << " (" << attempt.change.c_str() << ")\n";
                }
                if (sizesTried.curvatureRefinement > 0)
                {
                    logCurvatureSizing
                    (
                        curvature, surface.solidNames,
                        sizesTried.curvatureRefinement, sizes.minCellSize
                    );
                }
                return m;
            }
            catch (const ng::stlMeshingTimeout& e)
            {
                // Every later attempt asks for smaller triangles: it would
                // take longer still
                throw attemptFailed{e.reason(), true};
            }
            catch (const ng::stlMeshingFailure& e)
            {
                if (i + 1 < attempts.size())
                {
                    Info
                        << "    Netgen's STL mesh failed (" << e.reason().c_str()
                        << "); retrying with " << attempts[i + 1].change.c_str() << '\n';
                }
                throw attemptFailed{e.reason()};
            }
        },
        failed,
        withinLadderLimit
    );
    if (meshed)
    {
        return std::move(*meshed);
    }

    throwLadderFailure(what, attempts, failed, sizes, attemptLimit, ladderLimit);
}

} // End anonymous namespace
} // End namespace pmsh


pmsh::CoarseMesh pmsh::stlGeometry::netgenMesh
(
    const coarseMeshParameters& parameters,
    bool surfaceOnly
) const
{
    const char* function = "pmsh::stlGeometry::netgenMesh";
    const impl& d = *impl_;

    if (!(parameters.maxCellSize > 0))
    {
        throw FatalError
        (
            msg()
                << "maxCellSize " << parameters.maxCellSize << " for "
                << what_ << " must be positive",
            function
        );
    }

    ng::meshParameters mp;
    mp.grading = parameters.grading;
    mp.surfaceOnly = surfaceOnly;
    mp.regions = parameters.regions;
    mp.sizePoints = parameters.sizePoints;
    if (parameters.cellsAcrossGap > 0)
    {
        const gapSizing gaps =
            gapSizes(parameters.cellsAcrossGap, localTriangleSizes(parameters));
        gaps.log(parameters.cellsAcrossGap);
        mp.sizePoints.insert(mp.sizePoints.end(), gaps.points.begin(), gaps.points.end());
    }
    ng::volumeMesh m = retriedStlMesh(*this, mp, parameters, what_);

    // Netgen's boundary vertices lie on the STL up to rounding; a vertex is
    // "on" a region within this distance
    const double tol = 1e-8*d.diagonal;
    const double tol2 = tol*tol;

    // Regions of every boundary point, computed once
    std::vector<std::vector<label>> pointRegions(m.points.size());
    std::vector<bool> done(m.points.size(), false);

    CoarseMesh coarse;
    coarse.boundary.reserve(m.boundary.size());
    label nOff = 0;
    double maxOff = 0;
    for (const ng::boundaryTriangle& b : m.boundary)
    {
        std::vector<label> common;
        for (int k = 0; k < 3; ++k)
        {
            const label v = b.v[k];
            if (!done[v])
            {
                pointRegions[v] = d.regionsNear(m.points[v], tol2);
                done[v] = true;
            }
            if (k == 0)
            {
                common = pointRegions[v];
            }
            else
            {
                std::vector<label> c;
                std::set_intersection
                (
                    common.begin(), common.end(),
                    pointRegions[v].begin(), pointRegions[v].end(),
                    std::back_inserter(c)
                );
                common.swap(c);
            }
        }

        const point3 c = (1.0/3.0)
          * (m.points[b.v[0]] + m.points[b.v[1]] + m.points[b.v[2]]);

        label r = -1;
        if (common.size() == 1)
        {
            r = common[0];
        }
        else if (common.size() > 1)
        {
            // All three vertices on region boundaries: the region nearest
            // to the centroid
            r = d.nearestRegion(common, c);
        }
        else
        {
            // No region holds all three vertices: Netgen's face crosses a
            // feature edge (or a vertex is off the STL)
            ++nOff;
            point3 q;
            r = d.region[nearestTriangle(c, q)];
            for (label v : b.v)
            {
                nearestTriangle(m.points[v], q);
                maxOff = std::max(maxOff, std::sqrt(magSqr(q - m.points[v])));
            }
        }

        coarse.boundary.push_back({b.v, d.regionSolid[r], r});
    }

    if (nOff)
    {
        throw FatalError
        (
            msg()
                << "Netgen's coarse mesh of " << what_
                << " does not follow its feature edges: " << nOff
                << " boundary face(s) have vertices on different surfaces"
                << " (separated by edges sharper than " << featureAngle
                << " degrees or between solids), or off the STL (largest"
                << " distance of their vertices from the STL " << maxOff
                << ", tolerance " << tol << ").\nTry a smaller maxCellSize"
                << " (now " << parameters.maxCellSize << ")",
            function
        );
    }

    coarse.points = std::move(m.points);
    coarse.tets = std::move(m.tets);
    for (const std::string& name : d.surface.solidNames)
    {
        coarse.patches.push_back({name});
    }

    return coarse;
}


// ************************************************************************* //
