/*---------------------------------------------------------------------------*\
  Tests of the OpenFOAM dictionary reader/writer (src/io/dictionary).
\*---------------------------------------------------------------------------*/

#include "dictionary.H"
#include "testUtilities.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

using namespace pmsh;
using namespace pmsh::test;
namespace fs = std::filesystem;

namespace
{

const std::string dataDir = std::string(PMSH_TEST_DATA) + "/io";

std::string written(const dictionary& d)
{
    std::ostringstream os;
    d.write(os);
    return os.str();
}

//- Same keywords, kinds and value text, recursively.
void expectSameContent(const dictionary& a, const dictionary& b)
{
    ASSERT_EQ(a.entries().size(), b.entries().size()) << written(a) << "\n---\n" << written(b);
    for (std::size_t i = 0; i < a.entries().size(); ++i)
    {
        const entry& x = a.entries()[i];
        const entry& y = b.entries()[i];
        EXPECT_EQ(x.keyword(), y.keyword());
        EXPECT_EQ(x.isPattern(), y.isPattern()) << x.keyword();
        EXPECT_EQ(x.type(), y.type()) << x.keyword();
        if (x.isDict() && y.isDict())
        {
            expectSameContent(x.dict(), y.dict());
        }
        else
        {
            EXPECT_EQ(x.text(), y.text()) << x.keyword();
        }
    }
}

} // End anonymous namespace


// * * * * * * * * * * * * * * * * Syntax  * * * * * * * * * * * * * * * * //

TEST(dictionarySyntax, readsEveryValueKindOfTheSyntaxFile)
{
    const dictionary d = dictionary::read(dataDir + "/allSyntax");

    EXPECT_EQ(d.get<std::string>("word"), "scotch");
    EXPECT_EQ(d.get<std::string>("string"), "a \"quoted\" word");
    EXPECT_EQ(d.get<int>("integer"), 42);
    EXPECT_EQ(d.get<int>("negative"), -7);
    EXPECT_DOUBLE_EQ(d.get<double>("float"), 0.25);
    EXPECT_DOUBLE_EQ(d.get<double>("exponent"), -2.5e-3);
    EXPECT_DOUBLE_EQ(d.get<double>("bigExponent"), 1e6);
    EXPECT_DOUBLE_EQ(d.get<double>("leadingDot"), 0.5);
    EXPECT_TRUE(d.get<bool>("yes"));
    EXPECT_FALSE(d.get<bool>("no"));

    EXPECT_EQ(d.text("list"), "(1 2 3)");
    EXPECT_EQ(d.text("sizedList"), "3(4 5 6)");
    EXPECT_EQ(d.text("uniformList"), "4{0.5}");
    EXPECT_EQ(d.text("nested"), "((0 0 0) (1 0 0) (1 1 0))");
    EXPECT_EQ(d.text("dimensions"), "[0 1 -1 0 0 0 0]");
    EXPECT_EQ(d.text("internalField"), "uniform (0 0 1)");
    EXPECT_EQ(d.text("div(phi,U)"), "Gauss linearUpwind grad(U)");

    EXPECT_EQ(d.subDict("outer").subDict("inner").get<int>("value"), 12);
    EXPECT_EQ(d.subDict("outer").get<std::string>("type"), "fixedValue");
}

