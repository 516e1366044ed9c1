/*---------------------------------------------------------------------------*\
  pmshFoam: Netgen volume mesher (Netgen itself is behind netgenInterface).
\*---------------------------------------------------------------------------*/

#include "netgenVolumeMesher.H"
#include "netgenInterface.H"
#include "pmshError.H"
#include "meshingStep.H"

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace
{

//- While it lives, Netgen's task goes to the progress lines of stage 4
//  once a second (reportMeshingStep): Netgen's volume mesher says what it
//  does and how far it is, but only to whoever polls.
class netgenTaskReport
{
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    std::thread thread_;

public:

    netgenTaskReport()
    :
        thread_([this]
        {
            std::unique_lock<std::mutex> lock(mutex_);
            while (!wake_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; }))
            {
                const std::string task = pmsh::ng::currentTask();
                if (!task.empty())
                {
                    pmsh::reportMeshingStep("Netgen: " + task);
                }
            }
        })
    {}

    ~netgenTaskReport()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            done_ = true;
        }
        wake_.notify_one();
        thread_.join();
    }

    netgenTaskReport(const netgenTaskReport&) = delete;
    netgenTaskReport& operator=(const netgenTaskReport&) = delete;
};

} // End anonymous namespace


// * * * * * * * * * * * * * * Static Data Members * * * * * * * * * * * * //

namespace pmsh
{
    defineTypeNameAndDebug(netgenVolumeMesher, 0);
    addToRunTimeSelectionTable(VolumeMesher, netgenVolumeMesher, word);
}


// * * * * * * * * * * * * * * * Member Functions  * * * * * * * * * * * * * //

pmsh::TetMesh pmsh::netgenVolumeMesher::generate
(
    const std::vector<point3>& surfacePoints,
    const std::vector<triVerts>& surfaceTriangles,
    const volumeMeshParameters& parameters
) const
{
    const ng::meshParameters mp = ng::meshParametersOf(parameters);

    ng::volumeMesh m;
    {
        const netgenTaskReport report;
        m = ng::surfaceVolumeMesh(surfacePoints, surfaceTriangles, mp, parameters.what);
    }

    TetMesh result;
    result.points = std::move(m.points);
    result.tets = std::move(m.tets);
    return result;
}


// ************************************************************************* //
