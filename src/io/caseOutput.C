#include "caseOutput.H"
#include "foamShims.H"
#include "pmshError.H"

#include "fileOperation.H"

#include <filesystem>
#include <system_error>

namespace fs = std::filesystem;

namespace
{

const char* const scratchName = ".pmshFoam.tmp";

} // End anonymous namespace


std::vector<std::string> pmsh::caseOutput::targets() const
{
    if (!comm_.parallel())
    {
        return {"constant/polyMesh"};
    }
    std::vector<std::string> t{"processor" + std::to_string(comm_.rank())};
    if (comm_.master())
    {
        t.push_back(Foam::fileOperation::processorsBaseDir + std::to_string(comm_.size()));
    }
    return t;
}


pmsh::caseOutput::caseOutput
(
    const Communicator& comm,
    const Foam::Time& runTime,
    bool overwrite
)
:
    comm_(comm),
    caseDir_(runTime.globalPath()),
    scratchDir_(caseDir_ + "/" + scratchName)
{
    for (const std::string& target : targets())
    {
        if (fs::exists(caseDir_ + "/" + target) && !overwrite)
        {
            throw FatalError
            (
                msg() << "A mesh already exists in \"" << caseDir_ << "/" << target << "\"\n"
                    << "Use -overwrite to replace it (it is replaced only if"
                    << " meshing succeeds on every rank)",
                "caseOutput"
            );
        }
    }

    // A scratch case left by a run that was killed
    if (comm.master())
    {
        std::error_code ec;
        fs::remove_all(scratchDir_, ec);
        linkCaseData();
    }
    comm.barrier();

    // The scratch case mirrors the real one: same controlDict (writeFormat,
    // writePrecision, startTime), a processor case when parallel
    const Foam::fileName caseName =
        runTime.globalCaseName()/scratchName
      / (comm.parallel() ? Foam::word("processor" + Foam::name(comm.rank())) : Foam::word::null);
    scratchTime_.reset
    (
        foam::newTime(runTime.controlDict(), runTime.rootPath(), caseName)
    );
    // Made now, not by the first write: a condition's processorN/../
    // path (linkCaseData) resolves only through an existing directory, and
    // the fields are tried on the patches before the meshing
    fs::create_directories(std::string(scratchTime_->path()));
}


void pmsh::caseOutput::linkCaseData() const
{
    // Boundary conditions read case data relative to the processor case
    // the fields are built in: timeVaryingMappedFixedValue reads
    // processorN/../constant/boundaryData/<patch>, which must be the real
    // case's. Everything in constant/ but the mesh is linked (relative
    // links: the case may move); remove_all takes the links, not their
    // targets
    const fs::path constant = fs::path(caseDir_)/"constant";
    std::error_code ec;
    if (!fs::is_directory(constant, ec))
    {
        return;
    }
    const fs::path scratchConstant = fs::path(scratchDir_)/"constant";
    fs::create_directories(scratchConstant);
    for (const fs::directory_entry& e : fs::directory_iterator(constant))
    {
        const std::string name = e.path().filename().string();
        if (name == "polyMesh")
        {
            continue;
        }
        fs::create_symlink(fs::path("../../constant")/name, scratchConstant/name);
    }
}


pmsh::caseOutput::~caseOutput()
{
    if (!committed_ && comm_.master())
    {
        std::error_code ec;
        fs::remove_all(scratchDir_, ec);
    }
}


void pmsh::caseOutput::commit()
{
    // The collated fileHandler may still be writing in its thread
    Foam::fileHandler().flush();
    comm_.barrier();

    // Move the old output aside, the new into place, then drop the old:
    // a target never exists half-written
    for (const std::string& target : targets())
    {
        const std::string from = scratchDir_ + "/" + target;
        const std::string to = caseDir_ + "/" + target;
        const std::string previous = scratchDir_ + "/" + target + ".previous";
        if (fs::exists(to))
        {
            fs::create_directories(fs::path(previous).parent_path());
            fs::rename(to, previous);
        }
        // (the scratch processor case stays empty when the collated
        // fileHandler writes processors<P>: no output)
        if (fs::exists(from) && !fs::is_empty(from))
        {
            fs::create_directories(fs::path(to).parent_path());
            fs::rename(from, to);
        }
    }
    committed_ = true;
    comm_.barrier();
    if (comm_.master())
    {
        std::error_code ec;
        fs::remove_all(scratchDir_, ec);
    }
}
