// The FDI test data (tests/data/fdi): each file's verdict and function count as its README's
// Files table states them, judged by validate_fdi() and check_fdi_rules().
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/fdi_parser.hpp"
#include "cdi/fdi_validator.hpp"
#include "cdi/rule_finding.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;
using test::listing;

const fs::path kData = fs::path(OLCB_SOURCE_DIR) / "tests" / "data" / "fdi";

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// One row of the README's Files table.
struct Expected {
    bool valid = false;
    std::uint32_t first_error_line = 0;  // invalid files
    std::size_t functions = 0;           // valid files
};

/// Rows "| `name.xml` | source | commit | kind | valid | N | ... |" or "... | invalid L<n> | - |".
std::map<std::string, Expected> read_table() {
    std::map<std::string, Expected> rows;
    std::istringstream in(read_file(kData / "README.md"));
    const std::regex row(
        R"(^\| `([^`]+\.xml)` \|[^|]*\|[^|]*\|[^|]*\| (valid|invalid L(\d+)) \| (\d+|-) \|)");
    std::string line;
    while (std::getline(in, line)) {
        std::smatch m;
        if (!std::regex_search(line, m, row)) continue;
        Expected e;
        e.valid = m[2] == "valid";
        if (!e.valid) e.first_error_line = static_cast<std::uint32_t>(std::stoul(m[3]));
        if (e.valid) e.functions = std::stoul(m[4]);
        rows[m[1]] = e;
    }
    return rows;
}

TEST(CorpusFdi, EveryFileIsListedAndEveryListedFileExists) {
    const auto table = read_table();
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(kData)) {
        if (entry.path().extension() != ".xml") continue;
        ++files;
        EXPECT_TRUE(table.contains(entry.path().filename().string())) << entry.path();
    }
    EXPECT_EQ(files, table.size());
    EXPECT_GE(files, 17U);
}

TEST(CorpusFdi, VerdictsAndFunctionsAsTheReadmeStates) {
    std::size_t valid = 0;
    for (const auto& [name, expected] : read_table()) {
        SCOPED_TRACE(name);
        const std::string text = read_file(kData / name);
        const ValidatedFdi v = validate_fdi(text);
        EXPECT_EQ(v.ok(), expected.valid) << listing(v.diagnostics);
        if (expected.valid) {
            ++valid;
            ASSERT_TRUE(v.document);
            EXPECT_EQ(v.document->functions.size(), expected.functions);
            EXPECT_TRUE(is_fdi_text(text));
        } else {
            const Diagnostic* first = test::first_error(v.diagnostics);
            ASSERT_NE(first, nullptr);
            EXPECT_EQ(first->line, expected.first_error_line) << listing(v.diagnostics);
        }
        // The fdi.valid check agrees with the validator it reports.
        for (const RuleFinding& f : check_fdi_rules(text, v)) {
            if (f.check_id != "fdi.valid" || f.status == RuleStatus::kSkip) continue;
            EXPECT_EQ(f.status == RuleStatus::kFail, !expected.valid) << f.message;
        }
    }
    EXPECT_GE(valid, 9U);
}

}  // namespace
}  // namespace olcb::cdi
