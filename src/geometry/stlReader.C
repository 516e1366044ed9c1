/*---------------------------------------------------------------------------*\
  pmshFoam: reading and checking STL files (see stlReader.H).
\*---------------------------------------------------------------------------*/

#include "stlReader.H"
#include "surfaceTopology.H"
#include "pmshError.H"
#include "triangleGeometry.H"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <map>
#include <set>
#include <unordered_map>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

// STL coordinates in messages: enough digits to find the facet in the file
std::string stlPoint(const point3& p)
{
    return str(p, 10);
}


//- Characters OpenFOAM does not accept in a word (a patch name).
bool validWordChar(char c)
{
    return !std::isspace(static_cast<unsigned char>(c))
        && c != '"' && c != '\'' && c != '/' && c != ';'
        && c != '{' && c != '}' && c != '\\';
}


std::string sanitise(const std::string& name)
{
    std::string r;
    for (char c : name)
    {
        if (validWordChar(c))
        {
            r += c;
        }
    }
    return r;
}


//- Exact-coordinate key of a point: equal keys <=> equal coordinates
//  (after +0.0 folds -0.0 into 0.0).
struct pointKey
{
    std::uint64_t bits[3];

    explicit pointKey(const point3& p)
    {
        for (int k = 0; k < 3; ++k)
        {
            const double x = p[k] + 0.0;
            std::memcpy(&bits[k], &x, sizeof(double));
        }
    }

    bool operator==(const pointKey& o) const
    {
        return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
    }
};


struct pointKeyHash
{
    std::size_t operator()(const pointKey& k) const
    {
        std::uint64_t h = 0x9e3779b97f4a7c15ull;
        for (std::uint64_t b : k.bits)
        {
            h ^= b + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
        }
        return std::size_t(h);
    }
};


//- Builds an stlSurface: merges points and names solids.
class surfaceBuilder
{
    stlSurface& s_;
    std::unordered_map<pointKey, label, pointKeyHash> pointIndex_;
    std::string stem_;

public:

    surfaceBuilder(stlSurface& s, const std::string& stem)
    :
        s_(s),
        stem_(stem)
    {}

    label addSolid(const std::string& rawName)
    {
        std::string name = sanitise(rawName);
        if (name.empty())
        {
            name = stem_;
        }
        const auto it = std::find(s_.solidNames.begin(), s_.solidNames.end(), name);
        if (it != s_.solidNames.end())
        {
            return label(it - s_.solidNames.begin());
        }
        s_.solidNames.push_back(name);
        return label(s_.solidNames.size()) - 1;
    }

    label addPoint(const point3& p)
    {
        const point3 q{p[0] + 0.0, p[1] + 0.0, p[2] + 0.0};
        const auto ins = pointIndex_.emplace(pointKey(q), label(s_.points.size()));
        if (ins.second)
        {
            s_.points.push_back(q);
        }
        return ins.first->second;
    }

    void addTriangle(const point3& a, const point3& b, const point3& c, label solid)
    {
        s_.triangles.push_back({addPoint(a), addPoint(b), addPoint(c)});
        s_.solid.push_back(solid);
    }
};


//- A cursor over an ascii STL buffer that knows its line number.
class asciiScanner
{
    const std::string& buf_;
    const std::string& fileName_;
    std::size_t pos_ = 0;
    label line_ = 1;

public:

    asciiScanner(const std::string& buf, const std::string& fileName)
    :
        buf_(buf),
        fileName_(fileName)
    {}

    void skipSpace()
    {
        while (pos_ < buf_.size() && std::isspace(static_cast<unsigned char>(buf_[pos_])))
        {
            if (buf_[pos_] == '\n')
            {
                ++line_;
            }
            ++pos_;
        }
    }

    bool atEnd()
    {
        skipSpace();
        return pos_ >= buf_.size();
    }

