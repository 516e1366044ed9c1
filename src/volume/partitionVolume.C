#include "partitionVolume.H"
#include "childWatchdog.H"
#include "mesherChild.H"
#include "tetShape.H"
#include "pmshError.H"
#include "retryLadder.H"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <optional>
#include <unordered_map>

namespace
{

using namespace pmsh;

//- What one attempt of the ladder runs
struct volumeAttempt
{
    const VolumeMesher* mesher;
    volumeMeshParameters parameters;
};

//- "netgen; 1 thread": the mesher, and what else differs from the first
//  attempt
std::string describe(const ladderAttempt<volumeAttempt>& a)
{
    return a.parameters.mesher->name() + (a.change.empty() ? "" : "; " + a.change);
}

//- The ladder's attempts for a partition, first as asked
std::vector<ladderAttempt<volumeAttempt>> volumeAttempts
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const volumeMeshParameters& parameters
)
{
    // The attempts, in order: as asked; single-threaded; with the
    // optimiser changed; with a tighter interior size; then the other
    // meshers. Netgen's optimiser is where most of its rare crashes and
    // hangs live, so its retry goes without it; HXT's quality pass is what
    // removes the slivers the contract refuses, so its retry has more steps.
    // Asked for no steps (speed first), the first attempt was the one
    // without optimiser: the later ones have the default steps, as a mesh
    // that failed without them fails again the same way
    const VolumeMesher* first = meshers.at(0).get();
    std::vector<ladderAttempt<volumeAttempt>> attempts{{{first, parameters}, ""}};
    const auto addAttempt = [&](const VolumeMesher* mesher, const volumeMeshParameters& p, const std::string& change)
    {
        for (const ladderAttempt<volumeAttempt>& a : attempts)
        {
            const volumeMeshParameters& q = a.parameters.parameters;
            if
            (
                a.parameters.mesher == mesher && q.threads == p.threads
             && q.optimisationSteps == p.optimisationSteps && q.grading == p.grading
            )
            {
                return;
            }
        }
        attempts.push_back({{mesher, p}, change});
    };
    const bool stepsAsked = parameters.optimisationSteps > 0;
    volumeMeshParameters retry = parameters;
    retry.optimisationSteps =
        stepsAsked ? parameters.optimisationSteps : volumeMeshParameters().optimisationSteps;
    const std::string stepsAdded =
        stepsAsked ? "" : "optimisationSteps " + std::to_string(retry.optimisationSteps);

    volumeMeshParameters p = retry;
    if (p.threads > 1)
    {
        // Gmsh 4.8's multithreaded HXT can duplicate interior points
        p.threads = 1;
        addAttempt(first, p, "1 thread" + (stepsAsked ? "" : ", " + stepsAdded));
    }
    if (stepsAsked)
    {
        p.optimisationSteps = first->optimiserMayFail() ? 0 : 2*p.optimisationSteps;
    }
    addAttempt(first, p, "optimisationSteps " + std::to_string(p.optimisationSteps));
    p.grading = std::min(p.grading, 0.2);
    addAttempt
    (
        first, p,
        "optimisationSteps " + std::to_string(p.optimisationSteps) + ", grading <= 0.2"
    );
    for (std::size_t m = 1; m < meshers.size(); ++m)
    {
        addAttempt
        (
            meshers[m].get(), retry,
            "the " + meshers[m]->name() + " backend" + (stepsAsked ? "" : ", " + stepsAdded)
        );
    }
    return attempts;
}

//- One closed surface of a rank's surface (a piece, a zone): its points
//  (global: their indices in the rank's surface), its triangles in them,
//  and which are interface triangles
struct closedPiece
{
    std::vector<label> global;
    std::vector<point3> points;
    std::vector<triVerts> triangles;
    std::vector<char> interfaceTriangles;
};

//- The closed surface of `triangles` (indices into surfaceTriangles). Its
//  points keep the surface's order, or with ids the order of their ids:
//  then a piece goes to the mesher alike whatever else its rank holds
closedPiece closedPieceOf
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const std::vector<label>& triangles,
    const std::vector<char>& interfaceTriangles,
    const std::vector<barycentricId>* ids
)
{
    closedPiece c;
    for (label t : triangles)
    {
        c.global.insert(c.global.end(), surfaceTriangles[t].begin(), surfaceTriangles[t].end());
    }
    std::sort(c.global.begin(), c.global.end());
    c.global.erase(std::unique(c.global.begin(), c.global.end()), c.global.end());
    if (ids)
    {
        std::sort
        (
            c.global.begin(), c.global.end(),
            [&](label a, label b) { return (*ids)[a] < (*ids)[b]; }
        );
    }
    std::unordered_map<label, label> local;
    for (label v : c.global)
    {
        local.emplace(v, label(c.points.size()));
        c.points.push_back(surfacePoints[v]);
    }
    for (label t : triangles)
    {
        const triVerts& tri = surfaceTriangles[t];
        c.triangles.push_back({local.at(tri[0]), local.at(tri[1]), local.at(tri[2])});
        if (!interfaceTriangles.empty())
        {
            c.interfaceTriangles.push_back(interfaceTriangles[t]);
        }
    }
    return c;
}

} // End anonymous namespace


