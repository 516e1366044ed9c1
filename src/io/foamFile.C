#include "foamFile.H"
#include "error.H"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <limits>

namespace
{

// 1 MiB: large enough that fwrite is called rarely for millions of faces.
constexpr std::size_t bufferSize = 1u << 20;

// Labels converted between widths this many at a time.
constexpr std::size_t chunkSize = 1u << 16;

bool hostIsLittleEndian()
{
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

// "key" padded to OpenFOAM's 12-column keyword width.
std::string headerEntry(const std::string& key, const std::string& value)
{
    std::string s = "    " + key;
    s.append(key.size() < 12 ? 12 - key.size() : 1, ' ');
    s += value;
    s += ";\n";
    return s;
}

std::string quoted(const std::string& s)
{
    return '"' + s + '"';
}

const char* const banner =
    "/*--------------------------------*- C++ -*----------------------------------*\\\n"
    "  =========                 |\n"
    "  \\\\      /  F ield         | OpenFOAM: The Open Source CFD Toolbox\n"
    "   \\\\    /   O peration     | Version:  v1912 format\n"
    "    \\\\  /    A nd           | Written by pmshFoam\n"
    "     \\\\/     M anipulation  |\n"
    "\\*---------------------------------------------------------------------------*/\n";

const char* const separator =
    "// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n";

const char* const endDivider =
    "\n\n// ************************************************************************* //\n";

} // End anonymous namespace


// * * * * * * * * * * * * * * * Free functions  * * * * * * * * * * * * * //

std::string pmsh::foamArch(const foamFileFormat& fmt)
{
    return "LSB;label=" + std::to_string(fmt.labelBits) + ";scalar=64";
}


std::string pmsh::faceListClassName(const foamFileFormat& fmt)
{
    return fmt.binary ? "faceCompactList" : "faceList";
}


std::string pmsh::fileNameOf(const std::string& path)
{
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}


// * * * * * * * * * * * * * * * * Constructors  * * * * * * * * * * * * * * //

pmsh::foamOFstream::foamOFstream
(
    const std::string& path,
    const foamFileFormat& fmt
)
:
    path_(path),
    fmt_(fmt),
    buf_(bufferSize)
{
    if (fmt_.labelBits != 32 && fmt_.labelBits != 64)
    {
        throw FatalError
        (
            msg() << "Cannot write " << path_ << ": label size "
                << fmt_.labelBits << " is not supported (use 32 or 64)",
            "foamOFstream::foamOFstream"
        );
    }
    // The arch entry promises little-endian data
    if (fmt_.binary && !hostIsLittleEndian())
    {
        throw FatalError
        (
            msg() << "Cannot write " << path_ << " in binary on a big-endian"
                " host; use writeFormat ascii",
            "foamOFstream::foamOFstream"
        );
    }

    file_ = std::fopen(path_.c_str(), "wb");
    if (!file_)
    {
        throw FatalError
        (
            msg() << "Cannot open " << path_ << " for writing: "
                << std::strerror(errno),
            "foamOFstream::foamOFstream"
        );
    }
    // Our own buffer does the batching
    std::setvbuf(file_, nullptr, _IONBF, 0);
}


pmsh::foamOFstream::~foamOFstream()
{
    if (file_)
    {
        // Not closed: an error interrupted writing. Leave no truncated file
        // that could pass for a complete one.
        std::fclose(file_);
        std::remove(path_.c_str());
    }
}


// * * * * * * * * * * * * * * Private Member Functions  * * * * * * * * * * //

void pmsh::foamOFstream::flushBuffer()
{
    if (pos_ && file_)
    {
        if (std::fwrite(buf_.data(), 1, pos_, file_) != pos_)
        {
            const int err = errno;
            pos_ = 0;
            throw FatalError
            (
                msg() << "Error writing " << path_ << ": "
                    << std::strerror(err) << " (disk full?)",
                "foamOFstream::flushBuffer"
            );
        }
    }
    pos_ = 0;
}


void pmsh::foamOFstream::put(const char* s, std::size_t n)
{
    if (n > buf_.size() - pos_)
    {
        flushBuffer();
        if (n > buf_.size())
        {
            putRaw(s, n);
            return;
        }
    }
    std::memcpy(buf_.data() + pos_, s, n);
    pos_ += n;
}


void pmsh::foamOFstream::putRaw(const void* data, std::size_t nBytes)
{
    flushBuffer();
    if (nBytes && std::fwrite(data, 1, nBytes, file_) != nBytes)
    {
        throw FatalError
        (
            msg() << "Error writing " << path_ << ": " << std::strerror(errno)
                << " (disk full?)",
            "foamOFstream::putRaw"
        );
    }
}


char* pmsh::foamOFstream::reserve(std::size_t n)
{
    if (n > buf_.size() - pos_)
    {
        flushBuffer();
    }
    return buf_.data() + pos_;
}


void pmsh::foamOFstream::beginList(std::size_t n)
{
    char num[32];
    const auto r = std::to_chars(num, num + sizeof(num), n);

    if (fmt_.binary)
    {
        // "\nN\n(" raw ")"; an empty list is just "\n0\n" (facts A4)
        put('\n');
        put(num, r.ptr - num);
        put('\n');
        if (n)
        {
            put('(');
        }
    }
    else if (n == 0)
    {
        put("0()", 3);
    }
    else
    {
        put(num, r.ptr - num);
        put("\n(\n", 3);
    }
}


void pmsh::foamOFstream::endList(std::size_t n)
{
    if (fmt_.binary)
    {
        if (n)
        {
            put(')');
        }
    }
    else if (n)
    {
        put(')');
    }
}


void pmsh::foamOFstream::labelOverflow(long long value, const char* what) const
{
    throw FatalError
    (
        msg() << "Cannot write " << path_ << ": the " << what << " value "
            << value << " does not fit a 32-bit label.\n"
            "Write the mesh with label size 64 (labelSize 64, or"
            " WM_LABEL_SIZE=64) and use an OpenFOAM built with 64-bit labels",
        "foamOFstream::writeLabelList"
    );
}


template<class T>
void pmsh::foamOFstream::writeLabels
(
    const T* data,
    std::size_t n,
    const char* what
)
{
    constexpr long long lo = std::numeric_limits<std::int32_t>::min();
    constexpr long long hi = std::numeric_limits<std::int32_t>::max();
    const bool check32 = fmt_.labelBits == 32 && sizeof(T) > 4;

    beginList(n);

    if (fmt_.binary)
    {
        if (fmt_.labelBits == int(8*sizeof(T)))
        {
            // Same width in memory and on disk: one block
            putRaw(data, n*sizeof(T));
        }
        else if (fmt_.labelBits == 64)
        {
            std::vector<std::int64_t> chunk(std::min(n, chunkSize));
            for (std::size_t i = 0; i < n; i += chunkSize)
            {
                const std::size_t m = std::min(chunkSize, n - i);
                std::copy(data + i, data + i + m, chunk.begin());
                put(reinterpret_cast<const char*>(chunk.data()), m*8);
            }
        }
        else
        {
            std::vector<std::int32_t> chunk(std::min(n, chunkSize));
            for (std::size_t i = 0; i < n; i += chunkSize)
            {
                const std::size_t m = std::min(chunkSize, n - i);
                for (std::size_t j = 0; j < m; ++j)
                {
                    const long long v = data[i + j];
                    if (v < lo || v > hi)
                    {
                        labelOverflow(v, what);
                    }
                    chunk[j] = std::int32_t(v);
                }
                put(reinterpret_cast<const char*>(chunk.data()), m*4);
            }
        }
    }
    else
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            const long long v = data[i];
            if (check32 && (v < lo || v > hi))
            {
                labelOverflow(v, what);
            }
            char* p = reserve(24);
            p = std::to_chars(p, p + 24, v).ptr;
            *p++ = '\n';
            pos_ = p - buf_.data();
        }
    }

    endList(n);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

