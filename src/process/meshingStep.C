#include "meshingStep.H"

#include <algorithm>
#include <cstring>
#include <ctime>
#include <mutex>
#include <new>
#include <sys/mman.h>
#include <unistd.h>

namespace
{

// The child's page; nullptr in the parent, where reportMeshingStep does
// nothing
pmsh::sharedStep* childStep = nullptr;

void writeStep(pmsh::sharedStep& shared, const std::string& step)
{
    // One writer at a time (a backend may report from a thread of its own)
    static std::mutex writing;
    const std::lock_guard<std::mutex> lock(writing);
    shared.sequence.fetch_add(1, std::memory_order_acq_rel);
    const std::size_t n = std::min(step.size(), sizeof(shared.text) - 1);
    std::memcpy(shared.text, step.data(), n);
    shared.text[n] = 0;
    shared.sequence.fetch_add(1, std::memory_order_acq_rel);
}

} // End anonymous namespace


void pmsh::reportMeshingStep(const std::string& step)
{
    if (childStep)
    {
        writeStep(*childStep, step);
    }
}


void pmsh::expectProgressWithin(double cpuSeconds)
{
    if (childStep)
    {
        timespec now{};
        ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
        // Bound first: the parent never sees the new bound from the old time
        childStep->allowedCpu.store(0, std::memory_order_release);
        const double cpu = double(now.tv_sec) + 1e-9*double(now.tv_nsec);
        childStep->progressCpu.store(cpu, std::memory_order_release);
        childStep->allowedCpu.store(cpuSeconds, std::memory_order_release);
    }
}


double pmsh::overdueAllowance(const sharedStep& shared, double childCpu)
{
    const double allowed = shared.allowedCpu.load(std::memory_order_acquire);
    const double since = shared.progressCpu.load(std::memory_order_acquire);
    return allowed > 0 && childCpu > since + allowed ? allowed : 0;
}


void pmsh::reportStepsTo(sharedStep* shared)
{
    childStep = shared;
}


std::string pmsh::readStep(const sharedStep& shared, const std::string& previous)
{
    const unsigned before = shared.sequence.load(std::memory_order_acquire);
    if (before % 2)
    {
        return previous;
    }
    char text[sizeof(shared.text)];
    std::memcpy(text, shared.text, sizeof(text));
    text[sizeof(text) - 1] = 0;
    std::atomic_thread_fence(std::memory_order_acquire);
    return shared.sequence.load(std::memory_order_relaxed) == before ? text : previous;
}


pmsh::sharedStepPage::sharedStepPage()
{
    fd_ = ::memfd_create("pmshMeshingStep", 0);
    if (fd_ < 0 || ::ftruncate(fd_, sizeof(sharedStep)) != 0)
    {
        return;
    }
    page_ = mapStep(fd_);
    if (page_)
    {
        new (page_) sharedStep();
        writeStep(*page_, "starting");
    }
}


pmsh::sharedStepPage::~sharedStepPage()
{
    if (page_) ::munmap(page_, sizeof(sharedStep));
    if (fd_ >= 0) ::close(fd_);
}


pmsh::sharedStep* pmsh::sharedStepPage::mapStep(int fd)
{
    void* page = ::mmap
    (
        nullptr, sizeof(sharedStep), PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0
    );
    return page == MAP_FAILED ? nullptr : static_cast<sharedStep*>(page);
}
