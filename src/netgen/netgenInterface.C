/*---------------------------------------------------------------------------*\
  pmshFoam: every contact with Netgen 6.2.1905 (see netgenInterface.H).

  Netgen quirks handled here, each commented where it is handled:
  - global state: netgen::mparam, stlparam, printmessage_importance,
    multithread, nglib's STL triangle/edge buffers, the CSG parser's static
    geometry: one mutex, and every global we rely on is set at every call;
  - output noise: Netgen prints to std::cout/cerr regardless of
    printmessage_importance; it is captured and quoted in error messages;
  - never call Ng_Init(): it points testout at a new file "test.out" in the
    working directory;
  - return codes lie (GenerateMesh, Ng_STL_GenerateSurfaceMesh and
    Ng_GenerateVolumeMesh return OK on failure): counts are checked;
  - failures arrive as C++ exceptions (netgen::NgException is a
    std::exception; the CSG scanner throws std::string internally);
  - Mesh::Compress() in MeshVolume renumbers points not used by an element;
  - Netgen's tets have det(p1-p0, p2-p0, p3-p0) < 0: two vertices swapped;
  - a face's normal points from DomainIn to DomainOut: faces whose
    DomainOut is the meshed domain are flipped;
  - ParseCSG is not declared in the installed headers, and on a file not
    starting with algebraic3d it returns nullptr and leaks: checked first;
  - CSGeometry::GetRefinement() allocates a new object on every call: it is
    not used (projection calls Surface::Project / ProjectToEdge directly);
  - nglib has no Ng_STL_DeleteGeometry: the STLGeometry is deleted here;
  - Ng_STL_AddEdge's buffer is never emptied (only Ng_STL_LoadGeometry
    resets it): edges go straight to STLGeometry::AddEdges instead;
  - without those edges Netgen's STL mesh ignores boundaries it sees no
    angle at (two coplanar solids);
  - a CSG bcname that is a keyword or primitive name (-bcname=sphere) is a
    syntax error (hinted at in the message, documented in csgGeometry.H);
  - an unbounded CSG solid makes GenerateMesh eat all memory: checked after
    parsing;
  - an unknown CSG statement is only printed ("read unidentified token")
    and skipped: turned into an error;
  - when the advancing front fails after the Delaunay fill ("Call remove
    problem"), MeshVolume leaves nearly every tet flagged fixed, and the
    volume optimisation then removes no cells (1.2-1.8x as many; which
    surfaces take that path depends on the point order: 1 of 7 partition
    surfaces at r = 3 and 3 of 96 at r = 2 in the tutorials): the flags are
    cleared before it;
  - local sizes (restrictLocalSizes): the local size tree exists only
    inside the meshing calls. CSGGenerateMesh creates it in its analysis
    step and accepts only points (meshsize_points) before the edges: it is
    run up to the analysis, restricted, and resumed from the edges.
    Ng_STL_MakeEdges creates it (always with grading 0.3) before lines and
    surface are meshed in Ng_STL_GenerateSurfaceMesh: it is restricted in
    between. RestrictLocalH ignores points outside the tree's box;
  - STL curvature sizing (stlparam.resthsurfcurvenable) is off by default
    and has no floor: pmshFoam's own (stlGeometry) comes as size points.
\*---------------------------------------------------------------------------*/

#include "netgenInterface.H"
#include "pmshError.H"
#include "tetFaceMatching.H"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

// Netgen's C++ headers. The build defines PARALLEL: netgen::Mesh has a
// member only under PARALLEL and a mismatch silently corrupts memory.
#include <mystdlib.h>
#include <meshing.hpp>
#include <csg.hpp>
#include <stlgeom.hpp>

// nglib.h defines DLL_HEADER again (empty) and its types clash with nothing
// once wrapped in a namespace, as nglib.cpp itself does.
#undef DLL_HEADER
namespace nglib
{
#include <nglib.h>
}

// Exported by libcsg but not declared in any installed header.
namespace netgen
{
    CSGeometry* ParseCSG(std::istream&, CSGeometry* instance = nullptr);
}


// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

//- Serialises every Netgen call in this process (Netgen is not
//  thread-safe: global parameters, static buffers, static locals).
std::mutex netgenMutex;


