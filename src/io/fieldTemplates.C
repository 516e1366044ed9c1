#include "fieldTemplates.H"
#include "foamShims.H"

#include "IFstream.H"
#include "IOdictionary.H"
#include "OFstream.H"
#include "OSspecific.H"
#include "primitiveEntry.H"
#include "volFields.H"

namespace
{

const Foam::wordList fieldClasses
{
    Foam::volScalarField::typeName,
    Foam::volVectorField::typeName,
    Foam::volSphericalTensorField::typeName,
    Foam::volSymmTensorField::typeName,
    Foam::volTensorField::typeName
};


// Stop unless the value of `keyword` in dict starts with "uniform". The
// error names the field's file (file, not dict.name(), which for a
// sub-dictionary is "<file>.boundaryField.<patch>"), the entry's line and
// where the entry is (scope: "" or "boundaryField/<patch>").
void requireUniform
(
    const Foam::fileName& file,
    const Foam::dictionary& dict,
    const Foam::word& keyword,
    const std::string& scope = ""
)
{
    const Foam::entry* e = pmsh::foam::findEntry(dict, keyword);
    if (!e || !e->isStream())
    {
        return;
    }
    const Foam::ITstream& is = e->stream();
    if (is.size() && is[0].isWord() && is[0].wordToken() == "uniform")
    {
        return;
    }
    pmsh::foam::ioError
    (
        Foam::FatalIOError, FUNCTION_NAME, __FILE__, __LINE__,
        file, e->startLineNumber(), e->endLineNumber()
    )
        << "Entry '" << keyword.c_str() << "'"
        << (scope.empty() ? "" : " of " + scope).c_str() << " is nonuniform:"
        << " pmshFoam makes new cells and faces, so only uniform values"
        << " can be given to them." << Foam::nl
        << "Write it as '" << keyword.c_str() << " uniform <value>;'"
        << " and, to start from a solution on another mesh, map it onto"
        << " the new one afterwards (mapFieldsPar)"
        << Foam::exit(Foam::FatalIOError);
}

} // End anonymous namespace


std::vector<pmsh::fieldTemplate> pmsh::readFieldTemplates(const Foam::Time& runTime)
{
    using namespace Foam;

    // The case's own files, read directly: a processor case's IOobject
    // would look in processorN/<time>, which does not exist yet
    std::vector<fieldTemplate> fields;
    const fileName dir = runTime.globalPath()/pmsh::foam::timeName(runTime);
    for (const fileName& file : pmsh::foam::filesIn(dir))
    {
        IFstream is(dir/file);
        const dictionary dict(is, true);    // keep FoamFile: its class
        const dictionary* header = pmsh::foam::findDict(dict, "FoamFile");
        const word className =
            header ? pmsh::foam::getOrDefault<word>(*header, "class", word::null) : word::null;
        if (std::find(fieldClasses.begin(), fieldClasses.end(), className) == fieldClasses.end())
        {
            continue;
        }
        requireUniform(dir/file, dict, "internalField");
        for (const entry& patch : dict.subDict("boundaryField"))
        {
            if (patch.isDict())
            {
                requireUniform
                (
                    dir/file, patch.dict(), "value",
                    "boundaryField/" + patch.keyword()
                );
            }
        }
        fields.push_back({file.name(), className, dict});
    }
    return fields;
}


