#include "stageClock.H"

#include <algorithm>
#include <fstream>
#include <sys/resource.h>
#include <string>
#include <unistd.h>

long pmsh::peakMemoryBytes()
{
    // /proc/self/status reports the high-water mark as "VmHWM:  1234 kB"
    long self = 0;
    std::ifstream is("/proc/self/status");
    for (std::string key; is >> key; )
    {
        if (key == "VmHWM:")
        {
            long kB = 0;
            is >> kB;
            self = kB*1024;
            break;
        }
        std::getline(is, key);
    }

    // Volume meshing runs in child processes (childProcess.H): their peak
    // is this rank's peak too
    struct rusage children;
    const long child = ::getrusage(RUSAGE_CHILDREN, &children) == 0
        ? children.ru_maxrss*1024L : 0;     // ru_maxrss is in kB on Linux
    return std::max(self, child);
}


long pmsh::machineMemoryBytes()
{
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long pageSize = sysconf(_SC_PAGE_SIZE);
    return (pages > 0 && pageSize > 0) ? pages*pageSize : 0;
}
