#include "polyMeshWriter.H"
#include "error.H"

#include <filesystem>
#include <sstream>
#include <system_error>

namespace
{

// "key" padded to the 16-column width OpenFOAM uses in patch dictionaries.
void entry
(
    std::ostringstream& os,
    const std::string& key,
    const std::string& value
)
{
    os  << "        " << key;
    for (std::size_t i = key.size(); i < 16; ++i)
    {
        os  << ' ';
    }
    if (key.size() >= 16)
    {
        os  << ' ';
    }
    os  << value << ";\n";
}


//- The sizes and patch layout must be consistent before anything is written.
void checkMesh(const pmsh::PolyMesh& mesh, const std::string& dir)
{
    using namespace pmsh;

    std::string problem;
    if (mesh.owner.size() != mesh.faces.size())
    {
        problem = "owner has " + std::to_string(mesh.owner.size())
            + " entries for " + std::to_string(mesh.faces.size()) + " faces";
    }
    else if (mesh.neighbour.size() > mesh.faces.size())
    {
        problem = "more neighbours than faces";
    }
    else
    {
        label start = mesh.nInternalFaces();
        for (const polyPatchInfo& p : mesh.patches)
        {
            if (p.start != start || p.size < 0)
            {
                problem = "patch " + p.name + " starts at "
                    + std::to_string(p.start) + " instead of "
                    + std::to_string(start);
                break;
            }
            start += p.size;
        }
        if (problem.empty() && start != mesh.nFaces())
        {
            problem = "the patches end at face " + std::to_string(start)
                + " but there are " + std::to_string(mesh.nFaces()) + " faces";
        }
    }
    if (!problem.empty())
    {
        throw FatalError
        (
            msg() << "Cannot write the mesh into " << dir << ": " << problem,
            "writePolyMesh"
        );
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * Free functions  * * * * * * * * * * * * * //

std::string pmsh::polyMeshNote(const PolyMesh& mesh)
{
    std::ostringstream os;
    os  << "nPoints:" << mesh.points.size()
        << "  nCells:" << mesh.nCells
        << "  nFaces:" << mesh.faces.size()
        << "  nInternalFaces:" << mesh.neighbour.size();
    return os.str();
}


std::string pmsh::boundaryText(const PolyMesh& mesh)
{
    std::ostringstream os;
    os  << mesh.patches.size() << "\n(\n";
    for (const polyPatchInfo& p : mesh.patches)
    {
        os  << "    " << p.name << "\n    {\n";
        entry(os, "type", p.type);
        if (p.isProcessor())
        {
            entry(os, "inGroups", "1(processor)");
        }
        else if (p.type == "wall")
        {
            entry(os, "inGroups", "1(wall)");
        }
        entry(os, "nFaces", std::to_string(p.size));
        entry(os, "startFace", std::to_string(p.start));
        if (p.isProcessor())
        {
            entry(os, "matchTolerance", "0.0001");
            entry(os, "transform", "unknown");
            entry(os, "myProcNo", std::to_string(p.myProcNo));
            entry(os, "neighbProcNo", std::to_string(p.neighbProcNo));
        }
        os  << "    }\n";
    }
    os  << ")\n";
    return os.str();
}


void pmsh::writeBoundaryFile
(
    const std::string& path,
    const PolyMesh& mesh,
    const foamFileFormat& fmt,
    const std::string& location
)
{
    // OpenFOAM keeps boundary in ascii even when writing binary
    foamFileFormat asciiFmt = fmt;
    asciiFmt.binary = false;

    foamOFstream os(path, asciiFmt);
    os.writeHeader({"polyBoundaryMesh", location, fileNameOf(path), ""});
    os.writeText(boundaryText(mesh));
    os.close();
}


void pmsh::writePolyMesh
(
    const std::string& polyMeshDir,
    const PolyMesh& mesh,
    const foamFileFormat& fmt,
    const std::string& location
)
{
    checkMesh(mesh, polyMeshDir);

    std::error_code ec;
    std::filesystem::create_directories(polyMeshDir, ec);
    if (ec || !std::filesystem::is_directory(polyMeshDir))
    {
        throw FatalError
        (
            msg() << "Cannot create the directory " << polyMeshDir << ": "
                << (ec ? ec.message() : "not a directory"),
            "writePolyMesh"
        );
    }

    const std::string dir = polyMeshDir + '/';
    const std::string note = polyMeshNote(mesh);

    writePointFieldFile(dir + "points", mesh.points, fmt, location);
    writeFaceListFile(dir + "faces", mesh.faces, fmt, location);
    writeLabelListFile(dir + "owner", mesh.owner, fmt, location, note);
    writeLabelListFile(dir + "neighbour", mesh.neighbour, fmt, location, note);
    writeBoundaryFile(dir + "boundary", mesh, fmt, location);
}


// ************************************************************************* //
