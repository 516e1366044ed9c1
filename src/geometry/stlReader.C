/*---------------------------------------------------------------------------*\
  pmshFoam: reading STL files (see stlReader.H); the checks of the
  surface read are in stlChecks.C.
\*---------------------------------------------------------------------------*/

#include "stlReader.H"
#include "surfaceBuilder.H"
#include "pmshError.H"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <zlib.h>

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace pmsh
{
namespace
{

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



} // End anonymous namespace
} // End namespace pmsh


// * * * * * * * * * * * * * * * Global Functions  * * * * * * * * * * * * * //

std::string pmsh::fileBytes(const std::string& fileName, const std::string& type)
{
    const char* function = "pmsh::fileBytes";
    std::string buf;
    if (isGzipped(fileName))
    {
        gzFile in = gzopen(fileName.c_str(), "rb");
        if (!in)
        {
            throw FatalError
            (
                msg() << "Cannot open " << type << " file \"" << fileName << '"',
                function
            );
        }
        char chunk[1 << 16];
        int n = 0;
        while ((n = gzread(in, chunk, sizeof(chunk))) > 0)
        {
            buf.append(chunk, std::size_t(n));
        }
        int status = Z_OK;
        const std::string problem = n < 0 ? gzerror(in, &status) : "";
        gzclose(in);
        if (n < 0)
        {
            throw FatalError
            (
                msg() << "Cannot decompress " << type << " file \"" << fileName
                    << "\": " << problem << " (a damaged or truncated .gz?)",
                function
            );
        }
        return buf;
    }
    std::ifstream is(fileName, std::ios::binary);
    if (!is.good())
    {
        throw FatalError
        (
            msg() << "Cannot open " << type << " file \"" << fileName << '"',
            function
        );
    }
    buf.assign
    (
        (std::istreambuf_iterator<char>(is)),
        std::istreambuf_iterator<char>()
    );
    return buf;
}


bool pmsh::isGzipped(const std::string& fileName)
{
    const std::size_t n = fileName.size();
    return n > 3 && fileName[n - 3] == '.'
        && std::tolower(static_cast<unsigned char>(fileName[n - 2])) == 'g'
        && std::tolower(static_cast<unsigned char>(fileName[n - 1])) == 'z';
}


std::string pmsh::fileStem(const std::string& fileName)
{
    const std::size_t slash = fileName.find_last_of('/');
    std::string name =
        slash == std::string::npos ? fileName : fileName.substr(slash + 1);
    if (isGzipped(name))
    {
        name.resize(name.size() - 3);
    }
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

    const std::string buf = fileBytes(fileName, "STL");

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
    removeSolidsWithoutTriangles(s);

    return s;
}


void pmsh::removeSolidsWithoutTriangles(stlSurface& s)
{
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
}


// ************************************************************************* //
