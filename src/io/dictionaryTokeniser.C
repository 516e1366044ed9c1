// Dictionary files as tokens: the tokeniser, the token class and writing
// tokens back as text.

#include "dictionaryTokeniser.H"
#include "error.H"

#include <algorithm>
#include <cctype>

namespace pmsh
{

using namespace dictionaryDetail;

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

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

} // End anonymous namespace


void dictionaryDetail::syntaxError
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


// (strtod alone would also take "inf", "nan" and hex.)
bool dictionaryDetail::isNumberText(const std::string& s)
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


bool dictionaryDetail::isIntegerText(const std::string& s)
{
    std::size_t i = (!s.empty() && (s[0] == '+' || s[0] == '-')) ? 1 : 0;
    if (i == s.size()) return false;
    for (; i < s.size(); ++i)
    {
        if (!isDigit(s[i])) return false;
    }
    return true;
}


std::string dictionaryDetail::quoted(const std::string& s)
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


// * * * * * * * * * * * * * * * * Tokeniser * * * * * * * * * * * * * * * //

namespace
{

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

    //- Position of the closer of the block (/* */ or #{ #}) whose
    //  two-character opener is at i_, with the lines up to it counted;
    //  a syntax error at the opening line if it is never closed.
    std::size_t blockClose(const char* closer, const char* unterminated)
    {
        const std::size_t close = s_.find(closer, i_ + 2);
        if (close == std::string::npos)
        {
            syntaxError(file_, line_, unterminated);
        }
        line_ += int(std::count(s_.begin() + i_, s_.begin() + close, '\n'));
        return close;
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
                i_ = blockClose
                (
                    "*/", "unterminated comment ('/*' without a closing '*/')"
                ) + 2;
                space = std::max(space, line_ > startLine ? 2 : 1);
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
                const std::size_t close = blockClose
                (
                    "#}", "unterminated verbatim block ('#{' without '#}')"
                );
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


std::vector<token> dictionaryDetail::tokeniseFile
(
    const std::string& text,
    const std::string& file
)
{
    tokeniser lex(text, file);
    return lex.run();
}


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
    std::vector<token> tokens = tokeniseFile(text, name);
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

} // End namespace pmsh


// ************************************************************************* //