void pmsh::writeSurfaceStl
(
    const std::string& fileName,
    const std::string& solidName,
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles
)
{
    const std::filesystem::path path(fileName);
    if (path.has_parent_path())
    {
        std::filesystem::create_directories(path.parent_path());
    }
    std::ofstream os(fileName);
    os  << std::setprecision(17) << "solid " << solidName << '\n';
    for (const triVerts& t : triangles)
    {
        const vector3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        const double mag = std::sqrt(magSqr(n));
        const double s = mag > 0 ? 1/mag : 0;
        os  << "  facet normal " << s*n[0] << ' ' << s*n[1] << ' ' << s*n[2] << '\n'
            << "    outer loop\n";
        for (label p : t)
        {
            os  << "      vertex " << points[p][0] << ' ' << points[p][1] << ' '
                << points[p][2] << '\n';
        }
        os  << "    endloop\n  endfacet\n";
    }
    os  << "endsolid " << solidName << '\n';
}


pmsh::partitionVolumeResult pmsh::meshVolumeWithFallbacks
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters,
    const std::string& failedSurfaceFile,
    const std::string& advice
)
{
    const std::vector<ladderAttempt<volumeAttempt>> attempts =
        volumeAttempts(meshers, parameters);

    // Each failure as a line of the error (and of the log, if a later
    // attempt succeeds)
    const auto failureLines = [&](const ladderFailures& failed)
    {
        std::string lines;
        for (std::size_t a = 0; a < failed.nTried(); ++a)
        {
            lines += msg()
                << "\n  attempt " << a + 1 << " (" << describe(attempts[a])
                << "): " << failed.reasons[a];
        }
        return lines;
    };

    const auto attemptName = [&](std::size_t a)
    {
        return parameters.what + ", attempt " + std::to_string(a + 1)
          + " (" + describe(attempts[a]) + ")";
    };

    ladderFailures failed;
    std::optional<partitionVolumeResult> meshed = climbLadder
    (
        attempts,
        [&](const ladderAttempt<volumeAttempt>& at, std::size_t a)
        {
            partitionVolumeResult result;
            // Each attempt inserts the points in an order of its own: a
            // mesher that looped on one order (hxtLibrary.C) may not on
            // another
            volumeMeshParameters ordered = at.parameters.parameters;
            ordered.pointOrder = unsigned(a);
            try
            {
                result.mesh = meshInChildProcess
                (
                    *at.parameters.mesher, surfacePoints, surfaceTriangles,
                    ordered, attemptName(a)
                );
            }
            catch (const FatalError& e)
            {
                // Said now, not only once the partition is meshed: the
                // next attempt may take long (another mesher, a large
                // partition)
                if (a + 1 < attempts.size())
                {
                    const std::string why = e.message();
                    logMesherLine
                    (
                        attemptName(a) + " failed: " + why.substr(0, why.find('\n'))
                      + "; attempt " + std::to_string(a + 2) + " (" + describe(attempts[a + 1]) + ") next"
                    );
                }
                throw attemptFailed{e.message()};
            }
            result.backend = at.parameters.mesher->name();
            result.attempts = int(a) + 1;
            result.nCells = label(result.mesh.tets.size());
            const tetShapeRange shape = tetShapeRangeOf(result.mesh);
            result.minDihedral = shape.minDihedral;
            result.maxDihedral = shape.maxDihedral;
            result.maxAspectRatio = shape.maxAspectRatio;
            return result;
        },
        failed
    );
    if (meshed)
    {
        meshed->failures = failureLines(failed);
        return std::move(*meshed);
    }

    writeSurfaceStl(failedSurfaceFile, "surface", surfacePoints, surfaceTriangles);
    throw FatalError
    (
        msg() << "Volume meshing of " << parameters.what << " failed in all "
            << attempts.size() << " attempts:" << failureLines(failed) << "\n"
            << "Its surface is written to " << failedSurfaceFile << " for diagnosis.\n"
            << advice,
        "meshVolumeWithFallbacks"
    );
}


pmsh::partitionVolumeResult pmsh::meshVolumeByZone
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const std::vector<label>& triangleZone,
    const std::vector<std::string>& zoneNames,
    const volumeMeshParameters& parameters,
    const std::string& failedSurfaceFile,
    const std::string& advice
)
{
    const std::vector<label> onePiece;
    const std::vector<barycentricId> noIds;
    return meshVolumeInPieces
    (
        meshers, surfacePoints, surfaceTriangles,
        {triangleZone, zoneNames, onePiece, noIds},
        parameters, failedSurfaceFile, advice
    );
}


