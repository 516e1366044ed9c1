#include "dictionary.H"
#include "error.H"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace pmsh
{

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

//- Deepest #include nesting: deeper means a file includes itself.
constexpr int maxIncludeDepth = 32;

//- Deepest $variable substitution (a = $b; b = $a; must not hang).
constexpr int maxExpandDepth = 32;

[[noreturn]] void syntaxError
(
    const std::string& file,
    int line,
    const std::string& what
)
{
    throw FatalError
    (
        msg() << "Syntax error in file \"" << file << "\" line " << line
            << ": " << what,
        "pmsh::dictionary (reading \"" + file + "\")"
    );
}


//- OpenFOAM's word characters, less the brackets: [ ] always end a word so
//  that "0]" in [0 1 -1 0 0 0 0] is a number and a bracket.
bool isWordChar(char c)
{
    return
        !std::isspace(static_cast<unsigned char>(c))
     && c != '"' && c != '\'' && c != '/' && c != ';'
     && c != '{' && c != '}' && c != '[' && c != ']';
}


bool isPunctuationChar(char c)
{
    switch (c)
    {
        case ';': case '(': case ')': case '[': case ']': case '{': case '}':
        case ':': case ',': case '=': case '*':
            return true;
        default:
            return false;
    }
}


bool isDigit(char c)
{
    return c >= '0' && c <= '9';
}


//- The strict number syntax: [+-] digits [. digits] [(e|E) [+-] digits].
//  (strtod alone would also take "inf", "nan" and hex.)
bool isNumberText(const std::string& s)
{
    std::size_t i = 0;
    const std::size_t n = s.size();
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    std::size_t nDigits = 0;
    while (i < n && isDigit(s[i])) { ++i; ++nDigits; }
    if (i < n && s[i] == '.')
    {
        ++i;
        while (i < n && isDigit(s[i])) { ++i; ++nDigits; }
    }
    if (nDigits == 0) return false;
    if (i < n && (s[i] == 'e' || s[i] == 'E'))
    {
        ++i;
        if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
        std::size_t nExp = 0;
        while (i < n && isDigit(s[i])) { ++i; ++nExp; }
        if (nExp == 0) return false;
    }
    return i == n;
}


//- Integer syntax only: [+-] digits.
bool isIntegerText(const std::string& s)
{
    std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
    if (i == s.size()) return false;
    for (; i < s.size(); ++i)
    {
        if (!isDigit(s[i])) return false;
    }
    return true;
}


std::string quoted(const std::string& s)
{
    std::string out = "\"";
    for (char c : s)
    {
        if (c == '"') out += '\\';
        out += c;
    }
    out += '"';
    return out;
}


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


//- Shortest decimal text that reads back as the same double.
std::string doubleText(double v)
{
    for (int prec = 15; prec <= 17; ++prec)
    {
        std::ostringstream os;
        os.imbue(std::locale::classic());
        os << std::setprecision(prec) << v;
        if (prec == 17 || std::strtod(os.str().c_str(), nullptr) == v)
        {
            return os.str();
        }
    }
    return "";
}


// * * * * * * * * * * * * * * * * Tokeniser * * * * * * * * * * * * * * * //

class tokeniser
{
    const std::string& s_;
    const std::string& file_;
    std::size_t i_ = 0;
    int line_ = 1;

    char peek(std::size_t k = 0) const
    {
        return i_ + k < s_.size() ? s_[i_ + k] : '\0';
    }

    void readString(token& t)
    {
        const int startLine = line_;
        ++i_;   // opening quote
        bool escaped = false;
        std::string out;
        while (true)
        {
            if (i_ >= s_.size())
            {
                syntaxError
                (
                    file_, startLine,
                    "unterminated string (missing closing '\"'; the string"
                    " starts \"" + out.substr(0, 40) + "\")"
                );
            }
            const char c = s_[i_++];
            if (c == '\n')
            {
                if (escaped)
                {
                    // Backslash-newline continues the string on the next line
                    out.pop_back();
                    escaped = false;
                    ++line_;
                    continue;
                }
                syntaxError
                (
                    file_, startLine,
                    "unterminated string (missing closing '\"' before the end"
                    " of the line; the string starts \"" + out.substr(0, 40)
                  + "\")"
                );
            }
            if (c == '"')
            {
                if (escaped)
                {
                    // \" is a quote inside the string
                    out.back() = '"';
                    escaped = false;
                    continue;
                }
                break;
            }
            // As OpenFOAM: backslashes are kept; a backslash escapes only
            // the quote or newline after it (\\ does not escape a quote)
            escaped = (c == '\\') ? !escaped : false;
            out += c;
        }
        t.type = token::STRING;
        t.text = std::move(out);
    }

    //- Word characters with ( ) depth: div(phi,U) is one word.
    std::string readWordChars()
    {
        std::string w;
        int depth = 0;
        while (i_ < s_.size() && isWordChar(s_[i_]))
        {
            const char c = s_[i_];
            if (c == '(')
            {
                ++depth;
            }
            else if (c == ')')
            {
                if (depth == 0) break;
                --depth;
            }
            w += c;
            ++i_;
        }
        return w;
    }

public:

    tokeniser(const std::string& s, const std::string& file)
    :
        s_(s),
        file_(file)
    {}

    std::vector<token> run()
    {
        std::vector<token> tokens;
        int space = 2;      // the start of the file counts as a new line

        while (i_ < s_.size())
        {
            const char c = s_[i_];

            if (c == '\n')
            {
                ++line_;
                ++i_;
                space = 2;
                continue;
            }
            if (std::isspace(static_cast<unsigned char>(c)))
            {
                ++i_;
                space = std::max(space, 1);
                continue;
            }
            if (c == '/' && peek(1) == '/')
            {
                while (i_ < s_.size() && s_[i_] != '\n') ++i_;
                space = std::max(space, 1);
                continue;
            }
            if (c == '/' && peek(1) == '*')
            {
                const int startLine = line_;
                const std::size_t close = s_.find("*/", i_ + 2);
                if (close == std::string::npos)
                {
                    syntaxError
                    (
                        file_, startLine,
                        "unterminated comment ('/*' without a closing '*/')"
                    );
                }
                bool newline = false;
                for (std::size_t k = i_; k < close; ++k)
                {
                    if (s_[k] == '\n')
                    {
                        ++line_;
                        newline = true;
                    }
                }
                i_ = close + 2;
                space = std::max(space, newline ? 2 : 1);
                continue;
            }

            token t;
            t.line = line_;
            t.space = space;
            t.begin = i_;
            space = 0;

            if (c == '"')
            {
                readString(t);
            }
            else if (c == '#' && peek(1) == '{')
            {
                const int startLine = line_;
                const std::size_t close = s_.find("#}", i_ + 2);
                if (close == std::string::npos)
                {
                    syntaxError
                    (
                        file_, startLine,
                        "unterminated verbatim block ('#{' without '#}')"
                    );
                }
                for (std::size_t k = i_; k < close; ++k)
                {
                    if (s_[k] == '\n') ++line_;
                }
                t.type = token::VERBATIM;
                t.text = s_.substr(i_, close + 2 - i_);
                i_ = close + 2;
            }
            else if (c == '#')
            {
                ++i_;
                std::string name;
                while
                (
                    i_ < s_.size()
                 && (
                        std::isalnum(static_cast<unsigned char>(s_[i_]))
                     || s_[i_] == '_'
                    )
                )
                {
                    name += s_[i_++];
                }
                if (name.empty())
                {
                    syntaxError
                    (
                        file_, line_,
                        "'#' must be followed by a directive name"
                        " (#include, #includeEtc, #inputMode ...)"
                    );
                }
                t.type = token::DIRECTIVE;
                t.text = "#" + name;
            }
            else if (c == '$')
            {
                ++i_;
                std::string name;
                if (peek() == '{')
                {
                    const std::size_t close = s_.find('}', i_);
                    if (close == std::string::npos)
                    {
                        syntaxError
                        (
                            file_, line_, "unterminated '${' (missing '}')"
                        );
                    }
                    name = s_.substr(i_, close + 1 - i_);
                    i_ = close + 1;
                }
                else
                {
                    name = readWordChars();
                }
                if (name.empty())
                {
                    syntaxError
                    (
                        file_, line_,
                        "'$' must be followed by a variable name"
                    );
                }
                t.type = token::VARIABLE;
                t.text = "$" + name;
            }
            else if (c == '\'')
            {
                syntaxError
                (
                    file_, line_,
                    "unexpected character '\\'' (strings use double quotes)"
                );
            }
            else if
            (
                isDigit(c)
             || ((c == '-' || c == '+' || c == '.') && (isDigit(peek(1)) || peek(1) == '.'))
            )
            {
                // Number characters only, so that 3(1 2 3) and 0] split
                std::string w;
                while
                (
                    i_ < s_.size()
                 && (
                        isDigit(s_[i_]) || s_[i_] == '.' || s_[i_] == 'e'
                     || s_[i_] == 'E' || s_[i_] == '+' || s_[i_] == '-'
                    )
                )
                {
                    w += s_[i_++];
                }
                // 1stOrder, 2D: letters straight after make it a word
                if
                (
                    i_ < s_.size()
                 && (std::isalpha(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_')
                )
                {
                    w += readWordChars();
                }
                t.type = isNumberText(w) ? token::NUMBER : token::WORD;
                t.text = std::move(w);
            }
            else if (isPunctuationChar(c) || c == '/' || c == '+' || c == '-')
            {
                t.type = token::PUNCTUATION;
                t.text = std::string(1, c);
                ++i_;
            }
            else
            {
                t.type = token::WORD;
                t.text = readWordChars();
                if (t.text.empty())
                {
                    syntaxError
                    (
                        file_, line_,
                        std::string("unexpected character '") + c + "'"
                    );
                }
            }

            t.end = i_;
            tokens.push_back(std::move(t));
        }
        return tokens;
    }
};

} // End anonymous namespace


// * * * * * * * * * * * * * * * * * token * * * * * * * * * * * * * * * * //

std::string token::str() const
{
    return type == STRING ? quoted(text) : text;
}


std::string token::describe() const
{
    switch (type)
    {
        case WORD:        return "the word '" + text + "'";
        case STRING:      return "the string " + quoted(text);
        case NUMBER:      return "the number " + text;
        case PUNCTUATION: return "'" + text + "'";
        case DIRECTIVE:   return "the directive " + text;
        case VARIABLE:    return "the variable " + text;
        case VERBATIM:    return "a #{ #} block";
    }
    return text;
}


std::string tokensToString(const std::vector<token>& tokens, int indent)
{
    std::string out;
    int depth = 0;
    for (std::size_t i = 0; i < tokens.size(); ++i)
    {
        const token& t = tokens[i];
        const bool closes =
            t.isPunctuation(')') || t.isPunctuation(']') || t.isPunctuation('}');
        if (closes && depth > 0) --depth;

        if (i > 0)
        {
            if (t.space >= 2)
            {
                out += '\n';
                out += std::string(indent + 4*depth, ' ');
            }
            else if (t.space == 1)
            {
                out += ' ';
            }
        }
        out += t.str();

        if (t.isPunctuation('(') || t.isPunctuation('[') || t.isPunctuation('{'))
        {
            ++depth;
        }
    }
    return out;
}


std::vector<token> tokenise(const std::string& text, const std::string& name)
{
    tokeniser lex(text, name);
    std::vector<token> tokens = lex.run();
    for (token& t : tokens)
    {
        // Made by the program: no source line, no source range
        t.line = 0;
        t.begin = t.end = 0;
        if (t.space > 1) t.space = 1;
    }
    if (!tokens.empty()) tokens.front().space = 1;
    return tokens;
}


// * * * * * * * * * * * * * * * * * entry * * * * * * * * * * * * * * * * //

entry::entry() = default;

entry::entry(const entry& e)
:
    keyword_(e.keyword_),
    pattern_(e.pattern_),
    kind_(e.kind_),
    tokens_(e.tokens_),
    dict_(e.dict_ ? new dictionary(*e.dict_) : nullptr),
    regex_(e.regex_),
    file_(e.file_),
    line_(e.line_),
    begin_(e.begin_),
    end_(e.end_)
{}

entry::entry(entry&&) noexcept = default;

entry& entry::operator=(const entry& e)
{
    if (this != &e)
    {
        entry copy(e);
        *this = std::move(copy);
    }
    return *this;
}

entry& entry::operator=(entry&&) noexcept = default;

entry::~entry() = default;


void entry::compilePattern()
{
    regex_.reset();
    if (!pattern_) return;
    try
    {
        regex_ = std::make_shared<const std::regex>
        (
            keyword_, std::regex::ECMAScript | std::regex::optimize
        );
    }
    catch (const std::regex_error& err)
    {
        throw FatalError
        (
            msg() << "Invalid regular expression \"" << keyword_
                << "\" as the key of an entry in file \"" << file_
                << "\" line " << line_ << ": " << err.what() << '\n'
                << "Quoted keys are regular expressions (e.g. \".*\" or"
                << " \"(inlet|outlet)\"); write plain names without quotes",
            "pmsh::entry"
        );
    }
}


entry entry::primitive
(
    const std::string& keyword,
    bool isPattern,
    std::vector<token> tokens,
    const std::string& file,
    int line
)
{
    entry e;
    e.keyword_ = keyword;
    e.pattern_ = isPattern;
    e.kind_ = PRIMITIVE;
    e.tokens_ = std::move(tokens);
    e.file_ = file;
    e.line_ = line;
    e.compilePattern();
    return e;
}


entry entry::dict
(
    const std::string& keyword,
    bool isPattern,
    const dictionary& d,
    const std::string& file,
    int line
)
{
    entry e;
    e.keyword_ = keyword;
    e.pattern_ = isPattern;
    e.kind_ = DICT;
    e.dict_.reset(new dictionary(d));
    e.file_ = file;
    e.line_ = line;
    e.compilePattern();
    return e;
}


entry entry::directive
(
    const std::string& keyword,
    std::vector<token> tokens,
    const std::string& file,
    int line
)
{
    entry e;
    e.keyword_ = keyword;
    e.kind_ = DIRECTIVE;
    e.tokens_ = std::move(tokens);
    e.file_ = file;
    e.line_ = line;
    return e;
}


const dictionary& entry::dict() const
{
    if (!dict_)
    {
        throw FatalError
        (
            msg() << "Entry '" << keyword_ << "' (file \"" << file_
                << "\" line " << line_ << ") is not a dictionary",
            "pmsh::entry::dict"
        );
    }
    return *dict_;
}


dictionary& entry::dict()
{
    return const_cast<dictionary&>(static_cast<const entry&>(*this).dict());
}


std::string entry::text() const
{
    if (dict_)
    {
        std::ostringstream os;
        os << "{\n";
        dict_->write(os, 4);
        os << "}";
        return os.str();
    }
    return tokensToString(tokens_);
}


bool entry::matches(const std::string& name) const
{
    if (kind_ == DIRECTIVE) return false;
    if (name == keyword_) return true;
    return regex_ && std::regex_match(name, *regex_);
}


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

        entry e = entry::directive(t.text, std::move(args), in.file, t.line);
        e.begin_ = t.begin;
        e.end_ = e.tokens_.empty() ? t.end : e.tokens_.back().end;
        d.add(std::move(e));
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
                entry e = entry::directive(t.text, std::move(args), in.file, t.line);
                e.begin_ = t.begin;
                e.end_ = in.tokens[in.pos - 1].end;
                d.add(std::move(e));
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

            if (in.tokens[in.pos].isPunctuation('{'))
            {
                const token& brace = in.tokens[in.pos++];
                entry e;
                e.keyword_ = key.text;
                e.pattern_ = (key.type == token::STRING);
                e.kind_ = entry::DICT;
                e.file_ = in.file;
                e.line_ = key.line;
                e.dict_.reset(new dictionary(d.name_ + "/" + key.text));
                e.dict_->file_ = in.file;
                e.compilePattern();
                parseEntries(*e.dict_, in, &brace, key.text);
                e.begin_ = key.begin;
                e.end_ = in.tokens[in.pos - 1].end;
                d.add(std::move(e));
                continue;
            }

            entry e;
            e.keyword_ = key.text;
            e.pattern_ = (key.type == token::STRING);
            e.kind_ = entry::PRIMITIVE;
            e.file_ = in.file;
            e.line_ = key.line;
            e.begin_ = key.begin;
            e.compilePattern();
            parseValue(e, in);
            e.end_ = in.tokens[in.pos - 1].end;
            d.add(std::move(e));
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
        tokeniser lex(text, file);
        const std::vector<token> tokens = lex.run();
        input in{tokens, 0, file, depth};
        parseEntries(d, in, nullptr, "");
    }
};