void pmsh::foamOFstream::writeHeader(const foamFileHeader& header)
{
    std::string s = banner;
    s += "FoamFile\n{\n";
    s += headerEntry("version", "2.0");
    s += headerEntry("format", fmt_.binary ? "binary" : "ascii");
    s += headerEntry("arch", quoted(foamArch(fmt_)));
    if (!header.note.empty())
    {
        s += headerEntry("note", quoted(header.note));
    }
    s += headerEntry("class", header.className);
    if (!header.location.empty())
    {
        s += headerEntry("location", quoted(header.location));
    }
    s += headerEntry("object", header.object);
    s += "}\n";
    s += separator;
    s += '\n';
    put(s);
}


void pmsh::foamOFstream::writeText(const std::string& text)
{
    put(text);
}


void pmsh::foamOFstream::writeLabelList(const label* data, std::size_t n)
{
    writeLabels(data, n, "label");
}


void pmsh::foamOFstream::writeLabelList(const globalLabel* data, std::size_t n)
{
    writeLabels(data, n, "label");
}


void pmsh::foamOFstream::writeVectorField
(
    const vector* data,
    std::size_t n,
    int precision
)
{
    beginList(n);

    if (fmt_.binary)
    {
        static_assert(sizeof(vector) == 3*sizeof(double), "packed vector");
        putRaw(data, n*sizeof(vector));
    }
    else
    {
        precision = std::max(precision, 1);
        // %g with up to 'precision' digits: sign, digits, point, exponent
        const std::size_t maxChars = 3*(precision + 16) + 8;
        for (std::size_t i = 0; i < n; ++i)
        {
            char* p = reserve(maxChars);
            char* const end = p + maxChars;
            *p++ = '(';
            for (int d = 0; d < 3; ++d)
            {
                if (d)
                {
                    *p++ = ' ';
                }
                p = std::to_chars
                (
                    p, end, data[i][d], std::chars_format::general, precision
                ).ptr;
            }
            *p++ = ')';
            *p++ = '\n';
            pos_ = p - buf_.data();
        }
    }

    endList(n);
}


