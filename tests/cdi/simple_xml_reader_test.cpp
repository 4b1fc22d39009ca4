// read_simple_xml must build exactly the tree pugixml's reading gives, or decline.
#include "cdi/simple_xml_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "cdi/pugixml_tree.hpp"
#include "cdi/render.hpp"
#include "cdi/xml_tree.hpp"

namespace olcb::cdi {
namespace {

constexpr std::size_t kDepth = 144;

// Every element in document order: depth, name, offset, text and attributes.
std::string dump(const XmlTree& tree) {
    std::string out;
    const auto walk = [&out](XmlElement e, std::size_t depth, const auto& self) -> void {
        for (; e; e = e.next_sibling()) {
            out += std::string(depth, ' ') + std::string(e.name()) + "@" +
                   std::to_string(e.offset()) + " [" + std::string(e.text()) + "]";
            for (const XmlAttribute& a : e.attributes()) {
                out += " " + std::string(a.name) + "=[" + std::string(a.value) + "]";
            }
            out += "\n";
            self(e.first_child(), depth + 1, self);
        }
    };
    walk(tree.root(), 0, walk);
    return out;
}

// The tree pugixml gives, or "" when pugixml refuses the text.
std::string pugixml_dump(std::string_view text) {
    pugi::xml_document xml;
    if (!xml.load_buffer(text.data(), text.size(), kPugixmlOptions, pugi::encoding_utf8)) {
        return "";
    }
    XmlTree tree(text);
    copy_pugixml_elements(xml.document_element(), tree);
    return dump(tree);
}

// Reads text both ways; true when the simple reader accepted it (and then agreed).
bool agrees(const std::string& text) {
    XmlTree tree(text);
    if (!read_simple_xml(text, kDepth, tree)) return false;
    const std::string expected = pugixml_dump(text);
    EXPECT_FALSE(expected.empty()) << "accepted what pugixml refuses:\n" << text;
    EXPECT_EQ(dump(tree), expected) << text;
    return true;
}

bool declines(const std::string& text) {
    XmlTree tree(text);
    return !read_simple_xml(text, kDepth, tree);
}

TEST(SimpleXmlReader, ReadsElementsAttributesAndFirstTexts) {
    const std::string text =
        "<?xml version='1.0'?>\n<cdi a=\"1\" b='two'>\n  <x>hello</x>\n  <y/>\n"
        "  <z k = \"v\" >t1<w/>t2</z >\n</cdi>\n";
    XmlTree tree(text);
    ASSERT_TRUE(read_simple_xml(text, kDepth, tree));
    XmlElement root = tree.root();
    EXPECT_EQ(root.name(), "cdi");
    EXPECT_EQ(root.offset(), text.find("cdi"));
    ASSERT_EQ(root.attributes().size(), 2u);
    EXPECT_EQ(root.attribute("b")->value, "two");
    EXPECT_EQ(root.attribute("c"), nullptr);
    XmlElement x = root.first_child();
    EXPECT_EQ(x.text(), "hello");
    XmlElement y = x.next_sibling();
    EXPECT_EQ(y.name(), "y");
    EXPECT_FALSE(y.first_child());
    XmlElement z = y.next_sibling();
    EXPECT_EQ(z.text(), "t1");
    EXPECT_EQ(z.attribute("k")->value, "v");
    EXPECT_EQ(z.first_child().name(), "w");
    EXPECT_FALSE(z.first_child().next_sibling());
    EXPECT_FALSE(z.next_sibling());
    EXPECT_TRUE(agrees(text));
}

TEST(SimpleXmlReader, DecodesLikePugixml) {
    EXPECT_TRUE(agrees("<a>x &amp; y &lt;&gt;&quot;&apos;</a>"));
    EXPECT_TRUE(agrees("<a>line\r\nnext\rlast\n</a>"));
    EXPECT_TRUE(agrees("<a v=\"a&amp;b\tc\nd\r\ne\rf\" w='&quot;q&apos;'/>"));
    EXPECT_TRUE(agrees("<a v=\"x>y\" w='a\"b'>1 > 0 ]]> ok</a>"));
    EXPECT_TRUE(agrees("<a>  <!-- c -->  <?pi x?>  first<!-- c -->second<b/>third</a>"));
    EXPECT_TRUE(agrees("<a><b/>after child</a>"));
    EXPECT_TRUE(agrees("<a>\n\t \r\n</a>"));
    EXPECT_TRUE(agrees("<!-- before --><?pi?>\n<a x='1' x='2'/>\n<!-- after -->\n"));
    EXPECT_TRUE(agrees("<a>first<b>&amp;</b>&lt; &#65; &unknown; &</a>"));  // later text unread
    EXPECT_TRUE(agrees("<a\n  b='1'\n  c=\"2\"\n/>"));
    EXPECT_TRUE(agrees("<a><!---->x<!-- - -- --></a>"));
    EXPECT_TRUE(agrees("<a:b c:d='1' e-f.g_h='2'><_x/></a:b>"));
}

TEST(SimpleXmlReader, DeclinesWhatItLeavesToPugixml) {
    EXPECT_TRUE(declines("<a><![CDATA[x]]></a>"));
    EXPECT_TRUE(declines("<!DOCTYPE a><a/>"));
    EXPECT_TRUE(declines("<a>&#65;</a>"));
    EXPECT_TRUE(declines("<a>&unknown;</a>"));
    // pugixml ends text at a NUL (found by fuzz_cdi_xml_reader).
    EXPECT_TRUE(declines(std::string("<a>x\0y</a>", 11)));
    EXPECT_TRUE(declines("<a>fish & chips</a>"));
    EXPECT_TRUE(declines("<a v='&#10;'/>"));
    EXPECT_TRUE(declines("<\xC3\xA9/>"));
    EXPECT_TRUE(declines("<a \xC3\xA9='1'/>"));
    EXPECT_TRUE(declines("text<a/>"));
    EXPECT_TRUE(declines("<a/>text"));
    EXPECT_TRUE(declines("<a/><b/>"));
    EXPECT_TRUE(declines("<a x=1/>"));
    EXPECT_TRUE(declines("<a x='1'y='2'/>"));
    EXPECT_TRUE(declines("<a x/>"));
    EXPECT_TRUE(declines("< a/>"));
    EXPECT_TRUE(declines("<a></b>"));
    EXPECT_TRUE(declines("<a></ab>"));
    EXPECT_TRUE(declines("<ab></a>"));
    EXPECT_TRUE(declines("<a>"));
    EXPECT_TRUE(declines("<a/ >"));
    EXPECT_TRUE(declines("<a><!-- open </a>"));
    EXPECT_TRUE(declines("<?pi <a/>"));
    EXPECT_TRUE(declines("<? x?><a/>"));
    EXPECT_TRUE(declines("<a x='1"));
    EXPECT_TRUE(declines(""));
    EXPECT_TRUE(declines("   "));
}

TEST(SimpleXmlReader, DeclinesNestingDeeperThanTheLimit) {
    const auto nested = [](std::size_t depth) {
        std::string s;
        for (std::size_t i = 0; i < depth; ++i) s += "<a>";
        for (std::size_t i = 0; i < depth; ++i) s += "</a>";
        return s;
    };
    EXPECT_TRUE(agrees(nested(kDepth)));
    EXPECT_TRUE(declines(nested(kDepth + 1)));
}

std::filesystem::path corpus_dir() {
    return std::filesystem::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
}

std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    while (!text.empty() && text.back() == '\0') text.pop_back();
    return text;
}

TEST(SimpleXmlReader, AgreesWithPugixmlOnTheCorpus) {
    if (!std::filesystem::is_directory(corpus_dir())) GTEST_SKIP() << "corpus not found";
    std::size_t files = 0;
    std::size_t accepted = 0;
    for (const auto& entry : std::filesystem::directory_iterator(corpus_dir())) {
        const std::string text = read_file(entry.path());
        if (text.find('\0') != std::string::npos) continue;  // refused before any XML reading
        ++files;
        if (agrees(text)) ++accepted;
    }
    // Every well-formed corpus file is plain XML; one is deliberately malformed.
    EXPECT_GE(accepted + 1, files);
}

// Everything parse() and build_layout() say about a CDI, as text.
std::string outcome(std::string_view text) {
    std::ostringstream out;
    const ParseResult parsed = parse(text);
    for (const Diagnostic& d : parsed.diagnostics) out << d.line << ": " << d.message << "\n";
    if (!parsed.document) return out.str();
    const LayoutResult laid = build_layout(*parsed.document);
    for (const Diagnostic& d : laid.diagnostics) out << d.line << ": " << d.message << "\n";
    if (laid.layout) render(*laid.layout, out);
    return out.str();
}

// An empty CDATA section after a description's text changes nothing but makes the simple
// reader decline, so parse() then reads the file with pugixml: the outcome must not change.
TEST(SimpleXmlReader, ParseGivesTheSameOutcomeThroughPugixml) {
    if (!std::filesystem::is_directory(corpus_dir())) GTEST_SKIP() << "corpus not found";
    std::size_t compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(corpus_dir())) {
        const std::string text = read_file(entry.path());
        const std::size_t at = text.find("</description>");
        if (at == std::string::npos || declines(text)) continue;
        std::string general = text;
        general.insert(at, "<![CDATA[]]>");
        ASSERT_TRUE(declines(general));
        EXPECT_EQ(outcome(text), outcome(general)) << entry.path();
        ++compared;
    }
    EXPECT_GT(compared, 40u);
}

