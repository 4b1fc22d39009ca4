// Content-node indices (OpenLCB_Java's "seg<N>"/"child<N>" numbering): the parser's, for every
// segment and data element, against pugixml keeping every node, on hand-made cases, every
// corpus file and random edits of them; and the gap counter on its own.
#include "cdi/content_index.hpp"

#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

constexpr unsigned kKeepEveryNode =
    pugi::parse_default | pugi::parse_ws_pcdata | pugi::parse_comments | pugi::parse_pi;

std::uint32_t pugixml_index(pugi::xml_node node) {
    std::uint32_t index = 0;
    for (auto n = node.previous_sibling(); n; n = n.previous_sibling()) ++index;
    return index;
}

bool is_data_element(pugi::xml_node n, bool in_group) {
    const std::string tag = n.name();
    if (n.type() != pugi::node_element || tag == "name" || tag == "description" || tag == "link")
        return false;
    if (in_group && (tag == "repname" || tag == "hints")) return false;
    for (const char* kind : {"group", "int", "string", "eventid", "float", "action", "blob", "bit"})
        if (tag == kind) return true;
    return n.attribute("size");
}

// Every data element below xml against the parser's children, recursively; "" when all agree.
std::string compare(pugi::xml_node xml, const std::vector<Element>& children, bool in_group) {
    std::size_t i = 0;
    for (pugi::xml_node n = xml.first_child(); n; n = n.next_sibling()) {
        if (!is_data_element(n, in_group)) continue;
        if (i >= children.size()) return "more data elements than the parser's";
        const Element& e = children[i++];
        if (e.content_index != pugixml_index(n)) {
            return "<" + std::string(n.name()) + "> at offset " + std::to_string(n.offset_debug()) +
                   ": " + std::to_string(e.content_index) + ", pugixml " +
                   std::to_string(pugixml_index(n));
        }
        if (e.kind == ElementKind::kGroup) {
            if (std::string d = compare(n, e.children, true); !d.empty()) return d;
        }
    }
    return i == children.size() ? "" : "fewer data elements than the parser's";
}

// "" when the parser's indices are pugixml's for every segment and data element of text;
// "skip" when either refuses the text.
std::string agreement(const std::string& text) {
    pugi::xml_document xml;
    if (!xml.load_buffer(text.data(), text.size(), kKeepEveryNode)) return "skip";
    const ParseResult parsed = parse(text);
    if (!parsed.document) return "skip";
    std::size_t s = 0;
    for (pugi::xml_node n = xml.document_element().first_child(); n; n = n.next_sibling()) {
        if (std::string(n.name()) != "segment") continue;
        const Segment& seg = parsed.document->segments.at(s++);
        if (seg.content_index != pugixml_index(n)) {
            return "segment " + std::to_string(s) + ": " + std::to_string(seg.content_index) +
                   ", pugixml " + std::to_string(pugixml_index(n));
        }
        if (std::string d = compare(n, seg.children, false); !d.empty()) return d;
    }
    return "";
}

TEST(ContentIndex, TheParserCountsTextCommentsCdataAndPisAsPugixmlDoes) {
    for (const std::string& text : {
             std::string(R"(<?xml version="1.0"?>
<cdi>
<identification><manufacturer>M</manufacturer></identification>
<acdi/>
<!-- the user segment -->
<segment space="253"><int size="1"/>
<group replication="2"><name>Inner</name><eventid/></group></segment>
</cdi>)"),
             std::string("<cdi><segment space='1'><![CDATA[x]]><int size='1' t='>'/>t&amp;u"
                         "<?pi x?><group><name>G</name>\r\n\t<!--c--><int size='2'><name>A"
                         "</name><description>d > e</description></int> <string size='4'/>"
                         "</group></segment><?x?><segment space='2'><int/></segment></cdi>"),
             std::string("<cdi><segment space='1'><group><group><group><int/></group></group>"
                         "</group>\n<int/><group/><!---->x<int/></segment></cdi>"),
         }) {
        EXPECT_EQ(agreement(text), "") << text;
    }
    const ParseResult r = parse(R"(<?xml version="1.0"?>
<cdi>
<identification><manufacturer>M</manufacturer></identification>
<acdi/>
<!-- the user segment -->
<segment space="253"><int size="1"/>
<group replication="2"><name>Inner</name><eventid/></group></segment>
</cdi>)");
    ASSERT_TRUE(r.document.has_value());
    const Segment& seg = r.document->segments.at(0);
    EXPECT_EQ(seg.content_index, 7u);  // "\n", identification, "\n", acdi, "\n", comment, "\n"
    EXPECT_EQ(seg.children.at(1).content_index, 2u);              // after the int and a "\n"
    EXPECT_EQ(seg.children[1].children.at(0).content_index, 1u);  // after <name>
}

TEST(ContentIndex, TheGapCounterNeverReadsPastItsEndNorCrashes) {
    const std::string t = "<a>x<!--c--><b/>y</a>";
    // From <a> itself (depth -1) to <b>: "x" and the comment.
    EXPECT_EQ(non_element_nodes_between(t, 1, -1, t.find("<b") + 1), 2u);
    for (const std::string& bad : {std::string("<cdi><a"), std::string("<cdi><!-- x"),
                                   std::string("<cdi><!DOCTYPE x><a/>"), std::string("<")}) {
        EXPECT_LE(non_element_nodes_between(bad, 1, -1, bad.size()), 1u) << bad;
    }
    EXPECT_EQ(non_element_nodes_between(t, 0, -1, 5), 0u);
    EXPECT_EQ(non_element_nodes_between(t, 5, -1, 5), 0u);
    EXPECT_EQ(non_element_nodes_between(t, 1, -1, 500), 0u);
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::filesystem::path corpus_dir() {
    return std::filesystem::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
}

TEST(ContentIndex, AgreesWithPugixmlOnTheCorpusAndOnRandomEdits) {
    if (!std::filesystem::is_directory(corpus_dir())) {
        GTEST_SKIP() << "corpus absent at " << corpus_dir();
    }
    std::mt19937 rng(13);
    static const char* const kInserts[] = {"\n", "<!-- c -->", "<?p q?>", "<![CDATA[x]]>", " x "};
    std::size_t compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(corpus_dir())) {
        std::string text = read_file(entry.path());
        while (!text.empty() && text.back() == '\0') text.pop_back();
        const std::string whole = agreement(text);
        if (whole == "skip") continue;
        EXPECT_EQ(whole, "") << entry.path();
        ++compared;
        // A node inserted just before a random tag (never inside one), outside the root too.
        for (int edit = 0; edit < 30; ++edit) {
            std::string edited = text;
            const std::size_t at = edited.find('<', rng() % edited.size());
            if (at == std::string::npos) continue;
            edited.insert(at, kInserts[rng() % std::size(kInserts)]);
            const std::string d = agreement(edited);
            if (d != "skip") {
                EXPECT_EQ(d, "") << entry.path() << " edit at " << at;
            }
        }
    }
    EXPECT_GE(compared, 50u);
}

}  // namespace
}  // namespace olcb::cdi
