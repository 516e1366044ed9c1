// What an entry's value means: $variable expansion and typed access.

#include "dictionaryTokeniser.H"
#include "error.H"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

namespace pmsh
{

using namespace dictionaryDetail;

// * * * * * * * * * * * * * * * $variables  * * * * * * * * * * * * * * * //

namespace
{

//- Deepest $variable substitution (a = $b; b = $a; must not hang).
constexpr int maxExpandDepth = 32;


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

} // End namespace pmsh


// ************************************************************************* //