    std::string word()
    {
        skipSpace();
        const std::size_t start = pos_;
        while (pos_ < buf_.size() && !std::isspace(static_cast<unsigned char>(buf_[pos_])))
        {
            ++pos_;
        }
        return buf_.substr(start, pos_ - start);
    }

    //- The rest of the current line, trimmed (the solid name).
    std::string restOfLine()
    {
        const std::size_t start = pos_;
        while (pos_ < buf_.size() && buf_[pos_] != '\n')
        {
            ++pos_;
        }
        std::string r = buf_.substr(start, pos_ - start);
        const auto b = r.find_first_not_of(" \t\r");
        if (b == std::string::npos)
        {
            return "";
        }
        const auto e = r.find_last_not_of(" \t\r");
        return r.substr(b, e - b + 1);
    }

    [[noreturn]] void error(const std::string& what) const
    {
        throw FatalError
        (
            msg()
                << "Cannot read ascii STL file \"" << fileName_ << "\" at line "
                << line_ << ": " << what,
            "pmsh::readStl"
        );
    }

    static bool same(const std::string& a, const char* b)
    {
        const std::size_t n = std::strlen(b);
        if (a.size() != n)
        {
            return false;
        }
        for (std::size_t i = 0; i < n; ++i)
        {
            if (std::tolower(static_cast<unsigned char>(a[i])) != b[i])
            {
                return false;
            }
        }
        return true;
    }

    void expect(const char* keyword)
    {
        const std::string w = word();
        if (!same(w, keyword))
        {
            error
            (
                std::string("expected '") + keyword + "', found '"
              + (w.empty() ? std::string("end of file") : w) + "'"
            );
        }
    }

    double number()
    {
        std::string w = word();
        const char* first = w.data();
        const char* last = w.data() + w.size();
        if (first != last && *first == '+')
        {
            ++first;
        }
        double x = 0;
        const auto r = std::from_chars(first, last, x);
        if (w.empty() || r.ec != std::errc() || r.ptr != last || !std::isfinite(x))
        {
            error("expected a number, found '" + (w.empty() ? std::string("end of file") : w) + "'");
        }
        return x;
    }

    point3 vertex()
    {
        expect("vertex");
        point3 p;
        p[0] = number();
        p[1] = number();
        p[2] = number();
        return p;
    }
};


void readAscii(const std::string& buf, const std::string& fileName, surfaceBuilder& b)
{
    asciiScanner scan(buf, fileName);
    while (!scan.atEnd())
    {
        scan.expect("solid");
        const label solid = b.addSolid(scan.restOfLine());
        while (true)
        {
            if (scan.atEnd())
            {
                // A missing endsolid is common enough to forgive
                return;
            }
            const std::string w = scan.word();
            if (asciiScanner::same(w, "endsolid"))
            {
                scan.restOfLine();
                break;
            }
            if (!asciiScanner::same(w, "facet"))
            {
                scan.error("expected 'facet' or 'endsolid', found '" + w + "'");
            }
            // The normal is ignored: orientation is the vertex order
            scan.expect("normal");
            scan.number();
            scan.number();
            scan.number();
            scan.expect("outer");
            scan.expect("loop");
            const point3 p0 = scan.vertex();
            const point3 p1 = scan.vertex();
            const point3 p2 = scan.vertex();
            const std::string e = scan.word();
            if (asciiScanner::same(e, "vertex"))
            {
                scan.error("facet with more than 3 vertices (STL facets are triangles)");
            }
            if (!asciiScanner::same(e, "endloop"))
            {
                scan.error("expected 'endloop', found '" + e + "'");
            }
            scan.expect("endfacet");
            b.addTriangle(p0, p1, p2, solid);
        }
    }
}


