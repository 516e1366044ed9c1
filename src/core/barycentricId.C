#include "barycentricId.H"
#include "pmshError.H"

#include <algorithm>
#include <ostream>
#include <utility>

pmsh::barycentricId::barycentricId
(
    std::uint32_t i, std::uint32_t a,
    std::uint32_t j, std::uint32_t b,
    std::uint32_t k, std::uint32_t c
)
{
    std::array<std::pair<std::uint32_t, std::uint32_t>, 3> pairs
    {{
        {a ? i : 0u, a},
        {b ? j : 0u, b},
        {c ? k : 0u, c}
    }};
    std::sort(pairs.begin(), pairs.end());
    for (int n = 0; n < 3; ++n)
    {
        vertex[n] = pairs[n].first;
        weight[n] = pairs[n].second;
    }
}


bool pmsh::barycentricId::packable
(
    std::uint64_t nCoarsePoints,
    int refinementLevels
)
{
    const int weightBits = refinementLevels + 1;
    return weightBits < 32 && nCoarsePoints < (std::uint64_t(1) << (32 - weightBits));
}


std::array<std::uint32_t, 3> pmsh::barycentricId::pack(int refinementLevels) const
{
    const int weightBits = refinementLevels + 1;
    std::array<std::uint32_t, 3> packed;
    for (int n = 0; n < 3; ++n)
    {
        packed[n] = (vertex[n] << weightBits) | weight[n];
    }
    return packed;
}


pmsh::barycentricId pmsh::barycentricId::unpack
(
    const std::array<std::uint32_t, 3>& packed,
    int refinementLevels
)
{
    const int weightBits = refinementLevels + 1;
    const std::uint32_t mask = (std::uint32_t(1) << weightBits) - 1;
    barycentricId id;
    for (int n = 0; n < 3; ++n)
    {
        id.vertex[n] = packed[n] >> weightBits;
        id.weight[n] = packed[n] & mask;
    }
    return id;
}


std::ostream& pmsh::operator<<(std::ostream& os, const barycentricId& id)
{
    os  << '[';
    for (int n = 0; n < 3; ++n)
    {
        os  << (n ? "," : "") << '(' << id.vertex[n] << ',' << id.weight[n] << ')';
    }
    return os << ']';
}


int pmsh::ownerRank(const barycentricId& id, const std::vector<int>& sortedHolders)
{
    if (sortedHolders.empty())
    {
        throw FatalError(msg() << "Vertex " << id << " has no holder rank", "ownerRank");
    }
    return sortedHolders[id.ownerSum() % sortedHolders.size()];
}