//- One Netgen call: holds the lock, silences and captures Netgen's output
//  and resets the globals every call relies on.
class netgenSession
{
    std::lock_guard<std::mutex> lock_;
    std::ostringstream captured_;
    std::streambuf* cout_;
    std::streambuf* cerr_;
    std::streambuf* clog_;

public:

    netgenSession()
    :
        lock_(netgenMutex)
    {
        // Default 5 prints progress for every step; 0 keeps only errors,
        // which still go to cout/cerr (captured below)
        netgen::printmessage_importance = 0;

        // A terminate flag left set (e.g. by an earlier exception) makes
        // the meshers stop at once and report success
        netgen::multithread.terminate = 0;

        // nglib's Transfer_Parameters overwrites only some fields of the
        // global mparam, and STL meshing reads the global stlparam: start
        // every call from the defaults, not from what the last call left
        netgen::mparam = netgen::MeshingParameters();
        netgen::stlparam = netgen::STLParameters();

        cout_ = std::cout.rdbuf(captured_.rdbuf());
        cerr_ = std::cerr.rdbuf(captured_.rdbuf());
        clog_ = std::clog.rdbuf(captured_.rdbuf());
    }

    ~netgenSession()
    {
        std::cout.rdbuf(cout_);
        std::cerr.rdbuf(cerr_);
        std::clog.rdbuf(clog_);
    }

    std::string output() const
    {
        return captured_.str();
    }

    //- Where std::cout went before the session captured it (the log).
    std::streambuf* console() const
    {
        return cout_;
    }

    //- The last nLines non-empty lines Netgen printed, indented, for an
    //  error message ("" when it printed nothing).
    std::string tail(std::size_t nLines = 8) const
    {
        std::vector<std::string> lines;
        std::istringstream is(captured_.str());
        for (std::string line; std::getline(is, line); )
        {
            if (line.find_first_not_of(" \t\r") != std::string::npos)
            {
                lines.push_back(line);
            }
        }
        if (lines.empty())
        {
            return "";
        }
        std::ostringstream os;
        os  << "\nNetgen's output (last lines):";
        const std::size_t first =
            lines.size() > nLines ? lines.size() - nLines : 0;
        for (std::size_t i = first; i < lines.size(); ++i)
        {
            os  << "\n    " << lines[i];
        }
        return os.str();
    }
};


//- Trim whitespace (Netgen's messages carry newlines).
std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
    {
        return "";
    }
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}


//- Collapse a multi-line Netgen message to one line.
std::string oneLine(const std::string& s)
{
    std::string r;
    bool space = false;
    for (char c : trim(s))
    {
        if (c == '\n' || c == '\r' || c == '\t' || c == ' ')
        {
            space = true;
        }
        else
        {
            if (space && !r.empty())
            {
                r += ' ';
            }
            r += c;
            space = false;
        }
    }
    return r;
}


double boundingBoxDiagonal(const std::vector<pmsh::point3>& points)
{
    if (points.empty())
    {
        return 0;
    }
    pmsh::point3 lo = points[0];
    pmsh::point3 hi = points[0];
    for (const auto& p : points)
    {
        for (int k = 0; k < 3; ++k)
        {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    return std::sqrt(pmsh::magSqr(hi - lo));
}


//- Make every tet positive (Netgen's come with det < 0); a flat tet is an
//  error, whatever Netgen thought of it.
void makeTetsPositive(pmsh::ng::volumeMesh& m, const std::string& what)
{
    using namespace pmsh;
    for (std::size_t i = 0; i < m.tets.size(); ++i)
    {
        tetVerts& t = m.tets[i];
        const double v6 = tetVolume6
        (
            m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]
        );
        if (v6 < 0)
        {
            std::swap(t[1], t[2]);
        }
        else if (!(v6 > 0))
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a flat tetrahedron (zero volume) when"
                    << " meshing " << what << ": tet " << i << " with points "
                    << str(m.points[t[0]]) << ' ' << str(m.points[t[1]]) << ' '
                    << str(m.points[t[2]]) << ' ' << str(m.points[t[3]]),
                "pmsh::ng::makeTetsPositive"
            );
        }
    }
}


