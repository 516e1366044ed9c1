#include "foamFileReader.H"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace
{

//- A position in the file's bytes, with strict token readers.
class cursor
{
    const std::string& s_;
    const std::string& path_;
    std::size_t pos_;

public:

    cursor(const std::string& s, const std::string& path, std::size_t pos = 0)
    :
        s_(s), path_(path), pos_(pos)
    {}

    std::size_t pos() const { return pos_; }
    bool atEnd() const { return pos_ >= s_.size(); }
    char peek() const { return atEnd() ? '\0' : s_[pos_]; }

    [[noreturn]] void fail(const std::string& what) const
    {
        throw std::runtime_error
        (
            path_ + ": " + what + " at byte " + std::to_string(pos_)
        );
    }

    void skipSpace()
    {
        while (!atEnd() && std::isspace(static_cast<unsigned char>(s_[pos_])))
        {
            ++pos_;
        }
    }

    void skipSpaceAndComments()
    {
        for (;;)
        {
            skipSpace();
            if (s_.compare(pos_, 2, "//") == 0)
            {
                const auto nl = s_.find('\n', pos_);
                pos_ = nl == std::string::npos ? s_.size() : nl + 1;
            }
            else if (s_.compare(pos_, 2, "/*") == 0)
            {
                const auto end = s_.find("*/", pos_ + 2);
                if (end == std::string::npos)
                {
                    fail("unterminated comment");
                }
                pos_ = end + 2;
            }
            else
            {
                return;
            }
        }
    }

    void expect(char c)
    {
        if (peek() != c)
        {
            fail(std::string("expected '") + c + "', found '" + peek() + "'");
        }
        ++pos_;
    }

    std::string word()
    {
        const std::size_t start = pos_;
        while
        (
            !atEnd()
         && (std::isalnum(static_cast<unsigned char>(s_[pos_]))
          || std::strchr("_.:+-", s_[pos_]))
        )
        {
            ++pos_;
        }
        if (pos_ == start)
        {
            fail("expected a word");
        }
        return s_.substr(start, pos_ - start);
    }

    long long integer()
    {
        const char* begin = s_.c_str() + pos_;
        if (!(std::isdigit(static_cast<unsigned char>(*begin)) || *begin == '-'))
        {
            fail("expected an integer");
        }
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(begin, &end, 10);
        if (end == begin || errno)
        {
            fail("bad integer");
        }
        pos_ += end - begin;
        return v;
    }

    double scalar()
    {
        const char* begin = s_.c_str() + pos_;
        char* end = nullptr;
        const double v = std::strtod(begin, &end);
        if (end == begin)
        {
            fail("expected a number");
        }
        pos_ += end - begin;
        return v;
    }

    const char* raw(std::size_t n)
    {
        if (s_.size() - pos_ < n)
        {
            fail("binary block shorter than " + std::to_string(n) + " bytes");
        }
        const char* p = s_.data() + pos_;
        pos_ += n;
        return p;
    }

    //- The text up to the next ';' (consumed), trimmed, quotes removed.
    std::string valueToSemicolon()
    {
        // A ';' inside a quoted string ("LSB;label=32;...") is text
        std::size_t semi = pos_;
        bool inQuotes = false;
        for (; semi < s_.size(); ++semi)
        {
            if (s_[semi] == '"')
            {
                inQuotes = !inQuotes;
            }
            else if (s_[semi] == ';' && !inQuotes)
            {
                break;
            }
        }
        if (semi >= s_.size())
        {
            fail("missing ';'");
        }
        std::string v = s_.substr(pos_, semi - pos_);
        pos_ = semi + 1;
        const auto b = v.find_first_not_of(" \t\n");
        const auto e = v.find_last_not_of(" \t\n");
        v = b == std::string::npos ? "" : v.substr(b, e - b + 1);
        if (v.size() >= 2 && v.front() == '"' && v.back() == '"')
        {
            v = v.substr(1, v.size() - 2);
        }
        return v;
    }

    //- A "{ key value; ... }" block into entries; a repeated key fails with
    //  "duplicate <what> <key><where>".
    void readEntries
    (
        std::map<std::string, std::string>& entries,
        const std::string& what,
        const std::string& where
    )
    {
        skipSpaceAndComments();
        expect('{');
        for (;;)
        {
            skipSpaceAndComments();
            if (peek() == '}')
            {
                expect('}');
                return;
            }
            const std::string key = word();
            if (!entries.emplace(key, valueToSemicolon()).second)
            {
                fail("duplicate " + what + " " + key + where);
            }
        }
    }
};


//- The list size "N" (skipping comments before it).
std::size_t listSize(cursor& c)
{
    c.skipSpaceAndComments();
    const long long n = c.integer();
    if (n < 0)
    {
        c.fail("negative list size");
    }
    return std::size_t(n);
}


std::vector<std::int64_t> parseLabels(cursor& c, const pmshTest::foamFile& f)
{
    const std::size_t n = listSize(c);
    std::vector<std::int64_t> v(n);
    if (f.binary)
    {
        // "\nN\n(" raw ")"; empty: just N, no parentheses
        if (n == 0)
        {
            return v;
        }
        c.skipSpace();
        c.expect('(');
        const std::size_t w = std::size_t(f.labelBits/8);
        const char* p = c.raw(n*w);
        for (std::size_t i = 0; i < n; ++i)
        {
            if (w == 4)
            {
                std::int32_t x;
                std::memcpy(&x, p + 4*i, 4);
                v[i] = x;
            }
            else
            {
                std::memcpy(&v[i], p + 8*i, 8);
            }
        }
        c.expect(')');
    }
    else
    {
        c.skipSpace();
        c.expect('(');
        for (std::size_t i = 0; i < n; ++i)
        {
            c.skipSpace();
            v[i] = c.integer();
            if
            (
                f.labelBits == 32
             && (v[i] > std::numeric_limits<std::int32_t>::max()
              || v[i] < std::numeric_limits<std::int32_t>::min())
            )
            {
                c.fail("label " + std::to_string(v[i]) + " exceeds 32 bits");
            }
        }
        c.skipSpace();
        c.expect(')');
    }
    return v;
}


void checkClass(const pmshTest::foamFile& f, const std::string& className)
{
    if (f.header.at("class") != className)
    {
        throw std::runtime_error
        (
            f.path + ": class is " + f.header.at("class") + ", expected "
          + className
        );
    }
}


void checkEnd(cursor& c)
{
    c.skipSpaceAndComments();
    if (!c.atEnd())
    {
        c.fail("unexpected data after the list");
    }
}

} // End anonymous namespace


