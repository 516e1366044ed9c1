// The wmake build (Make/files) and the CMake build list the same sources,
// and every listed source exists.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>

namespace
{

std::string readFile(const std::string& path)
{
    std::ifstream is(path);
    return {std::istreambuf_iterator<char>(is), std::istreambuf_iterator<char>()};
}

// Every "*.C" path named in a text
std::set<std::string> sourcesIn(const std::string& text)
{
    std::set<std::string> sources;
    const std::regex source(R"(([A-Za-z0-9_./]+\.C)\b)");
    for (std::sregex_iterator it(text.begin(), text.end(), source), end; it != end; ++it)
    {
        sources.insert((*it)[1]);
    }
    return sources;
}

} // End anonymous namespace


TEST(buildFiles, makeFilesListsTheSameSourcesAsCMake)
{
    const std::string root = PMSH_SOURCE_DIR;
    const std::string cmake = readFile(root + "/CMakeLists.txt");
    const std::string makeFiles = readFile(root + "/Make/files");
    ASSERT_FALSE(cmake.empty());
    ASSERT_FALSE(makeFiles.empty()) << "Make/files is missing";

    // CMake: the library list plus the application
    const auto begin = cmake.find("set(PMSH_LIBRARY_SOURCES");
    const auto end = cmake.find(")", begin);
    ASSERT_NE(begin, std::string::npos);
    std::set<std::string> fromCMake = sourcesIn(cmake.substr(begin, end - begin));
    fromCMake.insert("pmshFoam.C");

    EXPECT_EQ(sourcesIn(makeFiles), fromCMake);
    for (const std::string& f : fromCMake)
    {
        EXPECT_TRUE(std::filesystem::exists(root + "/" + f)) << f;
    }
}
