#include "foamMeshOutput.H"
#include "foamShims.H"
#include "pmshError.H"

#include "processorPolyPatch.H"
#include "processorCyclicPolyPatch.H"
#include "syncTools.H"
#include "labelIOList.H"
#include "faceIOList.H"
#include "UPstream.H"

#include <algorithm>
#include <map>
#include <cstdlib>

namespace
{

// OpenFOAM's copy of the labels; the vector is freed at once
Foam::labelList movedToLabelList(std::vector<pmsh::label>& labels)
{
    Foam::labelList list(Foam::label(labels.size()));
    std::copy(labels.begin(), labels.end(), list.begin());
    pmsh::freeStorage(labels);
    return list;
}

} // End anonymous namespace


pmsh::foamRankMesh::foamRankMesh(const Foam::Time& time, tetPolyMesh&& mesh)
{
    using namespace Foam;

    pointField points(label(mesh.points.size()));
    forAll(points, i)
    {
        const pmsh::point3& p = mesh.points[i];
        points[i] = Foam::vector(p[0], p[1], p[2]);
    }
    freeStorage(mesh.points);

    // Each face is a view of its labels in a block this object owns: the
    // tetPolyMesh's triangles, or with prism layers (quads) one flat block
    // of 3 or 4 labels a face (OpenFOAM's own faces would take a heap
    // block each: 16 bytes of list and the allocator's header on top of
    // the labels). List<face> forbids this (List::shallowCopy is
    // deleted, as a List owns its storage): the view is set through UList,
    // and the destructor takes every view back before the faceList would
    // free it
    static_assert(sizeof(triVerts) == 3*sizeof(label), "triangles are 3 contiguous labels");
    faceList faces(label(mesh.faces.size()));
    if (mesh.quads.empty())
    {
        triangles_ = std::move(mesh.faces);
        forAll(faces, i)
        {
            static_cast<UList<label>&>(faces[i]).shallowCopy
            (
                UList<label>(triangles_[i].data(), 3)
            );
        }
    }
    else
    {
        mixedFaces_.resize(3*mesh.faces.size() + mesh.quads.size());
        std::size_t q = 0, at = 0;
        forAll(faces, i)
        {
            const std::size_t start = at;
            for (const label v : mesh.faces[i]) mixedFaces_[at++] = v;
            if (q < mesh.quads.size() && mesh.quads[q].face == i)
            {
                mixedFaces_[at++] = mesh.quads[q++].fourth;
            }
            static_cast<UList<label>&>(faces[i]).shallowCopy
            (
                UList<label>(mixedFaces_.data() + start, label(at - start))
            );
        }
        freeStorage(mesh.faces);
        freeStorage(mesh.quads);
    }

    labelList owner = movedToLabelList(mesh.owner);
    labelList neighbour = movedToLabelList(mesh.neighbour);

    mesh_.reset
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
                p.size, p.start, i, mesh_->boundaryMesh(),
                UPstream::myProcNo(), p.neighbProcNo
            );
        }
        else if (p.isProcessorCyclic())
        {
            patches[i] = foam::newProcessorCyclicPatch
            (
                p.size, p.start, i, mesh_->boundaryMesh(),
                UPstream::myProcNo(), p.neighbProcNo, word(p.neighbourPatch)
            );
        }
        else if (p.isCyclic())
        {
            // A translation known from the geometry: no guessing by
            // OpenFOAM (its faces are ordered as it wants, cyclicFaces.H)
            dictionary dict;
            dict.add("type", word("cyclic"));
            dict.add("nFaces", label(p.size));
            dict.add("startFace", label(p.start));
            dict.add("neighbourPatch", word(p.neighbourPatch));
            dict.add("transform", word("translational"));
            dict.add
            (
                "separationVector",
                Foam::vector(p.separation[0], p.separation[1], p.separation[2])
            );
            patches[i] = polyPatch::New(p.name, dict, i, mesh_->boundaryMesh()).ptr();
        }
        else
        {
            patches[i] = polyPatch::New
            (
                p.type, p.name, p.size, p.start, i, mesh_->boundaryMesh()
            ).ptr();
            // (a loop: ESI deprecates findIndex, the Foundation has no found)
            for (const std::string& group : p.groups)
            {
                bool known = false;
                for (const word& g : patches[i]->inGroups())
                {
                    known = known || g == group;
                }
                if (!known)
                {
                    patches[i]->inGroups().append(word(group));
                }
            }
        }
    }
    // Cyclic patches need their geometry (the transform) before anything
    // looks across them: a valid boundary has it computed (collective,
    // and every rank has the same patches). Otherwise nothing needs it
    bool cyclic = false;
    for (const meshPatch& p : mesh.patches)
    {
        cyclic = cyclic || p.isCyclic();
    }
    mesh_->addFvPatches(patches, cyclic);
    addZones(mesh);
}