void pmsh::foamOFstream::writePointField(const point* data, std::size_t n)
{
    writeVectorField(data, n, std::max(fmt_.precision, minPointPrecision));
}


void pmsh::foamOFstream::writeFaceList(const triFace* data, std::size_t n)
{
    if (fmt_.binary)
    {
        // faceCompactList: offsets 0,3,6,..,3n then the flat vertex labels
        const unsigned long long nVerts = 3ull*n;
        const unsigned long long maxLabel32 =
            std::numeric_limits<std::int32_t>::max();
        if (fmt_.labelBits == 32 && nVerts > maxLabel32)
        {
            labelOverflow((long long)nVerts, "face vertex count");
        }

        beginList(n + 1);
        if (fmt_.labelBits == 64)
        {
            std::vector<std::int64_t> chunk(std::min(n + 1, chunkSize));
            for (std::size_t i = 0; i <= n; i += chunkSize)
            {
                const std::size_t m = std::min(chunkSize, n + 1 - i);
                for (std::size_t j = 0; j < m; ++j)
                {
                    chunk[j] = 3*std::int64_t(i + j);
                }
                put(reinterpret_cast<const char*>(chunk.data()), m*8);
            }
        }
        else
        {
            std::vector<std::int32_t> chunk(std::min(n + 1, chunkSize));
            for (std::size_t i = 0; i <= n; i += chunkSize)
            {
                const std::size_t m = std::min(chunkSize, n + 1 - i);
                for (std::size_t j = 0; j < m; ++j)
                {
                    chunk[j] = std::int32_t(3*(i + j));
                }
                put(reinterpret_cast<const char*>(chunk.data()), m*4);
            }
        }
        endList(n + 1);

        static_assert(sizeof(triFace) == 3*sizeof(label), "packed triFace");
        writeLabels(data ? data->data() : nullptr, 3*n, "face vertex");
    }
    else
    {
        beginList(n);
        for (std::size_t i = 0; i < n; ++i)
        {
            char* p = reserve(48);
            char* const end = p + 48;
            *p++ = '3';
            *p++ = '(';
            p = std::to_chars(p, end, data[i][0]).ptr;
            *p++ = ' ';
            p = std::to_chars(p, end, data[i][1]).ptr;
            *p++ = ' ';
            p = std::to_chars(p, end, data[i][2]).ptr;
            *p++ = ')';
            *p++ = '\n';
            pos_ = p - buf_.data();
        }
        endList(n);
    }
}


void pmsh::foamOFstream::close()
{
    if (!file_)
    {
        return;
    }
    put(endDivider, std::strlen(endDivider));
    flushBuffer();

    std::FILE* f = file_;
    file_ = nullptr;
    if (std::fflush(f) != 0 || std::ferror(f))
    {
        const int err = errno;
        std::fclose(f);
        throw FatalError
        (
            msg() << "Error writing " << path_ << ": " << std::strerror(err),
            "foamOFstream::close"
        );
    }
    if (std::fclose(f) != 0)
    {
        throw FatalError
        (
            msg() << "Error closing " << path_ << ": " << std::strerror(errno),
            "foamOFstream::close"
        );
    }
}


// * * * * * * * * * * * * * * * Whole-file writers * * * * * * * * * * * * //

namespace
{

template<class LabelType>
void writeLabelListFileImpl
(
    const std::string& path,
    const std::vector<LabelType>& labels,
    const pmsh::foamFileFormat& fmt,
    const std::string& location,
    const std::string& note
)
{
    pmsh::foamOFstream os(path, fmt);
    os.writeHeader({"labelList", location, pmsh::fileNameOf(path), note});
    os.writeLabelList(labels.data(), labels.size());
    os.close();
}

} // End anonymous namespace


void pmsh::writeLabelListFile
(
    const std::string& path,
    const std::vector<label>& labels,
    const foamFileFormat& fmt,
    const std::string& location,
    const std::string& note
)
{
    writeLabelListFileImpl(path, labels, fmt, location, note);
}


void pmsh::writeLabelListFile
(
    const std::string& path,
    const std::vector<globalLabel>& labels,
    const foamFileFormat& fmt,
    const std::string& location,
    const std::string& note
)
{
    writeLabelListFileImpl(path, labels, fmt, location, note);
}


void pmsh::writePointFieldFile
(
    const std::string& path,
    const std::vector<point>& points,
    const foamFileFormat& fmt,
    const std::string& location,
    const std::string& note
)
{
    foamOFstream os(path, fmt);
    os.writeHeader({"vectorField", location, fileNameOf(path), note});
    os.writePointField(points.data(), points.size());
    os.close();
}


void pmsh::writeFaceListFile
(
    const std::string& path,
    const std::vector<triFace>& faces,
    const foamFileFormat& fmt,
    const std::string& location,
    const std::string& note
)
{
    foamOFstream os(path, fmt);
    os.writeHeader({faceListClassName(fmt), location, fileNameOf(path), note});
    os.writeFaceList(faces.data(), faces.size());
    os.close();
}


// ************************************************************************* //
