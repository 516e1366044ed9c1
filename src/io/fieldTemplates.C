#include "fieldTemplates.H"
#include "error.H"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace pmsh
{

namespace
{

bool endsWith(const std::string& s, const std::string& tail)
{
    return s.size() >= tail.size()
        && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}


//- Hidden and editor/backup files in a time directory are not fields.
bool isBackupName(const std::string& name)
{
    if (name.empty() || name[0] == '.') return true;
    for (const char* tail : {"~", ".orig", ".bak", ".old", ".swp", ".save"})
    {
        if (endsWith(name, tail)) return true;
    }
    return false;
}


std::string readText(const std::string& file)
{
    std::ifstream is(file, std::ios::binary);
    if (!is)
    {
        throw FatalError
        (
            msg() << "Cannot read field template \"" << file << "\""
                << " (check its permissions)",
            "pmsh::readFieldTemplate"
        );
    }
    std::ostringstream os;
    os << is.rdbuf();
    return os.str();
}


//- The FoamFile header alone (parsing a whole non-field file, possibly
//  binary, just to learn its class would be wasteful and fragile).
//  Returns an empty dictionary when there is no header.
dictionary readHeader(const std::string& file, const std::string& text)
{
    std::size_t pos = text.find("FoamFile");
    while (pos != std::string::npos)
    {
        // The keyword, not part of a comment or of a longer word
        const std::size_t lineStart = text.rfind('\n', pos);
        const std::string before = text.substr
        (
            lineStart == std::string::npos ? 0 : lineStart + 1,
            pos - (lineStart == std::string::npos ? 0 : lineStart + 1)
        );
        if (before.find("//") == std::string::npos)
        {
            break;
        }
        pos = text.find("FoamFile", pos + 8);
    }
    if (pos == std::string::npos) return dictionary(file);

    const std::size_t close = text.find('}', pos);
    if (close == std::string::npos) return dictionary(file);

    // Keep the line numbers: pad with the newlines before the header
    const std::string lines
    (
        static_cast<std::size_t>(std::count(text.begin(), text.begin() + pos, '\n')),
        '\n'
    );
    try
    {
        return dictionary::parse
        (
            lines + text.substr(pos, close + 1 - pos), file,
            readOptions{false, false}
        );
    }
    catch (const FatalError&)
    {
        // A file whose header does not parse is not one of our templates
        return dictionary(file);
    }
}


std::string headerClass(const dictionary& header)
{
    const entry* e = header.findEntry("FoamFile", false);
    if (!e || !e->isDict()) return "";
    const entry* c = e->dict().findEntry("class", false);
    if (!c || c->tokens().size() != 1) return "";
    return c->tokens()[0].text;
}


[[noreturn]] void nonuniformError(const std::string& file, int line)
{
    throw FatalError
    (
        msg() << "Field template \"" << file << "\" line " << line
            << ": internalField is nonuniform\n"
            << "pmshFoam only maps uniform initial fields onto the mesh it"
            << " generates (the template's cells are not the new cells).\n"
            << "Write 'internalField uniform <value>;' in the template and"
            << " initialise the field after meshing if needed (e.g. setFields"
            << " or mapFields).",
        "pmsh::readFieldTemplate"
    );
}


//- internalField nonuniform found without parsing (a large or binary
//  nonuniform field need not be tokenised to be rejected). 0 if none.
int nonuniformLine(const std::string& text)
{
    std::size_t pos = 0;
    while ((pos = text.find("internalField", pos)) != std::string::npos)
    {
        std::size_t k = pos + 13;
        while (k < text.size() && std::isspace(static_cast<unsigned char>(text[k])))
        {
            ++k;
        }
        if (text.compare(k, 10, "nonuniform") == 0)
        {
            const std::size_t lineStart = text.rfind('\n', pos);
            const std::size_t from =
                lineStart == std::string::npos ? 0 : lineStart + 1;
            if (text.substr(from, pos - from).find("//") == std::string::npos)
            {
                return 1 + static_cast<int>
                (
                    std::count(text.begin(), text.begin() + pos, '\n')
                );
            }
        }
        pos += 13;
    }
    return 0;
}


//- Patch types that put a patch into the group of that name (OpenFOAM
//  adds constraint types and wall to a patch's inGroups).
bool typeIsGroup(const std::string& type)
{
    return !type.empty() && type != "patch";
}


bool isProcessorType(const std::string& type)
{
    return type == "processor" || type == "processorCyclic";
}


//- Keys of a boundaryField as the user wrote them, for messages.
std::string boundaryKeys(const dictionary& bf)
{
    std::string s;
    for (const entry& e : bf.entries())
    {
        if (!s.empty()) s += ", ";
        if (e.isDirective())
        {
            s += e.keyword();
            if (!e.tokens().empty()) s += " " + tokensToString(e.tokens());
        }
        else if (e.isPattern())
        {
            s += "\"" + e.keyword() + "\"";
        }
        else
        {
            s += e.keyword();
        }
    }
    return s.empty() ? "(none)" : s;
}

//- OpenFOAM's constraint patch types: a patch of such a type takes only
//  the patchField of the same type, and only such a patch takes it
//  ("inconsistent patch and patchField types" otherwise).
bool isConstraintType(const std::string& type)
{
    static const char* const types[] =
    {
        "empty", "symmetry", "symmetryPlane", "wedge", "cyclic", "cyclicAMI",
        "cyclicACMI", "cyclicSlip", "nonuniformTransformCyclic", "processor",
        "processorCyclic"
    };
    for (const char* t : types)
    {
        if (type == t) return true;
    }
    return false;
}


//- The boundaryField entry OpenFOAM gives the patch: exact name, then
//  patch group (last entry wins, as for patterns), then the last matching
//  regular expression. nullptr if none.
const entry* matchEntry
(
    const fieldTemplate& field,
    const std::string& patchName,
    const std::string& patchType
)
{
    const entry* bfe = field.expanded.findEntry("boundaryField", false);
    if (!bfe || !bfe->isDict()) return nullptr;
    const std::vector<entry>& entries = bfe->dict().entries();

    for (const entry& e : entries)
    {
        if (e.isDict() && !e.isPattern() && e.keyword() == patchName)
        {
            return &e;
        }
    }
    if (typeIsGroup(patchType))
    {
        for (auto it = entries.rbegin(); it != entries.rend(); ++it)
        {
            if (it->isDict() && !it->isPattern() && it->keyword() == patchType)
            {
                return &*it;
            }
        }
    }
    for (auto it = entries.rbegin(); it != entries.rend(); ++it)
    {
        if (it->isDict() && it->isPattern() && it->matches(patchName))
        {
            return &*it;
        }
    }
    return nullptr;
}

//- A nonuniform patch value in a template has one value per face of the
//  template's mesh, not of ours: OpenFOAM would stop on the size.
void checkUniformBoundary(const std::string& file, const dictionary& d)
{
    for (const entry& e : d.entries())
    {
        if (e.isDict())
        {
            checkUniformBoundary(file, e.dict());
            continue;
        }
        for (const token& t : e.tokens())
        {
            if (t.type == token::WORD && t.text == "nonuniform")
            {
                throw FatalError
                (
                    msg() << "Field template \"" << file << "\" line "
                        << e.line() << ": entry '" << e.keyword() << "' of"
                        << " boundaryField \"" << d.name() << "\" is"
                        << " nonuniform\n"
                        << "pmshFoam only maps uniform values: the template's"
                        << " patch faces are not the faces of the new mesh."
                        << " Use 'uniform <value>' (or $internalField).",
                    "pmsh::readFieldTemplate"
                );
            }
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Templates * * * * * * * * * * * * * * * //

bool isFieldClass(const std::string& className)
{
    static const char* const types[] =
    {
        "Scalar", "Vector", "SphericalTensor", "SymmTensor", "Tensor"
    };
    for (const char* type : types)
    {
        if
        (
            className == std::string("vol") + type + "Field"
         || className == std::string("point") + type + "Field"
        )
        {
            return true;
        }
    }
    return false;
}


fieldTemplate readFieldTemplate(const std::string& fileName)
{
    fieldTemplate f;
    {
        std::error_code ec;
        f.file = fs::absolute(fileName, ec).lexically_normal().string();
    }
    f.name = fs::path(f.file).filename().string();

    const std::string text = readText(f.file);

    const dictionary header = readHeader(f.file, text);
    f.className = headerClass(header);
    if (!isFieldClass(f.className))
    {
        throw FatalError
        (
            msg() << "\"" << f.file << "\" is not a field template: its"
                << " FoamFile class is '" << f.className << "'\n"
                << "Expected vol or point Scalar, Vector, SphericalTensor,"
                << " SymmTensor or Tensor fields (e.g. volVectorField)",
            "pmsh::readFieldTemplate"
        );
    }

    if (const int line = nonuniformLine(text))
    {
        nonuniformError(f.file, line);
    }

    // What is written back: local #includes in place (the processor
    // directories are elsewhere, so relative names would break), the rest
    // as written, for OpenFOAM to resolve
    f.dict = dictionary::parse(text, f.file, readOptions{true, false});

    // What OpenFOAM will see, to check patch coverage
    f.expanded = dictionary::parse(text, f.file, readOptions{true, true});

    const entry* internal = f.dict.findEntry("internalField", false);
    if (!internal)
    {
        throw FatalError
        (
            msg() << "Entry 'internalField' not found in field template \""
                << f.file << "\"\n"
                << "Expected 'internalField uniform <value>;'",
            "pmsh::readFieldTemplate"
        );
    }
    const std::vector<token> value = f.dict.expandedTokens(*internal);
    if (!value.empty() && value[0].type == token::WORD && value[0].text == "nonuniform")
    {
        nonuniformError(f.file, internal->line());
    }
    if
    (
        internal->isDict() || value.size() < 2
     || value[0].type != token::WORD || value[0].text != "uniform"
    )
    {
        throw FatalError
        (
            msg() << f.dict.entryInfo(*internal) << " is '"
                << internal->text() << "'\n"
                << "Expected 'internalField uniform <value>;' (pmshFoam maps"
                << " only uniform initial fields)",
            "pmsh::readFieldTemplate"
        );
    }
    std::vector<token> rest(value.begin() + 1, value.end());
    rest.front().space = 1;
    f.internalValue = tokensToString(rest);

    const entry* bf = f.dict.findEntry("boundaryField", false);
    if (!bf || !bf->isDict())
    {
        throw FatalError
        (
            msg() << "Field template \"" << f.file << "\" has no"
                << " 'boundaryField { ... }' sub-dictionary\n"
                << "Every field needs one, with an entry for every patch",
            "pmsh::readFieldTemplate"
        );
    }

    checkUniformBoundary(f.file, bf->dict());

    return f;
}


std::vector<fieldTemplate> readFieldTemplates(const std::string& timeDir)
{
    std::vector<fieldTemplate> fields;
    std::error_code ec;
    if (!fs::is_directory(timeDir, ec)) return fields;

    std::vector<std::string> files;
    for (const fs::directory_entry& d : fs::directory_iterator(timeDir, ec))
    {
        const std::string name = d.path().filename().string();
        if (isBackupName(name) || !d.is_regular_file(ec)) continue;
        files.push_back(d.path().string());
    }
    std::sort(files.begin(), files.end());

    for (const std::string& file : files)
    {
        // The header decides, without parsing the whole file
        std::string text;
        {
            std::ifstream is(file, std::ios::binary);
            if (!is) continue;
            text.resize(65536);
            is.read(&text[0], std::streamsize(text.size()));
            text.resize(std::size_t(is.gcount()));
        }
        if (!isFieldClass(headerClass(readHeader(file, text)))) continue;

        fields.push_back(readFieldTemplate(file));
    }
    return fields;
}


std::string matchingPatchEntry
(
    const fieldTemplate& field,
    const std::string& patchName,
    const std::string& patchType
)
{
    const entry* e = matchEntry(field, patchName, patchType);
    return e ? e->keyword() : "";
}


void checkPatchCoverage
(
    const fieldTemplate& field,
    const std::vector<patchNameType>& patches
)
{
    for (const patchNameType& p : patches)
    {
        // Processor patches get their own entries when written
        if (isProcessorType(p.second)) continue;

        const entry* match = matchEntry(field, p.first, p.second);
        if (!match)
        {
            const dictionary& bf = field.dict.subDict("boundaryField");
            throw FatalError
            (
                msg() << "Field template \"" << field.file << "\" has no"
                    << " boundaryField entry for patch '" << p.first
                    << "' (type " << p.second << ")\n"
                    << "boundaryField entries: " << boundaryKeys(bf) << '\n'
                    << "Add an entry named " << p.first << ", a \"regular"
                    << " expression\" matching it (e.g. \".*\")"
                    << (typeIsGroup(p.second) ? ", or the patch group "
                        + p.second : std::string())
                    << "; OpenFOAM would stop with \"Cannot find patchField"
                    << " entry for " << p.first << "\"",
                "pmsh::checkPatchCoverage"
            );
        }

        // The patchField type must suit a constraint patch (and only one)
        const entry* typeEntry = match->dict().findEntry("type", false);
        if (!typeEntry) continue;
        const std::vector<token> t = match->dict().expandedTokens(*typeEntry);
        if (t.size() != 1 || t[0].type != token::WORD) continue;
        const std::string& fieldType = t[0].text;
        const std::string patchConstraint =
            isConstraintType(p.second) ? p.second : "";
        const std::string fieldConstraint =
            isConstraintType(fieldType) ? fieldType : "";
        if (patchConstraint != fieldConstraint)
        {
            const std::string key =
                match->isPattern() ? "\"" + match->keyword() + "\"" : match->keyword();
            std::ostringstream fix;
            if (!patchConstraint.empty())
            {
                fix << "A " << p.second << " patch needs type " << p.second
                    << ": add #includeEtc \"caseDicts/setConstraintTypes\""
                    << " to boundaryField, or '" << p.first << " { type "
                    << p.second << "; }'";
            }
            else
            {
                fix << "A patch of type " << p.second << " cannot take the"
                    << " constraint type " << fieldType << ": give '"
                    << p.first << "' its own entry";
            }
            throw FatalError
            (
                msg() << "Field template \"" << field.file << "\": patch '"
                    << p.first << "' (type " << p.second << ") gets"
                    << " boundaryField entry " << key << " (line "
                    << match->line() << ") of type " << fieldType << '\n'
                    << fix.str() << '\n'
                    << "OpenFOAM would stop with \"inconsistent patch and"
                    << " patchField types\"",
                "pmsh::checkPatchCoverage"
            );
        }
    }
}


void writeProcessorField
(
    const fieldTemplate& field,
    const std::string& outFile,
    const std::vector<patchNameType>& patches,
    const std::string& timeName
)
{
    checkPatchCoverage(field, patches);

    dictionary out(field.dict);

    // The header: same class and object, this processor's time directory
    dictionary& header = out.subDict("FoamFile");
    header.set("format", "ascii");
    const std::string time =
        timeName.empty()
      ? fs::path(outFile).parent_path().filename().string()
      : timeName;
    if (!time.empty())
    {
        header.set("location", "\"" + time + "\"");
    }

    const bool pointField = field.className.compare(0, 5, "point") == 0;
    dictionary& bf = out.subDict("boundaryField");
    for (const patchNameType& p : patches)
    {
        if (!isProcessorType(p.second)) continue;
        const entry* own = bf.findEntry(p.first, false);
        if (own && own->isDict()) continue;

        // Explicit, so no "regex" of the template can claim the patch
        std::string text = "type " + p.second + ";";
        if (!pointField)
        {
            text += " value uniform " + field.internalValue + ";";
        }
        bf.set(p.first, dictionary::parse(text, outFile, readOptions{false, false}));
    }

    out.writeFile(outFile);
}


// * * * * * * * * * * * * * * * decomposeParDict  * * * * * * * * * * * * //

void writeDecomposeParDict(const std::string& caseDir, int nProcs)
{
    if (nProcs < 1)
    {
        throw FatalError
        (
            msg() << "numberOfSubdomains must be at least 1, not " << nProcs,
            "pmsh::writeDecomposeParDict"
        );
    }
    const std::string path =
        (fs::path(caseDir)/"system"/"decomposeParDict").lexically_normal().string();
    const std::string n = std::to_string(nProcs);

    std::error_code ec;
    if (!fs::exists(path, ec))
    {
        dictionary d(path);
        d.set
        (
            "FoamFile",
            dictionary::parse
            (
                "version 2.0; format ascii; class dictionary;"
                " location \"system\"; object decomposeParDict;",
                path
            )
        );
        d.set("numberOfSubdomains", nProcs);
        d.set("method", "scotch");
        d.writeFile(path);
        return;
    }

    // Edit the text in place, so that the user's comments, layout and
    // every other entry stay exactly as they were
    const std::string text = readText(path);
    const readOptions keep{false, false};
    const dictionary d = dictionary::parse(text, path, keep);

    std::string edited;
    const entry* e = d.findEntry("numberOfSubdomains", false);
    if (e && !e->isDict() && !e->tokens().empty() && e->file() == path)
    {
        const std::size_t from = e->tokens().front().begin;
        const std::size_t to = e->tokens().back().end;
        edited = text.substr(0, from) + n + text.substr(to);
    }
    else
    {
        // After the last entry: a later entry wins over any #include
        std::size_t at = 0;
        for (const entry& x : d.entries())
        {
            if (x.file() == path) at = std::max(at, x.sourceEnd());
        }
        edited = text.substr(0, at) + "\n\nnumberOfSubdomains " + n + ";\n"
            + text.substr(at);
    }

    // Sanity: the edit must read back as intended
    bool ok = false;
    try
    {
        const dictionary check = dictionary::parse(edited, path, keep);
        ok = check.found("numberOfSubdomains", false)
          && check.get<long long>("numberOfSubdomains") == nProcs;
    }
    catch (const FatalError&)
    {}

    if (ok)
    {
        writeFileAtomically(path, edited);
    }
    else
    {
        dictionary rewritten(d);
        rewritten.set("numberOfSubdomains", nProcs);
        rewritten.writeFile(path);
    }
}

} // End namespace pmsh


// ************************************************************************* //