std::string pmsh::zonePairName(const std::string& a, const std::string& b)
{
    return a + "_to_" + b;
}


void pmsh::foamRankMesh::addZones(const tetPolyMesh& mesh)
{
    using namespace Foam;

    if (mesh.zoneNames.empty())
    {
        return;
    }

    const label nZones = label(mesh.zoneNames.size());
    labelList zoneOfCell(mesh_->nCells());
    List<DynamicList<label>> cells(nZones);
    forAll(zoneOfCell, celli)
    {
        zoneOfCell[celli] = mesh.cellZone[celli];
        cells[zoneOfCell[celli]].append(celli);
    }
    List<cellZone*> cellZones(nZones);
    forAll(cellZones, z)
    {
        cellZones[z] = foam::newCellZone
        (
            mesh.zoneNames[z], cells[z].shrink(), z, *mesh_
        );
    }

    // The zone across every boundary face (the neighbour rank's cell
    // across a processor face)
    labelList zoneAcross;
    syncTools::swapBoundaryCellList(*mesh_, zoneOfCell, zoneAcross);

    std::map<std::pair<label, label>, label> pairIndex;
    for (const auto& pair : mesh.zonePairs)
    {
        pairIndex.emplace(std::make_pair(pair[0], pair[1]), label(pairIndex.size()));
    }
    List<DynamicList<label>> faces(pairIndex.size());
    List<DynamicList<bool>> flips(pairIndex.size());
    auto addFace = [&](label facei, label ownZone, label otherZone)
    {
        if (ownZone == otherZone)
        {
            return;
        }
        const auto pair = std::minmax(ownZone, otherZone);
        const auto it = pairIndex.find({pair.first, pair.second});
        if (it == pairIndex.end())
        {
            throw pmsh::FatalError
            (
                msg() << "Zones " << mesh.zoneNames[pair.first] << " and "
                    << mesh.zoneNames[pair.second] << " meet at face " << facei
                    << " but the coarse mesh has no face between them",
                "pmsh::foamRankMesh::addZones"
            );
        }
        faces[it->second].append(facei);
        flips[it->second].append(ownZone != pair.first);
    };
    const labelList& own = mesh_->faceOwner();
    const labelList& nei = mesh_->faceNeighbour();
    for (label facei = 0; facei < mesh_->nInternalFaces(); ++facei)
    {
        addFace(facei, zoneOfCell[own[facei]], zoneOfCell[nei[facei]]);
    }
    for (const polyPatch& pp : mesh_->boundaryMesh())
    {
        if (pp.coupled())
        {
            forAll(pp, i)
            {
                const label facei = pp.start() + i;
                addFace
                (
                    facei, zoneOfCell[own[facei]],
                    zoneAcross[facei - mesh_->nInternalFaces()]
                );
            }
        }
    }

    List<faceZone*> faceZones(pairIndex.size());
    for (const auto& [pair, z] : pairIndex)
    {
        faceZones[z] = foam::newFaceZone
        (
            zonePairName(mesh.zoneNames[pair.first], mesh.zoneNames[pair.second]),
            faces[z].shrink(), boolList(flips[z]), z, *mesh_
        );
    }
    mesh_->addZones(List<pointZone*>(), faceZones, cellZones);
}


