// lcc-conform's configuration backup against OpenLCB_Java's own (corpus/jmri-backups: its
// BackupConfig output for simnode serving each corpus CDI from a fresh image), in-process: the
// same keys in the same order with the same values (float lines aside, OpenLCB_Java writes
// none), and a restore of the reference file knows every key, refuses exactly the values the
// CDI forbids (a fresh image's 0 below a <min> of 1), and with --force leaves the node equal to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "cdi/value_codec.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/run/config_backup.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

fs::path backups_dir() {
    return fs::path(OLCB_SHARED_DIR) / "corpus" / "jmri-backups";
}

struct Reference {
    std::string cdi;  // file name in corpus/cdi
    std::string node_id;
};

// The "NAME.xml NODE-ID" lines of MANIFEST.txt.
std::vector<Reference> references() {
    std::vector<Reference> out;
    std::istringstream in(read_text(backups_dir() / "MANIFEST.txt"));
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream words(line);
        Reference r;
        if (words >> r.cdi >> r.node_id) out.push_back(r);
    }
    if (out.empty()) out.push_back({"corpus-absent.xml", ""});  // one case that skips, saying so
    return out;
}

// The lines of a backup text that are values, float lines left out.
std::vector<std::string> value_lines(const std::string& text,
                                     const std::vector<ConfigEntry>& entries) {
    std::set<std::string> floats;
    for (const ConfigEntry& e : entries) {
        if (e.element->kind == cdi::ElementKind::kFloat) floats.insert(e.key);
    }
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        if (floats.count(line.substr(0, line.find('='))) != 0) continue;
        out.push_back(line);
    }
    return out;
}

// How many of the text's values check_value refuses for their variable (the n-th line of a key
// is its n-th variable), judged on the value the bytes hold as the node will.
std::size_t forbidden_values(const std::string& text, const std::vector<ConfigEntry>& entries) {
    std::map<std::string, std::vector<const ConfigEntry*>> by_key;
    for (const ConfigEntry& e : entries) by_key[e.key].push_back(&e);
    std::map<std::string, std::size_t> seen;
    std::size_t n = 0;
    for (const BackupRecord& r : parse_backup_file(text).records) {
        const auto it = by_key.find(r.key);
        const std::size_t nth = seen[r.key]++;
        if (it == by_key.end() || nth >= it->second.size()) continue;
        const cdi::Element& e = *it->second[nth]->element;
        std::string error;
        const auto bytes = parse_backup_value(e, r.value, error);
        if (!bytes) {
            ++n;
            continue;
        }
        const auto value = e.kind == cdi::ElementKind::kString
                               ? cdi::CodecResult<cdi::Value>(cdi::Value::text(r.value))
                               : cdi::decode(e, *bytes);
        n += !value || !cdi::check_value(e, *value);
    }
    return n;
}

std::size_t lines_starting(const std::string& text, std::string_view start) {
    std::size_t n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) n += line.starts_with(start);
    return n;
}

class JmriBackupCorpus : public ::testing::TestWithParam<Reference> {
protected:
    void start(const Reference& ref) {
        simnode::NodeConfig config;
        std::string error;
        const auto id = NodeId::parse(ref.node_id, &error);
        ASSERT_TRUE(id) << error;
        config.node_id = *id;
        config.cdi = read_text(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi" / ref.cdi);
        dut_ = simnode::SimNode::create(config, error);
        ASSERT_TRUE(dut_) << ref.cdi << ": " << error;
        net_.set_logging(false);
        net_.add_stack(dut_->stack());
        dut_->stack().start(net_.now());
        link_ = make_sim_link(net_, kTool);
        session_ = std::make_unique<Session>(*link_);
        ASSERT_TRUE(session_->start());
        node_ = session_->find_node(*id);
        ASSERT_TRUE(node_);
        ASSERT_TRUE(load_node_config(*session_, *node_, config_, error)) << error;
        memory_ = std::make_unique<SessionMemory>(*session_, *node_);
        entries_ = config_entries(*config_.layout);
    }

    std::string backup() {
        std::vector<std::string> errors;
        std::string text =
            make_config_backup(*config_.layout, *memory_, node_->id.to_string(), errors);
        EXPECT_TRUE(errors.empty()) << ::testing::PrintToString(errors);
        return text;
    }

    // Writes a value unlike the fresh one into every variable.
    void scramble() {
        for (const ConfigEntry& e : entries_) {
            std::vector<std::uint8_t> bytes(e.size, 0xA5);
            if (e.element->kind == cdi::ElementKind::kString) {
                bytes.assign(e.size, 0);
                const std::string s = "scrambled";
                std::copy_n(s.begin(), std::min<std::size_t>(s.size(), e.size - 1), bytes.begin());
            }
            memory_->write(static_cast<std::uint8_t>(e.space),
                           static_cast<std::uint32_t>(e.address), bytes);
        }
    }

    SimNetwork net_;
    std::unique_ptr<simnode::SimNode> dut_;
    std::unique_ptr<Link> link_;
    std::unique_ptr<Session> session_;
    std::optional<NodeInfo> node_;
    NodeConfig config_;
    std::unique_ptr<SessionMemory> memory_;
    std::vector<ConfigEntry> entries_;
};

TEST_P(JmriBackupCorpus, SameKeysOrderAndValuesAndARestoreKnowsEveryKey) {
    const Reference& ref = GetParam();
    const fs::path file = backups_dir() / (ref.cdi.substr(0, ref.cdi.size() - 4) + ".txt");
    if (!fs::exists(file)) GTEST_SKIP() << "corpus absent: no " << file;
    ASSERT_NO_FATAL_FAILURE(start(ref));
    const std::string reference = read_text(file);
    const std::vector<std::string> want = value_lines(reference, entries_);
    EXPECT_EQ(value_lines(backup(), entries_), want) << ref.cdi;

    scramble();
    std::ostringstream out;
    std::ostringstream err;
    const std::size_t forbidden = forbidden_values(reference, entries_);
    RestoreOptions options{file.string(), ref.node_id};
    int code = run_restore(*session_, options, out, err);
    EXPECT_EQ(code, forbidden == 0 ? 0 : 1) << out.str() << err.str();
    EXPECT_EQ(out.str().find("unknown"), std::string::npos) << out.str();
    EXPECT_EQ(lines_starting(out.str(), "  refused    line "), forbidden) << out.str();
    // --force writes them too: the node then holds every value of the file. Scrambled again, as
    // a variable sharing a refused one's bytes (openlcb_java__sample's "Reset Directly") wrote
    // them.
    scramble();
    options.force = true;
    out.str("");
    code = run_restore(*session_, options, out, err);
    EXPECT_EQ(code, 0) << out.str() << err.str();
    EXPECT_EQ(lines_starting(out.str(), "  forced     line "), forbidden) << out.str();
    EXPECT_EQ(value_lines(backup(), entries_), want) << ref.cdi << "\n" << out.str();
}

INSTANTIATE_TEST_SUITE_P(Corpus, JmriBackupCorpus, ::testing::ValuesIn(references()),
                         [](const auto& info) {
                             std::string n = info.param.cdi.substr(0, info.param.cdi.size() - 4);
                             for (char& c : n)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return n;
                         });

}  // namespace
}  // namespace olcb::conform
