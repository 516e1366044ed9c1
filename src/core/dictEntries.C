/*---------------------------------------------------------------------------*\
  pmshFoam: pmshDict's entries, read and checked (dictEntries.H).
\*---------------------------------------------------------------------------*/

#include "dictEntries.H"
#include "foamShims.H"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;

namespace
{

//- Edit distance (ignoring case), to suggest the entry a typo meant.
std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const bool same =
                std::tolower(static_cast<unsigned char>(a[i - 1]))
             == std::tolower(static_cast<unsigned char>(b[j - 1]));
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + !same});
        }
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

} // End anonymous namespace


std::string pmsh::joinedWords(const std::vector<std::string>& words)
{
    std::string s;
    for (const std::string& w : words)
    {
        s += (s.empty() ? "" : ", ") + w;
    }
    return s;
}


bool pmsh::containsWord(const std::vector<std::string>& words, const std::string& w)
{
    return std::find(words.begin(), words.end(), w) != words.end();
}


std::string pmsh::didYouMean(const std::string& key, const std::vector<std::string>& valid)
{
    std::string best;
    std::size_t bestDist = 3;
    for (const std::string& v : valid)
    {
        const std::size_t d = editDistance(key, v);
        if (d < bestDist)
        {
            bestDist = d;
            best = v;
        }
    }
    return best.empty() ? "" : " Did you mean '" + best + "'?";
}


const Foam::token* pmsh::singleToken(const Foam::entry& e)
{
    return e.isStream() && e.stream().size() == 1 ? &e.stream()[0] : nullptr;
}


bool pmsh::stringList
(
    const Foam::entry& e,
    std::vector<std::string>& items,
    bool oneWithoutParentheses
)
{
    items.clear();
    if (!e.isStream())
    {
        return false;
    }
    const Foam::ITstream& is = e.stream();
    const Foam::label n = is.size();
    auto punctuation = [&](Foam::label i, char c)
    {
        return is[i].isPunctuation() && is[i].pToken() == c;
    };
    // "a", or (a b ...), or N(a b ...) as OpenFOAM writes lists
    const Foam::label open = n >= 1 && is[0].isLabel() ? 1 : 0;
    const bool list =
        n >= open + 2 && punctuation(open, Foam::token::BEGIN_LIST)
     && punctuation(n - 1, Foam::token::END_LIST);
    if (!list && !(oneWithoutParentheses && n == 1))
    {
        return false;
    }
    for (Foam::label i = list ? open + 1 : 0; i < (list ? n - 1 : n); ++i)
    {
        if (!foam::isStringType(is[i]))
        {
            return false;
        }
        items.push_back(foam::stringToken(is[i]));
    }
    return open == 0 || is[0].labelToken() == Foam::label(items.size());
}


std::string pmsh::validRange(double lo, double hi)
{
    std::ostringstream os;
    os  << "Valid values are ";
    if (lo == aboveZero)
    {
        os  << "> 0";
    }
    else
    {
        os  << ">= " << lo;
    }
    if (hi < std::numeric_limits<double>::max())
    {
        os  << " and <= " << hi;
    }
    return os.str();
}


std::string pmsh::casePath(const std::string& caseDir, const std::string& name)
{
    std::string rest = name;
    bool caseRelative = false;
    for (const std::string tag : {"<case>", "${FOAM_CASE}", "$FOAM_CASE"})
    {
        if (rest.compare(0, tag.size(), tag) == 0)
        {
            rest.erase(0, tag.size());
            rest.erase(0, rest.find_first_not_of('/'));
            caseRelative = true;
            break;
        }
    }
    fs::path p(rest);
    if (caseRelative || p.is_relative())
    {
        p = fs::path(caseDir)/p;
    }
    std::error_code ec;
    const fs::path abs = fs::absolute(p, ec);
    return (ec ? p : abs).lexically_normal().string();
}


Foam::OSstream& pmsh::entryChecks::error
(
    const Foam::dictionary& d,
    const Foam::entry& e
) const
{
    return foam::ioError
    (
        Foam::FatalIOError, where_, __FILE__, __LINE__,
        d.topDict().name(), e.startLineNumber(), e.endLineNumber()
    );
}