//- Check the converted mesh: the boundary triangles are exactly the tet
//  faces on no other tet, each outward from its tet.
void checkBoundary(const pmsh::ng::volumeMesh& m, const std::string& what)
{
    using namespace pmsh;
    std::vector<triVerts> boundary(m.boundary.size());
    for (std::size_t b = 0; b < boundary.size(); ++b)
    {
        boundary[b] = m.boundary[b].v;
    }
    fittingTetFaces
    (
        m.points.size(), m.tets, boundary,
        "Netgen's mesh of " + what + " is inconsistent", "pmsh::ng::checkBoundary"
    );
}


//- Drop points used by no tet and no boundary or interface triangle and
//  renumber the rest in their order.
void compactPoints(pmsh::ng::volumeMesh& m)
{
    using namespace pmsh;
    std::vector<label> newIndex(m.points.size(), -1);
    for (const auto& t : m.tets)
    {
        for (label p : t)
        {
            newIndex[p] = 0;
        }
    }
    for (const auto* triangles : {&m.boundary, &m.interfaces})
    {
        for (const auto& b : *triangles)
        {
            for (label p : b.v)
            {
                newIndex[p] = 0;
            }
        }
    }
    label n = 0;
    std::vector<point3> points;
    for (std::size_t i = 0; i < m.points.size(); ++i)
    {
        if (newIndex[i] == 0)
        {
            newIndex[i] = n++;
            points.push_back(m.points[i]);
        }
    }
    if (std::size_t(n) == m.points.size())
    {
        return;
    }
    for (auto& t : m.tets)
    {
        for (label& p : t)
        {
            p = newIndex[p];
        }
    }
    for (auto* triangles : {&m.boundary, &m.interfaces})
    {
        for (auto& b : *triangles)
        {
            for (label& p : b.v)
            {
                p = newIndex[p];
            }
        }
    }
    for (auto& identification : m.periodic)
    {
        for (auto& pair : identification.points)
        {
            pair = {newIndex[pair[0]], newIndex[pair[1]]};
        }
    }
    m.points = std::move(points);
}


//- Points and elements of a Netgen C++ mesh, 0-based. Boundary triangles:
//  surface elements between a domain and the outside, flipped where
//  DomainOut is the domain (Netgen's normal points from DomainIn to
//  DomainOut). Faces between two domains are interfaces, as Netgen gives
//  them: out of DomainIn. Each tet keeps its domain (Element::GetIndex).
pmsh::ng::volumeMesh convertMesh(const netgen::Mesh& mesh, const std::string& what)
{
    using namespace pmsh;
    ng::volumeMesh m;

    const int np = int(mesh.GetNP());
    m.points.resize(np);
    for (int i = 1; i <= np; ++i)
    {
        const netgen::Point<3>& p = mesh.Point(netgen::PointIndex(i));
        m.points[i - 1] = {p(0), p(1), p(2)};
    }

    const int ne = int(mesh.GetNE());
    m.tets.reserve(ne);
    for (int i = 1; i <= ne; ++i)
    {
        const netgen::Element& el = mesh.VolumeElement(i);
        if (el.IsDeleted())
        {
            continue;
        }
        if (el.GetNP() != 4)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced an element with " << el.GetNP()
                    << " points when meshing " << what
                    << "; only linear tetrahedra are supported",
                "pmsh::ng::convertMesh"
            );
        }
        m.tets.push_back
        ({
            label(int(el.PNum(1))) - 1, label(int(el.PNum(2))) - 1,
            label(int(el.PNum(3))) - 1, label(int(el.PNum(4))) - 1
        });
        m.tetDomain.push_back(label(el.GetIndex()));
    }

    const int nse = int(mesh.GetNSE());
    for (int i = 1; i <= nse; ++i)
    {
        const netgen::Element2d& el = mesh.SurfaceElement(i);
        if (el.IsDeleted())
        {
            continue;
        }
        if (el.GetNP() != 3)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a surface element with " << el.GetNP()
                    << " points when meshing " << what
                    << "; only triangles are supported",
                "pmsh::ng::convertMesh"
            );
        }
        const netgen::FaceDescriptor& fd = mesh.GetFaceDescriptor(el.GetIndex());
        const bool inside = fd.DomainIn() > 0;
        const bool outside = fd.DomainOut() > 0;
        if (!inside && !outside)
        {
            continue;   // bounding no domain
        }
        ng::boundaryTriangle b;
        b.v =
        {
            label(int(el.PNum(1))) - 1,
            label(int(el.PNum(2))) - 1,
            label(int(el.PNum(3))) - 1
        };
        if (inside && outside)
        {
            // Between two domains
            b.bc = fd.BCProperty();
            b.surface = fd.SurfNr();
            b.domain = fd.DomainIn();
            b.otherDomain = fd.DomainOut();
            m.interfaces.push_back(b);
            continue;
        }
        if (outside)
        {
            // Normal points into the domain: flip
            std::swap(b.v[1], b.v[2]);
        }
        b.bc = fd.BCProperty();
        b.surface = fd.SurfNr();
        b.domain = inside ? fd.DomainIn() : fd.DomainOut();
        m.boundary.push_back(b);
        m.bcNames.emplace(b.bc, fd.GetBCName());
    }

    return m;
}