// Random edits of real CDIs: whenever the simple reader accepts, pugixml agrees.
TEST(SimpleXmlReader, AgreesWithPugixmlOnMutatedCdis) {
    if (!std::filesystem::is_directory(corpus_dir())) GTEST_SKIP() << "corpus not found";
    std::vector<std::string> sources;
    for (const auto& entry : std::filesystem::directory_iterator(corpus_dir())) {
        const std::string text = read_file(entry.path());
        if (text.find('\0') == std::string::npos && text.size() < 20000) sources.push_back(text);
    }
    ASSERT_FALSE(sources.empty());
    const std::string pieces[] = {"<",     ">",        "/",  "\"",        "'",   "=",   "&",
                                  "&amp;", "&#38;",    "\r", "\r\n",      "\t",  " ",   "<!--",
                                  "-->",   "<?",       "?>", "<![CDATA[", "]]>", "<x>", "</x>",
                                  "<x/>",  "\xC3\xA9", "a",  "1"};
    std::mt19937 rng(20261122);
    std::size_t accepted = 0;
    for (int round = 0; round < 3000; ++round) {
        std::string text = sources[rng() % sources.size()];
        const int edits = 1 + static_cast<int>(rng() % 3);
        for (int k = 0; k < edits; ++k) {
            const std::size_t at = rng() % (text.size() + 1);
            if (rng() % 2 == 0) {
                text.insert(at, pieces[rng() % std::size(pieces)]);
            } else {
                text.erase(at, 1 + rng() % 8);
            }
        }
        if (agrees(text)) ++accepted;
        if (HasFailure()) break;
    }
    EXPECT_GT(accepted, 100u);  // the edits leave plenty of documents it reads
}

}  // namespace
}  // namespace olcb::cdi
