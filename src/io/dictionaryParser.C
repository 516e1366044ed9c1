// Reading dictionary files: the parser that turns tokens into entries, and
// #include, #includeEtc and the other directives.

#include "dictionaryTokeniser.H"
#include "error.H"

#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pmsh
{

using namespace dictionaryDetail;

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

//- Deepest #include nesting: deeper means a file includes itself.
constexpr int maxIncludeDepth = 32;


//- $VAR and ${VAR} from the environment, for #include file names
//  ("$FOAM_CASE/constant/x"). Unknown variables are left as written so the
//  "cannot open" message shows what the user wrote.
std::string expandEnv(const std::string& s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i)
    {
        if (s[i] != '$')
        {
            out += s[i];
            continue;
        }
        std::size_t j = i + 1;
        std::string var;
        if (j < s.size() && s[j] == '{')
        {
            const std::size_t close = s.find('}', j);
            if (close == std::string::npos)
            {
                out += s[i];
                continue;
            }
            var = s.substr(j + 1, close - j - 1);
            j = close + 1;
        }
        else
        {
            while
            (
                j < s.size()
             && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '_')
            )
            {
                var += s[j++];
            }
        }
        const char* value = var.empty() ? nullptr : std::getenv(var.c_str());
        if (value)
        {
            out += value;
            i = j - 1;
        }
        else
        {
            out += s[i];
        }
    }
    return out;
}


std::string readWholeFile(const std::string& file)
{
    std::error_code ec;
    if (!fs::exists(file, ec))
    {
        throw FatalError
        (
            msg() << "Cannot open file \"" << file << "\": it does not exist",
            "pmsh::dictionary::read"
        );
    }
    if (fs::is_directory(file, ec))
    {
        throw FatalError
        (
            msg() << "Cannot read file \"" << file << "\": it is a directory",
            "pmsh::dictionary::read"
        );
    }
    std::ifstream is(file, std::ios::binary);
    if (!is)
    {
        throw FatalError
        (
            msg() << "Cannot open file \"" << file << "\" for reading"
                << " (check its permissions)",
            "pmsh::dictionary::read"
        );
    }
    std::ostringstream os;
    os << is.rdbuf();
    return os.str();
}