//- While Netgen works on a coarse mesh, which can take minutes (a
//  116k-triangle STL took 5 before failing), a log line every `every`
//  seconds with the task it is on and how far it is: Netgen publishes both
//  in netgen::multithread for its GUI to poll from another thread, which
//  is what this does. Written to the console the session took cout from.
//  Netgen's percentage can sit at 99% for minutes: given the mesh, the
//  line also counts its surface triangles and tets, which move. Given a
//  time limit, it sets netgen::multithread.terminate when the limit
//  passes: Netgen's meshing loops poll it and return (reporting success).
class progressReport
{
    std::ostream out_;
    const std::chrono::steady_clock::time_point start_;
    //- Read while Netgen adds to it (counts only: a stale count is fine)
    const netgen::Mesh* mesh_;
    const double timeLimit_;
    //- pmshFoam's step (Netgen's own task name is often empty)
    std::atomic<const char*> step_{nullptr};
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    bool timedOut_ = false;
    std::string taskAtTimeout_;
    std::thread thread_;

    double seconds() const
    {
        return std::chrono::duration<double>
        (
            std::chrono::steady_clock::now() - start_
        ).count();
    }

    //- Netgen's task and how far it is, e.g. "Surface meshing, 99%,
    //  5230 surface triangles".
    std::string state() const
    {
        // Read once: Netgen changes them as it goes
        const char* task = netgen::multithread.task;
        const double percent = netgen::multithread.percent;
        std::ostringstream os;
        const char* step = step_;
        if (step)
        {
            os << step << " (Netgen: " << (task && *task ? task : "working");
        }
        else
        {
            os << (task && *task ? task : "working");
        }
        if (percent > 0 && percent <= 100)
        {
            os << ", " << int(percent) << "%";
        }
        if (step)
        {
            os << ')';
        }
        if (mesh_)
        {
            os << ", " << mesh_->GetNSE() << " surface triangles";
            if (mesh_->GetNE())
            {
                os << ", " << mesh_->GetNE() << " tets";
            }
        }
        return os.str();
    }

    void run(std::chrono::seconds every)
    {
        std::unique_lock<std::mutex> lock(mutex_);
        auto nextReport = start_ + every;
        const auto deadline =
            timeLimit_ > 0
          ? start_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>
            (
                std::chrono::duration<double>(timeLimit_)
            )
          : std::chrono::steady_clock::time_point::max();
        while (!done_)
        {
            const auto until = std::min(nextReport, deadline);
            if (wake_.wait_until(lock, until, [this] { return done_; }))
            {
                break;
            }
            const auto now = std::chrono::steady_clock::now();
            if (now >= deadline && !timedOut_)
            {
                taskAtTimeout_ = state();
                timedOut_ = true;
                netgen::multithread.terminate = 1;
            }
            if (now >= nextReport)
            {
                out_
                    << "    Netgen, " << int(seconds()) << " s: " << state()
                    << std::endl;
                nextReport += every;
            }
        }
    }

public:

    progressReport
    (
        std::streambuf* console,
        std::chrono::seconds every,
        const netgen::Mesh* mesh = nullptr,
        double timeLimit = 0
    )
    :
        out_(console),
        start_(std::chrono::steady_clock::now()),
        mesh_(mesh),
        timeLimit_(timeLimit),
        thread_([this, every] { run(every); })
    {}

