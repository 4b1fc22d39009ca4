// Every real corpus CDI parses and lays out; variable counts match MANIFEST.md and addresses
// match the independent oracle (oracle/expected_addresses.json).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(OLCB_SHARED_DIR) / "corpus";

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

struct ManifestRow {
    std::string kind;
    std::string vars;
};

// The "## Files" table: | `file` | source | commit | licence | kind | bytes | vars | ...
std::map<std::string, ManifestRow> read_manifest() {
    std::map<std::string, ManifestRow> rows;
    std::istringstream in(read_file(kCorpus / "MANIFEST.md"));
    std::string line;
    bool in_files = false;
    while (std::getline(in, line)) {
        if (line.rfind("## ", 0) == 0) in_files = line == "## Files";
        if (!in_files || line.rfind("| `", 0) != 0) continue;
        std::vector<std::string> cells;
        std::size_t pos = 1;
        while (pos < line.size()) {
            const std::size_t bar = line.find(" | ", pos);
            const std::size_t end = bar == std::string::npos ? line.size() : bar;
            std::string cell = line.substr(pos, end - pos);
            while (!cell.empty() && (cell.front() == ' ')) cell.erase(0, 1);
            cells.push_back(cell);
            pos = end + 3;
            if (bar == std::string::npos) break;
        }
        if (cells.size() < 7) continue;
        std::string file = cells[0];
        file.erase(std::remove(file.begin(), file.end(), '`'), file.end());
        rows[file] = {cells[4], cells[6]};
    }
    return rows;
}

class CorpusLayout : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::is_directory(kCorpus / "cdi")) {
            GTEST_SKIP() << "corpus not found at " << kCorpus << "; corpus tests skipped";
        }
    }
};

struct Laid {
    Document doc;
    LayoutResult result;
};

std::unique_ptr<Laid> lay_file(const std::string& name, const LayoutOptions& options = {}) {
    auto out = std::make_unique<Laid>();
    ParseResult parsed = parse(read_file(kCorpus / "cdi" / name));
    for (const Diagnostic& d : parsed.diagnostics) {
        EXPECT_NE(d.severity, Severity::kError) << name << ":" << d.line << ": " << d.message;
    }
    if (!parsed.document) return out;
    out->doc = std::move(*parsed.document);
    out->result = build_layout(out->doc, options);
    for (const Diagnostic& d : out->result.diagnostics) {
        EXPECT_NE(d.severity, Severity::kError) << name << ":" << d.line << ": " << d.message;
    }
    return out;
}

