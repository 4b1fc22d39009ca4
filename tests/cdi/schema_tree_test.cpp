// The schema check on pugixml's tree against the same check on libxml2's own parse: the same
// findings, lines included, for every corpus and scenario CDI, and for texts pugixml accepts
// although they are not XML (the screen must hand those to libxml2).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cdi/schema_validator.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<fs::path> xml_files(const fs::path& dir) {
    std::vector<fs::path> files;
    if (!fs::is_directory(dir)) return files;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() == ".xml") files.push_back(entry.path());
    }
    return files;
}

std::string describe(const Diagnostics& diagnostics) {
    std::string out;
    for (const Diagnostic& d : diagnostics) {
        out += std::to_string(d.line) + (d.severity == Severity::kError ? " E " : " W ") +
               d.message + "\n";
    }
    return out;
}

// The tree path gives what the libxml2 path gives; returns whether the tree path was taken.
bool expect_same_as_parsed(const std::string& text) {
    SchemaChoice tree;
    SchemaChoice parsed;
    const Diagnostics from_tree = validate_schema(text, &tree);
    const Diagnostics reference = validate_schema_parsed(text, &parsed);
    EXPECT_EQ(describe(from_tree), describe(reference));
    EXPECT_EQ(tree.well_formed, parsed.well_formed);
    EXPECT_EQ(tree.version, parsed.version);
    EXPECT_EQ(tree.declared, parsed.declared);
    EXPECT_FALSE(parsed.from_tree);
    return tree.from_tree;
}

TEST(SchemaTree, EveryCorpusAndScenarioCdiGetsTheFindingsOfLibxml2sParse) {
    std::vector<fs::path> files = xml_files(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi");
    if (files.empty()) GTEST_SKIP() << "corpus not found under " << OLCB_SHARED_DIR;
    const std::vector<fs::path> scenarios = xml_files(fs::path(OLCB_SOURCE_DIR) / "scenarios");
    files.insert(files.end(), scenarios.begin(), scenarios.end());
    std::size_t from_tree = 0;
    for (const fs::path& file : files) {
        SCOPED_TRACE(file.filename().string());
        if (expect_same_as_parsed(read_file(file))) ++from_tree;
    }
    // Only the one malformed corpus file needs libxml2 (a CDATA section, a DOCTYPE, an unusual
    // declaration and the like would too).
    EXPECT_GE(from_tree, files.size() - 1) << from_tree << " of " << files.size();
}

TEST(SchemaTree, APlainCdiIsCheckedOnTheTree) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<!-- a node -->\n<cdi>\n<segment "
        "space=\"253\">\n<int size=\"1\"><name>A &amp; B &#x263A;</name></int>\n</segment>\n"
        "</cdi>\n",
        &choice);
    EXPECT_TRUE(choice.from_tree);
    EXPECT_TRUE(choice.well_formed);
    EXPECT_THAT(d, ::testing::SizeIs(1));  // the warning that no version is declared
}

// Each of these is accepted by pugixml; each is not XML, or is XML the tree alone cannot settle.
TEST(SchemaTree, WhatPugixmlLetsThroughGoesToLibxml2) {
    const std::string body = "<segment space=\"253\"><int size=\"1\"/></segment>";
    const std::vector<std::string> texts = {
        "<cdi>" + body + "</cdi>tail",
        "text<cdi>" + body + "</cdi>",
        "<cdi>" + body + "</cdi><cdi/>",
        "<cdi><!-- a -- b -->" + body + "</cdi>",
        "<cdi>" + body + "<!-- a ---></cdi>",
        "<cdi>&unknown;" + body + "</cdi>",
        "<cdi>&amp" + body + "</cdi>",
        "<cdi>&#0;" + body + "</cdi>",
        "<cdi>&#x110000;" + body + "</cdi>",
        "<cdi>]]>" + body + "</cdi>",
        "<cdi x=\"<\">" + body + "</cdi>",
        "<cdi x=\"1\" x=\"2\">" + body + "</cdi>",
        "<cdi>\x01" + body + "</cdi>",
        "<cdi>\xff" + body + "</cdi>",
        "<cdi>\xEF\xBF\xBF" + body + "</cdi>",
        "\xEF\xBB\xBF<cdi>" + body + "</cdi>",
        " <?xml version=\"1.0\"?><cdi>" + body + "</cdi>",
        "<?xml version=\"1.1\"?><cdi>" + body + "</cdi>",
        "<?xml version=\"1.0\" encoding=\"latin1\"?><cdi>" + body + "</cdi>",
        "<?xml version=\"1.0\"?><?xml x?><cdi>" + body + "</cdi>",
        "<?xml version=\"1.0\"?><?xmlfoo x?><cdi>" + body + "</cdi>",
        "<?xml version=\"1.0\"?><?a:b x?><cdi>" + body + "</cdi>",
        "<cdi><![CDATA[x]]>" + body + "</cdi>",
        "<cdi><q:x/>" + body + "</cdi>",
        "<cdi q:x=\"1\">" + body + "</cdi>",
        "<cdi xmlns=\"urn:x\">" + body + "</cdi>",
        "<cdi xmlns:q=\"not a uri\" q:x=\"1\">" + body + "</cdi>",
        "<cdi xmlns:q=\"http://a]b/\" q:x=\"1\">" + body + "</cdi>",
        "<cdi xmlns:q=\"http://host:port/\" q:x=\"1\">" + body + "</cdi>",
        "<cdi xmlns:q=\"http://www.w3.org/XML/1998/namespace\">" + body + "</cdi>",
        // Stray text libxml2 feeds in pieces (split at the CR, at the reference): its finding
        // lines and counts are libxml2's to give.
        "<cdi><segment space=\"253\"><int size=\"1\"/>x\r\ny\r\n</segment></cdi>",
        "<cdi><segment space=\"253\"><int size=\"1\"/>x&amp;y</segment></cdi>",
        "<cdi><segment xmlns:q=\"urn:q\" space=\"253\"/></cdi>",
        std::string("<cdi><segment space=\"253\"><int size=\"1\"><hints><slider><!-- c -->") +
            "</slider></hints></int></segment></cdi>",
    };
    for (const std::string& text : texts) {
        SCOPED_TRACE(text);
        EXPECT_FALSE(expect_same_as_parsed(text));
    }
}

