/*---------------------------------------------------------------------------*\
  pmshFoam: a Netgen CSG (.geo) model: parsing, coarse mesh, projection
  (see netgenInterface.H).

  Netgen quirks handled here, each commented where it is handled:
  - ParseCSG is not declared in the installed headers (netgenSession.H),
    and on a file not starting with algebraic3d it returns nullptr and
    leaks: checked first;
  - a CSG bcname that is a keyword or primitive name (-bcname=sphere) is a
    syntax error (hinted at in the message, documented in csgGeometry.H);
  - an unknown CSG statement is only printed ("read unidentified token")
    and skipped: turned into an error;
  - an unbounded CSG solid makes GenerateMesh eat all memory: checked after
    parsing;
  - CSGeometry::GetRefinement() allocates a new object on every call: it is
    not used (projection calls Surface::Project / ProjectToEdge directly);
  - CSGGenerateMesh creates the local size tree in its analysis step and
    accepts only points (meshsize_points) before the edges: it is run up
    to the analysis, restricted, and resumed from the edges;
  - the periodic identifications keep their surfaces private.
\*---------------------------------------------------------------------------*/

#include "netgenMeshConversion.H"
#include "pmshError.H"

#include <fstream>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

using namespace pmsh::ng;

//- The 'identify periodic' statements of g and Netgen's point pairs of
//  each in mesh. Quirks: the identifications keep their surfaces private;
//  GetData prints "periodic <surface> <surface>" with Netgen's surface
//  names (nnsurfN), and the parser took each solid's first surface. Mesh
//  identification numbers are the geometry's indices + 1.
std::vector<pmsh::ng::periodicIdentification> periodicIdentifications
(
    const netgen::CSGeometry& g,
    netgen::Mesh& mesh
)
{
    auto surfaceIndex = [&](const std::string& name)
    {
        const netgen::Surface* surface = g.GetSurface(name.c_str());
        for (int s = 0; surface && s < g.GetNSurf(); ++s)
        {
            if (g.GetSurface(s) == surface)
            {
                return label(g.GetSurfaceClassRepresentant(s));
            }
        }
        return label(-1);
    };
    // The solid of a surface: one of that surface alone, as 'identify'
    // names them (solid left = plane(...);)
    auto solidName = [&](label surface)
    {
        for (int i = 0; i < g.GetNSolids(); ++i)
        {
            netgen::Array<int> surfaces;
            g.GetSolid(i)->GetSurfaceIndices(surfaces);
            if
            (
                surfaces.Size() == 1
             && g.GetSurfaceClassRepresentant(surfaces[0]) == surface
            )
            {
                return std::string(g.GetSolid(i)->Name());
            }
        }
        return std::string();
    };

    std::vector<ng::periodicIdentification> result;
    netgen::Identifications& identifications = mesh.GetIdentifications();
    for (int i = 0; i < g.GetNIdentifications(); ++i)
    {
        std::ostringstream data;
        g.identifications[i]->GetData(data);
        std::istringstream words(data.str());
        std::string type, first, second;
        words >> type >> first >> second;
        if (type != "periodic")
        {
            continue;
        }
        ng::periodicIdentification p;
        p.firstSurface = surfaceIndex(first);
        p.secondSurface = surfaceIndex(second);
        p.firstSolid = solidName(p.firstSurface);
        p.secondSolid = solidName(p.secondSurface);
        netgen::Array<netgen::INDEX_2> pairs;
        identifications.GetPairs(i + 1, pairs);
        for (std::size_t k = 0; k < pairs.Size(); ++k)
        {
            p.points.push_back({label(pairs[k].I1()) - 1, label(pairs[k].I2()) - 1});
        }
        result.push_back(std::move(p));
    }
    return result;
}