std::string absolutePath(const std::string& file)
{
    std::error_code ec;
    fs::path p = fs::absolute(fs::path(file), ec);
    if (ec) return file;
    return p.lexically_normal().string();
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * parser * * * * * * * * * * * * * * * * //

//- Turns the tokens of one file into entries of a dictionary.
class dictionaryParser
{
    const readOptions& options_;

    struct input
    {
        const std::vector<token>& tokens;
        std::size_t pos;
        const std::string& file;
        int depth;
    };

    //- Add an entry just read to d, with its byte range in the source: from
    //  its first token to the last token read.
    static void addRead(dictionary& d, entry e, const token& first, const input& in)
    {
        e.begin_ = first.begin;
        e.end_ = in.tokens[in.pos - 1].end;
        d.add(std::move(e));
    }

    static bool isIncludeDirective(const std::string& name)
    {
        return
            name == "#include" || name == "#includeIfPresent"
         || name == "#sinclude" || name == "#includeEtc";
    }

    void parseDirective(dictionary& d, input& in)
    {
        const token& t = in.tokens[in.pos++];
        std::vector<token> args;

        if (isIncludeDirective(t.text))
        {
            if
            (
                in.pos >= in.tokens.size()
             || (
                    in.tokens[in.pos].type != token::STRING
                 && in.tokens[in.pos].type != token::WORD
                )
            )
            {
                syntaxError
                (
                    in.file, t.line,
                    "expected a file name after " + t.text
                  + " (e.g. " + t.text + " \"fileName\")"
                );
            }
            const token& arg = in.tokens[in.pos++];
            args.push_back(arg);
            if (in.pos < in.tokens.size() && in.tokens[in.pos].isPunctuation(';'))
            {
                args.push_back(in.tokens[in.pos++]);
            }

            if (include(d, in, t, arg.text))
            {
                return;
            }
        }
        else
        {
            // Other directives (#inputMode merge, #remove x, #default ...):
            // kept with their arguments on the same line (or inside
            // brackets opened there), up to a ';'
            int depth = 0;
            while (in.pos < in.tokens.size())
            {
                const token& a = in.tokens[in.pos];
                if (depth == 0)
                {
                    if (a.line != t.line || a.isPunctuation('}')) break;
                }
                if (a.isPunctuation('(') || a.isPunctuation('[') || a.isPunctuation('{'))
                {
                    ++depth;
                }
                else if
                (
                    (a.isPunctuation(')') || a.isPunctuation(']') || a.isPunctuation('}'))
                 && depth > 0
                )
                {
                    --depth;
                }
                args.push_back(a);
                ++in.pos;
                if (depth == 0 && a.isPunctuation(';')) break;
            }
        }

        addRead(d, entry::directive(t.text, std::move(args), in.file, t.line), t, in);
    }

    //- Read an #include'd file into d. False: keep the directive instead.
    bool include(dictionary& d, input& in, const token& t, const std::string& arg)
    {
        std::string path;
        if (t.text == "#includeEtc")
        {
            if (!options_.expandIncludeEtc) return false;
            const std::string etc = openfoamEtcDir();
            if (etc.empty())
            {
                // No OpenFOAM installation here: leave it for OpenFOAM
                return false;
            }
            path = (fs::path(etc)/arg).lexically_normal().string();
            std::error_code ec;
            if (!fs::is_regular_file(path, ec))
            {
                throw FatalError
                (
                    msg() << "Cannot open #includeEtc file \"" << arg
                        << "\" (looked for \"" << path << "\")\n"
                        << "included from file \"" << in.file << "\" line "
                        << t.line,
                    "pmsh::dictionary::read"
                );
            }
        }
        else
        {
            if (!options_.expandIncludes) return false;
            fs::path p(expandEnv(arg));
            if (p.is_relative())
            {
                p = fs::path(in.file).parent_path()/p;
            }
            path = p.lexically_normal().string();
            std::error_code ec;
            if (!fs::is_regular_file(path, ec))
            {
                if (t.text == "#includeIfPresent" || t.text == "#sinclude")
                {
                    return true;
                }
                throw FatalError
                (
                    msg() << "Cannot open include file \"" << path << "\"\n"
                        << "referenced by " << t.text << " \"" << arg
                        << "\" in file \"" << in.file << "\" line " << t.line
                        << "\n(relative names are relative to the directory"
                        << " of the including file)",
                    "pmsh::dictionary::read"
                );
            }
        }

        if (in.depth >= maxIncludeDepth)
        {
            throw FatalError
            (
                msg() << "#include nested more than " << maxIncludeDepth
                    << " deep at file \"" << in.file << "\" line " << t.line
                    << ": does a file include itself?",
                "pmsh::dictionary::read"
            );
        }

        // Read into a scratch dictionary first: the included file's own
        // FoamFile header is dropped, as OpenFOAM does
        dictionary inc(d.name_);
        inc.file_ = path;
        parseText(inc, readWholeFile(path), path, in.depth + 1);
        inc.remove("FoamFile");
        for (entry& e : inc.entries_)
        {
            d.add(std::move(e));
        }
        return true;
    }

    void parseEntries(dictionary& d, input& in, const token* open, const std::string& openKey)
    {
        while (true)
        {
            if (in.pos >= in.tokens.size())
            {
                if (open)
                {
                    syntaxError
                    (
                        in.file, open->line,
                        "unterminated sub-dictionary '" + openKey
                      + "': the '{' has no matching '}'"
                    );
                }
                return;
            }

            const token& t = in.tokens[in.pos];

            if (t.isPunctuation('}'))
            {
                if (open)
                {
                    ++in.pos;
                    return;
                }
                syntaxError(in.file, t.line, "unexpected '}' (no matching '{')");
            }
            if (t.isPunctuation(';'))
            {
                // A stray ';' is harmless
                ++in.pos;
                continue;
            }
            if (t.type == token::DIRECTIVE)
            {
                parseDirective(d, in);
                continue;
            }
            if (t.type == token::VARIABLE)
            {
                // $var at keyword position (merges a dictionary in OpenFOAM):
                // kept as written
                std::vector<token> args;
                ++in.pos;
                if (in.pos < in.tokens.size() && in.tokens[in.pos].isPunctuation(';'))
                {
                    args.push_back(in.tokens[in.pos++]);
                }
                addRead(d, entry::directive(t.text, std::move(args), in.file, t.line), t, in);
                continue;
            }
            if (t.type != token::WORD && t.type != token::STRING)
            {
                syntaxError
                (
                    in.file, t.line,
                    "expected a keyword, found " + t.describe()
                );
            }

            const token& key = t;
            ++in.pos;
            if (in.pos >= in.tokens.size())
            {
                syntaxError
                (
                    in.file, key.line,
                    "expected a value and ';' after entry '" + key.text
                  + "' (found the end of the file)"
                );
            }

            // A quoted key is a regular expression
            const bool isPattern = (key.type == token::STRING);
            if (in.tokens[in.pos].isPunctuation('{'))
            {
                const token& brace = in.tokens[in.pos++];
                dictionary sub(d.name_ + "/" + key.text);
                sub.file_ = in.file;
                entry e = entry::dict(key.text, isPattern, sub, in.file, key.line);
                parseEntries(*e.dict_, in, &brace, key.text);
                addRead(d, std::move(e), key, in);
                continue;
            }

            entry e = entry::primitive(key.text, isPattern, {}, in.file, key.line);
            parseValue(e, in);
            addRead(d, std::move(e), key, in);
        }
    }

    //- Value tokens up to the ';' outside brackets.
    void parseValue(entry& e, input& in)
    {
        std::vector<token>& value = e.tokens_;

        // Open brackets: the character and the token that opened it
        std::vector<const token*> open;

        auto missingSemicolon = [&](const token& found)
        {
            // The ';' is most likely missing after the token before the
            // last word: "maxCellSize 0.1 <newline> patches {"
            int line = value.empty() ? e.line_ : value.back().line;
            std::string detail = " (found " + found.describe() + " on line "
                + std::to_string(found.line) + ")";
            if
            (
                value.size() >= 2 && value.back().type == token::WORD
             && value.back().line != value[value.size() - 2].line
            )
            {
                line = value[value.size() - 2].line;
                detail = " (before '" + value.back().text + "' on line "
                    + std::to_string(value.back().line) + ")";
            }
            syntaxError
            (
                in.file, line,
                "expected ';' after entry '" + e.keyword_ + "'" + detail
            );
        };

        while (true)
        {
            if (in.pos >= in.tokens.size())
            {
                if (!open.empty())
                {
                    syntaxError
                    (
                        in.file, open.back()->line,
                        "'" + open.back()->text + "' in entry '" + e.keyword_
                      + "' is never closed (end of file reached)"
                    );
                }
                const int line = value.empty() ? e.line_ : value.back().line;
                syntaxError
                (
                    in.file, line,
                    "expected ';' after entry '" + e.keyword_
                  + "' (found the end of the file)"
                );
            }

            const token& v = in.tokens[in.pos];

            if (v.isPunctuation(';') && open.empty())
            {
                ++in.pos;
                return;
            }

            if (v.isPunctuation('{') && open.empty())
            {
                // Only N{value} and "#codeStream {" open a brace inside a
                // value; otherwise a ';' is missing before a sub-dictionary
                const bool allowed =
                    !value.empty()
                 && (
                        value.back().type == token::NUMBER
                     || value.back().type == token::DIRECTIVE
                    );
                if (!allowed)
                {
                    missingSemicolon(v);
                }
            }

            if (v.isPunctuation('(') || v.isPunctuation('[') || v.isPunctuation('{'))
            {
                open.push_back(&v);
            }
            else if (v.isPunctuation(')') || v.isPunctuation(']') || v.isPunctuation('}'))
            {
                if (open.empty())
                {
                    if (v.isPunctuation('}'))
                    {
                        missingSemicolon(v);
                    }
                    syntaxError
                    (
                        in.file, v.line,
                        "unmatched '" + v.text + "' in entry '" + e.keyword_ + "'"
                    );
                }
                const char o = open.back()->text[0];
                const char expected = (o == '(') ? ')' : (o == '[') ? ']' : '}';
                if (v.text[0] != expected)
                {
                    syntaxError
                    (
                        in.file, v.line,
                        "found '" + v.text + "' in entry '" + e.keyword_
                      + "' where '" + std::string(1, expected) + "' was expected"
                      + " to close the '" + open.back()->text + "' of line "
                      + std::to_string(open.back()->line)
                    );
                }
                open.pop_back();
            }

            value.push_back(v);
            ++in.pos;
        }
    }

public:

    explicit dictionaryParser(const readOptions& options)
    :
        options_(options)
    {}

    void parseText
    (
        dictionary& d,
        const std::string& text,
        const std::string& file,
        int depth
    )
    {
        const std::vector<token> tokens = tokeniseFile(text, file);
        input in{tokens, 0, file, depth};
        parseEntries(d, in, nullptr, "");
    }
};


// * * * * * * * * * * * * * * * * dictionary * * * * * * * * * * * * * * * //


dictionary dictionary::read(const std::string& file, const readOptions& options)
{
    const std::string path = absolutePath(file);
    return parse(readWholeFile(path), path, options);
}


dictionary dictionary::parse
(
    const std::string& text,
    const std::string& name,
    const readOptions& options
)
{
    dictionary d(name);
    dictionaryParser parser(options);
    parser.parseText(d, text, name, 0);
    return d;
}


// * * * * * * * * * * * * * * * Free functions  * * * * * * * * * * * * * //


std::string openfoamEtcDir()
{
    std::error_code ec;
    if (const char* dir = std::getenv("WM_PROJECT_DIR"))
    {
        const fs::path etc = fs::path(dir)/"etc";
        if (*dir && fs::is_directory(etc, ec)) return etc.string();
    }
    if (fs::is_directory("/usr/share/openfoam/etc", ec))
    {
        return "/usr/share/openfoam/etc";
    }
    return "";
}

} // End namespace pmsh


// ************************************************************************* //
