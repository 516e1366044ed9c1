/*---------------------------------------------------------------------------*\
  pmshFoam: the parent's watch over a child process (childWatchdog.H).
\*---------------------------------------------------------------------------*/

#include "childWatchdog.H"
#include "pmshError.H"
#include "streamManip.H"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <poll.h>
#include <unistd.h>

namespace
{

//- CPU seconds (user + system) and resident bytes of a process, from
//  /proc; zeros where it cannot be read.
void processUsage(pid_t pid, double& cpuSeconds, double& residentBytes)
{
    cpuSeconds = 0;
    residentBytes = 0;
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
    // The command name, in parentheses, may hold spaces: fields follow the
    // last ')', the state first; utime and stime are the 12th and 13th
    const std::size_t close = text.rfind(')');
    if (close != std::string::npos)
    {
        std::istringstream fields(text.substr(close + 1));
        std::string field;
        double ticks = 0;
        for (int i = 1; i <= 13 && fields >> field; ++i)
        {
            if (i >= 12) ticks += std::atof(field.c_str());
        }
        cpuSeconds = ticks/double(::sysconf(_SC_CLK_TCK));
    }
    std::ifstream statm("/proc/" + std::to_string(pid) + "/statm");
    double pages = 0, resident = 0;
    if (statm >> pages >> resident)
    {
        residentBytes = resident*double(::sysconf(_SC_PAGESIZE));
    }
}

} // End anonymous namespace


void pmsh::logMesherLine(const std::string& line)
{
    // Flushed once, prefix included: the lines of ranks that print at the
    // same time do not cut into each other
    const std::ios_base::fmtflags flags = std::cout.flags();
    std::cout.unsetf(std::ios_base::unitbuf);
    Foam::Pout<< "    " << line.c_str() << Foam::endl;
    std::cout.flags(flags);
}


double pmsh::progressInterval()
{
    const char* name = "PMSH_PROGRESS_INTERVAL";
    const char* value = std::getenv(name);
    if (!value || !*value)
    {
        return 30;
    }
    char* end = nullptr;
    const double seconds = std::strtod(value, &end);
    if (*end || !(seconds > 0) || !std::isfinite(seconds))
    {
        throw FatalError
        (
            msg() << "The environment variable " << name << " is '" << value
                << "': valid values are seconds above 0 between progress lines"
                << " of stage 4 (unset: 30)",
            "pmsh::progressInterval"
        );
    }
    return seconds;
}


std::string pmsh::waitForReply
(
    int fd,
    pid_t child,
    const sharedStep* step,
    double interval,
    const std::string& attempt
)
{
    using clock = std::chrono::steady_clock;
    const clock::time_point start = clock::now();
    const auto every = std::chrono::duration_cast<clock::duration>
    (
        std::chrono::duration<double>(interval)
    );
    clock::time_point next = start + every;
    std::string lastStep = "starting";
    for (;;)
    {
        const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>
        (
            next - clock::now()
        ).count();
        pollfd reply{fd, POLLIN, 0};
        const int ready = ::poll(&reply, 1, int(std::max<long long>(0, wait)));
        if (ready > 0 || (ready < 0 && errno != EINTR))
        {
            return {};
        }
        if (ready == 0)
        {
            if (step)
            {
                lastStep = readStep(*step, lastStep);
            }
            double cpu = 0, resident = 0;
            processUsage(child, cpu, resident);
            const double elapsed = std::chrono::duration<double>(clock::now() - start).count();
            const double allowed = step ? overdueAllowance(*step, cpu) : 0;
            if (allowed > 0)
            {
                return msg()
                    << "no sign of progress in " << std::lround(allowed)
                    << " s of CPU time (step: " << lastStep << ", " << std::lround(elapsed)
                    << " s so far): stopped as hung";
            }
            logMesherLine
            (
                msg() << attempt << ": " << std::lround(elapsed) << " s so far, CPU "
                    << std::lround(cpu) << " s, " << std::lround(resident/(1024*1024))
                    << " MiB, step: " << lastStep
            );
            next += every;
        }
    }
}


// ************************************************************************* //
