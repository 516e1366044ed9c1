#include "layerStage.H"
#include "coarseWallGap.H"
#include "mpiLayerExchange.H"
#include "failTogether.H"
#include "pmshError.H"

#include "streamManip.H"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <set>

namespace pmsh
{

namespace
{

const char* const where = "pmsh::layerStage";


//- How far a gap query must look: the thickest stack over its ratio.
double gapReach(const std::map<label, layerSpecification>& specs)
{
    double reach = 0;
    for (const auto& [patch, spec] : specs)
    {
        reach = std::max(reach, spec.totalThickness()/spec.maxThicknessToGapRatio);
    }
    return reach;
}

//- The surface's regions as the layer kernel sees them: a face between
//  two pieces of this rank (meshPieces.H) is a partition interface, with
//  this rank's own region, so that it rises over the stacks as a face
//  between two ranks does; the global mesh is then the same whether two
//  pieces fall in one rank or in two. A face between zones stays one (a
//  solid's wall: its two copies have different zones).
std::vector<label> kernelRegions(const FineSurface& surface, int rank)
{
    std::vector<label> region(surface.region);
    if (surface.piece.empty())
    {
        return region;
    }
    std::map<triangleKey, label> firstCopy;
    for (label t = 0; t < label(region.size()); ++t)
    {
        if (!isBetweenZones(region[t])) continue;
        const auto [it, first] = firstCopy.emplace(keyOf(surface.ids, surface.triangles[t]), t);
        if (first) continue;
        const label twin = it->second;
        if (surface.zone.empty() || surface.zone[twin] == surface.zone[t])
        {
            region[t] = region[twin] = interfaceRegion(rank);
        }
    }
    return region;
}

} // End anonymous namespace


std::map<label, layerSpecification> layerSpecsOf
(
    const meshSettings& settings,
    const CoarseMesh& coarse
)
{
    std::map<label, layerSpecification> specs;
    for (label p = 0; p < label(coarse.patches.size()); ++p)
    {
        const meshPatch& patch = coarse.patches[p];
        const layerSpecification spec = settings.patchLayers(patch.name);
        if (!spec.layered())
        {
            continue;
        }
        if (patch.type != "wall")
        {
            throw FatalError
            (
                msg() << "Patch '" << patch.name << "' asks for " << spec.nLayers
                    << " prism layers in " << settings.dictFile << " but is of type '"
                    << patch.type << "' (" << patch.typeOrigin << ").\n"
                    "Layers grow on walls only: give it 'type wall;' or take"
                    " its 'layers' entry out",
                where
            );
        }
        specs[p] = spec;
    }
    if (!specs.empty() && !coarse.periodicPatches.empty())
    {
        throw FatalError
        (
            msg() << "Prism layers in a geometry with periodic patches ('identify"
                " periodic') are not supported yet.\nTake the 'layers' entries"
                " out of " << settings.dictFile << " or the periodic pair out"
                " of the geometry",
            where
        );
    }
    return specs;
}


wallLayers growLayers
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    const FineSurface& surface,
    const std::map<label, layerSpecification>& specs,
    int refinementLevels
)
{
    const auto gap = std::make_shared<coarseWallGap>(coarse, specs, gapReach(specs));
    const std::vector<label> region = kernelRegions(surface, comm.rank());
    const layerSurface wall
    {
        surface.points, surface.ids, surface.triangles, region, surface.piece, specs,
        [gap](const point3& p, const vector3& d, double skip) { return (*gap)(p, d, skip); }
    };
    if (comm.parallel())
    {
        mpiLayerExchange exchange(comm, coarse, cellPart, refinementLevels);
        return growWallLayers(wall, exchange);
    }
    noLayerExchange exchange;
    return growWallLayers(wall, exchange);
}