// * * * * * * * * * * * * * * * * dictionary * * * * * * * * * * * * * * * //

dictionary::dictionary(const std::string& name)
:
    name_(name),
    file_(name)
{}


dictionary::dictionary(const dictionary& d)
:
    name_(d.name_),
    file_(d.file_),
    parent_(nullptr),
    entries_(d.entries_)
{
    reparent();
}


dictionary::dictionary(dictionary&& d) noexcept
:
    name_(std::move(d.name_)),
    file_(std::move(d.file_)),
    parent_(d.parent_),
    entries_(std::move(d.entries_))
{
    reparent();
}


dictionary& dictionary::operator=(const dictionary& d)
{
    if (this != &d)
    {
        dictionary copy(d);
        *this = std::move(copy);
    }
    return *this;
}


dictionary& dictionary::operator=(dictionary&& d) noexcept
{
    if (this != &d)
    {
        // Keep our own place in a parent: only the contents change
        name_ = std::move(d.name_);
        file_ = std::move(d.file_);
        entries_ = std::move(d.entries_);
        reparent();
    }
    return *this;
}


dictionary::~dictionary() = default;


void dictionary::reparent()
{
    for (entry& e : entries_)
    {
        if (e.dict_) e.dict_->parent_ = this;
    }
}


void dictionary::setName(const std::string& name, const std::string& file)
{
    name_ = name;
    if (!file.empty()) file_ = file;
    for (entry& e : entries_)
    {
        if (e.dict_) e.dict_->setName(name_ + "/" + e.keyword_, "");
    }
}


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


