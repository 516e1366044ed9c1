#include "stageReports.H"
#include "streamManip.H"
#include <algorithm>
#include <cmath>

using Foam::Info;
using Foam::Pout;
using Foam::fixed;
using Foam::setprecision;
using Foam::setw;

namespace
{

// A figure's spread over the ranks as the stages log it, in the stream's
// current format: "    <what> per rank min/avg/max: <min> / <avg> / <max>"
void logPerRank(const char* what, const pmsh::minAvgMax& n)
{
    Info<< "    " << what << " per rank min/avg/max: " << n.min << " / " << n.avg
        << " / " << n.max << '\n';
}

} // End anonymous namespace


std::string pmsh::rankPrefix(const Communicator& comm)
{
    return comm.parallel() ? "[" + std::to_string(comm.rank()) + "] " : "";
}


void pmsh::logCoarseMesh(const CoarseMesh& coarse)
{
    Info
        << "    volume filled by " << coarse.volumeMesher.c_str() << '\n'
        << "    coarse cells: " << coarse.nCells()
        << ", points: " << coarse.nPoints()
        << ", boundary faces: " << coarse.boundary.size() << '\n'
        << "    patches (coarse boundary faces):";
    std::vector<label> faces(coarse.patches.size(), 0);
    for (const coarseBoundaryFace& f : coarse.boundary)
    {
        ++faces[f.patch];
    }
    for (std::size_t p = 0; p < coarse.patches.size(); ++p)
    {
        Info << ' ' << coarse.patches[p].name.c_str() << " (" << faces[p] << ')';
    }
    Info << '\n';
    if (coarse.zones.empty())
    {
        return;
    }
    std::vector<label> cells(coarse.zones.size(), 0);
    for (label z : coarse.cellZone)
    {
        ++cells[z];
    }
    Info << "    zones (cellZones, coarse cells):";
    for (std::size_t z = 0; z < coarse.zones.size(); ++z)
    {
        Info << ' ' << coarse.zones[z].c_str() << " (" << cells[z] << ')';
    }
    Info << "\n    coarse faces between zones: " << coarse.zoneFaces.size() << '\n';
}


void pmsh::logLocalSizes(const CoarseMesh& coarse, const meshSettings& settings)
{
    auto edge = [&coarse](label a, label b)
    {
        return std::sqrt(magSqr(coarse.points[a] - coarse.points[b]));
    };
    auto note = [&settings](double size)
    {
        return
            size < settings.maxCellSize
          ? std::string()
          : " (not below the global maxCellSize: no effect)";
    };

    for (const sizeRegion& r : settings.refinementRegions)
    {
        label nCells = 0;
        double sum = 0;
        for (const tetVerts& t : coarse.tets)
        {
            const point3 centroid =
                0.25*(coarse.points[t[0]] + coarse.points[t[1]]
                    + coarse.points[t[2]] + coarse.points[t[3]]);
            if (r.contains(centroid))
            {
                ++nCells;
                sum +=
                    edge(t[0], t[1]) + edge(t[0], t[2]) + edge(t[0], t[3])
                  + edge(t[1], t[2]) + edge(t[1], t[3]) + edge(t[2], t[3]);
            }
        }
        Info
            << "    region " << r.name.c_str() << " (" << r.shapeName()
            << ", maxCellSize " << r.size << note(r.size).c_str() << "): " << nCells
            << " coarse cells, mean edge "
            << (nCells ? sum/(6*nCells) : 0) << '\n';
    }

    if (!settings.hasPatchSizes())
    {
        return;
    }
    for (std::size_t p = 0; p < coarse.patches.size(); ++p)
    {
        const double size = settings.patchMaxCellSize(coarse.patches[p].name);
        if (!(size > 0))
        {
            continue;
        }
        label nFaces = 0;
        double sum = 0;
        for (const coarseBoundaryFace& f : coarse.boundary)
        {
            if (f.patch == label(p))
            {
                ++nFaces;
                sum += edge(f.v[0], f.v[1]) + edge(f.v[1], f.v[2]) + edge(f.v[2], f.v[0]);
            }
        }
        Info
            << "    patch " << coarse.patches[p].name.c_str() << " (maxCellSize " << size
            << note(size).c_str() << "): " << nFaces << " coarse boundary faces, mean edge "
            << (nFaces ? sum/(3*nFaces) : 0) << '\n';
    }
}


void pmsh::logPartSizes(const Communicator& comm, const std::vector<label>& cellPart)
{
    std::vector<label> size(comm.size(), 0);
    for (label p : cellPart)
    {
        ++size[p];
    }
    const auto [small, large] = std::minmax_element(size.begin(), size.end());
    Info
        << "    coarse cells per part min/avg/max: " << *small << " / "
        << double(cellPart.size())/comm.size() << " / " << *large << '\n';
}


