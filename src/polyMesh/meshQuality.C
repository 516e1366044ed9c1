#include "meshQuality.H"
#include "checkMeshFaceMetrics.H"
#include "foamShims.H"
#include "streamManip.H"
#include "stageLog.H"

#include "syncTools.H"
#include "unitConversion.H"

#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <vector>

using Foam::Info;
using Foam::fixed;
using Foam::scientific;
using Foam::setprecision;

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
// cell), the largest part of stage 7's peak. Only the cell centres and
// volumes are kept here; the formulas are primitiveMesh's, so the figures
// are checkMesh's (to rounding: each internal face's centre is computed
// once for both its cells, so a cell's sums add the same terms in another
// order).

//- primitiveMeshFaceCentresAndAreas: a triangle directly (every face of a
//  tet mesh), a larger face (a prism's side quad) as the triangles from
//  its points' mean, area-weighted
inline void faceCentreAndArea
(
    const pointField& p,
    const face& f,
    vector& centre,
    vector& area
)
{
    const label n = f.size();
    if (n == 3)
    {
        centre = (1.0/3.0)*(p[f[0]] + p[f[1]] + p[f[2]]);
        area = 0.5*((p[f[1]] - p[f[0]]) ^ (p[f[2]] - p[f[0]]));
        return;
    }
    point fCentre = p[f[0]];
    for (label pi = 1; pi < n; ++pi)
    {
        fCentre += p[f[pi]];
    }
    fCentre /= n;
    vector sumN = Zero, sumAc = Zero;
    scalar sumA = 0;
    for (label pi = 0; pi < n; ++pi)
    {
        const point& nextPoint = p[f[(pi + 1) % n]];
        const vector c = p[f[pi]] + nextPoint + fCentre;
        const vector an = (nextPoint - p[f[pi]]) ^ (fCentre - p[f[pi]]);
        const scalar a = mag(an);
        sumN += an;
        sumA += a;
        sumAc += a*c;
    }
    if (sumA < ROOTVSMALL)
    {
        centre = fCentre;
        area = Zero;
    }
    else
    {
        centre = (1.0/3.0)*sumAc/sumA;
        area = 0.5*sumN;
    }
}


//- cellCentresAndVolumes of a mesh of tets alone, in one pass over the
//  faces instead of two: a tet's pyramids about the mean of its face
//  centres (its centroid) have their centroids' weighted mean there too,
//  so that mean is checkMesh's cell centre, to rounding. The volume is
//  the sum of S.(c - x)/3 over the faces for any point x: here the first
//  point of the mesh (against each cell's own centre, the relative
//  difference is below 1e-9 for cells 1e6 times smaller than the domain)
void tetCentresAndVolumes
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
    const label nInternal = mesh.nInternalFaces();
    const point x = p.empty() ? point(Zero) : p[0];

    centres = Zero;
    volumes = 0;
    vector c, s;
    forAll(own, facei)
    {
        faceCentreAndArea(p, faces[facei], c, s);
        const scalar pyr3Vol = s & (c - x);
        centres[own[facei]] += c;
        volumes[own[facei]] += pyr3Vol;
        if (facei < nInternal)
        {
            centres[nei[facei]] += c;
            volumes[nei[facei]] -= pyr3Vol;
        }
    }
    centres *= 0.25;
    volumes *= (1.0/3.0);
}