const dictionary& dictionary::topDict() const
{
    const dictionary* d = this;
    while (d->parent_) d = d->parent_;
    return *d;
}


std::vector<std::string> dictionary::toc() const
{
    std::vector<std::string> keys;
    for (const entry& e : entries_)
    {
        if (!e.isDirective()) keys.push_back(e.keyword_);
    }
    return keys;
}


std::size_t dictionary::size() const
{
    std::size_t n = 0;
    for (const entry& e : entries_)
    {
        if (!e.isDirective()) ++n;
    }
    return n;
}


const entry* dictionary::findEntry(const std::string& key, bool patterns) const
{
    for (const entry& e : entries_)
    {
        if (!e.isDirective() && e.keyword_ == key) return &e;
    }
    if (patterns)
    {
        // OpenFOAM: the last matching pattern wins
        for (auto it = entries_.rbegin(); it != entries_.rend(); ++it)
        {
            if (it->regex_ && std::regex_match(key, *it->regex_)) return &*it;
        }
    }
    return nullptr;
}


entry* dictionary::findEntry(const std::string& key, bool patterns)
{
    return const_cast<entry*>
    (
        static_cast<const dictionary&>(*this).findEntry(key, patterns)
    );
}


const entry& dictionary::lookupEntry(const std::string& key, bool patterns) const
{
    const entry* e = findEntry(key, patterns);
    if (!e)
    {
        throw FatalError
        (
            msg() << "Entry '" << key << "' not found in dictionary \""
                << name_ << "\"",
            "pmsh::dictionary::lookupEntry"
        );
    }
    return *e;
}