void readBinary
(
    const std::string& buf,
    const std::string& fileName,
    std::uint32_t n,
    surfaceBuilder& b
)
{
    const label solid = b.addSolid("");
    for (std::uint32_t i = 0; i < n; ++i)
    {
        // 12 little-endian floats (normal, 3 vertices) and a 2-byte attribute
        const char* rec = buf.data() + 84 + 50*std::size_t(i);
        float f[12];
        std::memcpy(f, rec, sizeof(f));
        point3 p[3];
        for (int k = 0; k < 3; ++k)
        {
            for (int j = 0; j < 3; ++j)
            {
                p[k][j] = double(f[3 + 3*k + j]);
                if (!std::isfinite(p[k][j]))
                {
                    throw FatalError
                    (
                        msg()
                            << "Binary STL file \"" << fileName << "\": triangle "
                            << i << " has a coordinate that is not a finite number",
                        "pmsh::readStl"
                    );
                }
            }
        }
        b.addTriangle(p[0], p[1], p[2], solid);
    }
}


//- Whether the buffer is plain text starting with "solid".
bool looksAscii(const std::string& buf)
{
    const std::size_t b = buf.find_first_not_of(" \t\r\n");
    if (b == std::string::npos || buf.compare(b, 5, "solid") != 0)
    {
        return false;
    }
    for (char c : buf)
    {
        const unsigned char u = static_cast<unsigned char>(c);
        if (u >= 0x7f || (u < 0x20 && !std::isspace(u)))
        {
            return false;
        }
    }
    return true;
}


std::string edgeString(const stlSurface& s, label a, label b)
{
    return stlPoint(s.points[a]) + "-" + stlPoint(s.points[b]);
}


//- The solids of a set of triangles, for messages: "solid a" or
//  "solids a, b".
std::string solidsOf(const stlSurface& s, const std::vector<label>& triangles)
{
    std::vector<label> solids;
    for (label t : triangles)
    {
        solids.push_back(s.solid[t]);
    }
    std::sort(solids.begin(), solids.end());
    solids.erase(std::unique(solids.begin(), solids.end()), solids.end());
    std::string names;
    for (label solid : solids)
    {
        names += (names.empty() ? "" : ", ") + s.solidNames[solid];
    }
    return (solids.size() > 1 ? "solids " : "solid ") + names;
}


//- What to do about surfaces that touch: Netgen cannot mesh a gap of zero
//  width, and stops with a message that names no solid.
const char* touchingAdvice =
    "Netgen needs the closed surfaces of a domain to be apart (it would stop"
    " with \"edgepoint does not exist\" or an overlapping boundary mesh)."
    " Either join the touching solids into one closed surface (their union,"
    " e.g. the desk's legs and top as one surface, or a leg and the floor it"
    " stands on with the shared part removed), or move them apart by at"
    " least a coarse cell (maxCellSize), e.g. lift the desk off the floor";