//- Check that a CSG file starts with the keyword algebraic3d, and rewind
//  it. Quirk: on a file without it ParseCSG returns nullptr and leaks the
//  CSGeometry it has just allocated. Netgen's scanner skips whitespace and
//  '#' comment lines first, and so does this.
void checkAlgebraic3d
(
    std::istream& is,
    const std::string& fileName,
    const char* function
)
{
    std::string word;
    for (std::string line; std::getline(is, line); )
    {
        std::istringstream ls(line);
        if ((ls >> word) && word[0] != '#')
        {
            break;
        }
        word.clear();
    }
    const std::string keyword = word.substr(0, std::min<std::size_t>(word.size(), 11));
    if (keyword != "algebraic3d")
    {
        throw FatalError
        (
            msg()
                << "CSG geometry file \"" << fileName << "\" does not"
                << " start with the keyword algebraic3d (found \""
                << word << "\").\nA Netgen CSG file starts with"
                << " algebraic3d, defines solids and ends with"
                << " 'tlo <solid>;', e.g.\n    algebraic3d\n    solid"
                << " ball = sphere(0, 0, 0; 1);\n    tlo ball;",
            function
        );
    }
    is.clear();
    is.seekg(0);
}


//- The CSGeometry that Netgen's parser makes of a CSG file (never null).
netgen::CSGeometry* parseCsg
(
    std::istream& is,
    const netgenSession& session,
    const std::string& fileName,
    const char* function
)
{
    // The parser keeps its geometry in a file-static pointer and reports
    // syntax errors as NgException("Parsing error in line N: ...") after
    // printing them (captured)
    netgen::CSGeometry* g = nullptr;
    try
    {
        g = netgen::ParseCSG(is);
    }
    catch (const std::exception& e)
    {
        // The two usual causes of a missing ';': flags on a primitive
        // inside an expression ("plane(...) -bcname=inlet and ...") and a
        // name that is a keyword or primitive ("-bcname=sphere")
        const std::string text = exceptionText(e);
        const bool semicolon = text.find("token ';' expected") != std::string::npos;
        throw FatalError
        (
            msg()
                << "Cannot parse CSG geometry file \"" << fileName << "\": "
                << text
                << (
                       semicolon
                     ? ".\nFlags (-bc=N, -bcname=name, -maxh=h) go at the end"
                       " of a solid definition ('solid in = plane(...)"
                       " -bcname=inlet;'), not on primitives inside an"
                       " expression, and a name cannot be a Netgen keyword or"
                       " primitive (sphere, plane, cylinder, ...)"
                     : ""
                   ),
            function
        );
    }
    catch (...)
    {
        throw FatalError
        (
            msg()
                << "Cannot parse CSG geometry file \"" << fileName << "\""
                << session.tail(),
            function
        );
    }
    if (!g)
    {
        throw FatalError
        (
            msg()
                << "CSG geometry file \"" << fileName << "\" does not start"
                << " with the keyword algebraic3d",
            function
        );
    }
    return g;
}


//- Quirk: an unknown statement is only printed ("read unidentified
//  token") and skipped: treat it as the syntax error it is.
void rejectUnidentifiedTokens
(
    const netgenSession& session,
    const std::string& fileName,
    const char* function
)
{
    std::istringstream os(session.output());
    for (std::string line; std::getline(os, line); )
    {
        if (line.find("unidentified token") != std::string::npos)
        {
            throw FatalError
            (
                msg()
                    << "Cannot parse CSG geometry file \"" << fileName
                    << "\": Netgen " << oneLine(line)
                    << ".\nValid statements: solid, tlo, boundarycondition,"
                    << " boundaryconditionname, identify, singular, point,"
                    << " boundingbox, curve2d, curve3d, define",
                function
            );
        }
    }
}


//- A geometry without a top-level object has nothing to mesh.
void checkTopLevelObjects
(
    const netgen::CSGeometry& g,
    const std::string& fileName,
    const char* function
)
{
    if (g.GetNTopLevelObjects() == 0)
    {
        throw FatalError
        (
            msg()
                << "CSG geometry file \"" << fileName << "\" defines no"
                << " top-level object: add 'tlo <solid>;' for the solid to"
                << " mesh",
            function
        );
    }
}


