// The collectives of Communicator.H on 1..4 ranks: payloads arrive whole
// and from the right rank, empty ones included, and a struct is gathered
// in one piece.

#include "mpiTestMain.H"

#include <cstdint>
#include <vector>

using namespace pmsh;
using namespace pmsh::test;

namespace
{

//- A record whose fields tell who made it and for whom.
struct record
{
    std::int64_t from;
    std::int32_t to;
    double value;
};

//- What rank `from` sends rank `to`: (from + to) % 3 records (none for
//  some pairs, itself included), each numbered.
std::vector<record> payload(int from, int to)
{
    std::vector<record> v;
    for (int i = 0; i < (from + to) % 3; ++i)
    {
        v.push_back({from, to, 0.5*i + 100*from + to});
    }
    return v;
}

} // End anonymous namespace


TEST(communicator, exchangeDeliversEachRanksPayloadToItsRank)
{
    const Communicator& comm = world();
    std::vector<std::vector<record>> send(comm.size());
    for (int r = 0; r < comm.size(); ++r)
    {
        send[r] = payload(comm.rank(), r);
    }
    const std::vector<std::vector<record>> received = comm.exchange(send);
    ASSERT_EQ(int(received.size()), comm.size());
    for (int r = 0; r < comm.size(); ++r)
    {
        const std::vector<record> expected = payload(r, comm.rank());
        ASSERT_EQ(received[r].size(), expected.size()) << "from rank " << r;
        for (std::size_t i = 0; i < expected.size(); ++i)
        {
            EXPECT_EQ(received[r][i].from, expected[i].from);
            EXPECT_EQ(received[r][i].to, expected[i].to);
            EXPECT_EQ(received[r][i].value, expected[i].value);
        }
    }
}


TEST(communicator, broadcastGivesEveryRankTheMastersVectorWhateverItHeld)
{
    const Communicator& comm = world();
    for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(100000)})
    {
        // The others hold something else, longer or shorter
        std::vector<record> data(comm.master() ? n : 7, record{-1, -1, -1});
        if (comm.master())
        {
            for (std::size_t i = 0; i < n; ++i)
            {
                data[i] = {std::int64_t(i), 0, 0.25*double(i)};
            }
        }
        comm.broadcast(data);
        ASSERT_EQ(data.size(), n);
        for (std::size_t i = 0; i < n; ++i)
        {
            ASSERT_EQ(data[i].from, std::int64_t(i));
            ASSERT_EQ(data[i].value, 0.25*double(i));
        }
    }
}


TEST(communicator, allGatherGivesEveryRankEachRanksStructInRankOrder)
{
    const Communicator& comm = world();
    const std::vector<record> all =
        comm.allGather(record{comm.rank(), 2*comm.rank(), 1.5*comm.rank()});
    ASSERT_EQ(int(all.size()), comm.size());
    for (int r = 0; r < comm.size(); ++r)
    {
        EXPECT_EQ(all[r].from, r);
        EXPECT_EQ(all[r].to, 2*r);
        EXPECT_EQ(all[r].value, 1.5*r);
    }
    EXPECT_EQ(comm.allGather(3.5*comm.rank()).back(), 3.5*(comm.size() - 1));
}


// ************************************************************************* //
