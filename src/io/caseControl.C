#include "caseControl.H"
#include "foamShims.H"
#include "pmshError.H"

#include "fileOperation.H"
#include "IFstream.H"
#include "Time.H"

pmsh::caseControl pmsh::readCaseControl(const Foam::argList& args)
{
    caseControl control;
    control.outputFileHandler = Foam::fileHandler().type();
    useFileHandler("uncollated");

    const Foam::fileName controlDictFile =
        args.rootPath()/args.globalCaseName()/"system"/Foam::Time::controlDictName;
    if (!Foam::isFile(controlDictFile))
    {
        throw FatalError
        (
            "cannot find file \"" + controlDictFile + "\"\n"
            "A case needs system/controlDict, as for any OpenFOAM"
            " application (see the tutorials)",
            "pmshFoam"
        );
    }
    Foam::IFstream controlDictStream(controlDictFile);
    control.controlDict = Foam::dictionary(controlDictStream);
    control.controlDict.name() = controlDictFile;
    if
    (
        Foam::dictionary* switches =
            foam::findDict(control.controlDict, "OptimisationSwitches")
    )
    {
        if (switches->readIfPresent("fileHandler", control.outputFileHandler))
        {
            switches->remove("fileHandler");
        }
    }
    return control;
}


void pmsh::useFileHandler(const Foam::word& type)
{
    if (Foam::fileHandler().type() != type)
    {
        Foam::autoPtr<Foam::fileOperation> handler(Foam::fileOperation::New(type, false));
        foam::setFileHandler(handler);
    }
}