namespace
{

// The faces as a faceCompactList (offsets, then every label), written
// straight from the block of labels the faces are views of: what
// CompactIOList<face> writes in binary, without its copy of the faces
class compactFacesIO
:
    public Foam::regIOobject
{
    const Foam::labelList offsets_;
    const Foam::UList<Foam::label> labels_;

public:

    compactFacesIO
    (
        const Foam::IOobject& io,
        Foam::labelList&& offsets,
        const Foam::UList<Foam::label>& labels
    )
    :
        Foam::regIOobject(io),
        offsets_(std::move(offsets)),
        labels_(labels)
    {}

    const Foam::word& type() const override
    {
        static const Foam::word compactFaces("faceCompactList");
        return compactFaces;
    }

    bool writeData(Foam::Ostream& os) const override
    {
        os  << offsets_ << labels_;
        return os.good();
    }
};

} // End anonymous namespace


void pmsh::foamRankMesh::write() const
{
    using namespace Foam;

    const label nFaces = mesh_->nFaces();
    const std::size_t nLabels =
        triangles_.empty() ? mixedFaces_.size() : std::size_t(3)*std::size_t(nFaces);
    const bool compact =
        mesh_->time().writeFormat() == IOstream::BINARY
     && nFaces > 0
     && nLabels > 0
     && nLabels <= std::size_t(labelMax);
    if (!compact)
    {
        mesh_->write();
        return;
    }

    // Where each face starts in the block: the faces are its views, in order
    const faceList& meshFaces = mesh_->faces();
    labelList offsets(nFaces + 1);
    offsets[0] = 0;
    forAll(meshFaces, i)
    {
        offsets[i + 1] = offsets[i] + meshFaces[i].size();
    }
    const label* block = triangles_.empty() ? mixedFaces_.data() : triangles_.front().data();

    IOobject& faces = const_cast<faceCompactIOList&>
    (
        mesh_->lookupObject<faceCompactIOList>("faces")
    );
    faces.writeOpt() = IOobject::NO_WRITE;
    mesh_->write();
    faces.writeOpt() = IOobject::AUTO_WRITE;

    compactFacesIO
    (
        IOobject
        (
            "faces",
            mesh_->facesInstance(),
            polyMesh::meshSubDir,
            *mesh_,
            IOobject::NO_READ,
            IOobject::NO_WRITE,
            false
        ),
        std::move(offsets),
        UList<label>(const_cast<label*>(block), label(nLabels))
    ).write();
}


pmsh::foamRankMesh::~foamRankMesh()
{
    // The faces must not free what the block owns
    if (mesh_.valid())
    {
        for (Foam::face& f : const_cast<Foam::faceList&>(mesh_->faces()))
        {
            static_cast<Foam::UList<Foam::label>&>(f).shallowCopy(Foam::UList<Foam::label>());
        }
    }
    mesh_.clear();
}


namespace
{

void writeLabelIOList
(
    const Foam::Time& time,
    const Foam::word& name,
    const std::vector<pmsh::label>& values
)
{
    Foam::labelIOList list
    (
        Foam::IOobject
        (
            name,
            time.constant(),
            Foam::polyMesh::meshSubDir,
            time,
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
    const Foam::Time& time,
    procAddressing&& addressing
)
{
    // Each list is freed once written: they are not needed afterwards
    writeLabelIOList(time, "pointProcAddressing", addressing.point);
    freeStorage(addressing.point);
    writeLabelIOList(time, "faceProcAddressing", addressing.face);
    freeStorage(addressing.face);
    writeLabelIOList(time, "cellProcAddressing", addressing.cell);
    freeStorage(addressing.cell);
    writeLabelIOList(time, "boundaryProcAddressing", addressing.boundary);
    freeStorage(addressing.boundary);
}