    ~progressReport()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        wake_.notify_one();
        thread_.join();
    }

    //- The step of pmshFoam's Netgen calls, for the progress lines.
    void step(const char* name)
    {
        step_ = name;
    }

    //- Whether the time limit passed (Netgen was told to stop), and what
    //  Netgen was doing then.
    bool timedOut()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return timedOut_;
    }

    std::string taskAtTimeout()
    {
        std::lock_guard<std::mutex> lock(mutex_);
        return taskAtTimeout_;
    }
};

//- A time in seconds for messages: "120 s", "0.5 s".
std::string secondsString(double seconds)
{
    std::ostringstream os;
    os << seconds << " s";
    return os.str();
}


//- How often a coarse mesh in the making is reported.
constexpr std::chrono::seconds coarseProgressInterval{15};


//- Delete an nglib mesh however the scope is left.
struct nglibMeshGuard
{
    nglib::Ng_Mesh* mesh;
    explicit nglibMeshGuard(nglib::Ng_Mesh* m) : mesh(m) {}
    ~nglibMeshGuard() { nglib::Ng_DeleteMesh(mesh); }
    nglibMeshGuard(const nglibMeshGuard&) = delete;
    nglibMeshGuard& operator=(const nglibMeshGuard&) = delete;
};


//- Points and tets of an nglib mesh, 0-based, through the C API.
void readNglibMesh
(
    nglib::Ng_Mesh* mesh,
    pmsh::ng::volumeMesh& m,
    const std::string& what
)
{
    using namespace pmsh;
    const int np = nglib::Ng_GetNP(mesh);
    m.points.resize(np);
    for (int i = 1; i <= np; ++i)
    {
        double x[3];
        nglib::Ng_GetPoint(mesh, i, x);
        m.points[i - 1] = {x[0], x[1], x[2]};
    }

    const int ne = nglib::Ng_GetNE(mesh);
    m.tets.resize(ne);
    for (int i = 1; i <= ne; ++i)
    {
        int pi[NG_VOLUME_ELEMENT_MAXPOINTS];
        if (nglib::Ng_GetVolumeElement(mesh, i, pi) != nglib::NG_TET)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a volume element that is not a linear"
                    << " tetrahedron when meshing " << what,
                "pmsh::ng::readNglibMesh"
            );
        }
        m.tets[i - 1] = {pi[0] - 1, pi[1] - 1, pi[2] - 1, pi[3] - 1};
    }
}


//- Netgen's exception text, one line.
std::string exceptionText(const std::exception& e)
{
    const std::string s = oneLine(e.what());
    return s.empty() ? std::string("(no message)") : s;
}