bool dictionary::found(const std::string& key, bool patterns) const
{
    return findEntry(key, patterns) != nullptr;
}


bool dictionary::isDict(const std::string& key) const
{
    const entry* e = findEntry(key);
    return e && e->isDict();
}


const dictionary& dictionary::subDict(const std::string& key) const
{
    const entry& e = lookupEntry(key);
    if (!e.isDict())
    {
        throw FatalError
        (
            msg() << entryInfo(e) << " is not a sub-dictionary: it is '"
                << e.text() << "'\n"
                << "Expected '" << key << " { ... }'",
            "pmsh::dictionary::subDict"
        );
    }
    return e.dict();
}


dictionary& dictionary::subDict(const std::string& key)
{
    return const_cast<dictionary&>
    (
        static_cast<const dictionary&>(*this).subDict(key)
    );
}


std::string dictionary::text(const std::string& key) const
{
    return lookupEntry(key).text();
}


std::string dictionary::entryInfo(const entry& e) const
{
    std::ostringstream os;
    os  << "Entry '" << e.keyword_ << "' in dictionary \"" << name_
        << "\" (line " << e.line_;
    if (e.file_ != topDict().file_ && !e.file_.empty())
    {
        os  << " of \"" << e.file_ << "\"";
    }
    os  << ")";
    return os.str();
}