Foam::OSstream& pmsh::entryChecks::error
(
    const Foam::dictionary& d,
    const char* key
) const
{
    const Foam::entry* e = foam::findEntry(d, key);
    return foam::ioError
    (
        Foam::FatalIOError, where_, __FILE__, __LINE__,
        d.topDict().name(),
        e ? e->startLineNumber() : d.startLineNumber(),
        e ? e->endLineNumber() : d.endLineNumber()
    );
}


void pmsh::entryChecks::require
(
    const Foam::dictionary& d,
    const char* key,
    const std::string& owner,
    const std::string& valid
) const
{
    if (!foam::findEntry(d, key))
    {
        error(d, key)
            << "Entry '" << key << "' not found in " << owner.c_str() << '\n'
            << valid.c_str() << Foam::exit(Foam::FatalIOError);
    }
}


void pmsh::entryChecks::invalid
(
    const Foam::dictionary& d,
    const Foam::entry& e,
    const std::string& valid,
    const std::string& note,
    const std::string& context
) const
{
    const std::string value =
        e.isStream() ? foam::tokensString(e.stream()) : "a sub-dictionary";
    error(d, e)
        << "Entry '" << e.keyword().c_str() << "'" << context.c_str() << " is "
        << value.c_str() << note.c_str() << '\n' << valid.c_str()
        << Foam::exit(Foam::FatalIOError);
}


double pmsh::entryChecks::bounded
(
    const Foam::dictionary& d,
    const char* key,
    double deflt,
    double lo,
    double hi,
    bool integral,
    const std::string& valid,
    const std::string& context
) const
{
    const Foam::entry* e = foam::findEntry(d, key);
    if (!e) return deflt;
    const Foam::token* t = singleToken(*e);
    if
    (
        !t || !(integral ? t->isLabel() : t->isNumber())
     || !(t->number() >= lo && t->number() <= hi)
    )
    {
        // 1e1 is written back as 10, and "is fine" reads as a verdict:
        // say why the value is wrong
        const bool real = integral && t && t->isScalar();
        const bool number = t && t->isNumber();
        invalid
        (
            d, *e, valid,
            real ? " (not an integer)" : t && !number ? " (not a number)" : "",
            context
        );
    }
    return t->number();
}


std::string pmsh::entryChecks::choice
(
    const Foam::dictionary& d,
    const char* key,
    const std::string& deflt,
    const std::vector<std::string>& choices
) const
{
    const Foam::entry* e = foam::findEntry(d, key);
    if (!e) return deflt;
    const Foam::token* t = singleToken(*e);
    if (!t || !foam::isStringType(*t) || !containsWord(choices, foam::stringToken(*t)))
    {
        invalid(d, *e, "Valid values are: " + joinedWords(choices));
    }
    return foam::stringToken(*t);
}


pmsh::point3 pmsh::entryChecks::point
(
    const Foam::dictionary& d,
    const char* key,
    const std::string& owner
) const
{
    const std::string valid =
        "Entry '" + std::string(key) + "' of " + owner
      + " must be a point (x y z), e.g. " + key + " (0 0 0);";
    require(d, key, owner, valid);
    const Foam::entry* e = foam::findEntry(d, key);
    const bool stream = e->isStream();
    Foam::ITstream* is = stream ? &e->stream() : nullptr;
    bool ok =
        stream && is->size() == 5
     && (*is)[0].isPunctuation() && (*is)[0].pToken() == Foam::token::BEGIN_LIST
     && (*is)[4].isPunctuation() && (*is)[4].pToken() == Foam::token::END_LIST;
    pmsh::point3 p{};
    for (int k = 0; ok && k < 3; ++k)
    {
        ok = (*is)[k + 1].isNumber() && std::isfinite((*is)[k + 1].number());
        if (ok) p[k] = (*is)[k + 1].number();
    }
    if (!ok)
    {
        invalid(d, *e, valid);
    }
    return p;
}


// ************************************************************************* //
