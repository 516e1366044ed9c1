#include "meshQuality.H"
#include "Info.H"
#include "stageLog.H"

#include "polyMeshTools.H"
#include "syncTools.H"
#include "unitConversion.H"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>

namespace
{

double degreesOfCos(double c)
{
    return Foam::radToDeg(std::acos(std::min(1.0, std::max(-1.0, c))));
}

} // End anonymous namespace


pmsh::meshQualityReport pmsh::meshQualityOf
(
    const Communicator& comm,
    const Foam::fvMesh& mesh,
    const partitionVolumeResult& volume
)
{
    using namespace Foam;

    // checkMesh's fields: the processor faces see the neighbour rank's
    // cell centres (swapped inside, collective)
    const vectorField& areas = mesh.faceAreas();
    const vectorField& centres = mesh.cellCentres();
    const tmp<scalarField> tortho =
        polyMeshTools::faceOrthogonality(mesh, areas, centres);
    const tmp<scalarField> tskew = polyMeshTools::faceSkewness
    (
        mesh, mesh.points(), mesh.faceCentres(), areas, centres
    );
    const scalarField& ortho = tortho();
    const scalarField& skew = tskew();

    // As checkMesh: statistics over internal faces and one side of each
    // processor face (uncoupled boundary faces have orthogonality 1)
    const bitSet counted(syncTools::getInternalOrMasterFaces(mesh));
    const double severeCos = std::cos(degToRad(70.0));
    double minCos = 1, sumCos = 0, minProcessorCos = 1;
    std::int64_t nCounted = 0, nSevere = 0;
    for (label facei = 0; facei < mesh.nFaces(); ++facei)
    {
        if (counted.test(facei))
        {
            minCos = std::min(minCos, double(ortho[facei]));
            sumCos += ortho[facei];
            ++nCounted;
            if (ortho[facei] < severeCos) ++nSevere;
        }
        if (!mesh.isInternalFace(facei))
        {
            minProcessorCos = std::min(minProcessorCos, double(ortho[facei]));
        }
    }
    const double maxSkew = skew.empty() ? 0 : double(max(skew));
    const double minVolume = mesh.nCells() ? double(min(mesh.cellVolumes())) : 0;

    meshQualityReport report;
    const std::vector<double> minCosR = comm.allGather(minCos);
    const std::vector<double> sumCosR = comm.allGather(sumCos);
    const std::vector<double> countedR = comm.allGather(double(nCounted));
    const std::vector<double> minProcCosR = comm.allGather(minProcessorCos);
    const std::vector<double> severeR = comm.allGather(double(nSevere));
    const std::vector<double> skewR = comm.allGather(maxSkew);
    const std::vector<double> volumeR = comm.allGather(minVolume);
    const std::vector<double> minDihedralR = comm.allGather(volume.minDihedral);
    const std::vector<double> maxDihedralR = comm.allGather(volume.maxDihedral);

    meshQuality& all = report.overall;
    double allSumCos = 0, allCounted = 0, allMinCos = 1, allMinProcCos = 1;
    all.minVolume = volumeR.empty() ? 0 : volumeR[0];
    all.minDihedral = 180;
    for (int r = 0; r < comm.size(); ++r)
    {
        meshQuality q;
        q.maxNonOrthogonality = degreesOfCos(minCosR[r]);
        q.avgNonOrthogonality =
            countedR[r] > 0 ? degreesOfCos(sumCosR[r]/countedR[r]) : 0;
        q.maxProcessorNonOrthogonality = degreesOfCos(minProcCosR[r]);
        q.maxSkewness = skewR[r];
        q.minVolume = volumeR[r];
        q.minDihedral = minDihedralR[r];
        q.maxDihedral = maxDihedralR[r];
        q.nSevereNonOrthogonal = std::int64_t(severeR[r]);
        report.perRank.push_back(q);

        allMinCos = std::min(allMinCos, minCosR[r]);
        allMinProcCos = std::min(allMinProcCos, minProcCosR[r]);
        allSumCos += sumCosR[r];
        allCounted += countedR[r];
        all.maxSkewness = std::max(all.maxSkewness, q.maxSkewness);
        all.minVolume = std::min(all.minVolume, q.minVolume);
        all.minDihedral = std::min(all.minDihedral, q.minDihedral);
        all.maxDihedral = std::max(all.maxDihedral, q.maxDihedral);
        all.nSevereNonOrthogonal += q.nSevereNonOrthogonal;
    }
    all.maxNonOrthogonality = degreesOfCos(allMinCos);
    all.avgNonOrthogonality = allCounted > 0 ? degreesOfCos(allSumCos/allCounted) : 0;
    all.maxProcessorNonOrthogonality = degreesOfCos(allMinProcCos);
    return report;
}


void pmsh::logMeshQuality(const Communicator& comm, const meshQualityReport& quality)
{
    const meshQuality& q = quality.overall;
    Info()
        << std::fixed << std::setprecision(1)
        << "    mesh quality (as checkMesh" << (comm.parallel() ? " -parallel" : "")
        << "):\n"
        << "        max non-orthogonality " << q.maxNonOrthogonality;
    if (comm.parallel())
    {
        Info() << " (processor faces " << q.maxProcessorNonOrthogonality << ")";
    }
    Info()
        << ", average " << q.avgNonOrthogonality << " degrees, "
        << q.nSevereNonOrthogonal << " faces above 70\n"
        << std::setprecision(3)
        << "        max skewness " << q.maxSkewness
        << std::scientific << std::setprecision(3)
        << ", min volume " << q.minVolume << '\n'
        << std::fixed << std::setprecision(1)
        << "        tet dihedral angles min/max: " << q.minDihedral << " / "
        << q.maxDihedral << " degrees\n";
    if (comm.parallel())
    {
        std::vector<double> nonOrth, skew;
        for (const meshQuality& r : quality.perRank)
        {
            nonOrth.push_back(r.maxNonOrthogonality);
            skew.push_back(r.maxSkewness);
        }
        const minAvgMax n = minAvgMaxOf(nonOrth);
        const minAvgMax s = minAvgMaxOf(skew);
        Info()
            << "        per rank max non-orthogonality min/avg/max: " << n.min
            << " / " << n.avg << " / " << n.max << '\n'
            << std::setprecision(3)
            << "        per rank max skewness min/avg/max: " << s.min << " / "
            << s.avg << " / " << s.max << '\n';
    }
    Info() << std::defaultfloat << std::setprecision(6);
}


// ************************************************************************* //