// * * * * * * * * * * * * * * * $variables  * * * * * * * * * * * * * * * //

namespace
{

//- name, or a.b.c through sub-dictionaries.
const entry* findPath(const dictionary& d, const std::string& name)
{
    if (const entry* e = d.findEntry(name)) return e;
    const std::size_t dot = name.find('.');
    if (dot == std::string::npos || dot == 0) return nullptr;
    const entry* e = d.findEntry(name.substr(0, dot));
    if (!e || !e->isDict()) return nullptr;
    return findPath(e->dict(), name.substr(dot + 1));
}

} // End anonymous namespace


const entry* dictionary::findScoped(const std::string& varName) const
{
    std::string name = varName;
    if (name.size() > 2 && name[0] == '{' && name.back() == '}')
    {
        name = name.substr(1, name.size() - 2);
    }
    if (name.empty()) return nullptr;

    if (name[0] == ':')
    {
        return findPath(topDict(), name.substr(1));
    }
    if (name[0] == '.')
    {
        // .a is here, ..a the parent, ...a the grandparent
        const dictionary* d = this;
        std::size_t k = 1;
        while (k < name.size() && name[k] == '.')
        {
            if (d->parent_) d = d->parent_;
            ++k;
        }
        return findPath(*d, name.substr(k));
    }

    for (const dictionary* d = this; d; d = d->parent_)
    {
        if (const entry* e = d->findEntry(name)) return e;
    }
    const std::size_t dot = name.find('.');
    if (dot != std::string::npos)
    {
        for (const dictionary* d = this; d; d = d->parent_)
        {
            if (const entry* e = findPath(*d, name)) return e;
        }
    }
    return nullptr;
}


