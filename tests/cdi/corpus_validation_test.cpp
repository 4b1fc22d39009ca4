// Cross-checks the validators against the shared corpus: schema outcomes against MANIFEST.md's
// "XSD" column (xmllint results), and the combined validator against the TEST_CHECKS blocks of
// the synthetic node-wizard fixtures.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cdi/cdi_test_util.hpp"
#include "cdi/schema_validator.hpp"
#include "cdi/validator.hpp"

namespace olcb::cdi {
namespace {

namespace fs = std::filesystem;
using test::listing;

const fs::path kCorpus = fs::path(OLCB_SHARED_DIR) / "corpus";

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::string trim(const std::string& text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos) return {};
    return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator)) parts.push_back(trim(part));
    return parts;
}

/// One file's row of MANIFEST.md's Files table, XSD column only.
struct ManifestXsd {
    bool pass = false;
    std::string version;                            // "1.1"
    std::optional<std::uint32_t> first_error_line;  // for FAIL
};

/// Reads MANIFEST.md's Files table: rows "| `name.xml` | ... | PASS 1.x (...)... |".
std::map<std::string, ManifestXsd> read_manifest() {
    std::map<std::string, ManifestXsd> rows;
    std::istringstream in(read_file(kCorpus / "MANIFEST.md"));
    const std::regex xsd(R"(^(PASS|FAIL) (1\.[0-9]) \(([^)]*)\)(: `line ([0-9]+):)?)");
    std::string line;
    while (std::getline(in, line)) {
        if (!line.starts_with("| `")) continue;
        const std::vector<std::string> cells = split(line, '|');
        // cells[0] is empty (text before the first '|'); the XSD column is the last one.
        if (cells.size() < 3 || !cells[1].ends_with(".xml`")) continue;
        std::smatch match;
        if (!std::regex_search(cells.back(), match, xsd)) continue;
        ManifestXsd row;
        row.pass = match[1] == "PASS";
        row.version = match[2];
        if (match[5].matched) row.first_error_line = std::stoul(match[5]);
        rows[cells[1].substr(1, cells[1].size() - 2)] = row;
    }
    return rows;
}

std::vector<fs::path> corpus_files() {
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(kCorpus / "cdi")) {
        if (entry.path().extension() == ".xml") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
    return files;
}

#define SKIP_WITHOUT_CORPUS()                                                                \
    if (!fs::is_directory(kCorpus / "cdi")) {                                                \
        GTEST_SKIP() << "corpus not found at " << kCorpus << "; schema cross-check skipped"; \
    }

TEST(CorpusSchema, ManifestTableIsReadable) {
    SKIP_WITHOUT_CORPUS();
    const auto manifest = read_manifest();
    const auto files = corpus_files();
    EXPECT_EQ(manifest.size(), files.size());
    for (const fs::path& file : files) {
        EXPECT_TRUE(manifest.contains(file.filename().string())) << file;
    }
    // MANIFEST's own summary: "Against the matching XSD: 42 pass, 16 fail".
    const auto passes = std::count_if(manifest.begin(), manifest.end(),
                                      [](const auto& row) { return row.second.pass; });
    EXPECT_EQ(passes, 42);
    EXPECT_EQ(manifest.size() - static_cast<std::size_t>(passes), 16u);
}

TEST(CorpusSchema, OutcomeVersionAndFirstErrorLineMatchManifest) {
    SKIP_WITHOUT_CORPUS();
    const auto manifest = read_manifest();
    int checked = 0;
    for (const fs::path& file : corpus_files()) {
        const std::string name = file.filename().string();
        SCOPED_TRACE(name);
        const auto row = manifest.find(name);
        ASSERT_NE(row, manifest.end());
        SchemaChoice choice;
        const Diagnostics d = validate_schema(read_file(file), &choice);
        EXPECT_EQ(!has_errors(d), row->second.pass);
        EXPECT_EQ(schema_version_name(choice.version), row->second.version);
        if (row->second.first_error_line) {
            const auto first_error = std::find_if(d.begin(), d.end(), [](const Diagnostic& x) {
                return x.severity == Severity::kError;
            });
            ASSERT_NE(first_error, d.end());
            EXPECT_EQ(first_error->line, *row->second.first_error_line) << first_error->message;
        }
        ++checked;
    }
    EXPECT_EQ(checked, 58);
}