//- Quirk: an unbounded solid (e.g. a cylinder not closed by planes)
//  reaches Netgen's bounding box (default [-1000, 1000]^3), and
//  GenerateMesh then meshes it at maxh until memory runs out. Sample the
//  bounding box faces.
void checkBounded
(
    const netgen::CSGeometry& g,
    const std::string& fileName,
    const char* function
)
{
    const netgen::Box<3>& box = g.BoundingBox();
    const netgen::Point<3> lo = box.PMin();
    const netgen::Point<3> hi = box.PMax();
    const int n = 8;
    for (int t = 0; t < g.GetNTopLevelObjects(); ++t)
    {
        const netgen::TopLevelObject* tlo = g.GetTopLevelObject(t);
        const netgen::Solid* solid = tlo->GetSolid();
        if (!solid || tlo->GetSurface())
        {
            continue;
        }
        for (int dir = 0; dir < 3; ++dir)
        {
            for (int side = 0; side < 2; ++side)
            {
                for (int a = 0; a <= n; ++a)
                {
                    for (int b = 0; b <= n; ++b)
                    {
                        const int d1 = (dir + 1) % 3;
                        const int d2 = (dir + 2) % 3;
                        netgen::Point<3> p;
                        p(dir) = side ? hi(dir) : lo(dir);
                        p(d1) = lo(d1) + (hi(d1) - lo(d1))*a/n;
                        p(d2) = lo(d2) + (hi(d2) - lo(d2))*b/n;
                        // Strictly: a solid may touch a user-given box
                        if (solid->IsStrictIn(p))
                        {
                            throw FatalError
                            (
                                msg()
                                    << "CSG geometry file \"" << fileName
                                    << "\": solid " << solid->Name()
                                    << " is not bounded: it reaches Netgen's"
                                    << " bounding box at (" << p(0) << ' '
                                    << p(1) << ' ' << p(2) << ").\nClose it,"
                                    << " e.g. intersect cylinders with planes"
                                    << " ('cylinder(...) and plane(...) and"
                                    << " plane(...)')",
                                function
                            );
                        }
                    }
                }
            }
        }
    }
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * * CSG model  * * * * * * * * * * * * * * * //

struct pmsh::ng::csgModel::impl
{
    netgen::CSGeometry* geometry = nullptr;

    ~impl()
    {
        std::lock_guard<std::mutex> lock(netgenMutex);
        delete geometry;
    }
};


pmsh::ng::csgModel::csgModel(const std::string& fileName)
:
    fileName_(fileName),
    impl_(new impl)
{
    const char* function = "pmsh::ng::csgModel::csgModel";

    std::ifstream is(fileName);
    if (!is.good())
    {
        throw FatalError
        (
            msg() << "Cannot open CSG geometry file \"" << fileName << '"',
            function
        );
    }
    checkAlgebraic3d(is, fileName, function);

    netgenSession session;

    // Owned from here on: deleted (under the lock) by impl if a check
    // below throws
    impl_->geometry = parseCsg(is, session, fileName, function);
    netgen::CSGeometry& g = *impl_->geometry;

    rejectUnidentifiedTokens(session, fileName, function);
    checkTopLevelObjects(g, fileName, function);

    // What CSGeometryRegister::Load does after parsing (not in the headers)
    g.FindIdenticSurfaces(1e-8*g.MaxSize());

    checkBounded(g, fileName, function);
}


pmsh::ng::csgModel::~csgModel() = default;


pmsh::label pmsh::ng::csgModel::nSurfaces() const
{
    return impl_->geometry->GetNSurf();
}


void pmsh::ng::csgModel::checkSurface(label s, const char* function) const
{
    if (s < 0 || s >= nSurfaces())
    {
        throw FatalError
        (
            msg()
                << "Surface " << s << " does not exist in CSG geometry \""
                << fileName_ << "\": valid surfaces are 0.." << nSurfaces() - 1,
            function
        );
    }
}


pmsh::ng::volumeMesh pmsh::ng::csgModel::generateMesh
(
    const meshParameters& parameters
) const
{
    const char* function = "pmsh::ng::csgModel::generateMesh";
    const std::string what = "CSG geometry \"" + fileName_ + "\"";

    netgenSession session;

    netgen::MeshingParameters mp;
    mp.maxh = parameters.maxh;
    mp.grading = parameters.grading;
    mp.optsteps3d = parameters.optimisationSteps;
    if (parameters.surfaceOnly)
    {
        mp.perfstepsend = netgen::MESHCONST_OPTSURFACE;
    }

    // Parts of the CSG mesher read the global mparam, not the argument
    netgen::mparam = mp;

    std::shared_ptr<netgen::Mesh> mesh;
    int rc = 0;
    try
    {
        const progressReport progress(session.console(), coarseProgressInterval);
        if (parameters.regions.empty() && parameters.sizePoints.empty())
        {
            rc = impl_->geometry->GenerateMesh(mesh, mp);
        }
        else
        {
            // Quirk: CSGGenerateMesh creates the local size tree in its
            // first step (analysis) and uses it from the edges on; only
            // points (mp.meshsize_points) can be added in between. So: stop
            // after the analysis, restrict the tree, and go on from the
            // edges (DeleteMesh in between keeps the tree)
            const auto end = mp.perfstepsend;
            mp.perfstepsend = netgen::MESHCONST_ANALYSE;
            rc = impl_->geometry->GenerateMesh(mesh, mp);
            if (rc == 0 && mesh && mesh->LocalHFunctionGenerated())
            {
                restrictLocalSizes(*mesh, parameters);
                mp.perfstepsstart = netgen::MESHCONST_MESHEDGES;
                mp.perfstepsend = end;
                netgen::mparam = mp;
                rc = impl_->geometry->GenerateMesh(mesh, mp);
            }
        }
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh " << what << " (maxCellSize "
                << parameters.maxh << "): " << exceptionText(e) << session.tail(),
            function
        );
    }

    // rc is 0 even when meshing stopped early: count the elements
    if
    (
        rc != 0 || !mesh || mesh->GetNSE() == 0
     || (!parameters.surfaceOnly && mesh->GetNE() == 0)
    )
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh " << what << " (maxCellSize "
                << parameters.maxh << "): return code " << rc << ", "
                << (mesh ? mesh->GetNE() : 0) << " tets, "
                << (mesh ? mesh->GetNSE() : 0) << " surface triangles"
                << session.tail(),
            function
        );
    }

    volumeMesh m = convertMesh(*mesh, what);

    m.periodic = periodicIdentifications(*impl_->geometry, *mesh);

    compactPoints(m);
    if (!parameters.surfaceOnly)
    {
        makeTetsPositive(m, what);
        checkBoundary(m, what);
    }

    // A CSG domain is a top-level object plus one (Netgen's face
    // descriptors number them so: csg/genmesh.cpp compares DomainIn() with
    // tlonr + 1)
    auto nameDomain = [&](label domain)
    {
        if (!m.domainNames.count(domain))
        {
            const netgen::TopLevelObject* tlo =
                impl_->geometry->GetTopLevelObject(int(domain) - 1);
            const netgen::Solid* solid = tlo ? tlo->GetSolid() : nullptr;
            m.domainNames[domain] = solid ? solid->Name() : "";
        }
    };
    for (const boundaryTriangle& b : m.boundary)
    {
        nameDomain(b.domain);
    }
    for (const boundaryTriangle& b : m.interfaces)
    {
        nameDomain(b.domain);
        nameDomain(b.otherDomain);
    }

    return m;
}