void dictionary::expandInto
(
    const std::vector<token>& in,
    std::vector<token>& out,
    int depth
) const
{
    for (const token& t : in)
    {
        if (t.type == token::VARIABLE && depth < maxExpandDepth)
        {
            const entry* e = findScoped(t.text.substr(1));
            if (e && !e->isDict() && !e->isDirective())
            {
                const std::size_t first = out.size();
                expandInto(e->tokens_, out, depth + 1);
                if (out.size() > first) out[first].space = t.space;
                continue;
            }
        }
        out.push_back(t);
    }
}


std::vector<token> dictionary::expandedTokens(const entry& e) const
{
    std::vector<token> out;
    expandInto(e.tokens_, out, 0);
    return out;
}


// * * * * * * * * * * * * * * * Typed access  * * * * * * * * * * * * * * //

void dictionary::typeError
(
    const entry& e,
    const std::vector<token>& value,
    const std::string& expected
) const
{
    std::ostringstream os;
    os  << entryInfo(e) << " is ";
    if (e.isDict())
    {
        os  << "a sub-dictionary";
    }
    else if (value.empty())
    {
        os  << "empty";
    }
    else if (value.size() == 1)
    {
        os  << value[0].describe();
        if (value[0].type == token::VARIABLE)
        {
            os  << " (not found in this or any enclosing dictionary)";
        }
    }
    else
    {
        // On one line, whatever the layout in the file
        std::vector<token> flat(value);
        for (token& t : flat) t.space = std::min(t.space, 1);
        os  << "'" << tokensToString(flat) << "' (" << value.size()
            << " items)";
    }
    os  << "\nExpected " << expected;

    if (value.size() > 1)
    {
        bool slash = false;
        for (const token& t : value)
        {
            if (t.isPunctuation('/')) slash = true;
        }
        // Judged on the tokens as written, not as expanded from $variables
        if (e.tokens_.size() > 1 && e.tokens_.back().line > e.line_)
        {
            os  << "\nIs a ';' missing at the end of line " << e.line_ << "?";
        }
        else if (slash)
        {
            os  << "\nFile names must be quoted: \"" << tokensToString(value)
                << "\"";
        }
    }
    throw FatalError(os.str(), "pmsh::dictionary::get");
}


