#include "layerStars.H"

#include <algorithm>

namespace pmsh
{

layerStars::layerStars(const layerSurface& surface, layerExchange& exchange)
:
    surface_(surface),
    exchange_(exchange),
    pointTriangles_(surface.points.size())
{
    const label nTriangles = surface.triangles.size();
    std::vector<bool> shared(surface.points.size(), false);
    for (label t = 0; t < nTriangles; ++t)
    {
        for (const label p : surface.triangles[t])
        {
            pointTriangles_[p].push_back(t);
            if (isInterface(t)) shared[p] = true;
        }
    }
    for (label p = 0; p < label(shared.size()); ++p)
    {
        if (shared[p])
        {
            shared_.push_back(p);
            sharedIds_.push_back(surface.ids[p]);
        }
    }
    sharedPoint_ = std::move(shared);

    // Every star in the order of its triangles' keys, once: the
    // contributions of a point no other rank holds then come in the
    // canonical order, and gather does not key and sort them at each call
    // (keyed star by star: keys for the whole surface at once would add
    // 72 bytes a triangle to the stage's peak)
    std::vector<std::pair<triangleKey, label>> keyed;
    for (std::vector<label>& star : pointTriangles_)
    {
        keyed.clear();
        for (const label t : star) keyed.emplace_back(keyOf(t), t);
        std::stable_sort
        (
            keyed.begin(), keyed.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; }
        );
        for (std::size_t i = 0; i < star.size(); ++i) star[i] = keyed[i].second;
    }
    const std::vector<double> lowest = minimum
    (
        [this](label, label) { return double(exchange_.rank()); }
    );
    counted_.resize(lowest.size());
    for (std::size_t p = 0; p < lowest.size(); ++p)
    {
        counted_[p] = lowest[p] == double(exchange_.rank());
    }
}


const layerSpecification* layerStars::specOf(label t) const
{
    const auto it = surface_.specs.find(surface_.region[t]);
    return it != surface_.specs.end() && it->second.layered() ? &it->second : nullptr;
}


triVerts layerStars::canonical(label t) const
{
    triVerts f = surface_.triangles[t];
    const auto& ids = surface_.ids;
    while (ids[f[1]] < ids[f[0]] || ids[f[2]] < ids[f[0]])
    {
        f = {f[1], f[2], f[0]};
    }
    return f;
}


vector3 layerStars::areaVector(label t) const
{
    const triVerts f = canonical(t);
    const auto& x = surface_.points;
    return cross(x[f[1]] - x[f[0]], x[f[2]] - x[f[0]]);
}


triangleKey layerStars::keyOf(label t) const
{
    return pmsh::keyOf(surface_.ids, surface_.triangles[t]);
}


std::vector<std::vector<keyedContribution>> layerStars::gather
(
    const contribution& f
) const
{
    const label nPoints = pointTriangles_.size();
    std::vector<std::vector<keyedContribution>> all(nPoints);
    for (label p = 0; p < nPoints; ++p)
    {
        for (const label t : pointTriangles_[p])
        {
            keyedContribution c{{}, 0, {0, 0, 0}};
            if (!f(t, p, c.tag, c.value)) continue;
            // Keys only where other ranks' contributions are merged in
            if (sharedPoint_[p]) c.key = keyOf(t);
            all[p].push_back(c);
        }
    }

    std::vector<std::vector<keyedContribution>> shared(shared_.size());
    for (std::size_t i = 0; i < shared_.size(); ++i)
    {
        shared[i] = std::move(all[shared_[i]]);
    }
    exchange_.gatherContributions(sharedIds_, shared);
    for (std::size_t i = 0; i < shared_.size(); ++i)
    {
        all[shared_[i]] = std::move(shared[i]);
    }

    // The canonical order: the same sequence of additions on every rank.
    // A point's star is in key order (the constructor), so its own
    // contributions need sorting by tag only; a shared point's are merged
    // with the other ranks' by key, and by value where two copies of one
    // interface triangle share a key
    for (label p = 0; p < nPoints; ++p)
    {
        auto& list = all[p];
        if (sharedPoint_[p])
        {
            std::sort
            (
                list.begin(), list.end(),
                [](const keyedContribution& a, const keyedContribution& b)
                {
                    if (a.tag != b.tag) return a.tag < b.tag;
                    if (a.key != b.key) return a.key < b.key;
                    return a.value < b.value;
                }
            );
            continue;
        }
        const auto byTag = [](const keyedContribution& a, const keyedContribution& b)
        {
            return a.tag < b.tag;
        };
        if (!std::is_sorted(list.begin(), list.end(), byTag))
        {
            std::stable_sort(list.begin(), list.end(), byTag);
        }
    }
    return all;
}


std::vector<std::vector<std::pair<label, vector3>>> layerStars::sums
(
    const contribution& f
) const
{
    const std::vector<std::vector<keyedContribution>> all = gather(f);
    std::vector<std::vector<std::pair<label, vector3>>> result(all.size());
    for (std::size_t p = 0; p < all.size(); ++p)
    {
        for (const keyedContribution& c : all[p])
        {
            if (result[p].empty() || result[p].back().first != c.tag)
            {
                result[p].push_back({c.tag, {0, 0, 0}});
            }
            result[p].back().second = result[p].back().second + c.value;
        }
    }
    return result;
}


std::vector<double> layerStars::minimum(const limit& f) const
{
    const label nPoints = pointTriangles_.size();
    std::vector<double> least(nPoints, none);
    for (label p = 0; p < nPoints; ++p)
    {
        for (const label t : pointTriangles_[p])
        {
            least[p] = std::min(least[p], f(t, p));
        }
    }
    std::vector<double> shared(shared_.size());
    for (std::size_t i = 0; i < shared_.size(); ++i)
    {
        shared[i] = least[shared_[i]];
    }
    exchange_.minimum(sharedIds_, shared);
    for (std::size_t i = 0; i < shared_.size(); ++i)
    {
        least[shared_[i]] = shared[i];
    }
    return least;
}

} // End namespace pmsh
