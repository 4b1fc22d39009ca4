// The display memory map: variables as the layout places them, gaps and overlaps, replication
// listed up to a bound with the rest summarized (and accounted for), and its JSON.
#include "cdi/memory_map.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/parser.hpp"
#include "cdi/variable_name.hpp"

namespace olcb::cdi {
namespace {

struct Laid {
    Document doc;
    std::optional<Layout> layout;
};

std::unique_ptr<Laid> lay(const std::string& body) {
    auto out = std::make_unique<Laid>();
    ParseResult parsed = parse("<?xml version=\"1.0\"?><cdi>" + body + "</cdi>");
    EXPECT_TRUE(parsed.document);
    if (!parsed.document) return out;
    out->doc = std::move(*parsed.document);
    out->layout = build_layout(out->doc).layout;
    EXPECT_TRUE(out->layout);
    return out;
}

// Every variable of a space is listed or counted in exactly one summary.
void expect_accounted(const SpaceMap& m) {
    std::uint64_t summarized = 0;
    for (const MapSummary& s : m.summaries) summarized += s.variables;
    EXPECT_EQ(m.variables.size() + summarized, m.variable_count) << "space " << m.space;
}

TEST(MemoryMap, ListsVariablesWithPathsTypesAndAddresses) {
    auto laid =
        lay("<segment space=\"253\" origin=\"16\"><name>Settings</name>"
            "<int size=\"2\"><name>A</name></int><string size=\"8\"><name>B</name></string>"
            "<eventid><name>C</name></eventid></segment>");
    const auto maps = build_memory_map(*laid->layout);
    ASSERT_EQ(maps.size(), 1u);
    const SpaceMap& m = maps[0];
    EXPECT_EQ(m.space, 253u);
    EXPECT_EQ(m.name, "Settings");
    EXPECT_EQ(m.begin, 16u);
    EXPECT_EQ(m.end, 34u);
    ASSERT_EQ(m.variables.size(), 3u);
    EXPECT_EQ(m.variables[0].name, "Settings.A");
    EXPECT_EQ(m.variables[0].replica, "");
    EXPECT_EQ(m.variables[0].label, "A");
    EXPECT_EQ(m.variables[0].type, "int");
    EXPECT_EQ(m.variables[1].type, "string");
    EXPECT_EQ(m.variables[1].address, 18u);
    EXPECT_EQ(m.variables[1].size, 8u);
    EXPECT_EQ(m.variables[2].type, "eventid");
    EXPECT_EQ(m.variables[2].ordinal, 2u);
    EXPECT_TRUE(m.gaps.empty());
    EXPECT_TRUE(m.overlaps.empty());
    expect_accounted(m);
}

TEST(MemoryMap, MarksGapsAndOverlaps) {
    // A at 0-1, a 4-byte gap, B at 6-9, C 2 bytes back (8-9, shared with B), D at 10.
    auto laid = lay(
        "<segment space=\"253\"><int size=\"2\"><name>A</name></int>"
        "<int size=\"4\" offset=\"4\"><name>B</name></int>"
        "<int size=\"2\" offset=\"-2\"><name>C</name></int><int><name>D</name></int></segment>");
    const SpaceMap m = build_memory_map(*laid->layout).at(0);
    ASSERT_EQ(m.variables.size(), 4u);
    EXPECT_EQ(m.gaps, (std::vector<MapRange>{{2, 4}}));
    EXPECT_EQ(m.overlaps, (std::vector<MapRange>{{8, 2}}));
}

TEST(MemoryMap, SeparateSpacesAndSharedSpaces) {
    auto laid =
        lay("<segment space=\"251\"><name>Id</name><string size=\"4\"/></segment>"
            "<segment space=\"253\"><name>One</name><int/></segment>"
            "<segment space=\"253\" origin=\"0\"><name>Two</name><int size=\"2\"/></segment>");
    const auto maps = build_memory_map(*laid->layout);
    ASSERT_EQ(maps.size(), 2u);
    EXPECT_EQ(maps[0].space, 251u);
    EXPECT_EQ(maps[1].space, 253u);
    EXPECT_EQ(maps[1].segments, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_EQ(maps[1].name, "One / Two");
    EXPECT_EQ(maps[1].overlaps, (std::vector<MapRange>{{0, 1}}));
    EXPECT_EQ(maps[1].variables[1].segment, 2u);
}

TEST(MemoryMap, ReplicationListsTheFirstReplicasAndTheLastAndSummarizesTheRest) {
    auto laid =
        lay("<segment space=\"253\"><name>S</name><group replication=\"1000\"><name>Port</name>"
            "<repname>Port</repname><int size=\"2\"><name>X</name></int><int><name>Y</name></int>"
            "</group><int><name>After</name></int></segment>");
    const SpaceMap m = build_memory_map(*laid->layout).at(0);
    // Replicas 1-16 and 1000, 2 variables each, then After.
    ASSERT_EQ(m.variables.size(), 17u * 2 + 1);
    EXPECT_EQ(m.variables[32].name, "S.Port(999).X");
    EXPECT_EQ(m.variables[32].replica, "Port 1000");
    EXPECT_EQ(m.variables[32].address, 999u * 3);
    EXPECT_EQ(m.variables.back().name, "S.After");
    ASSERT_EQ(m.summaries.size(), 1u);
    const MapSummary& s = m.summaries[0];
    EXPECT_EQ(s.group, "Port");
    EXPECT_EQ(s.first_replica, 16u);
    EXPECT_EQ(s.replicas, 983u);
    EXPECT_EQ(s.variables, 983u * 2);
    EXPECT_EQ(s.first_name, "S.Port(16).X");
    EXPECT_EQ(s.range, (MapRange{48, 2949}));
    EXPECT_TRUE(m.gaps.empty());  // the summary covers its bytes
    expect_accounted(m);
}

TEST(MemoryMap, NestedHugeReplicationStaysSmallAndFast) {
    auto laid =
        lay("<segment space=\"253\"><group replication=\"65536\"><name>Outer</name>"
            "<group replication=\"32768\"><name>Inner</name><int/></group></group></segment>");
    const auto start = std::chrono::steady_clock::now();
    const SpaceMap m = build_memory_map(*laid->layout).at(0);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
    EXPECT_EQ(m.variable_count, 65536ull * 32768);
    EXPECT_EQ(m.variables.size(), 17u * 17);
    expect_accounted(m);
    EXPECT_TRUE(m.gaps.empty());
}

TEST(MemoryMap, AlsoListedReplicasAreListed) {
    auto laid =
        lay("<segment space=\"253\"><group replication=\"100\"><name>G</name><int/></group>"
            "</segment>");
    MemoryMapOptions options;
    options.replicas = 2;
    options.also_list = [](std::uint64_t from, std::uint64_t) { return from <= 50 ? 50 : 100; };
    const SpaceMap m = build_memory_map(*laid->layout, options).at(0);
    std::vector<std::uint64_t> addresses;
    addresses.reserve(m.variables.size());
    for (const MapVariable& v : m.variables) addresses.push_back(v.address);
    EXPECT_EQ(addresses, (std::vector<std::uint64_t>{0, 1, 50, 99}));
    ASSERT_EQ(m.summaries.size(), 2u);
    EXPECT_EQ(m.summaries[0].first_replica, 2u);
    EXPECT_EQ(m.summaries[0].replicas, 48u);
    EXPECT_EQ(m.summaries[1].first_replica, 51u);
    EXPECT_EQ(m.summaries[1].replicas, 48u);
    expect_accounted(m);
}

TEST(MemoryMap, MaxVariablesSummarizesTheRestOfTheSegment) {
    std::string body = "<segment space=\"253\"><name>S</name>";
    for (int i = 0; i < 30; ++i) body += "<int/>";
    body += "</segment><segment space=\"251\"><string size=\"8\"/></segment>";
    auto laid = lay(body);
    MemoryMapOptions options;
    options.max_variables = 10;
    const auto maps = build_memory_map(*laid->layout, options);
    ASSERT_EQ(maps.size(), 2u);
    EXPECT_EQ(maps[0].variables.size(), 1u);  // space 251 is not starved by 253
    const SpaceMap& m = maps[1];
    EXPECT_EQ(m.variables.size(), 10u);
    ASSERT_EQ(m.summaries.size(), 1u);
    EXPECT_EQ(m.summaries[0].group, "");
    EXPECT_EQ(m.summaries[0].variables, 20u);
    EXPECT_EQ(m.summaries[0].range, (MapRange{10, 20}));
    expect_accounted(m);
}

TEST(MemoryMap, JsonCarriesEveryField) {
    auto laid =
        lay("<segment space=\"253\"><name>S</name><int/><group replication=\"40\"><name>G</name>"
            "<int offset=\"1\"/></group></segment>");
    const nlohmann::json j = memory_map_json(build_memory_map(*laid->layout));
    ASSERT_TRUE(j.is_array());
    ASSERT_EQ(j.size(), 1u);
    const nlohmann::json& s = j[0];
    for (const char* key : {"space", "segments", "name", "begin", "end", "variable_count",
                            "variables", "summaries", "gaps", "overlaps"})
        EXPECT_TRUE(s.contains(key)) << key;
    EXPECT_EQ(s["variable_count"], 41);
    EXPECT_EQ(s["variables"][0]["name"], "S.child1");
    EXPECT_EQ(s["variables"][0]["label"], "child1");
    for (const char* key :
         {"name", "replica", "label", "type", "segment", "address", "size", "ordinal"})
        EXPECT_TRUE(s["variables"][0].contains(key)) << key;
    ASSERT_EQ(s["summaries"].size(), 1u);
    for (const char* key :
         {"group", "first_name", "first_replica", "replicas", "variables", "address", "size"})
        EXPECT_TRUE(s["summaries"][0].contains(key)) << key;
    EXPECT_EQ(s["gaps"][0]["address"], 1);
    EXPECT_EQ(s["gaps"][0]["size"], 1);
}

// Every corpus CDI: listed variables are the layout's own (path and address at their ordinal),
// every variable is accounted for, and gaps never cover a listed variable.
TEST(MemoryMap, CorpusMapsAgreeWithTheLayout) {
    const std::filesystem::path dir = std::filesystem::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
    if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no corpus at " << dir;
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        if (entry.path().extension() != ".xml") continue;
        std::ifstream in(entry.path(), std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        ParseResult parsed = parse(text.str());
        if (!parsed.document) continue;
        auto laid = build_layout(*parsed.document);
        if (!laid.layout) continue;
        ++files;
        for (const SpaceMap& m : build_memory_map(*laid.layout)) {
            expect_accounted(m);
            for (const MapVariable& v : m.variables) {
                const Cursor c = laid.layout->at(v.ordinal);
                ASSERT_TRUE(c.valid()) << entry.path();
                EXPECT_EQ(variable_name(*laid.layout, c), v.name) << entry.path();
                EXPECT_EQ(c.address(), v.address) << entry.path();
                for (const MapRange& g : m.gaps) {
                    EXPECT_TRUE(v.address + v.size <= g.address || g.address + g.size <= v.address)
                        << entry.path() << " " << v.name;
                }
            }
        }
    }
    EXPECT_GT(files, 10u);
}

// A variable under 200 or 1,000 nested groups is mapped like any other (deep nesting:
// parser_test.cpp).
class MemoryMapDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(MemoryMapDeepNesting, MapsTheLeaf) {
    auto laid = test::lay(test::nested_cdi(GetParam()));
    ASSERT_TRUE(laid->result.layout) << test::first_error_text(laid->result.diagnostics);
    EXPECT_EQ(build_memory_map(laid->layout()).at(0).variable_count, 1u);
}

INSTANTIATE_TEST_SUITE_P(Depths, MemoryMapDeepNesting,
                         ::testing::ValuesIn(test::kValidNestingDepths));

}  // namespace
}  // namespace olcb::cdi
