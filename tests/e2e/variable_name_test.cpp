// One name per variable: what `lcc-cdi layout` calls a variable is the key `lcc-conform backup`
// writes for it (cdi/variable_name.hpp), for every variable of the shipped scenarios.
#include <gtest/gtest.h>

#include <sstream>

#include <nlohmann/json.hpp>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH) && defined(LCC_CDI_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;

// The keys of a backup file in file order ('#' lines are comments).
std::vector<std::string> backup_keys(const std::string& text) {
    std::vector<std::string> keys;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        const auto eq = line.find('=');
        if (!line.starts_with("#") && eq != std::string::npos) keys.push_back(line.substr(0, eq));
    }
    return keys;
}

// The names `lcc-cdi layout --json` gives the variables a backup holds, in document order.
std::vector<std::string> layout_names(const fs::path& cdi) {
    const auto [code, out] = run_program(LCC_CDI_PATH, {"layout", "--json", cdi.string()});
    EXPECT_EQ(code, 0) << out;
    const auto json = nlohmann::json::parse(out, nullptr, false);
    std::vector<std::string> names;
    if (json.is_discarded()) return names;
    for (const auto& v : json.at("variables")) {
        const std::string type = v.at("type");
        if (type == "int" || type == "string" || type == "eventid" || type == "float")
            names.push_back(v.at("name"));
    }
    return names;
}

class VariableName : public ::testing::TestWithParam<const char*> {};

TEST_P(VariableName, LayoutNamesEveryVariableAsItsBackupKey) {
    const std::string scenario = GetParam();
    Simnode sim(source_path("scenarios/" + scenario + ".ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir dir("variable-name-e2e");
    const fs::path file = dir.path() / "backup.txt";
    const auto [code, text] =
        run_program(LCC_CONFORM_PATH, {"--connect", sim.connect(), "backup", file.string()});
    ASSERT_EQ(code, 0) << text;
    const std::vector<std::string> keys = backup_keys(read_text(file));
    ASSERT_FALSE(keys.empty());
    EXPECT_EQ(layout_names(source_path("scenarios/" + scenario + ".xml")), keys);
}

INSTANTIATE_TEST_SUITE_P(Scenarios, VariableName, ::testing::Values("default", "io-board"));

}  // namespace
}  // namespace olcb::e2e

#endif