TEST(SchemaTree, InstructionsCommentsAndUtf8StayOnTheTree) {
    const std::string body = "<segment space=\"253\"><int size=\"1\"/></segment>";
    const std::vector<std::string> texts = {
        "<?xml version='1.0' encoding='UTF-8'?>\n<?xml-stylesheet type='text/xsl' href='x'?>\n"
        "<cdi>" +
            body + "</cdi>\n<!-- end -->\n",
        "<cdi>" + body + "<?pi data?></cdi><?after?>",
        "<cdi><!-- \xC3\xA9t\xC3\xA9 --><segment space=\"253\"><name>\xE2\x98\xBA</name>"
        "<int size=\"1\"/></segment></cdi>",
    };
    for (const std::string& text : texts) {
        SCOPED_TRACE(text);
        EXPECT_TRUE(expect_same_as_parsed(text));
    }
}

TEST(SchemaTree, WhitespaceInAnElementOfEmptyContentIsSeen) {
    const std::string text =
        "<cdi>\n<segment space=\"253\">\n<int size=\"1\">\n<hints><slider tickSpacing=\"1\"> "
        "</slider></hints>\n</int>\n</segment>\n</cdi>\n";
    EXPECT_TRUE(expect_same_as_parsed(text));
    EXPECT_THAT(describe(validate_schema(text)), ::testing::HasSubstr("content type is empty"));
    // An empty element followed by text holding a '>': that text is its parent's.
    EXPECT_TRUE(expect_same_as_parsed("<cdi>\n<acdi/>\n\"> !\n</cdi>\n"));
}

// A <slider> (empty content) inside a CDI.
std::string in_hints(const std::string& slider) {
    std::string text = "<cdi><segment space=\"253\"><int size=\"1\"><hints>";
    text += slider;
    text += "</hints></int></segment></cdi>";
    return text;
}

TEST(SchemaTree, WhitespaceBeforeTheFirstChildOfAnEmptyElementIsSeen) {
    for (const std::string mid :
         {"<slider>\n<x/></slider>", "<slider><x/>\n</slider>", "<slider> <x/> <y/></slider>",
          "<slider> <!-- c --> <x/></slider>", "<slider> <!-- c --><!-- d -->\n<x/></slider>"}) {
        SCOPED_TRACE(mid);
        EXPECT_TRUE(expect_same_as_parsed(in_hints(mid)));
    }
    // Text and elements mixed, an instruction before the first child: libxml2 reads those.
    for (const std::string mid : {"<slider>a<x/></slider>", "<slider> <?pi?> <x/></slider>"}) {
        SCOPED_TRACE(mid);
        EXPECT_FALSE(expect_same_as_parsed(in_hints(mid)));
    }
}

TEST(SchemaTree, LinesOfMultiLineTagsAreLibxml2s) {
    const std::string text =
        "<cdi>\n<segment\n space=\"253\">\n<int\n size=\"1\"\n colour=\"red\">\n<name>a</name>\n"
        "<map><relation><property>1</property>\n\n</relation></map>\n</int>\n<bogus\n/>\n"
        "</segment>\n</cdi>\n";
    EXPECT_TRUE(expect_same_as_parsed(text));
}

TEST(SchemaTree, DeepNestingIsLeftToLibxml2) {
    std::string text = "<cdi><segment space=\"253\">";
    for (int i = 0; i < 300; ++i) text += "<group>";
    for (int i = 0; i < 300; ++i) text += "</group>";
    text += "</segment></cdi>";
    EXPECT_FALSE(expect_same_as_parsed(text));
}

}  // namespace
}  // namespace olcb::cdi