//- Restrict the local mesh size of mesh (its tree must exist) by the local
//  sizes of the parameters: at every size point, and on a grid of spacing
//  region.size inside every region (the tree's boxes there become that
//  small; samples outside the tree's box are ignored by Netgen anyway, so
//  only the part of a region inside it is sampled). Sizes not below maxh
//  change nothing and are skipped.
void restrictLocalSizes(netgen::Mesh& mesh, const pmsh::ng::meshParameters& p)
{
    using namespace pmsh;
    for (const sizePoint& s : p.sizePoints)
    {
        if (s.size < p.maxh)
        {
            mesh.RestrictLocalH(netgen::Point3d(s.p[0], s.p[1], s.p[2]), s.size);
        }
    }
    if (p.regions.empty())
    {
        return;
    }
    const netgen::Box<3>& box = mesh.LocalHFunction().GetBoundingBox();
    const point3 lo{box.PMin()(0), box.PMin()(1), box.PMin()(2)};
    const point3 hi{box.PMax()(0), box.PMax()(1), box.PMax()(2)};
    for (const sizeRegion& r : p.regions)
    {
        if (r.size < p.maxh)
        {
            forEachSample
            (
                r, lo, hi,
                [&](const point3& x)
                {
                    mesh.RestrictLocalH(netgen::Point3d(x[0], x[1], x[2]), r.size);
                }
            );
        }
    }
}


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

    // Check the keyword ourselves: on a file without it ParseCSG returns
    // nullptr and leaks the CSGeometry it has just allocated. Netgen's
    // scanner skips whitespace and '#' comment lines first, and so do we.
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

    netgenSession session;

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
    impl_->geometry = g;

    // An unknown statement is only printed ("read unidentified token") and
    // skipped: treat it as the syntax error it is
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

    if (g->GetNTopLevelObjects() == 0)
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

    // What CSGeometryRegister::Load does after parsing (not in the headers)
    g->FindIdenticSurfaces(1e-8*g->MaxSize());

    // An unbounded solid (e.g. a cylinder not closed by planes) reaches
    // Netgen's bounding box (default [-1000, 1000]^3), and GenerateMesh then
    // meshes it at maxh until memory runs out. Sample the bounding box faces.
    const netgen::Box<3>& box = g->BoundingBox();
    const netgen::Point<3> lo = box.PMin();
    const netgen::Point<3> hi = box.PMax();
    const int n = 8;
    for (int t = 0; t < g->GetNTopLevelObjects(); ++t)
    {
        const netgen::TopLevelObject* tlo = g->GetTopLevelObject(t);
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


// * * * * * * * * * * * * * * * STL coarse mesh  * * * * * * * * * * * * * //

pmsh::ng::volumeMesh pmsh::ng::stlVolumeMesh
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const std::vector<std::array<label, 2>>& featureEdges,
    const meshParameters& parameters,
    const std::string& what
)
{
    const char* function = "pmsh::ng::stlVolumeMesh";

    netgenSession session;

    // stlparam (edge angles, curvature-based size restrictions) is at its
    // defaults (netgenSession): yangle 30 degrees, as stlGeometry's
    // featureAngle; our feature edges are passed as user edges anyway

    // nglib has no Ng_STL_DeleteGeometry; the object is a netgen::STLGeometry
    std::unique_ptr<netgen::STLGeometry> geometry
    (
        reinterpret_cast<netgen::STLGeometry*>(nglib::Ng_STL_NewGeometry())
    );
    nglib::Ng_STL_Geometry* geo =
        reinterpret_cast<nglib::Ng_STL_Geometry*>(geometry.get());

    // Ng_STL_AddTriangle appends to a file-global buffer that only
    // Ng_STL_InitSTLGeometry empties: nothing in between may throw.
    // Triangles are expected with positive (outward) orientation.
    for (const triVerts& t : triangles)
    {
        double p[3][3];
        for (int k = 0; k < 3; ++k)
        {
            for (int j = 0; j < 3; ++j)
            {
                p[k][j] = points[t[k]][j];
            }
        }
        const vector3 n = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
        double nv[3] = {n[0], n[1], n[2]};
        nglib::Ng_STL_AddTriangle(geo, p[0], p[1], p[2], nv);
    }

    nglib::Ng_Result rc = nglib::NG_OK;
    try
    {
        rc = nglib::Ng_STL_InitSTLGeometry(geo);
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg()
                << "Netgen cannot read " << what << ": " << exceptionText(e)
                << session.tail(),
            function
        );
    }
    if (rc != nglib::NG_OK)
    {
        throw FatalError
        (
            msg()
                << "Netgen rejects " << what << " (its STL check failed,"
                << " code " << int(rc) << ")" << session.tail(),
            function
        );
    }

    // Feature edges, confirmed as edges Netgen's surface mesh must follow
    // (without them it ignores, e.g., the boundary between two coplanar
    // solids). Not through Ng_STL_AddEdge: its file-global buffer is never
    // emptied, so every later geometry would get this one's edges too, fail
    // to find their points and then drop all of its own edges. Init does
    // exactly this call with that buffer.
    if (!featureEdges.empty())
    {
        netgen::Array<netgen::Point<3>> ends;
        for (const auto& e : featureEdges)
        {
            for (label v : e)
            {
                ends.Append(netgen::Point<3>(points[v][0], points[v][1], points[v][2]));
            }
        }
        geometry->AddEdges(ends);

        // AddEdges reports unmatched end points only by printing, and then
        // adds no edge at all
        const std::string out = session.output();
        if
        (
            out.find("edgepoint does not exist") != std::string::npos
         || out.find("too much points") != std::string::npos
        )
        {
            throw FatalError
            (
                msg()
                    << "Netgen did not accept the feature edges of " << what
                    << " (points closer than 1e-10 of its size?)"
                    << session.tail(),
                function
            );
        }
    }

    nglibMeshGuard guard(nglib::Ng_NewMesh());
    nglib::Ng_Mesh* mesh = guard.mesh;

    nglib::Ng_Meshing_Parameters mp;
    mp.maxh = parameters.maxh;
    mp.grading = parameters.grading;
    mp.optsteps_3d = parameters.optimisationSteps;

    const char* step = "finding edges";
    progressReport progress
    (
        session.console(), coarseProgressInterval,
        reinterpret_cast<const netgen::Mesh*>(mesh), parameters.timeLimit
    );
    // Netgen stopped by the time limit returns as if it had finished
    auto checkTime = [&]()
    {
        if (progress.timedOut())
        {
            throw stlMeshingTimeout
            (
                msg()
                    << "Netgen did not finish " << step << " of " << what
                    << " within " << parameters.timeLimit << " s",
                function,
                "stopped at the time limit of " + secondsString(parameters.timeLimit)
              + " while " + progress.taskAtTimeout()
            );
        }
    };
    try
    {
        progress.step(step);
        nglib::Ng_STL_MakeEdges(geo, mesh, &mp);
        checkTime();

        // Ng_STL_MakeEdges creates the local size tree (with grading 0.3,
        // whatever mp.grading says) and builds the charts; lines and
        // surface are meshed in Ng_STL_GenerateSurfaceMesh, from the tree
        // as restricted here
        restrictLocalSizes(*reinterpret_cast<netgen::Mesh*>(mesh), parameters);

        step = "meshing the surface";
        progress.step(step);
        nglib::Ng_STL_GenerateSurfaceMesh(geo, mesh, &mp);
        checkTime();

        // Always NG_OK: count the triangles instead
        if (nglib::Ng_GetNSE(mesh) == 0)
        {
            throw stlMeshingFailure
            (
                msg()
                    << "Netgen failed to mesh the surface of " << what
                    << " (maxCellSize " << parameters.maxh << "): no surface"
                    << " triangles" << session.tail(),
                function,
                "meshing the surface: no surface triangles"
            );
        }

        if (!parameters.surfaceOnly)
        {
            step = "meshing the volume";
            progress.step(step);
            nglib::Ng_GenerateVolumeMesh(mesh, &mp);
            checkTime();
        }
    }
    catch (const FatalError&)
    {
        throw;
    }
    catch (const std::exception& e)
    {
        // What Netgen throws once told to stop is not the reason
        checkTime();
        // E.g. "Stop meshing since boundary mesh is overlapping": the
        // surface mesh's chords of a thin curved wall cross the other side
        // (stlGeometry retries with smaller sizes)
        throw stlMeshingFailure
        (
            msg()
                << "Netgen failed " << step << " of " << what
                << " (maxCellSize " << parameters.maxh << "): "
                << exceptionText(e) << session.tail(),
            function,
            std::string(step) + ": " + exceptionText(e)
        );
    }

    // Always NG_OK: count the tets instead
    if (!parameters.surfaceOnly && nglib::Ng_GetNE(mesh) == 0)
    {
        throw stlMeshingFailure
        (
            msg()
                << "Netgen failed to mesh the volume of " << what
                << " (maxCellSize " << parameters.maxh << "): no tets"
                << session.tail(),
            function,
            "meshing the volume: no tets"
        );
    }

    volumeMesh m;
    readNglibMesh(mesh, m, what);

    // Every STL face descriptor has DomainIn 1 and DomainOut 0, so the
    // surface triangles already point out of the domain (checkBoundary
    // below verifies it against the tets)
    const int nse = nglib::Ng_GetNSE(mesh);
    m.boundary.resize(nse);
    for (int i = 1; i <= nse; ++i)
    {
        int pi[NG_SURFACE_ELEMENT_MAXPOINTS];
        if (nglib::Ng_GetSurfaceElement(mesh, i, pi) != nglib::NG_TRIG)
        {
            throw FatalError
            (
                msg()
                    << "Netgen produced a surface element that is not a"
                    << " triangle when meshing " << what,
                function
            );
        }
        m.boundary[i - 1] = {{pi[0] - 1, pi[1] - 1, pi[2] - 1}, 1, -1};
    }
    m.bcNames[1] = "default";

    compactPoints(m);
    if (!parameters.surfaceOnly)
    {
        makeTetsPositive(m, what);
        checkBoundary(m, what);
    }

    return m;
}