pmshTest::foamFile pmshTest::readFoamFile(const std::string& path)
{
    std::ifstream is(path, std::ios::binary);
    if (!is)
    {
        throw std::runtime_error("cannot open " + path);
    }
    std::ostringstream ss;
    ss << is.rdbuf();
    const std::string all = ss.str();

    foamFile f;
    f.path = path;

    cursor c(all, path);
    c.skipSpaceAndComments();
    if (c.word() != "FoamFile")
    {
        c.fail("expected FoamFile");
    }
    c.readEntries(f.header, "header entry", "");
    for (const char* key : {"version", "format", "class", "object"})
    {
        if (!f.header.count(key))
        {
            throw std::runtime_error(path + ": header has no " + key);
        }
    }

    const std::string& format = f.header["format"];
    if (format != "ascii" && format != "binary")
    {
        throw std::runtime_error(path + ": bad format " + format);
    }
    f.binary = format == "binary";

    if (f.header.count("arch"))
    {
        const std::string& arch = f.header["arch"];
        if (arch.find("LSB") == std::string::npos
         || arch.find("scalar=64") == std::string::npos)
        {
            throw std::runtime_error(path + ": unsupported arch " + arch);
        }
        if (arch.find("label=64") != std::string::npos)
        {
            f.labelBits = 64;
        }
        else if (arch.find("label=32") == std::string::npos)
        {
            throw std::runtime_error(path + ": arch without label size");
        }
    }

    f.data = all.substr(c.pos());

    // body: strip leading space/comments and the final divider line
    cursor b(f.data, path);
    b.skipSpaceAndComments();
    std::string body = f.data.substr(b.pos());
    auto rtrim = [&body]()
    {
        while (!body.empty() && std::isspace(static_cast<unsigned char>(body.back())))
        {
            body.pop_back();
        }
    };
    rtrim();
    if (body.size() >= 2 && body.compare(body.size() - 2, 2, "//") == 0)
    {
        const auto nl = body.rfind('\n');
        body.erase(nl == std::string::npos ? 0 : nl);
        rtrim();
    }
    f.body = body;

    return f;
}


