// The dictionary and its entries: construction, lookup and editing.

#include "dictionaryTokeniser.H"
#include "error.H"

#include <cstdlib>
#include <iomanip>
#include <locale>
#include <sstream>

namespace pmsh
{

// * * * * * * * * * * * * * * * Local helpers * * * * * * * * * * * * * * //

namespace
{

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

} // End anonymous namespace


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
    entry e = primitive(keyword, isPattern, {}, file, line);
    e.kind_ = DICT;
    e.dict_.reset(new dictionary(d));
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
    // Never a pattern: directives are not looked up
    entry e = primitive(keyword, false, std::move(tokens), file, line);
    e.kind_ = DIRECTIVE;
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

    // Keywords are unique (add and set replace or merge), so exact lookup
    // finds the only entry of that keyword
    entry* existing = findEntry(e.keyword_, false);
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
    if (entry* e = findEntry(key, false))
    {
        if (e->isDict())
        {
            *e = entry::primitive(key, e->pattern_, std::move(tokens), e->file_, e->line_);
        }
        else
        {
            e->tokens_ = std::move(tokens);
        }
        return;
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
    if (entry* x = findEntry(key, false))
    {
        e.pattern_ = x->pattern_;
        e.regex_ = x->regex_;
        e.line_ = x->line_;
        *x = std::move(e);
    }
    else
    {
        entries_.push_back(std::move(e));
    }
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


} // End namespace pmsh


// ************************************************************************* //