//- primitiveMeshCellCentresAndVols: the face-pyramid decomposition about
//  the mean of the cell's face centres. Besides centres and volumes, the
//  peak of the write stage, it keeps only that mean, in single precision
//  (12 bytes a cell instead of 24 and a face count): for planar faces the
//  decomposition's result does not depend on the apex, for a warped
//  prism side only to second order in the warp, so checkMesh's figures
//  come out the same (tests/tutorials/testLayers.py)
void cellCentresAndVolumes
(
    const polyMesh& mesh,
    pointField& centres,
    scalarField& volumes,
    std::int64_t& nPrisms
)
{
    const pointField& p = mesh.points();
    const faceList& faces = mesh.faces();
    const labelList& own = mesh.faceOwner();
    const labelList& nei = mesh.faceNeighbour();

    // Cells are tets (4 faces) or prisms (5): their faces count them
    const label nInternal = mesh.nInternalFaces();
    const std::int64_t nCellFaces = 2*std::int64_t(nInternal) + (mesh.nFaces() - nInternal);
    nPrisms = nCellFaces - 4*std::int64_t(mesh.nCells());
    if (nPrisms == 0)
    {
        tetCentresAndVolumes(mesh, centres, volumes);
        return;
    }

    // The apex of each cell's pyramids: the mean of its face centres,
    // summed in centres and counted in volumes first
    std::vector<std::array<float, 3>> apex(mesh.nCells());
    {
        centres = Zero;
        volumes = 0;
        vector c, s;
        forAll(own, facei)
        {
            // One face centre for both cells of an internal face: the sums
            // take the same terms as primitiveMesh's (owner loop, then
            // neighbour loop), in another order
            faceCentreAndArea(p, faces[facei], c, s);
            centres[own[facei]] += c;
            volumes[own[facei]] += 1;
            if (facei < nInternal)
            {
                centres[nei[facei]] += c;
                volumes[nei[facei]] += 1;
            }
        }
        forAll(centres, celli)
        {
            const vector mean = centres[celli]/volumes[celli];
            apex[celli] = {float(mean.x()), float(mean.y()), float(mean.z())};
        }
    }
    auto apexOf = [&apex](label celli)
    {
        const std::array<float, 3>& a = apex[celli];
        return vector(a[0], a[1], a[2]);
    };

    centres = Zero;
    volumes = 0;
    vector c, s;
    forAll(own, facei)
    {
        faceCentreAndArea(p, faces[facei], c, s);
        const label o = own[facei];
        const vector ownApex = apexOf(o);
        const scalar ownPyr3Vol = s & (c - ownApex);
        centres[o] += ownPyr3Vol*((3.0/4.0)*c + (1.0/4.0)*ownApex);
        volumes[o] += ownPyr3Vol;
        if (facei < nInternal)
        {
            const label n = nei[facei];
            const vector neiApex = apexOf(n);
            const scalar neiPyr3Vol = s & (neiApex - c);
            centres[n] += neiPyr3Vol*((3.0/4.0)*c + (1.0/4.0)*neiApex);
            volumes[n] += neiPyr3Vol;
        }
    }
    forAll(centres, celli)
    {
        if (mag(volumes[celli]) > VSMALL)
        {
            centres[celli] /= volumes[celli];
        }
        else
        {
            centres[celli] = apexOf(celli);
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
    const tetShapeFigures& volume
)
{
    using namespace Foam;

    const pointField& p = mesh.points();
    const faceList& faces = mesh.faces();
    const labelList& own = mesh.faceOwner();
    const label nInternal = mesh.nInternalFaces();

    pointField centres(mesh.nCells());
    scalarField volumes(mesh.nCells());
    std::int64_t nPrisms = 0;
    cellCentresAndVolumes(mesh, centres, volumes, nPrisms);

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
        faceCentreAndArea(p, f, c, s);
        const pmsh::point3 a = asPoint3(p[f[0]]), b = asPoint3(p[f[1]]), e = asPoint3(p[f[2]]);
        // A quad's skewness is normalised by its extent over all 4 points:
        // the smaller of the kernel's over (a b e) and over (a e g)
        const bool quad = f.size() == 4;
        const pmsh::point3 g = quad ? asPoint3(p[f[3]]) : e;
        const pmsh::point3 fc = asPoint3(c);
        const pmsh::vector3 S = asPoint3(s);
        const Foam::point& ownCc = centres[own[facei]];
        const pmsh::vector3 Cpf = asPoint3(c - ownCc);
        const bool internal = facei < nInternal;
        if (!internal && !coupled[facei - nInternal])
        {
            double skew = boundaryFaceMetricsOf(a, b, e, fc, S, Cpf).skewness;
            if (quad)
            {
                skew = std::min(skew, boundaryFaceMetricsOf(a, e, g, fc, S, Cpf).skewness);
            }
            maxSkew = std::max(maxSkew, skew);
            continue;
        }
        const Foam::point& neiCc =
            internal ? centres[mesh.faceNeighbour()[facei]] : neighbourCentres[facei - nInternal];
        const pmsh::vector3 d = asPoint3(neiCc - ownCc);
        const double ortho = nonOrthogonalityCos(S, d);
        double skew = internalFaceSkewness(a, b, e, fc, S, Cpf, d);
        if (quad)
        {
            skew = std::min(skew, internalFaceSkewness(a, e, g, fc, S, Cpf, d));
        }
        maxSkew = std::max(maxSkew, skew);
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

    // This rank's figures, gathered in one collective
    struct rankFigures
    {
        double minCos, sumCos, minProcessorCos, maxSkew, minVolume;
        double minDihedral, maxDihedral, maxAspectRatio;
        std::int64_t nCounted, nSevere, nCells, nPrisms;
    };
    const std::vector<rankFigures> ranks = comm.allGather
    (
        rankFigures
        {
            minCos, sumCos, minProcessorCos, maxSkew, minVolume,
            volume.minDihedral, volume.maxDihedral, volume.maxAspectRatio,
            nCounted, nSevere, std::int64_t(mesh.nCells()), nPrisms
        }
    );

    meshQualityReport report;
    meshQuality& all = report.overall;
    double allSumCos = 0, allMinCos = 1, allMinProcCos = 1;
    std::int64_t allCounted = 0;
    all.minVolume = ranks.empty() ? 0 : ranks[0].minVolume;
    all.minDihedral = 180;
    for (const rankFigures& r : ranks)
    {
        meshQuality q;
        q.maxNonOrthogonality = degreesOfCos(r.minCos);
        q.avgNonOrthogonality =
            r.nCounted > 0 ? degreesOfCos(r.sumCos/double(r.nCounted)) : 0;
        q.maxProcessorNonOrthogonality = degreesOfCos(r.minProcessorCos);
        q.maxSkewness = r.maxSkew;
        q.minVolume = r.minVolume;
        q.minDihedral = r.minDihedral;
        q.maxDihedral = r.maxDihedral;
        q.maxAspectRatio = r.maxAspectRatio;
        q.nSevereNonOrthogonal = r.nSevere;
        q.nCells = r.nCells;
        q.nPrisms = r.nPrisms;
        report.perRank.push_back(q);

        allMinCos = std::min(allMinCos, r.minCos);
        allMinProcCos = std::min(allMinProcCos, r.minProcessorCos);
        allSumCos += r.sumCos;
        allCounted += r.nCounted;
        all.maxSkewness = std::max(all.maxSkewness, q.maxSkewness);
        all.minVolume = std::min(all.minVolume, q.minVolume);
        all.minDihedral = std::min(all.minDihedral, q.minDihedral);
        all.maxDihedral = std::max(all.maxDihedral, q.maxDihedral);
        all.maxAspectRatio = std::max(all.maxAspectRatio, q.maxAspectRatio);
        all.nSevereNonOrthogonal += q.nSevereNonOrthogonal;
        all.nCells += q.nCells;
        all.nPrisms += q.nPrisms;
    }
    all.maxNonOrthogonality = degreesOfCos(allMinCos);
    all.avgNonOrthogonality = allCounted > 0 ? degreesOfCos(allSumCos/double(allCounted)) : 0;
    all.maxProcessorNonOrthogonality = degreesOfCos(allMinProcCos);
    return report;
}


void pmsh::logMeshQuality(const Communicator& comm, const meshQualityReport& quality)
{
    const meshQuality& q = quality.overall;
    Info
        << fixed << setprecision(1)
        << "    mesh quality (as checkMesh" << (comm.parallel() ? " -parallel" : "")
        << "):\n"
        << "        max non-orthogonality " << q.maxNonOrthogonality;
    if (comm.parallel())
    {
        Info << " (processor faces " << q.maxProcessorNonOrthogonality << ")";
    }
    Info
        << ", average " << q.avgNonOrthogonality << " degrees, "
        << q.nSevereNonOrthogonal << " faces above 70\n"
        << setprecision(3)
        << "        max skewness " << q.maxSkewness
        << scientific << setprecision(3)
        << ", min volume " << q.minVolume << '\n'
        << fixed << setprecision(1)
        << "        tet dihedral angles min/max: " << q.minDihedral << " / "
        << q.maxDihedral << " degrees, max aspect ratio " << q.maxAspectRatio
        << '\n';
    if (q.nPrisms > 0)
    {
        Info
            << "        cells: " << q.nCells - q.nPrisms << " tets, "
            << q.nPrisms << " prisms\n";
    }
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
        Info
            << "        per rank max non-orthogonality min/avg/max: " << n.min
            << " / " << n.avg << " / " << n.max << '\n'
            << setprecision(3)
            << "        per rank max skewness min/avg/max: " << s.min << " / "
            << s.avg << " / " << s.max << '\n';
    }
    Info << defaultfloat << setprecision(6);
}


// ************************************************************************* //