label writeThinnedLayers
(
    const Communicator& comm,
    const wallLayers& layers,
    const FineSurface& surface,
    const std::string& file,
    std::size_t maxPoints
)
{
    struct thinnedPoint
    {
        barycentricId id;
        point3 x;
        layerThinning why;
    };
    std::vector<std::vector<thinnedPoint>> toMaster(comm.size());
    for (label p = 0; p < label(layers.thinnedBy.size()); ++p)
    {
        if (layers.thinnedBy[p] != layerThinning::none)
        {
            toMaster[0].push_back({surface.ids[p], surface.points[p], layers.thinnedBy[p]});
        }
    }
    // The master holds them all at once: on a massive mesh a sample, at
    // most maxPoints over all ranks, every k-th of each rank's
    const std::size_t perRank = std::max<std::size_t>(maxPoints/comm.size(), 1);
    std::vector<thinnedPoint>& mine = toMaster[0];
    const bool sampled = comm.any(mine.size() > perRank);
    if (mine.size() > perRank)
    {
        const std::size_t stride = (mine.size() + perRank - 1)/perRank;
        std::size_t n = 0;
        for (std::size_t i = 0; i < mine.size(); i += stride) mine[n++] = mine[i];
        mine.resize(n);
    }
    // Every rank's points at the master: a point on a partition interface
    // comes from each of its holders, alike (the ranks agree on its stack)
    const std::vector<std::vector<thinnedPoint>> received = comm.exchange(toMaster);
    label nPoints = 0;
    failTogether(comm, [&]
    {
        if (!comm.master()) return;
        std::set<barycentricId> seen;
        std::vector<thinnedPoint> points;
        for (const auto& fromRank : received)
        {
            for (const thinnedPoint& t : fromRank)
            {
                if (seen.insert(t.id).second) points.push_back(t);
            }
        }
        nPoints = label(points.size());
        namespace fs = std::filesystem;
        if (points.empty())
        {
            fs::remove(file);
            return;
        }
        fs::create_directories(fs::path(file).parent_path());
        std::ofstream os(file);
        os.precision(10);
        os  << "# vtk DataFile Version 2.0\n"
            << "pmshFoam: wall points whose prism layers were thinned, and why\n"
            << "ASCII\nDATASET POLYDATA\nPOINTS " << points.size() << " double\n";
        for (const thinnedPoint& t : points)
        {
            os << t.x[0] << ' ' << t.x[1] << ' ' << t.x[2] << '\n';
        }
        os  << "VERTICES " << points.size() << ' ' << 2*points.size() << '\n';
        for (std::size_t i = 0; i < points.size(); ++i)
        {
            os << "1 " << i << '\n';
        }
        os  << "POINT_DATA " << points.size() << "\nSCALARS thinnedBy int 1\n"
            << "LOOKUP_TABLE default\n";
        for (const thinnedPoint& t : points)
        {
            os << int(t.why) << '\n';
        }
        if (!os.flush())
        {
            throw FatalError
            (
                msg() << "Cannot write " << file << ": check the disk and the"
                    " permissions of the case's postProcessing directory",
                where
            );
        }
        Foam::Info
            << "    where and why stacks thinned: " << file.c_str() << ", "
            << nPoints << " points" << (sampled ? " (a sample)" : "")
            << ", thinnedBy 1 sharp edge, 2 gap, 3 valid prisms and tops,"
            " 4 partition interface\n";
    });
    return nPoints;
}


std::vector<point3> liftedSurfacePoints
(
    const wallLayers& layers,
    const std::vector<point3>& surfacePoints
)
{
    if (layers.nLayers.empty())
    {
        return {};
    }
    std::vector<point3> lifted(surfacePoints.size());
    for (label p = 0; p < label(lifted.size()); ++p)
    {
        lifted[p] = layers.topPoint(surfacePoints, p);
    }
    return lifted;
}


layerPointList::layerPointList(const wallLayers& layers, label nSurfacePoints, label first)
:
    levelZero_(nSurfacePoints, -1)
{
    std::vector<bool> used(nSurfacePoints, false);
    for (const std::array<layerPointRef, 6>& prism : layers.prisms)
    {
        for (const layerPointRef& r : prism) used[r.point] = true;
    }
    for (label p = 0; p < nSurfacePoints; ++p)
    {
        if (!used[p]) continue;
        levelZero_[p] = first + label(refs_.size());
        for (int k = 0; k < layers.nLayers[p]; ++k)
        {
            refs_.push_back({p, k});
        }
    }
}