// * * * * * * * * * * * * * Volume of a closed surface  * * * * * * * * * * //

pmsh::ng::volumeMesh pmsh::ng::surfaceVolumeMesh
(
    const std::vector<point3>& points,
    const std::vector<triVerts>& triangles,
    const meshParameters& parameters,
    const std::string& what
)
{
    const char* function = "pmsh::ng::surfaceVolumeMesh";
    const label nPoints = label(points.size());

    // An element larger than the domain is meaningless, and Netgen's local
    // size tree does not need 1e300
    const double diagonal = boundingBoxDiagonal(points);
    meshParameters p = parameters;
    if (!(p.maxh < diagonal))
    {
        p.maxh = diagonal;
    }

    netgenSession session;

    nglibMeshGuard guard(nglib::Ng_NewMesh());
    nglib::Ng_Mesh* mesh = guard.mesh;

    for (const point3& x : points)
    {
        double xyz[3] = {x[0], x[1], x[2]};
        nglib::Ng_AddPoint(mesh, xyz);
    }
    for (const triVerts& t : triangles)
    {
        // 1-based; Ng_NewMesh's face descriptor has DomainIn 1, DomainOut 0:
        // triangles must point outward (right-hand rule)
        int pi[3] = {int(t[0] + 1), int(t[1] + 1), int(t[2] + 1)};
        nglib::Ng_AddSurfaceElement(mesh, nglib::NG_TRIG, pi);
    }

    // Transfer_Parameters copies these into the global netgen::mparam;
    // fineness, closeedge*, minedgelen* and opt*meshenable are ignored
    nglib::Ng_Meshing_Parameters mp;
    mp.maxh = p.maxh;
    mp.grading = p.grading;
    mp.optsteps_3d = p.optimisationSteps;

    try
    {
        // Ng_GenerateVolumeMesh's steps, with the fixed flags cleared
        // before the optimisation. Failures are exceptions, e.g. "Stop
        // meshing since surface mesh not consistent" (open or badly
        // oriented) or "Stop meshing since too many attempts" (inverted)
        mp.Transfer_Parameters();
        netgen::Mesh& volume = *reinterpret_cast<netgen::Mesh*>(mesh);
        volume.CalcLocalH(netgen::mparam.grading);
        restrictLocalSizes(volume, p);
        netgen::MeshVolume(netgen::mparam, volume);
        netgen::RemoveIllegalElements(volume);
        for (netgen::Element& tet : volume.VolumeElements())
        {
            // Quirk: left set by MeshVolume's failure path ("Call remove
            // problem": FreeOpenElementsEnvironment), they stop the
            // optimiser from touching the tet
            tet.flags.fixed = false;
        }
        netgen::OptimizeVolume(netgen::mparam, volume);
    }
    catch (const std::exception& e)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what << " ("
                << nPoints << " points, " << triangles.size()
                << " triangles): " << exceptionText(e) << session.tail(),
            function
        );
    }
    catch (...)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what
                << " with an unknown exception" << session.tail(),
            function
        );
    }

    // Ng_GenerateVolumeMesh's steps report no failure but an empty mesh
    if (nglib::Ng_GetNE(mesh) == 0)
    {
        throw FatalError
        (
            msg()
                << "Netgen failed to mesh the volume of " << what << ": no tets"
                << session.tail(),
            function
        );
    }

    // The contract (surface points kept in place and in order, the surface
    // triangles faces of the tets) is VolumeMesher::mesh's to check
    volumeMesh m;
    readNglibMesh(mesh, m, what);
    makeTetsPositive(m, what);

    return m;
}


std::string pmsh::ng::currentTask()
{
    // Read once: Netgen changes them as it goes
    const char* task = netgen::multithread.task;
    const double percent = netgen::multithread.percent;
    std::string text = task && *task ? task : "";
    if (!text.empty() && percent > 0 && percent <= 100)
    {
        text += ", " + std::to_string(int(percent)) + "%";
    }
    return text;
}


// ************************************************************************* //