TEST(dictionarySyntax, commentsAreSkippedAndLinesStillCounted)
{
    const dictionary d = dictionary::parse
    (
        "// line 1\n"
        "/* line 2\n"
        "   line 3 */ a 1; // after\n"
        "b /* inside */ 2;\n",
        "/c/test"
    );
    ASSERT_EQ(d.toc(), (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(d.lookupEntry("a").line(), 3);
    EXPECT_EQ(d.lookupEntry("b").line(), 4);
    EXPECT_EQ(d.get<int>("b"), 2);
}

TEST(dictionarySyntax, foamFileHeaderStaysAccessible)
{
    const dictionary d = dictionary::read(dataDir + "/allSyntax");
    ASSERT_TRUE(d.isDict("FoamFile"));
    EXPECT_EQ(d.subDict("FoamFile").get<std::string>("class"), "dictionary");
    EXPECT_EQ(d.subDict("FoamFile").get<std::string>("object"), "allSyntax");
    EXPECT_EQ(d.toc().front(), "FoamFile");
}

TEST(dictionarySyntax, valueIsATokenSequenceWithKinds)
{
    const dictionary d = dictionary::parse
    (
        "v uniform (1 -2.5e3 \"s\") $x #calc;", "/c/test"
    );
    const std::vector<token>& t = d.lookupEntry("v").tokens();
    ASSERT_EQ(t.size(), 8u);
    EXPECT_EQ(t[0].type, token::WORD);
    EXPECT_TRUE(t[1].isPunctuation('('));
    EXPECT_EQ(t[2].type, token::NUMBER);
    EXPECT_EQ(t[3].type, token::NUMBER);
    EXPECT_EQ(t[3].text, "-2.5e3");
    EXPECT_EQ(t[4].type, token::STRING);
    EXPECT_TRUE(t[5].isPunctuation(')'));
    EXPECT_EQ(t[6].type, token::VARIABLE);
    EXPECT_EQ(t[6].text, "$x");
    EXPECT_EQ(t[7].type, token::DIRECTIVE);
}

TEST(dictionarySyntax, backslashEscapesOnlyTheQuote)
{
    // As OpenFOAM: \" is a quote, \\ stays two backslashes and does not
    // escape the closing quote
    const dictionary d = dictionary::parse
    (
        "a \"say \\\"hi\\\"\";\n"
        "b \"ends with \\\\\";\n",
        "/c/test"
    );
    EXPECT_EQ(d.get<std::string>("a"), "say \"hi\"");
    EXPECT_EQ(d.get<std::string>("b"), "ends with \\\\");
}

TEST(dictionarySyntax, entriesRememberFileAndLine)
{
    const dictionary d = dictionary::read(dataDir + "/allSyntax");
    const entry& e = d.lookupEntry("integer");
    EXPECT_EQ(e.line(), 15);
    EXPECT_EQ(e.file(), fs::absolute(dataDir + "/allSyntax").lexically_normal().string());
    EXPECT_EQ(d.subDict("outer").lookupEntry("type").line(), 40);
}

TEST(dictionarySyntax, laterDuplicateReplacesAndDictionariesMerge)
{
    const dictionary d = dictionary::parse
    (
        "a 1;\n"
        "s { x 1; y 2; }\n"
        "a 2;\n"
        "s { y 3; z 4; }\n",
        "/c/test"
    );
    EXPECT_EQ(d.toc(), (std::vector<std::string>{"a", "s"}));
    EXPECT_EQ(d.get<int>("a"), 2);
    EXPECT_EQ(d.lookupEntry("a").line(), 3);
    EXPECT_EQ(d.subDict("s").toc(), (std::vector<std::string>{"x", "y", "z"}));
    EXPECT_EQ(d.subDict("s").get<int>("y"), 3);
}


// * * * * * * * * * * * * * * * Regex keys  * * * * * * * * * * * * * * * //

TEST(dictionaryRegex, exactKeyWinsOverAnyPattern)
{
    const dictionary d = dictionary::parse
    (
        "inlet { type patch; }\n"
        "\".*\" { type wall; }\n",
        "/c/test"
    );
    EXPECT_EQ(d.subDict("inlet").get<std::string>("type"), "patch");
    EXPECT_EQ(d.subDict("outlet").get<std::string>("type"), "wall");
}

TEST(dictionaryRegex, lastMatchingPatternWins)
{
    const dictionary d = dictionary::parse
    (
        "\"(inlet|outlet)\" { type patch; }\n"
        "\"in.*\"           { type symmetry; }\n"
        "\"x.*\"            { type wall; }\n",
        "/c/test"
    );
    EXPECT_EQ(d.subDict("inlet").get<std::string>("type"), "symmetry");
    EXPECT_EQ(d.subDict("outlet").get<std::string>("type"), "patch");
    EXPECT_TRUE(d.lookupEntry("inlet").isPattern());
}

TEST(dictionaryRegex, patternsMatchTheWholeName)
{
    const dictionary d = dictionary::parse("\"in\" 1; \"wall[0-9]\" 2;", "/c/test");
    EXPECT_FALSE(d.found("inlet"));
    EXPECT_TRUE(d.found("in"));
    EXPECT_TRUE(d.found("wall7"));
    EXPECT_FALSE(d.found("wall77"));
}

TEST(dictionaryRegex, invalidPatternIsAnErrorNamingTheLine)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\n\"wall[\" { type wall; }\n", "/c/system/pmshDict");
    });
    EXPECT_NE(err.find("wall["), std::string::npos) << err;
    EXPECT_NE(err.find("/c/system/pmshDict"), std::string::npos) << err;
    EXPECT_NE(err.find("line 2"), std::string::npos) << err;
}


