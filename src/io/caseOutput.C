#include "caseOutput.H"
#include "error.H"

#include <filesystem>
#include <system_error>
#include <unistd.h>

namespace fs = std::filesystem;

pmsh::caseOutput::caseOutput
(
    const Communicator& comm,
    const std::string& caseDir,
    bool overwrite
)
:
    comm_(comm),
    caseDir_(caseDir),
    overwrite_(overwrite)
{
    if (comm.parallel())
    {
        const std::string name = "processor" + std::to_string(comm.rank());
        target_ = caseDir + "/" + name;
        temporary_ = caseDir + "/." + name + ".pmshFoam-" + std::to_string(getpid());
    }
    else
    {
        target_ = caseDir + "/constant/polyMesh";
        temporary_ = caseDir + "/constant/.polyMesh.pmshFoam-" + std::to_string(getpid());
    }

    if (fs::exists(target_) && !overwrite)
    {
        throw FatalError
        (
            msg() << "A mesh already exists in \"" << target_ << "\"\n"
                << "Use -overwrite to replace it (it is replaced only if"
                << " meshing succeeds on every rank)",
            "caseOutput"
        );
    }
}


pmsh::caseOutput::~caseOutput()
{
    if (!committed_)
    {
        std::error_code ec;
        fs::remove_all(temporary_, ec);
    }
}


std::string pmsh::caseOutput::polyMeshDir() const
{
    return comm_.parallel()
        ? temporary_ + "/constant/polyMesh"
        : temporary_;
}


std::string pmsh::caseOutput::timeDir(const std::string& timeName) const
{
    return temporary_ + "/" + timeName;
}


std::string pmsh::caseOutput::polyMeshLocation() const
{
    return comm_.parallel()
        ? "processor" + std::to_string(comm_.rank()) + "/constant/polyMesh"
        : "constant/polyMesh";
}


bool pmsh::caseOutput::commit(bool succeeded)
{
    if (!comm_.all(succeeded))
    {
        std::error_code ec;
        fs::remove_all(temporary_, ec);
        return false;
    }

    // Move the old output aside, the new into place, then drop the old: the
    // target never exists half-written.
    const std::string previous = temporary_ + ".previous";
    if (fs::exists(target_))
    {
        fs::rename(target_, previous);
    }
    fs::rename(temporary_, target_);
    std::error_code ec;
    fs::remove_all(previous, ec);
    committed_ = true;
    comm_.barrier();
    return true;
}
