#include "caseInputs.H"
#include "failTogether.H"
#include "foamShims.H"
#include "partitionCoarseMesh.H"
#include "pmshError.H"

#include "IOdictionary.H"

pmsh::caseInputs pmsh::readCaseInputs
(
    const Communicator& comm,
    const Foam::argList& args,
    const Foam::Time& runTime
)
{
    caseInputs inputs;
    failTogether(comm, [&]
    {
        const Foam::IOobject dictIO = foam::systemDictIO("pmshDict", args, runTime);
        // Every rank stops on a missing file: reading it would leave the
        // others waiting for the master's copy
        const Foam::fileName dictFile = foam::globalObjectPath(dictIO, runTime);
        if (!Foam::isFile(dictFile))
        {
            throw FatalError
            (
                "The mesh dictionary \"" + dictFile + "\" does not exist.\n"
                "Create system/pmshDict (see the tutorials), or name"
                " another file with -dict <file>",
                "pmshFoam"
            );
        }
        inputs.settings =
            readMeshSettings(Foam::IOdictionary(dictIO), runTime.globalPath());
        if (comm.parallel())
        {
            inputs.decomposition = decompositionDict(args, comm.size());
        }
        inputs.geometry = Geometry::New(inputs.settings.geometryFiles, inputs.settings.domain);
    });
    return inputs;
}


// ************************************************************************* //
