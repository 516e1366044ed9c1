/*---------------------------------------------------------------------------*\
  pmshFoam: how src/netgen calls Netgen (see netgenSession.H).
\*---------------------------------------------------------------------------*/

#include "netgenSession.H"

namespace pmsh
{
namespace ng
{

std::mutex netgenMutex;


std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
    {
        return "";
    }
    const auto e = s.find_last_not_of(" \t\r\n");
    return s.substr(b, e - b + 1);
}


std::string oneLine(const std::string& s)
{
    std::string r;
    bool space = false;
    for (char c : trim(s))
    {
        if (c == '\n' || c == '\r' || c == '\t' || c == ' ')
        {
            space = true;
        }
        else
        {
            if (space && !r.empty())
            {
                r += ' ';
            }
            r += c;
            space = false;
        }
    }
    return r;
}


std::string exceptionText(const std::exception& e)
{
    const std::string s = oneLine(e.what());
    return s.empty() ? std::string("(no message)") : s;
}


std::string secondsString(double seconds)
{
    std::ostringstream os;
    os << seconds << " s";
    return os.str();
}


namespace
{

//- restrictLocalSizes' samples, each given to setH(point, size); the
//  tree's box (treeBox()) is asked for only when there are regions
template<class TreeBox, class SetH>
void restrictAtSamples(const meshParameters& p, TreeBox treeBox, SetH setH)
{
    using namespace pmsh;
    for (const sizePoint& s : p.sizePoints)
    {
        if (s.size < p.maxh)
        {
            setH(s.p, s.size);
        }
    }
    if (p.regions.empty())
    {
        return;
    }
    const netgen::Box<3>& box = treeBox();
    const point3 lo{box.PMin()(0), box.PMin()(1), box.PMin()(2)};
    const point3 hi{box.PMax()(0), box.PMax()(1), box.PMax()(2)};
    for (const sizeRegion& r : p.regions)
    {
        if (r.size < p.maxh)
        {
            forEachSample(r, lo, hi, [&](const point3& x) { setH(x, r.size); });
        }
    }
}

} // End anonymous namespace


void restrictLocalSizes(netgen::Mesh& mesh, const meshParameters& p)
{
    restrictAtSamples
    (
        p,
        [&]() -> const netgen::Box<3>& { return mesh.LocalHFunction().GetBoundingBox(); },
        [&](const point3& x, double h)
        {
            mesh.RestrictLocalH(netgen::Point3d(x[0], x[1], x[2]), h);
        }
    );
}


void restrictLocalSizes(netgen::LocalH& tree, const meshParameters& p)
{
    // What Mesh::RestrictLocalH does but for its floor, mparam.minh (0:
    // pmshFoam sets none)
    restrictAtSamples
    (
        p,
        [&]() -> const netgen::Box<3>& { return tree.GetBoundingBox(); },
        [&](const point3& x, double h)
        {
            tree.SetH(netgen::Point<3>(x[0], x[1], x[2]), h);
        }
    );
}

} // End namespace ng
} // End namespace pmsh


std::string pmsh::ng::currentTask()
{
    // Read once: Netgen changes them as it goes
    const char* task = netgen::multithread.task;
    const double percent = netgen::multithread.percent;
    std::string text = task && *task ? task : "";
    if (!text.empty() && percent > 0 && percent <= 100)
    {
        text += ", " + std::to_string(int(percent)) + "%";
    }
    return text;
}

// ************************************************************************* //