pmsh::partitionVolumeResult pmsh::meshVolumeInPieces
(
    const std::vector<std::unique_ptr<VolumeMesher>>& meshers,
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const closedSurfaces& closed,
    const volumeMeshParameters& parameters,
    const std::string& failedSurfaceFile,
    const std::string& advice
)
{
    const bool zoned = !closed.triangleZone.empty();
    const bool pieces = !closed.trianglePiece.empty();
    if (!zoned && !pieces)
    {
        partitionVolumeResult whole = meshVolumeWithFallbacks
        (
            meshers, surfacePoints, surfaceTriangles, parameters,
            failedSurfaceFile, advice
        );
        whole.nCalls = 1;
        whole.largestCall = whole.nCells;
        return whole;
    }

    // The closed surfaces, by (piece, zone), in that order
    const label nZones = std::max(label(closed.zoneNames.size()), label(1));
    std::map<label, std::vector<label>> trianglesOf;
    for (label t = 0; t < label(surfaceTriangles.size()); ++t)
    {
        const label piece = pieces ? closed.trianglePiece[t] : 0;
        const label zone = zoned ? closed.triangleZone[t] : 0;
        trianglesOf[piece*nZones + zone].push_back(t);
    }

    partitionVolumeResult joined;
    joined.mesh.points = surfacePoints;
    joined.minDihedral = 180;
    joined.attempts = 0;
    joined.nCalls = 0;
    // A progress line at most every progressInterval(), as a long attempt
    // gets: a rank's many short pieces would otherwise leave the log
    // silent for the whole stage
    using clock = std::chrono::steady_clock;
    const clock::time_point start = clock::now();
    clock::time_point lastLine = start;
    const double interval = progressInterval();
    for (const auto& [key, ofKey] : trianglesOf)
    {
        const label piece = key/nZones;
        const label zone = key % nZones;

        closedPiece surface = closedPieceOf
        (
            surfacePoints, surfaceTriangles, ofKey, parameters.interfaceTriangles,
            pieces ? &closed.pointIds : nullptr
        );
        std::vector<label>& global = surface.global;
        volumeMeshParameters p = parameters;
        p.interfaceTriangles = std::move(surface.interfaceTriangles);

        // "piece 3, zone fluid" in messages, "piece3_fluid" in file names
        const auto named = [&](const char* pieceWord, const char* join, const char* zoneWord)
        {
            return
                std::string(pieces ? pieceWord + std::to_string(piece) : "")
              + (pieces && zoned ? join : "")
              + (zoned ? zoneWord + closed.zoneNames[zone] : "");
        };
        const std::string name = named("piece ", ", ", "zone ");
        const std::string suffix = named("piece", "_", "");
        p.what = parameters.what + ", " + name;
        const std::filesystem::path file(failedSurfaceFile);
        partitionVolumeResult part = meshVolumeWithFallbacks
        (
            meshers, surface.points, surface.triangles, p,
            (file.parent_path()/(file.stem().string() + "_" + suffix
          + file.extension().string())).string(),
            advice
        );

        // Interior points follow the surface points of every piece before
        for (std::size_t v = surface.points.size(); v < part.mesh.points.size(); ++v)
        {
            global.push_back(label(joined.mesh.points.size()));
            joined.mesh.points.push_back(part.mesh.points[v]);
        }
        for (const tetVerts& t : part.mesh.tets)
        {
            joined.mesh.tets.push_back
            ({global[t[0]], global[t[1]], global[t[2]], global[t[3]]});
            if (zoned)
            {
                joined.tetZone.push_back(zone);
            }
        }
        ++joined.nCalls;
        joined.largestCall = std::max(joined.largestCall, part.nCells);
        // The backend reported is that of the piece that needed most attempts
        if (part.attempts > joined.attempts)
        {
            joined.backend = part.backend;
            joined.attempts = part.attempts;
        }
        if (!part.failures.empty())
        {
            joined.failures += "\n  " + name + ":" + part.failures;
        }
        joined.minDihedral = std::min(joined.minDihedral, part.minDihedral);
        joined.maxDihedral = std::max(joined.maxDihedral, part.maxDihedral);
        joined.maxAspectRatio = std::max(joined.maxAspectRatio, part.maxAspectRatio);

        const clock::time_point now = clock::now();
        if (std::chrono::duration<double>(now - lastLine).count() >= interval)
        {
            lastLine = now;
            logMesherLine
            (
                msg() << parameters.what << ": " << joined.nCalls << " of "
                    << trianglesOf.size()
                    << (pieces ? (zoned ? " pieces and zones" : " pieces") : " zones")
                    << " meshed, "
                    << joined.mesh.tets.size() << " cells, "
                    << std::lround(std::chrono::duration<double>(now - start).count()) << " s"
            );
        }
    }
    joined.nCells = label(joined.mesh.tets.size());
    joined.attempts = std::max(joined.attempts, 1);
    return joined;
}
