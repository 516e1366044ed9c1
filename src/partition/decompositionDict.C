#include "partitionCoarseMesh.H"
#include "decompositionMethodCheck.H"
#include "foamShims.H"
#include "pmshError.H"
#include "streamManip.H"

// OpenFOAM
#include "argList.H"
#include "dictionary.H"
#include "IFstream.H"
#include "OSspecific.H"

#include <set>

using Foam::Info;

namespace
{

using namespace pmsh;

// Methods whose decompose(globalCellCells, ...) is NotImplemented: they need
// an OpenFOAM polyMesh, which the coarse mesh is not
const std::set<std::string> meshOnlyMethods{"manual", "structured"};

std::vector<std::string> knownMethods()
{
    std::vector<std::string> methods;
    for (const Foam::word& name : foam::decompositionMethodNames())
    {
        if (!meshOnlyMethods.count(name))
        {
            methods.push_back(name);
        }
    }
    return methods;
}


// The method's name ("" when the dictionary has none)
std::string methodName(const Foam::dictionary& dict)
{
    const foamErrorsThrow throwing;
    Foam::word method;
    try
    {
        dict.readIfPresent("method", method);
    }
    catch (const Foam::error&)
    {
        return "(not a word)";
    }
    return method;
}


// The name of the default dictionary (a valid fileName: no spaces)
const char* const defaultName = "defaultDecomposition";

// Where the dictionary comes from, for messages
std::string dictSource(const Foam::dictionary& dict)
{
    if (dict.name() == defaultName)
    {
        return "the default, as the case has no decomposeParDict";
    }
    if (dict.name().empty())
    {
        return "the decomposition dictionary";
    }
    return dict.name();
}

} // End anonymous namespace


std::string pmsh::methodFrom(const Foam::dictionary& dict)
{
    return "decomposition method '" + methodName(dict) + "' (from "
        + dictSource(dict) + ")";
}


void pmsh::checkDecompositionMethod(const Foam::dictionary& dict)
{
    const std::string method = methodName(dict);
    const std::vector<std::string> known = knownMethods();
    if (method.empty())
    {
        throw FatalError
        (
            msg() << "No decomposition 'method' in " << dictSource(dict) << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    if (meshOnlyMethods.count(method))
    {
        throw FatalError
        (
            msg() << "The " << methodFrom(dict) << " needs an OpenFOAM"
                << " polyMesh: it cannot split the coarse tet mesh.\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
    if (std::find(known.begin(), known.end(), method) == known.end())
    {
        throw FatalError
        (
            msg() << "Unknown " << methodFrom(dict) << ".\n"
                << "Valid decomposition methods: " << validDecompositionMethods(),
            "partitionCells"
        );
    }
}


Foam::fileName pmsh::decompositionDictFile(const Foam::argList& args)
{
    Foam::fileName file;
    if (foam::readIfPresent(args, "decomposeParDict", file))
    {
        // As argList resolves it for a parallel run (it leaves it as given
        // in a serial one)
        if (Foam::isDir(file))
        {
            file /= "decomposeParDict";
        }
        if (!file.isAbsolute() && file.compare(0, 1, ".") != 0)
        {
            file = foam::globalPath(args)/file;
        }
        file.expand();
        file.clean();
        return file;
    }
    return foam::globalPath(args)/"system"/"decomposeParDict";
}


Foam::dictionary pmsh::decompositionDict
(
    const Foam::fileName& dictFile,
    int nParts,
    bool required
)
{
    Foam::dictionary dict;
    if (Foam::isFile(dictFile))
    {
        try
        {
            const foamErrorsThrow throwing;
            Foam::IFstream is(dictFile);
            if (!is.good())
            {
                throw FatalError
                (
                    msg() << "Cannot open the decomposition dictionary " << dictFile,
                    "decompositionDict"
                );
            }
            dict = Foam::dictionary(is);
            dict.name() = dictFile;
        }
        catch (const Foam::error& e)
        {
            throw FatalError
            (
                msg() << "Cannot read the decomposition dictionary " << dictFile
                    << ":\n" << FatalError::of(e).message(),
                "decompositionDict"
            );
        }
        if (!dict.found("method"))
        {
            throw FatalError
            (
                msg() << "No 'method' in " << dictFile << ".\n"
                    << "Valid decomposition methods: " << validDecompositionMethods(),
                "decompositionDict"
            );
        }
    }
    else if (required)
    {
        throw FatalError
        (
            msg() << "The decomposition dictionary " << dictFile
                << " (-decomposeParDict) does not exist.\n"
                << "Name an existing file, or leave -decomposeParDict out to use"
                << " system/decomposeParDict (method metis when there is none)",
            "decompositionDict"
        );
    }
    else
    {
        dict = defaultDecompositionDict();
    }

    // numberOfSubdomains is the number of ranks, whatever the file says
    if (dict.found("numberOfSubdomains"))
    {
        std::string inFile = "?";
        Foam::label n = -1;
        try
        {
            const foamErrorsThrow throwing;
            inFile = foam::tokensString(dict.lookup("numberOfSubdomains"));
            n = foam::get<Foam::label>(dict, "numberOfSubdomains");
        }
        catch (const Foam::error&)
        {
            n = -1;     // not a number: replaced all the same
        }
        if (n != nParts)
        {
            Info
                << "Note: numberOfSubdomains " << inFile.c_str() << " in " << dictFile.c_str()
                << " is replaced by the number of ranks, " << nParts << "\n";
        }
    }
    dict.set("numberOfSubdomains", Foam::label(nParts));

    // A wrong method stops now, before the coarse mesh is made
    checkDecompositionMethod(dict);
    return dict;
}


Foam::dictionary pmsh::decompositionDict(const Foam::argList& args, int nParts)
{
    return decompositionDict
    (
        decompositionDictFile(args),
        nParts,
        foam::found(args, "decomposeParDict")
    );
}


const Foam::dictionary& pmsh::defaultDecompositionDict()
{
    static const Foam::dictionary dict = []
    {
        Foam::dictionary d;
        d.name() = defaultName;
        d.add("method", Foam::word("metis"));

        // k-way, not OpenFOAM's default recursive bisection: on the sphere
        // at r = 4 the recursive parts gave HXT a surface it filled with a
        // flat cell (checkMesh: aspect ratio 6e9); k-way parts did not
        Foam::dictionary coeffs;
        coeffs.add("method", Foam::word("k-way"));
        d.add("metisCoeffs", coeffs);
        return d;
    }();
    return dict;
}


std::string pmsh::validDecompositionMethods()
{
    std::string list = "(";
    for (const std::string& method : knownMethods())
    {
        list += (list.size() > 1 ? " " : "") + method;
    }
    return list + ")";
}


// ************************************************************************* //
