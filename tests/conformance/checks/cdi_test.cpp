// One rule set: for every corpus CDI and every scenarios/*.xml, lcc-conform's cdi.* checks on the
// text a node serves in-process report exactly what cdi::check_rules() (so `lcc-cdi validate`)
// finds in the file: status, message, expected, seen and details. The project's own scenario
// CDIs are clean under both.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/rule_finding.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

ProtocolOptions cdi_checks_only() {
    ProtocolOptions options;
    options.selection.only = {"cdi.*"};
    return options;
}

// The cdi.* checks against simnode serving text; nullopt when simnode refuses the CDI (it must
// parse and lay out to be served), with why in `refused`.
std::optional<std::vector<CheckResult>> served_by_simnode(const std::string& text,
                                                          std::string& refused) {
    simnode::NodeConfig config;
    config.node_id = kDut;
    config.cdi = text;
    auto bench = testing::SimBench::serve(config, refused);
    if (!bench) return std::nullopt;
    auto node = bench->start();
    if (!node) return std::vector<CheckResult>{};
    CheckContext ctx;
    return run_protocol_checks(*bench->session, *node, cdi_checks_only(), ctx);
}

// The cdi.* checks against a bare node serving the bytes before text's first NUL, and a NUL, in
// space 0xFF (what simnode would serve): for the CDIs simnode cannot lay out.
std::vector<CheckResult> served_raw(const std::string& text) {
    const std::string_view served = std::string_view(text).substr(0, text.find('\0'));
    std::vector<std::uint8_t> space(served.begin(), served.end());
    space.push_back(0);
    SimNetwork net;
    net.set_logging(false);
    testing::ScriptedNode dut(net, kDut);
    dut.answer = [&space](const memory::Message& m) -> testing::ScriptedNode::Answer {
        if (const auto* info = std::get_if<memory::GetSpaceInfo>(&m)) {
            if (info->space != memory::Space::kCdi) return {0x1081, {}};
            const auto highest = static_cast<std::uint32_t>(space.size() - 1);
            return {0, memory::encode(memory::SpaceInfoReply{info->space, highest, true, {}, ""})};
        }
        const auto* read = std::get_if<memory::Read>(&m);
        if (!read || read->space != memory::Space::kCdi) return {0x1081, {}};
        if (read->address >= space.size())
            return {0, memory::encode(memory::ReadReplyFail{read->space, read->address,
                                                            memory::ErrorCode::kOutOfBounds, "",
                                                            read->form})};
        const std::span<const std::uint8_t> data =
            std::span(space)
                .subspan(read->address)
                .first(std::min<std::size_t>(space.size() - read->address, read->count));
        return {0, memory::encode(memory::ReadReply{
                       read->space, read->address, {data.begin(), data.end()}, read->form})};
    };
    auto link = make_sim_link(net, kTool);
    Session session(*link);
    EXPECT_TRUE(session.start());
    auto node = session.find_node(kDut);
    if (!node) {
        ADD_FAILURE() << "scripted node not found";
        return {};
    }
    CheckContext ctx;
    return run_protocol_checks(session, *node, cdi_checks_only(), ctx);
}

void expect_same_verdicts(const std::vector<CheckResult>& results, const std::string& text) {
    for (const cdi::RuleFinding& f : cdi::check_rules(text)) {
        SCOPED_TRACE(f.check_id);
        const CheckResult* c = testing::find_check(results, f.check_id);
        ASSERT_NE(c, nullptr) << testing::dump(results);
        EXPECT_EQ(status_name(c->status), cdi::rule_status_name(f.status))
            << c->message << " / " << f.message;
        EXPECT_EQ(c->message, f.message);
        EXPECT_EQ(c->expected, f.expected);
        EXPECT_EQ(c->seen, f.seen);
        std::vector<std::string> details;
        for (const cdi::Diagnostic& d : f.diagnostics) details.push_back(cdi::located(d));
        EXPECT_EQ(c->details, details);
    }
}

// check_rules() answers for registry checks, in registry order (so reports read the same).
TEST(CdiRuleIds, AreCdiChecksOfTheRegistryInItsOrder) {
    const auto& all = check_registry();
    std::size_t last = 0;
    for (std::string_view id : cdi::kRuleCheckIds) {
        const CheckSpec* spec = find_check(id);
        ASSERT_NE(spec, nullptr) << id;
        EXPECT_EQ(spec->category, Category::kCdi) << id;
        const auto at = static_cast<std::size_t>(spec - all.data());
        EXPECT_GT(at, last) << id;
        last = at;
    }
}

class CdiRuleSet : public ::testing::TestWithParam<fs::path> {};

TEST_P(CdiRuleSet, LccConformReportsWhatCheckRulesFinds) {
    const fs::path& file = GetParam();
    if (!fs::exists(file)) GTEST_SKIP() << file << " absent (corpus at ../shared/corpus)";
    const std::string text = read_text(file);
    std::string refused;
    std::optional<std::vector<CheckResult>> results = served_by_simnode(text, refused);
    if (!results) {
        // Served as simnode would serve it, had it laid the CDI out: the same bytes, a NUL.
        EXPECT_NE(file.parent_path().filename(), "scenarios") << refused;
        RecordProperty("served_by", "a scripted node: simnode refused it (" + refused + ")");
        results = served_raw(text);
    }
    const CheckResult* read = testing::find_check(*results, "cdi.read");
    ASSERT_NE(read, nullptr) << testing::dump(*results);
    ASSERT_EQ(read->status, Status::kPass) << testing::dump(*results);
    expect_same_verdicts(*results, text);

    if (file.parent_path().filename() != "scenarios") return;
    for (const CheckResult& c : *results) {
        EXPECT_TRUE(c.status == Status::kPass || c.status == Status::kSkip)
            << file.filename() << ": " << status_name(c.status) << " " << c.id << " " << c.message;
    }
}

std::vector<fs::path> rule_set_files() {
    std::vector<fs::path> out;
    for (const auto& e : fs::directory_iterator(fs::path(OLCB_SOURCE_DIR) / "scenarios"))
        if (e.path().extension() == ".xml") out.push_back(e.path());
    std::error_code ec;
    std::vector<fs::path> corpus;
    for (const auto& e : fs::directory_iterator(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi", ec))
        if (e.path().extension() == ".xml") corpus.push_back(e.path());
    if (corpus.empty())
        corpus.push_back(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi" / "absent.xml");
    std::sort(out.begin(), out.end());
    std::sort(corpus.begin(), corpus.end());
    out.insert(out.end(), corpus.begin(), corpus.end());
    return out;
}

INSTANTIATE_TEST_SUITE_P(Files, CdiRuleSet, ::testing::ValuesIn(rule_set_files()),
                         [](const auto& info) {
                             std::string n = info.param.parent_path().filename().string() + "_" +
                                             info.param.stem().string();
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

}  // namespace
}  // namespace olcb::conform