layerPointList numberLayerPoints
(
    const Communicator& comm,
    const CoarseMesh& coarse,
    const std::vector<label>& cellPart,
    const FineSurface& surface,
    const wallLayers& layers,
    bool layered,
    globalPointNumbering& numbering
)
{
    if (!layered)
    {
        return layerPointList();
    }
    layerPointList list
    (
        layers, label(surface.points.size()), label(numbering.globalIds().size())
    );
    numbering.addLayerPoints(comm, coarse, cellPart, surface.ids, list.refs());
    return list;
}


layerCells layerCellsOf
(
    FineSurface& surface,
    const wallLayers& layers,
    const layerPointList& list,
    const std::vector<point3>& wallPoints
)
{
    layerCells cells;
    for (const auto& [p, k] : list.refs())
    {
        cells.points.push_back(layers.levelPoint(wallPoints, p, k));
    }
    cells.prisms.reserve(layers.prisms.size());
    for (std::size_t j = 0; j < layers.prisms.size(); ++j)
    {
        std::array<label, 6> prism;
        for (int i = 0; i < 6; ++i) prism[i] = list.index(layers, layers.prisms[j][i]);
        cells.prisms.push_back(prism);
        if (!surface.zone.empty())
        {
            cells.prismZone.push_back(surface.zone[layers.prismTriangle[j]]);
        }
    }
    for (const layerSideFace& f : layers.sideFaces)
    {
        if (isBetweenZones(f.region))
        {
            const point3& x = wallPoints[f.points[0].point];
            throw FatalError
            (
                msg() << "Prism layers end at the surface between two cellZones"
                    " near (" << x[0] << ' ' << x[1] << ' ' << x[2] << "): not"
                    " supported yet (the other solid's cells would meet the"
                    " layers' side faces with triangles).\nTake the 'layers'"
                    " entry off the patch that meets the other solid",
                where
            );
        }
        std::array<label, 4> quad;
        for (int i = 0; i < 4; ++i) quad[i] = list.index(layers, f.points[i]);
        cells.quads.push_back(quad);
        cells.quadRegion.push_back(f.region);
    }
    // The tets meet a layered triangle at its top: what stays on the
    // surface there is the bottom prism's base, on the wall
    for (label t = 0; t < label(surface.triangles.size()); ++t)
    {
        if (!layers.triangleLayered[t]) continue;
        for (label& v : surface.triangles[t])
        {
            v = list.index(layers, {v, 0});
        }
    }
    return cells;
}


void appendLayerCells(rankTets& share, layerCells&& cells)
{
    share.points.insert(share.points.end(), cells.points.begin(), cells.points.end());
    share.prisms = std::move(cells.prisms);
    share.prismZone = std::move(cells.prismZone);
    share.quads = std::move(cells.quads);
    share.quadRegion = std::move(cells.quadRegion);
}