template<>
bool dictionary::value<bool>(const entry& e) const
{
    const std::vector<token> v = expandedTokens(e);
    const char* expected =
        "a switch: true/false, on/off or yes/no";
    if (e.isDict() || v.size() != 1) typeError(e, v, expected);
    const std::string& s = v[0].text;
    if (v[0].type == token::WORD)
    {
        if (s == "true" || s == "on" || s == "yes") return true;
        if (s == "false" || s == "off" || s == "no") return false;
    }
    else if (v[0].type == token::NUMBER && (s == "1" || s == "0"))
    {
        return s == "1";
    }
    typeError(e, v, expected);
}


template<>
long long dictionary::value<long long>(const entry& e) const
{
    const std::vector<token> v = expandedTokens(e);
    const char* expected = "an integer (e.g. 3)";
    if (e.isDict() || v.size() != 1 || v[0].type != token::NUMBER)
    {
        typeError(e, v, expected);
    }
    const std::string& s = v[0].text;
    if (isIntegerText(s))
    {
        errno = 0;
        const long long i = std::strtoll(s.c_str(), nullptr, 10);
        if (errno == ERANGE)
        {
            typeError(e, v, "an integer in the range of 64-bit integers");
        }
        return i;
    }
    // 2.0 and 1e3 are integers too
    const double d = std::strtod(s.c_str(), nullptr);
    if (d != std::floor(d) || std::abs(d) > 9.0e15)
    {
        typeError(e, v, expected);
    }
    return static_cast<long long>(d);
}


template<>
long dictionary::value<long>(const entry& e) const
{
    return static_cast<long>(value<long long>(e));
}


template<>
int dictionary::value<int>(const entry& e) const
{
    const long long i = value<long long>(e);
    if
    (
        i < std::numeric_limits<int>::min()
     || i > std::numeric_limits<int>::max()
    )
    {
        typeError(e, expandedTokens(e), "an integer in the range of 32-bit integers");
    }
    return static_cast<int>(i);
}


