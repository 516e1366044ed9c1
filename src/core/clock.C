#include "clock.H"

#include <fstream>
#include <string>
#include <unistd.h>

long pmsh::peakMemoryBytes()
{
    // /proc/self/status reports the high-water mark as "VmHWM:  1234 kB"
    std::ifstream is("/proc/self/status");
    for (std::string key; is >> key; )
    {
        if (key == "VmHWM:")
        {
            long kB = 0;
            is >> kB;
            return kB*1024;
        }
        std::getline(is, key);
    }
    return 0;
}


long pmsh::machineMemoryBytes()
{
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long pageSize = sysconf(_SC_PAGE_SIZE);
    return (pages > 0 && pageSize > 0) ? pages*pageSize : 0;
}