//- Sheets: the triangles connected across edges that exactly two
//  triangles share. On a closed manifold surface a sheet is a shell;
//  shells that touch at a point share it but stay separate sheets.
std::vector<label> manifoldSheets(const stlSurface& s, label& nSheets)
{
    const label nt = s.nTriangles();
    std::vector<label> parent(nt);
    for (label t = 0; t < nt; ++t)
    {
        parent[t] = t;
    }
    auto root = [&parent](label i)
    {
        while (parent[i] != i)
        {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    };

    // (lower point, higher point, triangle), grouped by edge
    std::vector<std::array<label, 3>> edges;
    edges.reserve(3*nt);
    for (label t = 0; t < nt; ++t)
    {
        const triVerts& f = s.triangles[t];
        for (int k = 0; k < 3; ++k)
        {
            const label a = f[k], b = f[(k + 1) % 3];
            edges.push_back({std::min(a, b), std::max(a, b), t});
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();)
    {
        std::size_t j = i + 1;
        while
        (
            j < edges.size() && edges[j][0] == edges[i][0]
         && edges[j][1] == edges[i][1]
        )
        {
            ++j;
        }
        if (j - i == 2)
        {
            const label a = root(edges[i][2]), b = root(edges[i + 1][2]);
            if (a != b)
            {
                parent[std::max(a, b)] = std::min(a, b);
            }
        }
        i = j;
    }

    std::unordered_map<label, label> sheetOfRoot;
    std::vector<label> sheet(nt);
    for (label t = 0; t < nt; ++t)
    {
        sheet[t] = sheetOfRoot.emplace(root(t), label(sheetOfRoot.size())).first->second;
    }
    nSheets = label(sheetOfRoot.size());
    return sheet;
}


//- Where two sheets touch: the first contact found, and how.
struct sheetContact
{
    label sheetA = -1, sheetB = -1;
    point3 where{0, 0, 0};
    std::string how;
};


//- Triangles of different sheets that share a point or come within tol of
//  each other (overlapping coplanar faces, a leg on a floor, crossing
//  surfaces): candidates from a grid of about twice the typical triangle
//  size, each pair tested once, in the cell of its boxes' lower corner.
//  Calls found(contact) for each pair of sheets that touch, once.
template<class Found>
void findSheetContacts
(
    const stlSurface& s,
    const std::vector<label>& sheet,
    double tol,
    const Found& found
)
{
    const label nt = s.nTriangles();
    std::set<std::pair<label, label>> reported;
    auto report = [&](label a, label b, const point3& x, const std::string& how)
    {
        const std::pair<label, label> key{std::min(a, b), std::max(a, b)};
        if (reported.insert(key).second)
        {
            found(sheetContact{key.first, key.second, x, how});
        }
    };

    // A point used by two sheets
    std::vector<label> pointSheet(s.points.size(), -1);
    for (label t = 0; t < nt; ++t)
    {
        for (label v : s.triangles[t])
        {
            if (pointSheet[v] < 0)
            {
                pointSheet[v] = sheet[t];
            }
            else if (pointSheet[v] != sheet[t])
            {
                report(pointSheet[v], sheet[t], s.points[v], "share the point");
            }
        }
    }

    // Boxes, grown by tol
    std::vector<point3> lo(nt), hi(nt);
    std::vector<double> extent(nt);
    for (label t = 0; t < nt; ++t)
    {
        const triVerts& f = s.triangles[t];
        lo[t] = hi[t] = s.points[f[0]];
        for (label v : f)
        {
            for (int k = 0; k < 3; ++k)
            {
                lo[t][k] = std::min(lo[t][k], s.points[v][k] - tol);
                hi[t][k] = std::max(hi[t][k], s.points[v][k] + tol);
            }
        }
        extent[t] = std::max({hi[t][0] - lo[t][0], hi[t][1] - lo[t][1], hi[t][2] - lo[t][2]});
    }
    if (nt < 2)
    {
        return;
    }
    std::vector<double> sorted(extent);
    std::nth_element(sorted.begin(), sorted.begin() + nt/2, sorted.end());
    const double cell = 2*sorted[nt/2];

    auto overlap = [&](label a, label b)
    {
        for (int k = 0; k < 3; ++k)
        {
            if (lo[a][k] > hi[b][k] || lo[b][k] > hi[a][k])
            {
                return false;
            }
        }
        return true;
    };
    auto test = [&](label a, label b)
    {
        if (sheet[a] == sheet[b] || !overlap(a, b))
        {
            return;
        }
        const std::pair<label, label> key
        {
            std::min(sheet[a], sheet[b]), std::max(sheet[a], sheet[b])
        };
        if (reported.count(key))
        {
            return;
        }
        point3 ta[3], tb[3];
        for (int k = 0; k < 3; ++k)
        {
            ta[k] = s.points[s.triangles[a][k]];
            tb[k] = s.points[s.triangles[b][k]];
        }
        point3 where;
        if (trianglesTouch(ta, tb, tol, where))
        {
            report(sheet[a], sheet[b], where, "touch or overlap");
        }
    };

    // Triangles far larger than the cells (a box's faces) are tested
    // against every other triangle whose box meets theirs
    using cellKey = std::array<long long, 3>;
    auto cellOf = [cell](const point3& p)
    {
        return cellKey
        {
            (long long)std::floor(p[0]/cell), (long long)std::floor(p[1]/cell),
            (long long)std::floor(p[2]/cell)
        };
    };
    constexpr long long maxCells = 512;
    std::map<cellKey, std::vector<label>> grid;
    std::vector<label> large;
    for (label t = 0; t < nt; ++t)
    {
        const cellKey a = cellOf(lo[t]), b = cellOf(hi[t]);
        const long long n =
            (b[0] - a[0] + 1)*(b[1] - a[1] + 1)*(b[2] - a[2] + 1);
        if (!(cell > 0) || n > maxCells)
        {
            large.push_back(t);
            continue;
        }
        for (long long i = a[0]; i <= b[0]; ++i)
            for (long long j = a[1]; j <= b[1]; ++j)
                for (long long k = a[2]; k <= b[2]; ++k)
                    grid[{i, j, k}].push_back(t);
    }
    std::vector<char> isLarge(nt, 0);
    for (label t : large)
    {
        isLarge[t] = 1;
        for (label u = 0; u < nt; ++u)
        {
            if (u != t && !(isLarge[u] && u < t))
            {
                test(t, u);
            }
        }
    }
    for (const auto& c : grid)
    {
        const std::vector<label>& in = c.second;
        for (std::size_t i = 0; i < in.size(); ++i)
        {
            for (std::size_t j = i + 1; j < in.size(); ++j)
            {
                const label a = in[i], b = in[j];
                // Once per pair: in the cell of their common box's lower corner
                point3 corner;
                for (int k = 0; k < 3; ++k)
                {
                    corner[k] = std::max(lo[a][k], lo[b][k]);
                }
                if (cellOf(corner) == c.first)
                {
                    test(a, b);
                }
            }
        }
    }
}

} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

std::string pmsh::fileStem(const std::string& fileName)
{
    const std::size_t slash = fileName.find_last_of('/');
    std::string name =
        slash == std::string::npos ? fileName : fileName.substr(slash + 1);
    const std::size_t dot = name.find_last_of('.');
    if (dot != std::string::npos && dot > 0)
    {
        name = name.substr(0, dot);
    }
    return name;
}


pmsh::stlSurface pmsh::readStl(const std::string& fileName)
{
    const char* function = "pmsh::readStl";

    std::ifstream is(fileName, std::ios::binary);
    if (!is.good())
    {
        throw FatalError
        (
            msg() << "Cannot open STL file \"" << fileName << '"',
            function
        );
    }
    std::string buf
    (
        (std::istreambuf_iterator<char>(is)),
        std::istreambuf_iterator<char>()
    );

    if (buf.empty())
    {
        throw FatalError
        (
            msg() << "STL file \"" << fileName << "\" is empty",
            function
        );
    }

    std::string stem = sanitise(fileStem(fileName));
    if (stem.empty())
    {
        stem = "stl";
    }

    stlSurface s;
    surfaceBuilder builder(s, stem);

    const bool ascii = looksAscii(buf);
    std::uint32_t n = 0;
    if (buf.size() >= 84)
    {
        std::memcpy(&n, buf.data() + 80, 4);
    }
    const std::size_t binarySize = 84 + 50*std::size_t(n);

    if (!ascii && buf.size() >= 84 && buf.size() == binarySize)
    {
        s.binary = true;
        readBinary(buf, fileName, n, builder);
    }
    else if (ascii)
    {
        readAscii(buf, fileName, builder);
    }
    else if (buf.size() < 84)
    {
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is neither ascii STL (text"
                << " starting with 'solid') nor binary STL: " << buf.size()
                << " bytes, less than the 84-byte binary header (truncated?)",
            function
        );
    }
    else if (buf.size() < binarySize)
    {
        throw FatalError
        (
            msg()
                << "Binary STL file \"" << fileName << "\" is truncated: its"
                << " header announces " << n << " triangles (" << binarySize
                << " bytes) but the file has " << buf.size() << " bytes",
            function
        );
    }
    else
    {
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is neither ascii STL (text"
                << " starting with 'solid') nor binary STL: its header"
                << " announces " << n << " triangles (" << binarySize
                << " bytes) but the file has " << buf.size() << " bytes",
            function
        );
    }

    if (s.triangles.empty())
    {
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is empty: it contains no"
                << " triangles",
            function
        );
    }

    // Solids without triangles (e.g. an empty ascii solid) are not patches
    std::vector<label> used(s.solidNames.size(), 0);
    for (label so : s.solid)
    {
        used[so] = 1;
    }
    if (std::find(used.begin(), used.end(), 0) != used.end())
    {
        std::vector<label> newIndex(used.size(), -1);
        std::vector<std::string> names;
        for (std::size_t i = 0; i < used.size(); ++i)
        {
            if (used[i])
            {
                newIndex[i] = label(names.size());
                names.push_back(s.solidNames[i]);
            }
        }
        for (label& so : s.solid)
        {
            so = newIndex[so];
        }
        s.solidNames = names;
    }

    return s;
}