template<>
double dictionary::value<double>(const entry& e) const
{
    const std::vector<token> v = expandedTokens(e);
    if (e.isDict() || v.size() != 1 || v[0].type != token::NUMBER)
    {
        typeError(e, v, "a number (e.g. 0.1 or 1e-3)");
    }
    return std::strtod(v[0].text.c_str(), nullptr);
}


template<>
std::string dictionary::value<std::string>(const entry& e) const
{
    const std::vector<token> v = expandedTokens(e);
    if
    (
        e.isDict() || v.size() != 1
     || (v[0].type != token::WORD && v[0].type != token::STRING)
    )
    {
        typeError(e, v, "a word or a \"string\"");
    }
    return v[0].text;
}


// * * * * * * * * * * * * * * * * * * Edit * * * * * * * * * * * * * * * //

void dictionary::add(entry e)
{
    if (e.isDirective())
    {
        entries_.push_back(std::move(e));
        return;
    }
    if (e.dict_)
    {
        e.dict_->parent_ = this;
        e.dict_->setName(name_ + "/" + e.keyword_, "");
    }

    entry* existing = nullptr;
    for (entry& x : entries_)
    {
        if (!x.isDirective() && x.keyword_ == e.keyword_)
        {
            existing = &x;
        }
    }
    if (!existing)
    {
        entries_.push_back(std::move(e));
        return;
    }
    if (existing->isDict() && e.isDict())
    {
        // #inputMode merge (OpenFOAM's default): sub-dictionaries merge
        for (entry& sub : e.dict_->entries_)
        {
            existing->dict_->add(std::move(sub));
        }
        return;
    }
    *existing = std::move(e);
}


void dictionary::set(const std::string& key, const std::string& valueText)
{
    std::vector<token> tokens = tokenise(valueText, name_ + " (value of " + key + ")");
    for (entry& e : entries_)
    {
        if (!e.isDirective() && e.keyword_ == key)
        {
            if (e.isDict())
            {
                e = entry::primitive(key, e.pattern_, std::move(tokens), e.file_, e.line_);
            }
            else
            {
                e.tokens_ = std::move(tokens);
            }
            return;
        }
    }
    entries_.push_back(entry::primitive(key, false, std::move(tokens), file_, 0));
}


void dictionary::set(const std::string& key, const char* valueText)
{
    set(key, std::string(valueText));
}


void dictionary::set(const std::string& key, int value)
{
    set(key, std::to_string(value));
}


void dictionary::set(const std::string& key, long long value)
{
    set(key, std::to_string(value));
}


void dictionary::set(const std::string& key, double value)
{
    set(key, doubleText(value));
}


void dictionary::set(const std::string& key, const dictionary& d)
{
    entry e = entry::dict(key, false, d, file_, 0);
    e.dict_->parent_ = this;
    e.dict_->setName(name_ + "/" + key, "");
    for (entry& x : entries_)
    {
        if (!x.isDirective() && x.keyword_ == key)
        {
            e.pattern_ = x.pattern_;
            e.regex_ = x.regex_;
            e.line_ = x.line_;
            x = std::move(e);
            reparent();
            return;
        }
    }
    entries_.push_back(std::move(e));
    reparent();
}


bool dictionary::remove(const std::string& key)
{
    for (auto it = entries_.begin(); it != entries_.end(); ++it)
    {
        if (!it->isDirective() && it->keyword_ == key)
        {
            entries_.erase(it);
            reparent();
            return true;
        }
    }
    return false;
}


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
    const std::string text = os.str();

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
                "pmsh::dictionary::writeFile"
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
            "pmsh::dictionary::writeFile"
        );
    }
}


std::ostream& operator<<(std::ostream& os, const dictionary& d)
{
    d.write(os);
    return os;
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

} // End namespace pmsh


// ************************************************************************* //
