#include "Info.H"

#include <iostream>
#include <string>
#include <ostream>
#include <streambuf>

namespace
{

// A stream that swallows everything: Info on non-master ranks.
class nullBuffer : public std::streambuf
{
protected:
    int overflow(int c) override { return c; }
};

nullBuffer theNullBuffer;
std::ostream theNullStream(&theNullBuffer);

// Process-wide log settings: written once at start-up.
int logRank = 0;
bool logParallel = false;

} // End anonymous namespace


void pmsh::setLogRank(int rank, bool parallel)
{
    logRank = rank;
    logParallel = parallel;

    // The log goes to a file in every Allrun: write it as the run goes, as
    // OpenFOAM's Info << endl does, so that a long or killed run shows
    // where it is (the log is small: flushing costs nothing)
    std::cout << std::unitbuf;
}


std::ostream& pmsh::Info()
{
    if (logRank != 0)
    {
        return theNullStream;
    }
    return std::cout;
}


std::ostream& pmsh::Pout()
{
    if (logParallel)
    {
        std::cout << '[' << logRank << "] ";
    }
    return std::cout;
}


void pmsh::PoutLine(const std::string& line)
{
    std::string text =
        logParallel ? '[' + std::to_string(logRank) + "] " + line : line;
    text += '\n';
    std::cout.write(text.data(), std::streamsize(text.size()));
    std::cout.flush();
}
