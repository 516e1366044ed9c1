#include "argList.H"
#include "Info.H"
#include "error.H"

#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{

const char* const usage =
R"(Usage: pmshFoam [OPTIONS]
options:
  -case <dir>       Specify case directory to use (instead of the cwd)
  -dict <file>      Use specified mesh dictionary (default: system/pmshDict)
  -overwrite        Replace an existing mesh (constant/polyMesh or processor*)
  -parallel         Run in parallel: one partition per MPI rank
  -help             Print the usage

Generate a tetrahedral mesh of the geometry named in system/pmshDict and
write it as constant/polyMesh (serial) or as processor*/constant/polyMesh
with initial fields and system/decomposeParDict (-parallel), ready for
"mpirun -np N <solver> -parallel" without decomposePar.
)";

} // End anonymous namespace


bool pmsh::argList::parallelRequested(int argc, char** argv)
{
    for (int i = 1; i < argc; ++i)
    {
        if (std::string(argv[i]) == "-parallel")
        {
            return true;
        }
    }
    return false;
}


void pmsh::argList::printUsage()
{
    std::cout << '\n' << usage << '\n';
}


pmsh::argList::argList(int argc, char** argv)
:
    executable_(argc > 0 ? fs::path(argv[0]).filename().string() : "pmshFoam"),
    caseDir_(fs::current_path().string())
{
    for (int i = 1; i < argc; ++i)
    {
        args_.push_back(argv[i]);
    }

    auto value = [&](std::size_t& i) -> std::string
    {
        if (i + 1 >= args_.size())
        {
            throw FatalError
            (
                msg() << "Option '" << args_[i] << "' requires an argument\n"
                    << "See 'pmshFoam -help' for usage",
                "argList"
            );
        }
        return args_[++i];
    };

    for (std::size_t i = 0; i < args_.size(); ++i)
    {
        const std::string& a = args_[i];
        if (a == "-help" || a == "--help" || a == "-h")
        {
            printUsage();
            std::exit(0);
        }
        else if (a == "-parallel")
        {
            parallel_ = true;
        }
        else if (a == "-overwrite")
        {
            overwrite_ = true;
        }
        else if (a == "-case")
        {
            caseDir_ = fs::absolute(value(i)).lexically_normal().string();
        }
        else if (a == "-dict")
        {
            dictFile_ = value(i);
        }
        else
        {
            throw FatalError
            (
                msg() << "Invalid option: " << a << "\n\n"
                    << "Valid options are: -case <dir>, -dict <file>, -overwrite,"
                    << " -parallel, -help",
                "argList"
            );
        }
    }

    // Strip a trailing "/." left by lexically_normal
    while (caseDir_.size() > 1 && caseDir_.back() == '/')
    {
        caseDir_.pop_back();
    }
    if (!fs::is_directory(caseDir_))
    {
        throw FatalError
        (
            msg() << "Case directory \"" << caseDir_ << "\" does not exist",
            "argList"
        );
    }
}


void pmsh::argList::printBanner(int nProcs) const
{
    char host[256] = "unknown";
    gethostname(host, sizeof(host) - 1);
    const std::time_t now = std::time(nullptr);
    char date[64], time[64];
    std::strftime(date, sizeof(date), "%b %d %Y", std::localtime(&now));
    std::strftime(time, sizeof(time), "%H:%M:%S", std::localtime(&now));

    std::string exec = executable_;
    for (const std::string& a : args_)
    {
        exec += ' ' + a;
    }

    Info()
        << "/*---------------------------------------------------------------------------*\\\n"
        << "  =========                 |\n"
        << "  \\\\      /  F ield         | pmshFoam: massive parallel tetrahedral meshes\n"
        << "   \\\\    /   O peration     | PMSH method (coarse Netgen mesh, METIS,\n"
        << "    \\\\  /    A nd           | surface refinement, per-partition remeshing)\n"
        << "     \\\\/     M anipulation  |\n"
        << "\\*---------------------------------------------------------------------------*/\n"
        << "Exec   : " << exec << '\n'
        << "Date   : " << date << '\n'
        << "Time   : " << time << '\n'
        << "Host   : " << host << '\n'
        << "PID    : " << getpid() << '\n'
        << "Case   : " << caseDir_ << '\n'
        << "nProcs : " << nProcs << '\n'
        << "\n";
}