// * * * * * * * * * * * * * * * * Includes  * * * * * * * * * * * * * * * //

TEST(dictionaryInclude, includeIsResolvedRelativeToTheIncludingFile)
{
    const dictionary d = dictionary::read(dataDir + "/include/main");
    EXPECT_EQ(d.toc(), (std::vector<std::string>{"FoamFile", "before", "fromInclude", "after"}));
    EXPECT_EQ(d.get<int>("fromInclude"), 3);

    // The included file's own header is dropped, ours kept
    EXPECT_EQ(d.subDict("FoamFile").get<std::string>("object"), "main");

    // The entry knows where it really came from
    const entry& e = d.lookupEntry("fromInclude");
    EXPECT_EQ(e.line(), 10);
    EXPECT_NE(e.file().find("sub/included"), std::string::npos);
    EXPECT_NE(d.entryInfo(e).find("sub/included"), std::string::npos);
}

TEST(dictionaryInclude, missingIncludeNamesIncludingFileAndLine)
{
    const std::string err = errorOf([]
    {
        dictionary::read(dataDir + "/include/missing");
    });
    EXPECT_NE(err.find("doesNotExist"), std::string::npos) << err;
    EXPECT_NE(err.find("include/missing\" line 3"), std::string::npos) << err;
}

TEST(dictionaryInclude, includeIfPresentToleratesAMissingFile)
{
    const dictionary d = dictionary::parse
    (
        "a 1;\n#includeIfPresent \"nothingHere\"\nb 2;\n",
        dataDir + "/include/virtual"
    );
    EXPECT_EQ(d.toc(), (std::vector<std::string>{"a", "b"}));
}

TEST(dictionaryInclude, includesCanBeKeptAsDirectives)
{
    const dictionary d = dictionary::read
    (
        dataDir + "/include/main", readOptions{false, false}
    );
    EXPECT_FALSE(d.found("fromInclude"));
    const std::string out = written(d);
    EXPECT_NE(out.find("#include \"sub/included\""), std::string::npos) << out;
}

TEST(dictionaryInclude, includeEtcIsReadFromTheOpenFOAMEtcDirectory)
{
    const scopedEnv env("WM_PROJECT_DIR", (dataDir + "/fakeOpenFOAM").c_str());
    const dictionary d = dictionary::parse
    (
        "internalField uniform 0;\n"
        "boundaryField\n{\n    #includeEtc \"caseDicts/setConstraintTypes\"\n}\n",
        "/c/0/p"
    );
    const dictionary& bf = d.subDict("boundaryField");
    ASSERT_TRUE(bf.isDict("processor"));
    EXPECT_EQ(bf.subDict("processor").get<std::string>("type"), "processor");

    // $internalField is found in the enclosing dictionary
    EXPECT_EQ
    (
        tokensToString(bf.subDict("processor").expandedTokens
        (
            bf.subDict("processor").lookupEntry("value")
        )),
        "uniform 0"
    );
}

TEST(dictionaryInclude, missingIncludeEtcFileIsAnError)
{
    const scopedEnv env("WM_PROJECT_DIR", (dataDir + "/fakeOpenFOAM").c_str());
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\n#includeEtc \"caseDicts/nothing\"\n", "/c/x");
    });
    EXPECT_NE(err.find("caseDicts/nothing"), std::string::npos) << err;
    EXPECT_NE(err.find("\"/c/x\" line 2"), std::string::npos) << err;
}

