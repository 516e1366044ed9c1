#include "stageLog.H"
#include "Info.H"

#include <iomanip>
#include <ostream>

pmsh::minAvgMax pmsh::reduceMinAvgMax(const Communicator& comm, double x)
{
    return {comm.min(x), comm.sum(x)/comm.size(), comm.max(x)};
}


pmsh::stageLog::stageLog(const Communicator& comm)
:
    comm_(comm)
{}


void pmsh::stageLog::begin(const std::string& name)
{
    name_ = name;
    Info() << name << '\n';
    timer_.restart();
}


void pmsh::stageLog::end()
{
    const minAvgMax t = reduceMinAvgMax(comm_, timer_.elapsed());
    Info() << std::fixed << std::setprecision(2);
    if (comm_.parallel())
    {
        Info()
            << "    time (s) min/avg/max: " << t.min << " / " << t.avg << " / " << t.max
            << '\n';
    }
    else
    {
        Info() << "    time: " << t.max << " s\n";
    }
    Info() << std::defaultfloat << std::setprecision(6) << '\n';
    times_.emplace_back(name_, t.max);
}
