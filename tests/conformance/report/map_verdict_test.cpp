// The memory map's verdicts as the reports show them: each listed variable carries its verdict
// and evidence, and each space counts its verdicts.
#include "conformance/report/map_verdict.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "cdi/memory_map.hpp"
#include "conformance/conform_test_util.hpp"

namespace olcb::conform {
namespace {

constexpr const char* kCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name>
<int size="1"><name>A</name></int><int size="2"><name>B</name></int>
<string size="4"><name>C</name></string>
</segment></cdi>)";

TEST(MapVerdictTest, NamesAreTheReportsWords) {
    EXPECT_EQ(map_verdict_name(MapVerdict::kVerified), "verified");
    EXPECT_EQ(map_verdict_name(MapVerdict::kFailed), "failed");
    EXPECT_EQ(map_verdict_name(MapVerdict::kSkipped), "skipped");
    EXPECT_EQ(map_verdict_name(MapVerdict::kProtected), "protected");
}

TEST(MapVerdictTest, EachVariableCarriesItsVerdictAndEvidenceAndTheSpaceCountsThem) {
    cdi::Document doc;
    std::optional<cdi::Layout> layout;
    load_cdi(kCdi, doc, layout);
    const std::vector<cdi::SpaceMap> maps = cdi::build_memory_map(*layout);
    ASSERT_EQ(maps.size(), 1u);
    ASSERT_EQ(maps[0].variables.size(), 3u);
    MemoryMapSpace space{maps[0], {}};
    VariableVerdict failed;
    failed.verdict = MapVerdict::kFailed;
    failed.reason = "read back differently";
    failed.original_value = "5";
    failed.original_bytes = "00 05";
    failed.values.push_back({"-1", "FF FF", "FF 00", "65280", "", false});
    space.verdicts = {VariableVerdict{MapVerdict::kVerified, "", "", "", {}}, failed,
                      VariableVerdict{MapVerdict::kProtected, "says do not change", "", "", {}}};
    const nlohmann::json j = memory_map_json({space});
    ASSERT_EQ(j.size(), 1u);
    const auto& vars = j[0]["variables"];
    EXPECT_EQ(vars[0]["verdict"], "verified");
    EXPECT_FALSE(vars[0].contains("reason"));
    EXPECT_FALSE(vars[0].contains("original"));
    EXPECT_EQ(vars[1]["verdict"], "failed");
    EXPECT_EQ(vars[1]["reason"], "read back differently");
    EXPECT_EQ(vars[1]["original"]["bytes"], "00 05");
    EXPECT_EQ(vars[1]["values"][0]["read"], "FF 00");
    EXPECT_EQ(vars[1]["values"][0]["ok"], false);
    EXPECT_EQ(vars[2]["verdict"], "protected");
    EXPECT_EQ(j[0]["verdicts"]["verified"], 1);
    EXPECT_EQ(j[0]["verdicts"]["failed"], 1);
    EXPECT_EQ(j[0]["verdicts"]["protected"], 1);
    EXPECT_EQ(j[0]["verdicts"]["skipped"], 0);
}

}  // namespace
}  // namespace olcb::conform
