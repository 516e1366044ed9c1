// Writing dictionaries: OpenFOAM layout, and whole files replaced atomically.

#include "dictionaryTokeniser.H"
#include "error.H"

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace pmsh
{

using namespace dictionaryDetail;

// * * * * * * * * * * * * * * * * * * Write  * * * * * * * * * * * * * * * //

void dictionary::write(std::ostream& os, int indent) const
{
    const std::string ind(indent, ' ');

    for (std::size_t i = 0; i < entries_.size(); ++i)
    {
        const entry& e = entries_[i];

        if (e.isDirective())
        {
            os  << ind << e.keyword_;
            if (!e.tokens_.empty())
            {
                if (e.tokens_.front().space > 0) os << ' ';
                os  << tokensToString(e.tokens_, indent);
            }
            os  << '\n';
            continue;
        }

        const std::string key = e.pattern_ ? quoted(e.keyword_) : e.keyword_;

        if (e.isDict())
        {
            // Sub-dictionaries stand apart from what precedes them
            if (i > 0 && !entries_[i - 1].isDict()) os << '\n';
            os  << ind << key << '\n' << ind << "{\n";
            e.dict_->write(os, indent + 4);
            os  << ind << "}\n";
            // A blank line after a sub-dictionary, as OpenFOAM writes it
            if (i + 1 < entries_.size()) os << '\n';
            continue;
        }

        os  << ind << key;
        if (e.tokens_.empty())
        {
            os  << ";\n";
            continue;
        }
        if (e.tokens_.front().space >= 2)
        {
            // The value starts on the next line (lists written as blocks)
            os  << '\n' << ind;
        }
        else
        {
            // Values start in column 16 (at least one space), as OpenFOAM
            const std::size_t width = 16;
            os  << std::string(key.size() < width ? width - key.size() : 1, ' ');
        }
        os  << tokensToString(e.tokens_, indent) << ";\n";
    }
}


void dictionary::writeFile(const std::string& file) const
{
    std::ostringstream os;
    os  << foamBanner();
    write(os);
    os  << '\n' << foamEndLine() << '\n';
    writeFileAtomically(file, os.str());
}


std::ostream& operator<<(std::ostream& os, const dictionary& d)
{
    d.write(os);
    return os;
}


// * * * * * * * * * * * * * * * Free functions  * * * * * * * * * * * * * //

std::string foamBanner()
{
    return
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "| OpenFOAM dictionary written by pmshFoam                                     |\n"
        "\\*---------------------------------------------------------------------------*/\n";
}


std::string foamEndLine()
{
    return
        "// ************************************************************************* //";
}

void writeFileAtomically(const std::string& file, const std::string& text)
{
    const char* function = "pmsh::writeFileAtomically";
    const fs::path path(file);
    std::error_code ec;
    if (path.has_parent_path())
    {
        fs::create_directories(path.parent_path(), ec);
    }
    const std::string tmp =
        file + ".pmshTmp" + std::to_string(static_cast<long>(::getpid()));
    {
        std::ofstream out(tmp, std::ios::binary);
        out << text;
        out.close();
        if (!out)
        {
            fs::remove(tmp, ec);
            throw FatalError
            (
                msg() << "Cannot write file \"" << file << "\""
                    << " (check that the directory is writable and the disk"
                    << " is not full)",
                function
            );
        }
    }
    fs::rename(tmp, file, ec);
    if (ec)
    {
        fs::remove(tmp, ec);
        throw FatalError
        (
            msg() << "Cannot write file \"" << file << "\": " << ec.message(),
            function
        );
    }
}

} // End namespace pmsh


// ************************************************************************* //