double pmsh::enclosedVolume(const stlSurface& s)
{
    // About a point near the surface, for accuracy far from the origin
    const point3 o = s.points.empty() ? point3{0, 0, 0} : s.points[0];
    double v6 = 0;
    for (const triVerts& f : s.triangles)
    {
        v6 += tetVolume6(o, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
    }
    return v6/6;
}


void pmsh::checkStl(const stlSurface& s, const std::string& fileName)
{
    const char* function = "pmsh::checkStl";
    const label nt = s.nTriangles();

    // Degenerate triangles: repeated vertices or (numerically) zero area,
    // relative to the triangle's longest edge
    {
        label nBad = 0;
        label first = -1;
        for (label t = 0; t < nt; ++t)
        {
            const triVerts& f = s.triangles[t];
            double l2 = 0;
            for (int k = 0; k < 3; ++k)
            {
                l2 = std::max(l2, magSqr(s.points[f[(k + 1) % 3]] - s.points[f[k]]));
            }
            const double a2 = magSqr(s.areaNormal(t));
            if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || !(a2 > 1e-24*l2*l2))
            {
                if (first < 0)
                {
                    first = t;
                }
                ++nBad;
            }
        }
        if (nBad)
        {
            const triVerts& f = s.triangles[first];
            throw FatalError
            (
                msg()
                    << "STL file \"" << fileName << "\" has " << nBad
                    << " degenerate (zero-area) triangle(s), e.g. triangle "
                    << first << " of solid " << s.solidNames[s.solid[first]]
                    << ": " << stlPoint(s.points[f[0]]) << ' ' << stlPoint(s.points[f[1]])
                    << ' ' << stlPoint(s.points[f[2]]) << ".\nRemove them (or"
                    << " repair the surface) before meshing",
                function
            );
        }
    }

    const surfaceEdgeDefects defects = findSurfaceEdgeDefects(s.triangles);
    auto edge = [&](const std::pair<label, label>& e) { return edgeString(s, e.first, e.second); };
    const label nOpen = defects.nOpen;
    const label nNonManifold = defects.nNonManifold;
    const label nFlipped = defects.nInconsistent;

    if (nNonManifold)
    {
        // Solids that share faces or edges (two cubes sharing a face) are
        // touching shells: say which and what to do
        std::vector<label> atEdge;
        const auto e = defects.firstNonManifold;
        for (label t = 0; t < nt; ++t)
        {
            const triVerts& f = s.triangles[t];
            for (int k = 0; k < 3; ++k)
            {
                if
                (
                    std::min(f[k], f[(k + 1) % 3]) == std::min(e.first, e.second)
                 && std::max(f[k], f[(k + 1) % 3]) == std::max(e.first, e.second)
                )
                {
                    atEdge.push_back(t);
                }
            }
        }
        const std::string solids = solidsOf(s, atEdge);
        const bool severalSolids = solids.compare(0, 7, "solids ") == 0;
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is not manifold: "
                << nNonManifold << " edge(s) are used by more than two"
                << " triangles, e.g. the edge " << edge(e) << " by "
                << atEdge.size() << " triangles of " << solids
                << ".\nEvery edge of a closed surface must be shared by"
                << " exactly two triangles"
                << (
                       severalSolids
                     ? ": the closed surfaces of these solids share faces or"
                       " edges (touching shells). " + std::string(touchingAdvice)
                     : std::string(" (closed surfaces sharing faces or edges,"
                       " or a stray triangle)")
                   ),
            function
        );
    }
    if (nOpen)
    {
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is not closed: " << nOpen
                << " edge(s) are used by only one triangle, e.g. the edge "
                << edge(defects.firstOpen) << ".\nThe surface must enclose a volume: fill"
                << " the holes (vertices of neighbouring triangles must match"
                << " exactly)",
            function
        );
    }
    if (nFlipped)
    {
        throw FatalError
        (
            msg()
                << "STL file \"" << fileName << "\" is inconsistently"
                << " oriented: " << nFlipped << " edge(s) are traversed in the"
                << " same direction by both their triangles (one of the two"
                << " normals is flipped), e.g. the edge " << edge(defects.firstInconsistent)
                << ".\nOrient all triangles consistently (normals outward)",
            function
        );
    }

    checkShellContacts(s, fileName);
    checkShellOrientation(s, fileName);
}