pmsh::point3 pmsh::ng::csgModel::projectToSurface(const point3& p, label s) const
{
    checkSurface(s, "pmsh::ng::csgModel::projectToSurface");

    // Surface::Project is virtual: Plane and Sphere project exactly, other
    // surfaces run a bounded Newton iteration on their implicit function.
    // No global state, so the result is a pure function of (p, s).
    netgen::Point<3> q(p[0], p[1], p[2]);
    impl_->geometry->GetSurface(s)->Project(q);
    return {q(0), q(1), q(2)};
}


pmsh::point3 pmsh::ng::csgModel::projectToEdge
(
    const point3& p,
    label s1,
    label s2
) const
{
    checkSurface(s1, "pmsh::ng::csgModel::projectToEdge");
    checkSurface(s2, "pmsh::ng::csgModel::projectToEdge");
    if (s1 == s2)
    {
        return projectToSurface(p, s1);
    }

    // At most 10 generalised Newton steps onto f1 = f2 = 0; pure. The
    // order of the two surfaces changes the last bits: fix it, so that
    // (s1, s2) and (s2, s1) give the same point
    if (s2 < s1)
    {
        std::swap(s1, s2);
    }
    netgen::Point<3> q(p[0], p[1], p[2]);
    netgen::ProjectToEdge
    (
        impl_->geometry->GetSurface(s1),
        impl_->geometry->GetSurface(s2),
        q
    );
    return {q(0), q(1), q(2)};
}

// ************************************************************************* //