TEST(dictionaryInclude, preservedIncludeEtcSurvivesARoundTrip)
{
    const std::string text =
        "FoamFile { version 2.0; format ascii; class volScalarField; object p; }\n"
        "internalField uniform 0;\n"
        "boundaryField\n{\n"
        "    #includeEtc \"caseDicts/setConstraintTypes\"\n"
        "    \".*\" { type zeroGradient; }\n"
        "}\n";
    const dictionary d = dictionary::parse(text, "/c/0/p", readOptions{true, false});
    const std::string out = written(d);
    EXPECT_NE(out.find("    #includeEtc \"caseDicts/setConstraintTypes\"\n"), std::string::npos) << out;

    const dictionary again = dictionary::parse(out, "/c/0/p", readOptions{true, false});
    expectSameContent(d, again);
    ASSERT_TRUE(again.subDict("boundaryField").entries()[0].isDirective());
    EXPECT_EQ(again.subDict("boundaryField").entries()[0].keyword(), "#includeEtc");
}


// * * * * * * * * * * * * * * * * Directives  * * * * * * * * * * * * * * //

TEST(dictionaryDirectives, otherDirectivesAndMacrosAreWrittenBack)
{
    const std::string text =
        "#inputMode merge\n"
        "common { type wall; }\n"
        "a { $common; }\n"
        "#remove (x y)\n"
        "v $internalField;\n"
        "c #calc \"1 + 2\";\n"
        "code #{ int i = 0; #};\n";
    const dictionary d = dictionary::parse(text, "/c/test", readOptions{false, false});
    EXPECT_EQ(d.toc(), (std::vector<std::string>{"common", "a", "v", "c", "code"}));

    const std::string out = written(d);
    for
    (
        const char* piece :
        {
            "#inputMode merge\n", "$common;\n", "#remove (x y)\n",
            "$internalField;", "#calc \"1 + 2\";", "#{ int i = 0; #};"
        }
    )
    {
        EXPECT_NE(out.find(piece), std::string::npos) << piece << " in\n" << out;
    }
    expectSameContent(d, dictionary::parse(out, "/c/test", readOptions{false, false}));
}

TEST(dictionaryDirectives, variablesExpandForTypedAccess)
{
    const dictionary d = dictionary::parse
    (
        "size 0.5;\n"
        "alias $size;\n"
        "sub { local 2; deep { up $..local; top $:size; plain $size; } }\n"
        "missing $nothing;\n",
        "/c/test"
    );
    EXPECT_DOUBLE_EQ(d.get<double>("alias"), 0.5);
    const dictionary& deep = d.subDict("sub").subDict("deep");
    EXPECT_EQ(deep.get<int>("up"), 2);
    EXPECT_DOUBLE_EQ(deep.get<double>("top"), 0.5);
    EXPECT_DOUBLE_EQ(deep.get<double>("plain"), 0.5);

    const std::string err = errorOf([&]{ d.get<double>("missing"); });
    EXPECT_NE(err.find("$nothing"), std::string::npos) << err;
}


// * * * * * * * * * * * * * * * Syntax errors * * * * * * * * * * * * * * //