std::vector<std::int64_t> pmshTest::readLabelList(const foamFile& f)
{
    checkClass(f, "labelList");
    cursor c(f.data, f.path);
    auto v = parseLabels(c, f);
    checkEnd(c);
    return v;
}


std::vector<std::array<double, 3>> pmshTest::readVectorField(const foamFile& f)
{
    checkClass(f, "vectorField");
    cursor c(f.data, f.path);
    const std::size_t n = listSize(c);
    std::vector<std::array<double, 3>> v(n);
    if (f.binary)
    {
        if (n)
        {
            c.skipSpace();
            c.expect('(');
            std::memcpy(v.data(), c.raw(n*24), n*24);
            c.expect(')');
        }
    }
    else
    {
        c.skipSpace();
        c.expect('(');
        for (std::size_t i = 0; i < n; ++i)
        {
            c.skipSpace();
            c.expect('(');
            for (int d = 0; d < 3; ++d)
            {
                c.skipSpace();
                v[i][d] = c.scalar();
            }
            c.skipSpace();
            c.expect(')');
        }
        c.skipSpace();
        c.expect(')');
    }
    checkEnd(c);
    return v;
}


std::vector<std::vector<std::int64_t>> pmshTest::readFaces(const foamFile& f)
{
    std::vector<std::vector<std::int64_t>> faces;
    cursor c(f.data, f.path);
    const std::string& cls = f.header.at("class");

    if (cls == "faceCompactList")
    {
        const auto offsets = parseLabels(c, f);
        const auto verts = parseLabels(c, f);
        if (offsets.empty() || offsets.front() != 0
         || offsets.back() != std::int64_t(verts.size()))
        {
            c.fail("compact offsets do not span the vertex list");
        }
        faces.resize(offsets.size() - 1);
        for (std::size_t i = 0; i + 1 < offsets.size(); ++i)
        {
            if (offsets[i + 1] < offsets[i])
            {
                c.fail("decreasing compact offsets");
            }
            faces[i].assign
            (
                verts.begin() + offsets[i], verts.begin() + offsets[i + 1]
            );
        }
    }
    else if (cls == "faceList")
    {
        if (f.binary)
        {
            c.fail("binary faceList is not supported by this reader");
        }
        const std::size_t n = listSize(c);
        faces.resize(n);
        c.skipSpace();
        c.expect('(');
        for (std::size_t i = 0; i < n; ++i)
        {
            c.skipSpace();
            const long long m = c.integer();
            if (m < 0)
            {
                c.fail("negative face size");
            }
            c.expect('(');
            faces[i].resize(std::size_t(m));
            for (auto& v : faces[i])
            {
                c.skipSpace();
                v = c.integer();
            }
            c.skipSpace();
            c.expect(')');
        }
        c.skipSpace();
        c.expect(')');
    }
    else
    {
        c.fail("class " + cls + " is not a face list");
    }
    checkEnd(c);
    return faces;
}


std::vector<pmshTest::boundaryPatch> pmshTest::readBoundary(const foamFile& f)
{
    checkClass(f, "polyBoundaryMesh");
    if (f.binary)
    {
        throw std::runtime_error(f.path + ": boundary must be ascii");
    }
    cursor c(f.data, f.path);
    const std::size_t n = listSize(c);
    c.skipSpaceAndComments();
    c.expect('(');
    std::vector<boundaryPatch> patches(n);
    for (auto& p : patches)
    {
        c.skipSpaceAndComments();
        p.name = c.word();
        c.readEntries(p.entries, "entry", " in patch " + p.name);
    }
    c.skipSpaceAndComments();
    c.expect(')');
    checkEnd(c);
    return patches;
}


std::vector<std::int64_t> pmshTest::readLabelListFile(const std::string& path)
{
    return readLabelList(readFoamFile(path));
}


std::vector<std::array<double, 3>>
pmshTest::readVectorFieldFile(const std::string& path)
{
    return readVectorField(readFoamFile(path));
}


std::vector<std::vector<std::int64_t>>
pmshTest::readFacesFile(const std::string& path)
{
    return readFaces(readFoamFile(path));
}