void pmsh::checkPatchCoverage
(
    const std::vector<fieldTemplate>& fields,
    const std::vector<meshPatch>& physicalPatches
)
{
    using namespace Foam;

    for (const fieldTemplate& field : fields)
    {
        const dictionary& bf = field.dict.subDict("boundaryField");
        for (const meshPatch& patch : physicalPatches)
        {
            // As OpenFOAM matches: name, group (a patch's group is its
            // constraint or wall type), regular expression
            bool inGroup = false;
            for (const std::string& group : patch.groups)
            {
                inGroup = inGroup || pmsh::foam::found(bf, group);
            }
            if
            (
                pmsh::foam::found(bf, patch.name)
             || (patch.type != "patch" && pmsh::foam::found(bf, patch.type))
             || inGroup
             || pmsh::foam::found(bf, patch.name, true)
            )
            {
                continue;
            }
            // The field's file (bf.name() is "<file>.boundaryField"), no
            // line: boundaryField's first entry may come from an #include
            pmsh::foam::ioError
            (
                FatalIOError, FUNCTION_NAME, __FILE__, __LINE__, field.dict.name(), -1, -1
            )
                << "Field " << field.name.c_str() << " has no boundary condition"
                << " for patch '" << patch.name.c_str() << "' (type "
                << patch.type.c_str() << ")." << nl
                << "Add an entry '" << patch.name.c_str() << " { type ...; }'"
                << " (or one for its group or a matching \"regex\") to its"
                << " boundaryField"
                << exit(FatalIOError);
        }
    }
}


namespace
{

// Build the field from dict on mesh, as a solver reads it; write it if
// asked (building alone runs every condition's checks)
template<class FieldType>
void buildField
(
    const pmsh::fieldTemplate& field,
    const Foam::dictionary& dict,
    const Foam::fvMesh& mesh,
    const bool write
)
{
    const FieldType f
    (
        Foam::IOobject
        (
            field.name,
            pmsh::foam::timeName(mesh.time()),
            mesh,
            Foam::IOobject::NO_READ,
            Foam::IOobject::NO_WRITE,
            false
        ),
        mesh,
        dict
    );
    if (write)
    {
        f.write();
    }
}


void buildProcessorField
(
    const pmsh::fieldTemplate& field,
    const Foam::fvMesh& mesh,
    const bool write
)
{
    using namespace Foam;

    // Processor patches: the internal value, unless the template says
    // (setConstraintTypes, which most cases include, does: adding it again
    // would make OpenFOAM warn)
    dictionary dict(field.dict);
    dictionary& boundaryField = dict.subDict("boundaryField");
    for (const word type : {"processor", "processorCyclic"})
    {
        if (!pmsh::foam::found(boundaryField, type))
        {
            dictionary processor;
            processor.add("type", type);
            processor.add(new primitiveEntry("value", dict.lookup("internalField")));
            boundaryField.add(type, processor);
        }
    }

    if (field.className == volScalarField::typeName)
    {
        buildField<volScalarField>(field, dict, mesh, write);
    }
    else if (field.className == volVectorField::typeName)
    {
        buildField<volVectorField>(field, dict, mesh, write);
    }
    else if (field.className == volSphericalTensorField::typeName)
    {
        buildField<volSphericalTensorField>(field, dict, mesh, write);
    }
    else if (field.className == volSymmTensorField::typeName)
    {
        buildField<volSymmTensorField>(field, dict, mesh, write);
    }
    else
    {
        buildField<volTensorField>(field, dict, mesh, write);
    }
}

} // End anonymous namespace


void pmsh::writeProcessorField(const fieldTemplate& field, const Foam::fvMesh& mesh)
{
    buildProcessorField(field, mesh, true);
}


void pmsh::checkFieldOnPatches(const fieldTemplate& field, const Foam::fvMesh& patchesOnly)
{
    buildProcessorField(field, patchesOnly, false);
}


void pmsh::writeDecomposeParDict
(
    const Foam::Time& runTime,
    const Foam::dictionary& decomposition
)
{
    // The master writes the case's file directly: a global object, and
    // the other ranks must not wait on a collective write of it
    if (!Foam::Pstream::master())
    {
        return;
    }
    const Foam::IOdictionary dict
    (
        Foam::IOobject
        (
            "decomposeParDict",
            runTime.system(),
            runTime,
            Foam::IOobject::NO_READ,
            Foam::IOobject::NO_WRITE,
            false
        ),
        decomposition
    );
    Foam::OFstream os(runTime.globalPath()/runTime.system()/"decomposeParDict");
    dict.writeHeader(os);
    dict.writeData(os);
    Foam::IOobject::writeEndDivider(os);
}
