// Shared helpers of the cdi tests: a document parsed and laid out in one step, the variables of a
// layout as a list, the findings as text, and the CDIs several units' tests are run on (deep
// nesting, the annotated CdiPanelTest layout).
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "cdi/diagnostic.hpp"
#include "cdi/layout.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi::test {

/// One variable of a layout: its path, space, address and size.
struct Placed {
    std::string path;
    std::uint32_t space;
    std::uint64_t address;
    std::uint64_t size;
    bool operator==(const Placed&) const = default;
};

inline std::ostream& operator<<(std::ostream& os, const Placed& p) {
    return os << p.path << " @" << p.space << ":" << p.address << "+" << p.size;
}

/// A parsed and laid out CDI; keeps the Document alive next to the Layout.
struct Laid {
    Document doc;
    LayoutResult result;
    const Layout& layout() const { return *result.layout; }
};

/// Parses xml (which must parse) and lays it out with options.
inline std::unique_ptr<Laid> lay(const std::string& xml, const LayoutOptions& options = {}) {
    auto out = std::make_unique<Laid>();
    ParseResult parsed = parse(xml);
    EXPECT_TRUE(parsed.document) << (parsed.diagnostics.empty() ? ""
                                                                : parsed.diagnostics[0].message);
    if (parsed.document) out->doc = std::move(*parsed.document);
    out->result = build_layout(out->doc, options);
    return out;
}

/// The first `limit` variables of a layout in document order.
inline std::vector<Placed> all(const Layout& layout, std::size_t limit = 1000) {
    std::vector<Placed> out;
    layout.visit([&](const Cursor& c) {
        out.push_back({c.path(), c.space(), c.address(), c.size()});
        return out.size() < limit;
    });
    return out;
}

/// How many findings have severity s.
inline std::size_t count_severity(const Diagnostics& d, Severity s) {
    std::size_t n = 0;
    for (const Diagnostic& x : d) n += x.severity == s;
    return n;
}

/// The first error, or nullptr when there is none.
inline const Diagnostic* first_error(const Diagnostics& d) {
    for (const Diagnostic& x : d) {
        if (x.severity == Severity::kError) return &x;
    }
    return nullptr;
}

/// The first error's message ("" when there is none).
inline std::string first_error_text(const Diagnostics& d) {
    const Diagnostic* e = first_error(d);
    return e ? e->message : std::string();
}

/// Every finding as "cdi:LINE: severity: message" lines, for failure messages.
inline std::string listing(const Diagnostics& d) {
    std::string out;
    for (const Diagnostic& x : d) out += format_diagnostic("cdi", x) + "\n";
    return out;
}

/// The annotated CDI of OpenLCB_Java's CdiPanelTest.testOffsets (addresses in its comments).
inline constexpr const char* kPanelTest = R"(<cdi>
  <segment space="13" origin="132">
    <int size="2" offset="21" />
    <eventid offset="3" />
    <group offset="1" />
    <int size="1" />
    <group replication="2" offset="11">
      <int size="2" offset="3" />
      <group offset="-5" />
      <group replication="3">
        <string size="9" />
      </group>
    </group>
    <int size="2" offset="21" />
  </segment>
  <segment space="14" origin="0">
    <int size="2" />
  </segment>
</cdi>)";

/// A schema-valid CDI whose one variable ("Leaf", 2 bytes) sits under `depth` nested groups
/// named L1..L<depth>.
inline std::string nested_cdi(std::size_t depth) {
    std::string out =
        "<?xml version=\"1.0\"?>\n"
        "<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/4/cdi.xsd\">\n"
        "<identification><manufacturer>Deep</manufacturer><model>Nest</model>"
        "<hardwareVersion>1</hardwareVersion><softwareVersion>1</softwareVersion>"
        "</identification>\n<acdi/>\n<segment space=\"253\" origin=\"0\"><name>S</name>\n";
    for (std::size_t i = 0; i < depth; ++i) {
        out += "<group><name>L" + std::to_string(i + 1) + "</name>\n";
    }
    out += "<int size=\"2\"><name>Leaf</name></int>\n";
    for (std::size_t i = 0; i < depth; ++i) out += "</group>\n";
    return out + "</segment>\n</cdi>\n";
}

/// depth bare nested groups around nothing: no names, no variables, only nesting.
inline std::string hostile_cdi(std::size_t depth) {
    std::string out = "<?xml version=\"1.0\"?>\n<cdi><segment space=\"253\">";
    out.reserve(out.size() + depth * 15 + 32);
    for (std::size_t i = 0; i < depth; ++i) out += "<group>";
    for (std::size_t i = 0; i < depth; ++i) out += "</group>";
    return out + "</segment></cdi>\n";
}

/// A small FDI: the declaration (line 1), the root naming FDI 1.`minor` (line 2; minor < 0: no
/// location), `<segment>` (line 3), `body` from line 4, then the closing tags.
inline std::string fdi_text(const std::string& body, int minor = 1) {
    std::string text =
        "<?xml version=\"1.0\"?>\n<fdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"";
    if (minor >= 0) {
        text += " xsi:noNamespaceSchemaLocation=\"https://openlcb.org/schema/fdi/1/" +
                std::to_string(minor) + "/fdi.xsd\"";
    }
    return text + ">\n<segment>\n" + body + "</segment>\n</fdi>\n";
}

/// One <function> of an FDI on one line.
inline std::string fdi_function(int number, const std::string& name = "F",
                                const std::string& kind = "binary") {
    return "<function kind=\"" + kind + "\"><name>" + name + "</name><number>" +
           std::to_string(number) + "</number></function>\n";
}

/// The depths of nesting a valid CDI is tested at (deeper than any real one, within the limit).
inline constexpr std::size_t kValidNestingDepths[] = {200, 1000};
/// The depths of hostile nesting: far beyond kMaxGroupDepth.
inline constexpr std::size_t kHostileNestingDepths[] = {100000, 1000000};

}  // namespace olcb::cdi::test