TEST(dictionarySyntaxErrors, missingSemicolonBeforeSubDictNamesLineOfEntry)
{
    const std::string err = errorOf([]
    {
        dictionary::parse
        (
            "geometry \"g.stl\";\n"
            "maxCellSize 0.1\n"
            "patches\n"
            "{\n"
            "}\n",
            "/c/system/pmshDict"
        );
    });
    EXPECT_NE(err.find("file \"/c/system/pmshDict\" line 2"), std::string::npos) << err;
    EXPECT_NE(err.find("expected ';' after entry 'maxCellSize'"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, missingSemicolonAtEndOfFile)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\nb 2\n", "/c/d");
    });
    EXPECT_NE(err.find("file \"/c/d\" line 2"), std::string::npos) << err;
    EXPECT_NE(err.find("expected ';' after entry 'b'"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, missingSemicolonBeforeClosingBrace)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("s\n{\n    a 1\n}\n", "/c/d");
    });
    EXPECT_NE(err.find("line 3"), std::string::npos) << err;
    EXPECT_NE(err.find("after entry 'a'"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, unterminatedStringNamesItsLine)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\nb \"open;\nc 2;\n", "/c/d");
    });
    EXPECT_NE(err.find("file \"/c/d\" line 2"), std::string::npos) << err;
    EXPECT_NE(err.find("unterminated string"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, unterminatedCommentNamesWhereItStarts)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\n\n/* never closed\nb 2;\n", "/c/d");
    });
    EXPECT_NE(err.find("line 3"), std::string::npos) << err;
    EXPECT_NE(err.find("unterminated comment"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, unterminatedBraceNamesTheSubDictionary)
{
    const std::string err = errorOf([]
    {
        dictionary::parse("a 1;\npatches\n{\n    inlet { type patch; }\n", "/c/d");
    });
    EXPECT_NE(err.find("line 3"), std::string::npos) << err;
    EXPECT_NE(err.find("'patches'"), std::string::npos) << err;
}

TEST(dictionarySyntaxErrors, strayClosingBraceAndBadBrackets)
{
    std::string err = errorOf([]{ dictionary::parse("a 1;\n}\n", "/c/d"); });
    EXPECT_NE(err.find("line 2"), std::string::npos) << err;
    EXPECT_NE(err.find("unexpected '}'"), std::string::npos) << err;

    err = errorOf([]{ dictionary::parse("a 1;\nl (1 2];\n", "/c/d"); });
    EXPECT_NE(err.find("line 2"), std::string::npos) << err;
    EXPECT_NE(err.find("']'"), std::string::npos) << err;

    err = errorOf([]{ dictionary::parse("l (1 2\n\n", "/c/d"); });
    EXPECT_NE(err.find("line 1"), std::string::npos) << err;
    EXPECT_NE(err.find("never closed"), std::string::npos) << err;

    err = errorOf([]{ dictionary::parse("a 1;\n(1 2);\n", "/c/d"); });
    EXPECT_NE(err.find("line 2: expected a keyword"), std::string::npos) << err;
}


// * * * * * * * * * * * * * * * Typed access  * * * * * * * * * * * * * * //

TEST(dictionaryAccess, missingEntryNamesEntryAndDictionary)
{
    const dictionary d = dictionary::parse("a 1;", "/c/system/pmshDict");
    EXPECT_EQ
    (
        errorOf([&]{ d.get<std::string>("geometry"); }),
        "Entry 'geometry' not found in dictionary \"/c/system/pmshDict\""
    );
}

TEST(dictionaryAccess, wrongTypeNamesEntryFileLineFoundAndExpected)
{
    const dictionary d = dictionary::parse
    (
        "FoamFile { version 2.0; }\n"
        "maxCellSize fine;\n"
        "levels 2.5;\n"
        "mesher \"netgen\";\n"
        "flag maybe;\n"
        "sub { }\n",
        "/c/system/pmshDict"
    );

    std::string err = errorOf([&]{ d.get<double>("maxCellSize"); });
    EXPECT_NE(err.find("Entry 'maxCellSize' in dictionary \"/c/system/pmshDict\" (line 2)"), std::string::npos) << err;
    EXPECT_NE(err.find("the word 'fine'"), std::string::npos) << err;
    EXPECT_NE(err.find("Expected a number"), std::string::npos) << err;

    err = errorOf([&]{ d.get<int>("levels"); });
    EXPECT_NE(err.find("(line 3)"), std::string::npos) << err;
    EXPECT_NE(err.find("2.5"), std::string::npos) << err;
    EXPECT_NE(err.find("integer"), std::string::npos) << err;

    err = errorOf([&]{ d.get<int>("mesher"); });
    EXPECT_NE(err.find("the string \"netgen\""), std::string::npos) << err;

    err = errorOf([&]{ d.get<bool>("flag"); });
    EXPECT_NE(err.find("'maybe'"), std::string::npos) << err;
    EXPECT_NE(err.find("on/off"), std::string::npos) << err;

    err = errorOf([&]{ d.get<std::string>("sub"); });
    EXPECT_NE(err.find("sub-dictionary"), std::string::npos) << err;

    err = errorOf([&]{ d.subDict("maxCellSize"); });
    EXPECT_NE(err.find("not a sub-dictionary"), std::string::npos) << err;
}

TEST(dictionaryAccess, multiLineValueHintsAtTheMissingSemicolon)
{
    const dictionary d = dictionary::parse
    (
        "maxCellSize 0.1\ngrading 0.3;\n", "/c/system/pmshDict"
    );
    const std::string err = errorOf([&]{ d.get<double>("maxCellSize"); });
    EXPECT_NE(err.find("'0.1 grading 0.3'"), std::string::npos) << err;
    EXPECT_NE(err.find("';' missing at the end of line 1"), std::string::npos) << err;
}

TEST(dictionaryAccess, switchesAcceptOpenFOAMWords)
{
    const dictionary d = dictionary::parse
    (
        "a true; b on; c yes; d false; e off; f no;", "/c/d"
    );
    EXPECT_TRUE(d.get<bool>("a"));
    EXPECT_TRUE(d.get<bool>("b"));
    EXPECT_TRUE(d.get<bool>("c"));
    EXPECT_FALSE(d.get<bool>("d"));
    EXPECT_FALSE(d.get<bool>("e"));
    EXPECT_FALSE(d.get<bool>("f"));
}

TEST(dictionaryAccess, getOrDefaultUsesDefaultOnlyWhenMissing)
{
    const dictionary d = dictionary::parse("a 2; bad x;", "/c/d");
    EXPECT_EQ(d.getOrDefault<int>("a", 7), 2);
    EXPECT_EQ(d.getOrDefault<int>("b", 7), 7);
    EXPECT_EQ(d.getOrDefault<std::string>("c", "dflt"), "dflt");
    EXPECT_NE(errorOf([&]{ d.getOrDefault<int>("bad", 1); }), "");
}

TEST(dictionaryAccess, readingAMissingFileNamesIt)
{
    const std::string err = errorOf([]{ dictionary::read("/nonexistent/system/pmshDict"); });
    EXPECT_NE(err.find("\"/nonexistent/system/pmshDict\""), std::string::npos) << err;
}


// * * * * * * * * * * * * * * * * * Write * * * * * * * * * * * * * * * * //

TEST(dictionaryWrite, writtenSyntaxFileReadsBackTheSame)
{
    const dictionary d = dictionary::read(dataDir + "/allSyntax");
    const std::string out = written(d);
    const dictionary again = dictionary::parse(out, "/c/again");
    expectSameContent(d, again);

    // Lists written on several lines stay on several lines
    EXPECT_NE(out.find("multiLine\n(\n    (0 0 0)\n    (1 0 0)\n);\n"), std::string::npos) << out;
}

TEST(dictionaryWrite, regexKeysAreWrittenQuoted)
{
    const dictionary d = dictionary::parse("\"(in|out)let\" { type patch; }", "/c/d");
    const std::string out = written(d);
    EXPECT_NE(out.find("\"(in|out)let\"\n{"), std::string::npos) << out;
    EXPECT_TRUE(dictionary::parse(out, "/c/d").lookupEntry("inlet").isPattern());
}

TEST(dictionaryWrite, setReplacesInPlaceOrAppends)
{
    dictionary d = dictionary::parse
    (
        "numberOfSubdomains 2;\nmethod simple;\n", "/c/d"
    );
    d.set("numberOfSubdomains", 8);
    d.set("coeffs", "(2 2 1)");
    d.set("scale", 0.1);
    d.set("name", "\"a b\"");
    EXPECT_EQ(d.toc(), (std::vector<std::string>{"numberOfSubdomains", "method", "coeffs", "scale", "name"}));

    const dictionary again = dictionary::parse(written(d), "/c/d");
    EXPECT_EQ(again.get<int>("numberOfSubdomains"), 8);
    EXPECT_EQ(again.text("coeffs"), "(2 2 1)");
    EXPECT_EQ(again.get<double>("scale"), 0.1);
    EXPECT_EQ(again.get<std::string>("name"), "a b");
    EXPECT_TRUE(d.remove("method"));
    EXPECT_FALSE(d.found("method"));
}

TEST(dictionaryWrite, writeFileIsReadableByOpenFOAM)
{
    if (!fs::exists("/usr/bin/foamDictionary"))
    {
        GTEST_SKIP() << "OpenFOAM's foamDictionary is not installed";
    }
    const tempDir dir("dict");
    dictionary d = dictionary::read(dataDir + "/allSyntax");
    d.set("numberOfSubdomains", 5);
    d.writeFile(dir/"system/written");

    auto valueOf = [&](const std::string& key)
    {
        return runFoam("foamDictionary -entry " + key + " -value " + (dir/"system/written"));
    };
    const auto [subdomains, rc1] = valueOf("numberOfSubdomains");
    const auto [value, rc2] = valueOf("outer/inner/value");
    EXPECT_EQ(rc1, 0) << subdomains;
    EXPECT_EQ(rc2, 0) << value;
    EXPECT_EQ(subdomains + value, "5\n12\n");
}