namespace
{

//- One patch's figures on one rank, gathered in one collective.
struct patchLayerFigures
{
    double faces = 0, layeredFaces = 0;
    double samples = 0;
    double firstSum = 0, firstMin = std::numeric_limits<double>::infinity(), firstMax = 0;
    double totalSum = 0, totalMin = std::numeric_limits<double>::infinity(), totalMax = 0;
};


patchLayerFigures patchFigures
(
    const wallLayers& layers,
    const FineSurface& surface,
    label patch
)
{
    patchLayerFigures f;
    for (label t = 0; t < label(surface.triangles.size()); ++t)
    {
        if (surface.region[t] != patch) continue;
        ++f.faces;
        if (!layers.triangleLayered[t]) continue;
        ++f.layeredFaces;
        for (label v : surface.triangles[t])
        {
            const double total = layers.thickness[v];
            const double first = total*layers.levelFractions.at(layers.specPatch[v])[1];
            ++f.samples;
            f.firstSum += first;
            f.firstMin = std::min(f.firstMin, first);
            f.firstMax = std::max(f.firstMax, first);
            f.totalSum += total;
            f.totalMin = std::min(f.totalMin, total);
            f.totalMax = std::max(f.totalMax, total);
        }
    }
    return f;
}


patchLayerReport gatheredReport
(
    const Communicator& comm,
    const std::string& name,
    int nLayers,
    const patchLayerFigures& mine
)
{
    patchLayerReport r;
    r.patch = name;
    r.layers = nLayers;
    patchLayerFigures all;
    for (const patchLayerFigures& f : comm.allGather(mine))
    {
        all.faces += f.faces;
        all.layeredFaces += f.layeredFaces;
        all.samples += f.samples;
        all.firstSum += f.firstSum;
        all.totalSum += f.totalSum;
        all.firstMin = std::min(all.firstMin, f.firstMin);
        all.firstMax = std::max(all.firstMax, f.firstMax);
        all.totalMin = std::min(all.totalMin, f.totalMin);
        all.totalMax = std::max(all.totalMax, f.totalMax);
    }
    r.faces = all.faces;
    r.layeredFaces = all.layeredFaces;
    if (all.samples > 0)
    {
        r.firstLayer[0] = all.firstMin;
        r.firstLayer[1] = all.firstSum/all.samples;
        r.firstLayer[2] = all.firstMax;
        r.thickness[0] = all.totalMin;
        r.thickness[1] = all.totalSum/all.samples;
        r.thickness[2] = all.totalMax;
    }
    return r;
}


void logLayerReport(const layerReport& report)
{
    using namespace Foam;
    Info<< "    " << pmsh::left << setw(16) << "patch" << pmsh::right << setw(10)
        << "faces" << setw(8) << "layers" << setw(10) << "coverage"
        << "   first layer min/avg/max        thickness min/avg/max\n";
    for (const patchLayerReport& r : report.patches)
    {
        Info<< "    " << pmsh::left << setw(16) << r.patch.c_str() << pmsh::right
            << setw(10) << label(r.faces) << setw(8) << r.layers << setw(8)
            << std::round(1000*r.coverage())/10 << " %   " << setprecision(3)
            << r.firstLayer[0] << " / " << r.firstLayer[1] << " / " << r.firstLayer[2]
            << "      " << r.thickness[0] << " / " << r.thickness[1] << " / "
            << r.thickness[2] << setprecision(6) << nl;
    }
    Info<< "    prisms: " << label(report.prisms) << "; noisy directions smoothed at "
        << report.thinned.nSmoothedDirections << " points; points thinned at sharp edges "
        << report.thinned.nFeatureLimited << ", by gaps " << report.thinned.nGapLimited
        << ", for valid prisms and tops " << report.thinned.nInvalidLimited
        << " (partition interfaces " << report.thinned.nInterfaceLimited << ") in "
        << report.thinned.nRounds << " rounds" << endl;
}

} // End anonymous namespace


layerReport reportLayers
(
    const Communicator& comm,
    const wallLayers& layers,
    const FineSurface& surface,
    const CoarseMesh& coarse,
    const std::map<label, layerSpecification>& specs
)
{
    layerReport report;
    for (const auto& [patch, spec] : specs)
    {
        report.patches.push_back
        (
            gatheredReport
            (
                comm, coarse.patches[patch].name, spec.nLayers,
                patchFigures(layers, surface, patch)
            )
        );
    }
    struct counts { double prisms; wallLayerStats stats; };
    for (const counts& c : comm.allGather(counts{double(layers.prisms.size()), layers.stats}))
    {
        report.prisms += c.prisms;
        report.thinned.nSmoothedDirections += c.stats.nSmoothedDirections;
        report.thinned.nFeatureLimited += c.stats.nFeatureLimited;
        report.thinned.nGapLimited += c.stats.nGapLimited;
        report.thinned.nInvalidLimited += c.stats.nInvalidLimited;
        report.thinned.nInterfaceLimited += c.stats.nInterfaceLimited;
        report.thinned.nRounds = std::max(report.thinned.nRounds, c.stats.nRounds);
    }
    logLayerReport(report);
    return report;
}

} // End namespace pmsh


// ************************************************************************* //
