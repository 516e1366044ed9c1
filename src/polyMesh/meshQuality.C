#include "meshQuality.H"
#include "checkMeshFaceMetrics.H"
#include "foamShims.H"
#include "Info.H"
#include "stageLog.H"

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


namespace
{

using namespace Foam;

// The geometry of OpenFOAM's primitiveMesh (v1912), computed face by face
// from the points: the mesh's own faceCentres()/faceAreas()/cellCentres()
// would keep three face fields and two cell fields (about 130 bytes per
// cell), the largest part of stage 6's peak. Only the cell centres and
// volumes are kept here; the formulas are primitiveMesh's, so the figures
// are checkMesh's.

//- primitiveMeshFaceCentresAndAreas for a triangle (every face here)
inline void triangleCentreAndArea
(
    const pointField& p,
    const face& f,
    vector& centre,
    vector& area
)
{
    centre = (1.0/3.0)*(p[f[0]] + p[f[1]] + p[f[2]]);
    area = 0.5*((p[f[1]] - p[f[0]]) ^ (p[f[2]] - p[f[0]]));
}


//- primitiveMeshCellCentresAndVols: the face-pyramid decomposition about
//  the mean of the cell's face centres
void cellCentresAndVolumes
(
    const polyMesh& mesh,
    pointField& centres,
    scalarField& volumes
)
{
    const pointField& p = mesh.points();
    const faceList& faces = mesh.faces();
    const labelList& own = mesh.faceOwner();
    const labelList& nei = mesh.faceNeighbour();

    vectorField estimate(mesh.nCells(), Zero);
    {
        labelField nCellFaces(mesh.nCells(), 0);
        vector c, s;
        forAll(own, facei)
        {
            triangleCentreAndArea(p, faces[facei], c, s);
            estimate[own[facei]] += c;
            ++nCellFaces[own[facei]];
        }
        forAll(nei, facei)
        {
            triangleCentreAndArea(p, faces[facei], c, s);
            estimate[nei[facei]] += c;
            ++nCellFaces[nei[facei]];
        }
        forAll(estimate, celli)
        {
            estimate[celli] /= nCellFaces[celli];
        }
    }

    centres = Zero;
    volumes = 0;
    vector c, s;
    forAll(own, facei)
    {
        triangleCentreAndArea(p, faces[facei], c, s);
        const scalar pyr3Vol = s & (c - estimate[own[facei]]);
        centres[own[facei]] += pyr3Vol*((3.0/4.0)*c + (1.0/4.0)*estimate[own[facei]]);
        volumes[own[facei]] += pyr3Vol;
    }
    forAll(nei, facei)
    {
        triangleCentreAndArea(p, faces[facei], c, s);
        const scalar pyr3Vol = s & (estimate[nei[facei]] - c);
        centres[nei[facei]] += pyr3Vol*((3.0/4.0)*c + (1.0/4.0)*estimate[nei[facei]]);
        volumes[nei[facei]] += pyr3Vol;
    }
    forAll(centres, celli)
    {
        if (mag(volumes[celli]) > VSMALL)
        {
            centres[celli] /= volumes[celli];
        }
        else
        {
            centres[celli] = estimate[celli];
        }
    }
    volumes *= (1.0/3.0);
}


inline pmsh::point3 asPoint3(const Foam::vector& v)
{
    return {v.x(), v.y(), v.z()};
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

    const pointField& p = mesh.points();
    const faceList& faces = mesh.faces();
    const labelList& own = mesh.faceOwner();
    const label nInternal = mesh.nInternalFaces();

    pointField centres(mesh.nCells());
    scalarField volumes(mesh.nCells());
    cellCentresAndVolumes(mesh, centres, volumes);

    // checkMesh -parallel: processor faces see the neighbour rank's cell
    // centres (swapped inside, collective)
    pointField neighbourCentres;
    syncTools::swapBoundaryCellPositions(mesh, centres, neighbourCentres);
    std::vector<bool> coupled(mesh.nFaces() - nInternal, false);
    for (const polyPatch& pp : mesh.boundaryMesh())
    {
        if (pp.coupled())
        {
            for (label i = 0; i < pp.size(); ++i)
            {
                coupled[pp.start() + i - nInternal] = true;
            }
        }
    }

    // As checkMesh: non-orthogonality over internal faces and one side of
    // each processor face (uncoupled boundary faces have none), skewness
    // over every face
    const std::vector<bool> counted = pmsh::foam::internalOrMasterFaces(mesh);
    const double severeCos = std::cos(degToRad(70.0));
    double minCos = 1, sumCos = 0, minProcessorCos = 1, maxSkew = 0;
    std::int64_t nCounted = 0, nSevere = 0;
    Foam::vector c, s;
    for (label facei = 0; facei < mesh.nFaces(); ++facei)
    {
        const face& f = faces[facei];
        triangleCentreAndArea(p, f, c, s);
        const pmsh::point3 a = asPoint3(p[f[0]]), b = asPoint3(p[f[1]]), e = asPoint3(p[f[2]]);
        const pmsh::point3 fc = asPoint3(c);
        const pmsh::vector3 S = asPoint3(s);
        const Foam::point& ownCc = centres[own[facei]];
        const pmsh::vector3 Cpf = asPoint3(c - ownCc);
        const bool internal = facei < nInternal;
        if (!internal && !coupled[facei - nInternal])
        {
            maxSkew = std::max(maxSkew, boundaryFaceMetricsOf(a, b, e, fc, S, Cpf).skewness);
            continue;
        }
        const Foam::point& neiCc =
            internal ? centres[mesh.faceNeighbour()[facei]] : neighbourCentres[facei - nInternal];
        const pmsh::vector3 d = asPoint3(neiCc - ownCc);
        const double ortho = nonOrthogonalityCos(S, d);
        maxSkew = std::max(maxSkew, internalFaceSkewness(a, b, e, fc, S, Cpf, d));
        if (counted[facei])
        {
            minCos = std::min(minCos, ortho);
            sumCos += ortho;
            ++nCounted;
            if (ortho < severeCos) ++nSevere;
        }
        if (!internal)
        {
            minProcessorCos = std::min(minProcessorCos, ortho);
        }
    }
    const double minVolume = mesh.nCells() ? double(min(volumes)) : 0;

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
    const std::vector<double> aspectR = comm.allGather(volume.maxAspectRatio);

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
        q.maxAspectRatio = aspectR[r];
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
        all.maxAspectRatio = std::max(all.maxAspectRatio, q.maxAspectRatio);
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
        << q.maxDihedral << " degrees, max aspect ratio " << q.maxAspectRatio
        << '\n';
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