/// One check of a synthetic file's TEST_CHECKS block that concerns the validator.
struct Check {
    std::string
        kind;  // validate_has, validate_min_count, validate_count, map_is_null, map_not_null
    Severity severity = Severity::kError;
    std::string pattern;
    long number = 0;
    std::string text;  // the line, for messages
};

std::vector<Check> read_checks(const std::string& cdi_text) {
    std::vector<Check> checks;
    const auto begin = cdi_text.find("<!-- TEST_CHECKS");
    if (begin == std::string::npos) return checks;
    const auto end = cdi_text.find("-->", begin);
    std::istringstream block(cdi_text.substr(begin, end - begin));
    std::string line;
    std::getline(block, line);  // the "<!-- TEST_CHECKS" opener
    while (std::getline(block, line)) {
        const std::vector<std::string> fields = split(line, '|');
        if (fields.empty()) continue;
        Check check;
        check.kind = fields[0];
        check.text = trim(line);
        for (const std::string& field : fields) {
            if (field.starts_with("severity:")) {
                check.severity =
                    field == "severity:warning" ? Severity::kWarning : Severity::kError;
            } else if (field.starts_with("pattern:")) {
                check.pattern = field.substr(8);
            } else if (field.starts_with("min:")) {
                check.number = std::stol(field.substr(4));
            } else if (field.starts_with("expected:")) {
                check.number = std::stol(field.substr(9));
            }
        }
        checks.push_back(check);
    }
    return checks;
}

long count_of(const Diagnostics& d, Severity severity) {
    return std::count_if(d.begin(), d.end(),
                         [severity](const Diagnostic& x) { return x.severity == severity; });
}

TEST(CorpusSynthetic, CombinedValidatorMeetsEachTestChecksBlock) {
    SKIP_WITHOUT_CORPUS();
    int files = 0;
    int asserted = 0;
    for (const fs::path& file : corpus_files()) {
        const std::string name = file.filename().string();
        if (!name.starts_with("openlcbclib__nodewizard_")) continue;
        SCOPED_TRACE(name);
        ++files;
        const std::string text = read_file(file);
        const ValidationReport report = validate(text);
        const std::vector<Check> checks = read_checks(text);
        ASSERT_FALSE(checks.empty()) << "no TEST_CHECKS block";
        for (const Check& check : checks) {
            SCOPED_TRACE(check.text);
            if (check.kind == "validate_has") {
                const std::regex pattern(check.pattern, std::regex::icase | std::regex::ECMAScript);
                const bool found = std::any_of(report.diagnostics.begin(), report.diagnostics.end(),
                                               [&](const Diagnostic& x) {
                                                   return x.severity == check.severity &&
                                                          std::regex_search(x.message, pattern);
                                               });
                EXPECT_TRUE(found) << listing(report.diagnostics);
            } else if (check.kind == "validate_min_count") {
                EXPECT_GE(count_of(report.diagnostics, check.severity), check.number)
                    << listing(report.diagnostics);
            } else if (check.kind == "validate_count") {
                EXPECT_EQ(count_of(report.diagnostics, check.severity), check.number)
                    << listing(report.diagnostics);
            } else if (check.kind == "map_is_null") {
                EXPECT_FALSE(report.parsed);
            } else if (check.kind == "map_not_null") {
                EXPECT_TRUE(report.parsed);
            } else {
                continue;  // name:, defines_no_dupes, struct_no_dupes: code-generator checks
            }
            ++asserted;
        }
    }
    EXPECT_EQ(files, 8);
    EXPECT_EQ(asserted, 16);
}

TEST(CorpusValidate, ReportsAreSortedAndCarrySchemaErrors) {
    SKIP_WITHOUT_CORPUS();
    for (const fs::path& file : corpus_files()) {
        SCOPED_TRACE(file.filename().string());
        const std::string text = read_file(file);
        const ValidationReport report = validate(text);
        EXPECT_TRUE(std::is_sorted(
            report.diagnostics.begin(), report.diagnostics.end(),
            [](const Diagnostic& a, const Diagnostic& b) { return a.line < b.line; }));
        if (has_errors(validate_schema(text))) {
            EXPECT_FALSE(report.ok());
        }
        EXPECT_EQ(report.schema.version, [&] {
            SchemaChoice choice;
            (void)validate_schema(text, &choice);
            return choice.version;
        }());
    }
}

}  // namespace
}  // namespace olcb::cdi
