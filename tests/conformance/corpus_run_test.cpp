// lcc-conform against simnode serving each device/capture CDI of the corpus, in-process: every
// check passes except what the CDI itself breaks, reported as a cdi failure, never a crash.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/report/report.hpp"
#include "conformance/run/runner.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"
#include "support/report_schema.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

// File name -> kind, from the "Files" table of MANIFEST.md (column 6).
std::map<std::string, std::string> corpus_kinds(const fs::path& manifest) {
    std::map<std::string, std::string> out;
    std::istringstream in(read_text(manifest));
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("| `") || line.find(".xml`") == std::string::npos) continue;
        std::vector<std::string> cells;
        std::size_t pos = 1;
        while (pos < line.size()) {
            const std::size_t bar = line.find('|', pos);
            if (bar == std::string::npos) break;
            std::string cell = line.substr(pos, bar - pos);
            cell.erase(0, cell.find_first_not_of(' '));
            cell.erase(cell.find_last_not_of(' ') + 1);
            cells.push_back(cell);
            pos = bar + 1;
        }
        if (cells.size() > 4 && cells[0].size() > 2) {
            out[cells[0].substr(1, cells[0].size() - 2)] = cells[4];
        }
    }
    return out;
}

class CorpusRun : public ::testing::TestWithParam<std::string> {};

TEST_P(CorpusRun, OnlyTheCdisOwnFaultsFail) {
    const fs::path dir = fs::path(OLCB_SHARED_DIR) / "corpus";
    if (!fs::exists(dir / "MANIFEST.md")) GTEST_SKIP() << "corpus absent at " << dir;
    const auto kinds = corpus_kinds(dir / "MANIFEST.md");
    ASSERT_GE(kinds.size(), 58U) << "MANIFEST table not found";
    const std::string& file = GetParam();
    const auto kind = kinds.find(file);
    ASSERT_NE(kind, kinds.end()) << file;
    if (kind->second != "device" && kind->second != "capture") {
        GTEST_SKIP() << file << " is " << kind->second << ", not device/capture";
    }

    simnode::NodeConfig config;
    config.node_id = kDut;
    config.cdi = read_text(dir / "cdi" / file);
    std::string error;
    auto bench = testing::SimBench::serve(config, error);
    // A CDI that can't be parsed or laid out can't be served: that is the CDI's own fault.
    if (!bench) GTEST_SKIP() << file << " can't be served: " << error;
    auto node = bench->start();
    ASSERT_TRUE(node);
    Session& session = *bench->session;

    RunOptions options;
    options.sample = 1;
    options.backup_path = (fs::temp_directory_path() / ("corpus_run_" + file + ".backup")).string();
    std::ostringstream progress;
    NodeReport report = run_node(
        session, *node, options,
        [](Session& s, const NodeInfo& n, CheckContext& ctx) {
            return run_protocol_checks(s, n, ProtocolOptions{}, ctx);
        },
        progress);
    ASSERT_FALSE(report.checks.empty());
    for (const auto& c : report.checks) {
        if (c.status != Status::kFail) continue;
        EXPECT_EQ(c.category, Category::kCdi)
            << file << ": " << c.id << " [" << category_name(c.category) << "] " << c.message
            << " expected=" << c.expected << " seen=" << c.seen;
    }
    EXPECT_NE(report.restore_summary.find("byte-identical"), std::string::npos)
        << report.restore_summary;
    // The reports of every corpus CDI's run validate (CDI text reaches messages and details).
    EXPECT_EQ(test::json_report_errors(to_json({report})), "") << file;
    EXPECT_EQ(test::junit_report_errors(to_junit({report})), "") << file;
}

std::vector<std::string> corpus_files() {
    std::vector<std::string> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi", ec)) {
        if (e.path().extension() == ".xml") out.push_back(e.path().filename().string());
    }
    std::sort(out.begin(), out.end());
    if (out.empty()) out.push_back("corpus-absent.xml");  // one case that skips, saying so
    return out;
}

INSTANTIATE_TEST_SUITE_P(Corpus, CorpusRun, ::testing::ValuesIn(corpus_files()),
                         [](const auto& info) {
                             std::string n = info.param.substr(0, info.param.size() - 4);
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

}  // namespace
}  // namespace olcb::conform
