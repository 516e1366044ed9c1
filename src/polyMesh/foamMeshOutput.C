#include "foamMeshOutput.H"
#include "pmshError.H"

#include "processorPolyPatch.H"
#include "labelIOList.H"
#include "UPstream.H"

#include <algorithm>
#include <cstdlib>

Foam::autoPtr<Foam::fvMesh> pmsh::toFvMesh(const Foam::Time& time, tetPolyMesh&& mesh)
{
    using namespace Foam;

    pointField points(label(mesh.points.size()));
    forAll(points, i)
    {
        const pmsh::point& p = mesh.points[i];
        points[i] = Foam::vector(p[0], p[1], p[2]);
    }
    mesh.points = {};

    faceList faces(label(mesh.faces.size()));
    forAll(faces, i)
    {
        const pmsh::triFace& f = mesh.faces[i];
        faces[i] = Foam::face(Foam::labelList({f[0], f[1], f[2]}));
    }
    mesh.faces = {};

    labelList owner(label(mesh.owner.size()));
    std::copy(mesh.owner.begin(), mesh.owner.end(), owner.begin());
    mesh.owner = {};
    labelList neighbour(label(mesh.neighbour.size()));
    std::copy(mesh.neighbour.begin(), mesh.neighbour.end(), neighbour.begin());
    mesh.neighbour = {};

    autoPtr<fvMesh> fvm
    (
        new fvMesh
        (
            IOobject
            (
                fvMesh::defaultRegion,
                time.constant(),
                time,
                IOobject::NO_READ,
                IOobject::AUTO_WRITE
            ),
            std::move(points),
            std::move(faces),
            std::move(owner),
            std::move(neighbour),
            false       // the processor patches are not there yet
        )
    );

    List<polyPatch*> patches(label(mesh.patches.size()));
    forAll(patches, i)
    {
        const meshPatch& p = mesh.patches[i];
        if (p.isProcessor())
        {
            patches[i] = new processorPolyPatch
            (
                p.size, p.start, i, fvm->boundaryMesh(),
                UPstream::myProcNo(), p.neighbProcNo
            );
        }
        else
        {
            patches[i] = polyPatch::New
            (
                p.type, p.name, p.size, p.start, i, fvm->boundaryMesh()
            ).ptr();
        }
    }
    fvm->addFvPatches(patches, false);
    return fvm;
}


void pmsh::checkGlobalNumbersFitLabel
(
    const Communicator& comm,
    const procAddressing& addressing,
    globalLabel maxLabel
)
{
    // The largest global number of each kind (faces are stored as +-(f + 1))
    auto largest = [](const std::vector<globalLabel>& v)
    {
        globalLabel m = 0;
        for (globalLabel x : v) m = std::max(m, std::abs(x));
        return m;
    };
    const globalLabel points = comm.max(std::int64_t(largest(addressing.point)));
    const globalLabel cells = comm.max(std::int64_t(largest(addressing.cell)));
    const globalLabel faces = comm.max(std::int64_t(largest(addressing.face)));
    if (std::max({points, cells, faces}) > maxLabel)
    {
        throw FatalError
        (
            msg() << "The mesh is too large for this OpenFOAM's " << 8*sizeof(Foam::label)
                << "-bit labels (largest label " << maxLabel << "): its global numbers reach "
                << points << " (points), " << cells << " (cells) and " << faces
                << " (faces, counted from 1)\n"
                << "The processor meshes would fit, but their procAddressing and the"
                << " reconstructed mesh would not.\n"
                << "Use an OpenFOAM built with WM_LABEL_SIZE=64, or fewer cells"
                << " (larger maxCellSize or fewer refinementLevels)",
            "checkGlobalNumbersFitLabel"
        );
    }
}


namespace
{

void writeLabelIOList
(
    const Foam::polyMesh& mesh,
    const Foam::word& name,
    const std::vector<pmsh::globalLabel>& values
)
{
    Foam::labelIOList list
    (
        Foam::IOobject
        (
            name,
            mesh.facesInstance(),
            Foam::polyMesh::meshSubDir,
            mesh,
            Foam::IOobject::NO_READ,
            Foam::IOobject::NO_WRITE,
            false
        ),
        Foam::label(values.size())
    );
    std::copy(values.begin(), values.end(), list.begin());
    list.write();
}

} // End anonymous namespace


void pmsh::writeProcAddressing
(
    const Foam::polyMesh& mesh,
    const procAddressing& addressing
)
{
    writeLabelIOList(mesh, "pointProcAddressing", addressing.point);
    writeLabelIOList(mesh, "faceProcAddressing", addressing.face);
    writeLabelIOList(mesh, "cellProcAddressing", addressing.cell);
    writeLabelIOList(mesh, "boundaryProcAddressing", addressing.boundary);
}