void pmsh::logSurfaceSizes(const Communicator& comm, const FineSurface& surface)
{
    const minAvgMax n = reduceMinAvgMax(comm, double(surface.triangles.size()));
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        logPerRank("fine surface triangles", n);
    }
    else
    {
        Info << "    fine surface triangles: " << n.max << '\n';
    }
    Info << defaultfloat;
}


pmsh::projectionRepairSummary pmsh::logProjectionRepair
(
    const Communicator& comm,
    const projectionRepairStats& repair
)
{
    projectionRepairSummary total;
    total.nPointsOff = comm.sum(std::int64_t(repair.nPointsOff));
    total.maxDistance = comm.max(repair.maxDistance);
    const double sumDistance = comm.sum(repair.sumDistance);
    total.meanDistance = total.nPointsOff ? sumDistance/total.nPointsOff : 0;
    if (total.nPointsOff)
    {
        Info
            << "    refined points left off the geometry (their projection"
            << " folded the surface): " << total.nPointsOff
            << ", distance from the geometry max " << total.maxDistance
            << ", mean " << total.meanDistance << '\n';
    }
    return total;
}


void pmsh::balanceAndLog
(
    const Communicator& comm,
    rankTets& share,
    partitionVolumeResult& volume
)
{
    // The cells of the rank's share: its tets and prisms
    const auto nCells = [&] { return label(share.tets.size() + share.prisms.size()); };
    volume.nCells = nCells();
    if (!comm.parallel())
    {
        Info << "    serial: nothing to balance\n";
        return;
    }
    const fineBalanceStats stats = balanceFineCells(comm, share);
    volume.nCells = nCells();
    const minAvgMax n = reduceMinAvgMax(comm, double(nCells()));
    // Layered when any rank has prisms (the master may hold none)
    const bool layered = comm.sum(std::int64_t(share.prisms.size())) > 0;
    Info<< fixed << setprecision(3)
        << "    largest rank's fine cells over the mean: " << stats.before
        << " -> " << stats.after << " (" << stats.moved << " cells moved"
        << (layered ? ", prism stacks whole" : "") << ")\n"
        << defaultfloat;
    Info << fixed << setprecision(0);
    logPerRank("fine cells", n);
    Info << defaultfloat;
}


std::int64_t pmsh::logVolumeMeshing
(
    const Communicator& comm,
    const partitionVolumeResult& volume
)
{
    const TetMesh& tets = volume.mesh;
    if (volume.attempts > 1)
    {
        Pout
            << "    partition " << comm.rank() << " meshed by " << volume.backend.c_str()
            << " at attempt " << volume.attempts << "; earlier attempts:"
            << volume.failures.c_str() << '\n';
    }
    const std::int64_t nCells = comm.sum(std::int64_t(tets.tets.size()));
    const minAvgMax n = reduceMinAvgMax(comm, double(tets.tets.size()));
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        logPerRank("fine cells", n);
    }
    Info << "    fine cells: " << nCells << '\n' << defaultfloat;
    const double calls = comm.sum(double(volume.nCalls));
    if (calls > comm.size())
    {
        Info
            << "    volume-mesher calls (pieces and zones): " << std::int64_t(calls)
            << ", the largest " << std::int64_t(comm.max(double(volume.largestCall)))
            << " fine cells\n";
    }
    return nCells;
}


void pmsh::logWritten
(
    const Communicator& comm,
    const std::string& caseDir,
    const meshSizes& sizes
)
{
    Info
        << "    written to " << caseDir.c_str()
        << (comm.parallel() ? "/processor*" : "/constant/polyMesh") << '\n';
    const minAvgMax faces = reduceMinAvgMax(comm, sizes.faces);
    const minAvgMax points = reduceMinAvgMax(comm, sizes.points);
    Info << fixed << setprecision(0);
    if (comm.parallel())
    {
        logPerRank("faces", faces);
        logPerRank("points", points);
    }
    else
    {
        Info << "    faces: " << faces.max << ", points: " << points.max << '\n';
    }

    // Every physical patch (every rank has all of them, some empty)
    std::size_t width = 4;
    for (const meshPatch& p : sizes.patches)
    {
        width = std::max(width, p.name.size());
    }
    if (!sizes.zones.empty())
    {
        Info << "    cellZones (cells):";
        for (std::size_t z = 0; z < sizes.zones.size(); ++z)
        {
            Info << ' ' << sizes.zones[z].c_str() << ' ' << comm.sum(sizes.zoneCells[z]);
        }
        Info << '\n';
    }
    Info << "    patches (faces, type and why):\n";
    for (const meshPatch& p : sizes.patches)
    {
        const std::int64_t nFaces = comm.sum(std::int64_t(p.size));
        Info
            << "        " << left << setw(int(width)) << p.name.c_str() << ' '
            << right << setw(10) << nFaces << "  " << left
            << setw(13) << p.type.c_str() << right << ' ' << p.typeOrigin.c_str() << '\n';
    }
    Info << defaultfloat;
}


// ************************************************************************* //