void pmsh::checkShellContacts(const stlSurface& s, const std::string& fileName)
{
    label nSheets = 0;
    const std::vector<label> sheet = manifoldSheets(s, nSheets);
    if (nSheets < 2)
    {
        return;
    }

    std::vector<std::vector<label>> triangles(nSheets);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        triangles[sheet[t]].push_back(t);
    }

    // The outer boundary is the shell whose box is the whole surface's
    point3 lo = s.points[0], hi = s.points[0];
    for (const point3& p : s.points)
    {
        for (int k = 0; k < 3; ++k)
        {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    const double diagonal = std::sqrt(magSqr(hi - lo));
    const double tol = 1e-8*diagonal;
    auto describe = [&](label sh)
    {
        point3 slo = s.points[s.triangles[triangles[sh][0]][0]], shi = slo;
        for (label t : triangles[sh])
        {
            for (label v : s.triangles[t])
            {
                for (int k = 0; k < 3; ++k)
                {
                    slo[k] = std::min(slo[k], s.points[v][k]);
                    shi[k] = std::max(shi[k], s.points[v][k]);
                }
            }
        }
        const bool outer =
            magSqr(slo - lo) <= tol*tol && magSqr(shi - hi) <= tol*tol;
        return
            "the closed surface of " + solidsOf(s, triangles[sh])
          + (outer ? " (the outer boundary)" : "") + " ("
          + std::to_string(triangles[sh].size()) + " triangles between "
          + stlPoint(slo) + " and " + stlPoint(shi) + ")";
    };

    std::vector<sheetContact> contacts;
    findSheetContacts
    (
        s, sheet, tol,
        [&contacts](const sheetContact& c) { contacts.push_back(c); }
    );
    if (contacts.empty())
    {
        return;
    }

    msg message;
    message
        << "STL file \"" << fileName << "\": " << contacts.size()
        << " pair(s) of closed surfaces touch or overlap:";
    constexpr std::size_t shown = 5;
    for (std::size_t i = 0; i < contacts.size() && i < shown; ++i)
    {
        const sheetContact& c = contacts[i];
        message
            << "\n    " << describe(c.sheetA) << "\n    and "
            << describe(c.sheetB) << "\n        " << c.how << " at "
            << stlPoint(c.where);
    }
    if (contacts.size() > shown)
    {
        message << "\n    ... and " << contacts.size() - shown << " more";
    }
    message << ".\n" << touchingAdvice;
    throw FatalError(message, "pmsh::checkShellContacts");
}


void pmsh::checkShellOrientation(const stlSurface& s, const std::string& fileName)
{
    const char* function = "pmsh::checkShellOrientation";

    label nShells = 0;
    const std::vector<label> shell = surfaceShells(label(s.points.size()), s.triangles, nShells);
    std::vector<std::vector<label>> triangles(nShells);
    for (label t = 0; t < s.nTriangles(); ++t)
    {
        triangles[shell[t]].push_back(t);
    }

    // The solids a shell is made of, for messages
    auto solidsOfShell = [&](label sh) { return solidsOf(s, triangles[sh]); };
    // Where a shell is: a solid may hold several
    auto extentOf = [&](label sh)
    {
        point3 lo = s.points[s.triangles[triangles[sh][0]][0]];
        point3 hi = lo;
        for (label t : triangles[sh])
        {
            for (label p : s.triangles[t])
            {
                for (int k = 0; k < 3; ++k)
                {
                    lo[k] = std::min(lo[k], s.points[p][k]);
                    hi[k] = std::max(hi[k], s.points[p][k]);
                }
            }
        }
        return " (" + std::to_string(triangles[sh].size()) + " triangles between "
            + stlPoint(lo) + " and " + stlPoint(hi) + ")";
    };

    for (label sh = 0; sh < nShells; ++sh)
    {
        // Volume about a point of the shell, for accuracy far from the origin
        const point3 o = s.points[s.triangles[triangles[sh][0]][0]];
        double v6 = 0;
        for (label t : triangles[sh])
        {
            const triVerts& f = s.triangles[t];
            v6 += tetVolume6(o, s.points[f[0]], s.points[f[1]], s.points[f[2]]);
        }
        if (!(v6 != 0))
        {
            throw FatalError
            (
                msg()
                    << "STL file \"" << fileName << "\": the closed surface of "
                    << solidsOfShell(sh) << " encloses no volume",
                function
            );
        }

        // Nesting depth: the other shells around this one (shells do not
        // cross, so any of its points tells)
        const triVerts& f = s.triangles[triangles[sh][0]];
        const point3 x =
            (1.0/3.0)*(s.points[f[0]] + s.points[f[1]] + s.points[f[2]]);
        label depth = 0;
        std::string around;
        for (label other = 0; other < nShells; ++other)
        {
            if
            (
                other != sh
             && std::abs(windingNumber(s.points, s.triangles, triangles[other], x)) > 0.5
            )
            {
                ++depth;
                around = solidsOfShell(other);
            }
        }

        // The fluid lies inside the outermost shell and outside a shell
        // nested in it: normals point out of the fluid
        const bool inward = v6 < 0;
        if (depth % 2 == 0 && inward)
        {
            throw FatalError
            (
                msg()
                    << "STL file \"" << fileName << "\" is oriented inward: the"
                    << " closed surface of " << solidsOfShell(sh) << extentOf(sh)
                    << " encloses a negative volume (" << v6/6 << ").\nIts triangle normals"
                    << " point into the solid: flip the normals (reverse the"
                    << " vertex order of every triangle of "
                    << solidsOfShell(sh) << ")",
                function
            );
        }
        if (depth % 2 == 1 && !inward)
        {
            throw FatalError
            (
                msg()
                    << "STL file \"" << fileName << "\": the closed surface of "
                    << solidsOfShell(sh) << extentOf(sh) << " lies inside that of " << around
                    << " but its normals point out of it, into the fluid"
                    << " around it.\nA body in the flow is a hole in the"
                    << " domain: its normals must point out of the fluid, into"
                    << " the body. Flip the normals of " << solidsOfShell(sh)
                    << " (reverse the vertex order of each of its triangles)",
                function
            );
        }
    }
}


// ************************************************************************* //
