#include "stageLog.H"
#include "streamManip.H"

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <ostream>

using Foam::Info;
using Foam::fixed;
using Foam::setprecision;

pmsh::minAvgMax pmsh::minAvgMaxOf(const std::vector<double>& perRank)
{
    const auto [low, high] = std::minmax_element(perRank.begin(), perRank.end());
    const double sum = std::accumulate(perRank.begin(), perRank.end(), 0.0);
    return {*low, sum/perRank.size(), *high};
}


pmsh::minAvgMax pmsh::reduceMinAvgMax(const Communicator& comm, double x)
{
    return minAvgMaxOf(comm.allGather(x));
}


pmsh::stageLog::stageLog(const Communicator& comm)
:
    comm_(comm)
{}


void pmsh::stageLog::begin(const std::string& key, const std::string& title)
{
    key_ = key;
    title_ = title;
    Info << title.c_str() << '\n';
    timer_.restart();
}


const pmsh::stageLog::stageTime* pmsh::stageLog::find(const std::string& key) const
{
    for (const stageTime& t : times_)
    {
        if (t.key == key)
        {
            return &t;
        }
    }
    return nullptr;
}


double pmsh::stageLog::time(const std::string& key) const
{
    const stageTime* t = find(key);
    return t ? t->max : 0;
}


double pmsh::stageLog::peakMemory(const std::string& key) const
{
    const stageTime* t = find(key);
    return t ? t->peakMemoryBytes : 0;
}


void pmsh::stageLog::end()
{
    const std::vector<double> perRank = comm_.allGather(timer_.elapsed());
    const minAvgMax t = minAvgMaxOf(perRank);
    const double memory = minAvgMaxOf(comm_.allGather(double(peakMemoryBytes()))).max;
    Info << fixed << setprecision(2);
    if (comm_.parallel())
    {
        Info
            << "    time (s) min/avg/max: " << t.min << " / " << t.avg << " / " << t.max
            << setprecision(1)
            << ", peak memory (MiB) max: " << memory/1048576.0 << '\n';
    }
    else
    {
        Info
            << "    time: " << t.max << " s" << setprecision(1)
            << ", peak memory: " << memory/1048576.0 << " MiB\n";
    }
    Info << defaultfloat << setprecision(6) << '\n';
    times_.push_back({key_, title_, perRank, t.max, memory});
}