std::vector<std::uint64_t> addresses_of(const Layout& layout, ElementKind kind,
                                        std::uint32_t space) {
    std::vector<std::uint64_t> out;
    layout.visit([&](const Cursor& c) {
        if (c.element().kind == kind && c.space() == space) out.push_back(c.address());
    });
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::uint64_t> oracle_events(const nlohmann::json& oracle, const std::string& file) {
    return oracle.at(file).at("eventid_addresses").get<std::vector<std::uint64_t>>();
}

nlohmann::json read_oracle() {
    return nlohmann::json::parse(read_file(kCorpus / "oracle" / "expected_addresses.json"));
}

TEST_F(CorpusLayout, EveryRealFileLaysOutWithManifestVariableCount) {
    const auto rows = read_manifest();
    std::size_t checked = 0;
    for (const auto& entry : fs::directory_iterator(kCorpus / "cdi")) {
        const std::string name = entry.path().filename().string();
        auto row = rows.find(name);
        ASSERT_NE(row, rows.end()) << name << " is not in MANIFEST.md";
        const std::string& kind = row->second.kind;
        if (kind == "synthetic") {
            EXPECT_EQ(name.rfind("openlcbclib__nodewizard_", 0), 0u) << name;
            continue;
        }
        ASSERT_TRUE(kind == "device" || kind == "capture" || kind == "library" || kind == "test" ||
                    kind == "doc")
            << name << ": " << kind;
        SCOPED_TRACE(name);
        auto laid = lay_file(name);
        ASSERT_TRUE(laid->result.layout) << name;
        EXPECT_EQ(std::to_string(laid->result.layout->variable_count()), row->second.vars);
        // Lookup agrees with enumeration for every variable: the byte is held by a variable
        // that starts no later than it and ends after it.
        const Layout& layout = *laid->result.layout;
        layout.visit([&](const Cursor& c) {
            Cursor f = layout.find(c.space(), c.address());
            ASSERT_TRUE(f.valid()) << c.path();
            EXPECT_LE(f.address(), c.address());
            EXPECT_GT(f.address() + f.size(), c.address());
            EXPECT_LE(f.ordinal(), c.ordinal());
            EXPECT_EQ(layout.at(c.ordinal()).address(), c.address());
        });
        ++checked;
    }
    EXPECT_EQ(checked, 50u);
}

TEST_F(CorpusLayout, SyntheticFixturesReportWhatTheySay) {
    auto check_error = [](const std::string& name, std::uint32_t line, const std::string& text) {
        ParseResult r = parse(read_file(kCorpus / "cdi" / name));
        EXPECT_FALSE(r.document) << name;
        ASSERT_FALSE(r.diagnostics.empty()) << name;
        EXPECT_EQ(r.diagnostics[0].line, line) << name;
        EXPECT_NE(r.diagnostics[0].message.find(text), std::string::npos)
            << name << ": " << r.diagnostics[0].message;
    };
    check_error("openlcbclib__nodewizard_02_malformed_xml.xml", 22, "malformed XML");
    check_error("openlcbclib__nodewizard_03_wrong_root_element.xml", 14, "<configuration>");
    check_error("openlcbclib__nodewizard_36_bad_attributes_segment.xml", 28, "space");
}

TEST_F(CorpusLayout, OpenMrnEventIdsMatchTheFirmware) {
    const nlohmann::json oracle = read_oracle();
    for (const char* file :
         {"openmrn__io_board_linux_x86.xml", "openmrn__io_board_stm32g0b1_railcom.xml",
          "openmrn__dmx_controller.xml", "openmrn__modbus_controller.xml"}) {
        SCOPED_TRACE(file);
        auto laid = lay_file(file);
        ASSERT_TRUE(laid->result.layout);
        EXPECT_EQ(addresses_of(*laid->result.layout, ElementKind::kEventId, 253),
                  oracle_events(oracle, file));
    }
}

TEST_F(CorpusLayout, Wrap32RuleShowsTheDocumentedDmxModbusDifference) {
    // With 32-bit wrap-around the Scenes group lands on the legacy data: every event ID after
    // the bogus padding moves down by exactly the padding's negative value.
    const nlohmann::json oracle = read_oracle();
    const std::pair<const char*, std::uint64_t> cases[] = {{"openmrn__dmx_controller.xml", 140},
                                                           {"openmrn__modbus_controller.xml", 108}};
    for (const auto& [file, shift] : cases) {
        SCOPED_TRACE(file);
        auto laid = lay_file(file, LayoutOptions{UnsignedOffsetRule::kWrap32});
        ASSERT_TRUE(laid->result.layout);
        const Element* scenes = nullptr;
        for (const Segment& seg : laid->doc.segments) {
            for (const Element& e : seg.children) {
                if (e.name == "Scenes") scenes = &e;
            }
        }
        ASSERT_NE(scenes, nullptr);
        const auto placement = laid->result.layout->placement(*scenes);
        ASSERT_TRUE(placement);
        EXPECT_EQ(placement->address, 128u);  // "Scenes[0] at 128" (MANIFEST)
        std::vector<std::uint64_t> expected = oracle_events(oracle, file);
        const std::uint64_t padding_end = 128 + shift;  // legacy group 128..128+shift
        for (std::uint64_t& a : expected) {
            if (a >= padding_end) a -= shift;
        }
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(addresses_of(*laid->result.layout, ElementKind::kEventId, 253), expected);
    }
}

TEST_F(CorpusLayout, NucleoMatchesExceptTheHiddenGroup) {
    const nlohmann::json oracle = read_oracle();
    const char* file = "openmrn__nucleo_io_f303re.xml";
    auto laid = lay_file(file);
    ASSERT_TRUE(laid->result.layout);
    const std::vector<std::uint64_t> ours =
        addresses_of(*laid->result.layout, ElementKind::kEventId, 253);
    const std::vector<std::uint64_t> expected = oracle_events(oracle, file);
    std::vector<std::uint64_t> missing;
    std::set_difference(expected.begin(), expected.end(), ours.begin(), ours.end(),
                        std::back_inserter(missing));
    EXPECT_EQ(missing, (std::vector<std::uint64_t>{740, 748, 776, 784, 812, 820, 848, 856}));
    EXPECT_EQ(ours.size() + 8, expected.size());
    EXPECT_TRUE(std::includes(expected.begin(), expected.end(), ours.begin(), ours.end()));
}

TEST_F(CorpusLayout, CdiPanelTestAddresses) {
    const nlohmann::json oracle = read_oracle();
    const nlohmann::json& o = oracle.at("openlcb_java__cdipaneltest_offsets.xml");
    auto laid = lay_file("openlcb_java__cdipaneltest_offsets.xml");
    ASSERT_TRUE(laid->result.layout);
    const Layout& layout = *laid->result.layout;
    const nlohmann::json& s13 = o.at("space_13");
    std::vector<const Element*> top;
    for (const Element& e : laid->doc.segments[0].children) top.push_back(&e);
    auto address_of = [&](const Element& e) { return layout.placement(e)->address; };
    EXPECT_EQ(address_of(*top[0]), s13.at("int (first)").get<std::uint64_t>());
    EXPECT_EQ(address_of(*top[1]), s13.at("eventid").get<std::uint64_t>());
    EXPECT_EQ(address_of(*top[3]), s13.at("int size 1").get<std::uint64_t>());
    EXPECT_EQ(address_of(*top[5]), s13.at("int (last)").get<std::uint64_t>());
    const auto group_starts = s13.at("replicated group starts").get<std::vector<std::uint64_t>>();
    const auto placement = layout.placement(*top[4]);
    ASSERT_TRUE(placement);
    for (std::size_t k = 0; k < group_starts.size(); ++k) {
        EXPECT_EQ(placement->address + k * static_cast<std::uint64_t>(placement->stride),
                  group_starts[k]);
    }
    std::vector<std::uint64_t> ints, strings;
    layout.visit([&](const Cursor& c) {
        if (c.space() != 13) return;
        if (c.group_depth() == 1 && c.element().kind == ElementKind::kInt)
            ints.push_back(c.address());
        if (c.element().kind == ElementKind::kString) strings.push_back(c.address());
    });
    EXPECT_EQ(ints, s13.at("int inside group").get<std::vector<std::uint64_t>>());
    EXPECT_EQ(strings, s13.at("strings").get<std::vector<std::uint64_t>>());
    EXPECT_EQ(layout.find(14, o.at("space_14").at("int").get<std::uint64_t>()).element().kind,
              ElementKind::kInt);
}

}  // namespace
}  // namespace olcb::cdi
