// lcc-conform's configuration backups as a user runs them against the simnode program over
// GridConnect TCP: restore --dry-run, diff of two files and of a node against a file, the CSV
// form both ways, files for another node type or with unknown keys, JMRI files that name no
// node, values the node's CDI forbids (refused, or written with --force, judged by simnode's
// audit too) and files that are no backup at all (docs/backup.md).
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "base/utf8.hpp"
#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

// lcc-conform with args, its stderr merged into the output (the verdicts users read are there).
std::pair<int, std::string> conform_all(const std::vector<std::string>& args) {
    std::vector<std::string> all = {"-c", "exec \"$0\" \"$@\" 2>&1", LCC_CONFORM_PATH};
    all.insert(all.end(), args.begin(), args.end());
    return run_program("/bin/sh", all, milliseconds(60000));
}

void write_text(const fs::path& p, const std::string& text) {
    std::ofstream(p, std::ios::binary) << text;
}

// text with the first occurrence of from replaced by to.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
}

// Where a CSV backup says a key's bytes lie: space, address and size (its last three columns).
struct Place {
    std::string space;
    std::size_t address = 0;
    std::size_t size = 0;
};
Place place_in_csv(const std::string& csv, const std::string& key) {
    const auto at = csv.find("\n" + key + ",");
    EXPECT_NE(at, std::string::npos) << key;
    if (at == std::string::npos) return {};
    std::string row = csv.substr(at + 1, csv.find('\r', at + 1) - at - 1);
    std::vector<std::string> tail;
    for (int k = 0; k < 3; ++k) {
        const auto comma = row.rfind(',');
        tail.push_back(row.substr(comma + 1));
        row.resize(comma);
    }
    return {tail[2], std::stoul(tail[1]), std::stoul(tail[0])};
}

// The bytes of a variable in a node's image files (simnode's --image-dir, space-N.img).
std::string image_bytes(const std::map<std::string, std::string>& images, const Place& p) {
    for (const auto& [name, bytes] : images) {
        if (name.ends_with("space-" + p.space + ".img") && p.address + p.size <= bytes.size())
            return bytes.substr(p.address, p.size);
    }
    ADD_FAILURE() << "no image of space " << p.space;
    return {};
}

// The image files once the variable at p holds bytes (or as they are after a bounded wait:
// simnode may apply a journaled write to its image a little after acknowledging it).
std::map<std::string, std::string> images_once(const fs::path& dir, const Place& p,
                                               const std::string& bytes) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    auto now = snapshot_images(dir);
    while (image_bytes(now, p) != bytes && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(milliseconds(20));
        now = snapshot_images(dir);
    }
    return now;
}

// Delay (ms) = 300, the allowed change of the edited files, as its 4 bytes.
std::string delay_300() {
    return {"\0\0\x01\x2C", 4};
}

// A failure for each byte of out that a terminal would act on: below 0x20 except the line end,
// DEL, or bytes that are not UTF-8 (a raw byte of a binary file).
void expect_only_text(const std::string& out) {
    std::size_t controls = 0;
    for (char c : out) {
        const auto b = static_cast<unsigned char>(c);
        controls += (b < 0x20 && b != '\n') || b == 0x7F;
    }
    EXPECT_EQ(controls, 0u) << out;
    EXPECT_TRUE(base::is_valid_utf8(out)) << out;
}

// The lines of a backup that are not '#' comments: what JMRI writes.
std::string without_comments(const std::string& text) {
    std::istringstream in(text);
    std::string out;
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("#")) out += line + "\n";
    }
    return out;
}

class LccConformBackup : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_NE(sim_.port, 0) << "simnode did not start";
        base_ = out_.path() / "base.txt";
        const auto [code, text] = run({"backup", "--node", kNode, base_.string()});
        ASSERT_EQ(code, 0) << text;
        saved_ = read_text(base_);
        ASSERT_NE(saved_.find("\nSettings.Trim=65531\n"), std::string::npos) << saved_;
    }
    std::pair<int, std::string> run(std::vector<std::string> args) {
        args.insert(args.begin(), {"--connect", sim_.connect()});
        return conform_all(args);
    }
    fs::path file(const std::string& name, const std::string& text) {
        fs::path p = out_.path() / name;
        write_text(p, text);
        return p;
    }
    // The node's configuration as a fresh backup.
    std::string current() {
        const fs::path p = out_.path() / "current.txt";
        const auto [code, text] = run({"backup", "--node", kNode, p.string()});
        EXPECT_EQ(code, 0) << text;
        return read_text(p);
    }

    Simnode sim_{source_path("scenarios/default.ini")};
    TempDir out_{"lcc-conform-backup-e2e"};
    fs::path base_;
    std::string saved_;
};

TEST_F(LccConformBackup, DryRunAndDiffShowWhatARestoreWouldChange) {
    const std::string edited_text =
        replaced(replaced(saved_, "Settings.Trim=65531", "Settings.Trim=7"),
                 "Node identity.User Name=simnode default", "Node identity.User Name=a\\x003db");
    const fs::path edited = file("edited.txt", edited_text);
    const auto images = snapshot_images(sim_.images.path());

    auto [code, text] = run({"restore", "--dry-run", edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore --dry-run: 2 change(s) to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("nothing written"), std::string::npos) << text;
    EXPECT_NE(text.find("change     Settings.Trim: node \"65531\" -> file \"7\""),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("Node identity.User Name: node \"simnode default\" -> file \"a\\x003db\""),
              std::string::npos)
        << text;
    EXPECT_EQ(snapshot_images(sim_.images.path()), images);
    EXPECT_EQ(current(), saved_);

    std::tie(code, text) = run({"diff", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("2 change(s) a restore would write"), std::string::npos) << text;
    EXPECT_NE(text.find("change     Settings.Trim: node \"65531\" -> file \"7\""),
              std::string::npos)
        << text;
    std::tie(code, text) = run({"diff", "--node", kNode, base_.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("0 change(s) a restore would write"), std::string::npos) << text;

    std::tie(code, text) = conform_all({"diff", base_.string(), edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("changed    Settings.Trim: \"65531\" -> \"7\""), std::string::npos) << text;
    EXPECT_NE(text.find("diff: 2 difference(s)"), std::string::npos) << text;
    std::tie(code, text) = conform_all({"diff", base_.string(), base_.string()});
    EXPECT_EQ(code, 0) << text;

    std::tie(code, text) = run({"restore", edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore: 2 variable(s) written to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    EXPECT_EQ(current(), edited_text);
}

TEST_F(LccConformBackup, CsvBackupRestoresAndDiffsLikeTheKeyValueForm) {
    const fs::path csv = out_.path() / "config.csv";
    auto [code, text] = run({"backup", "--csv", "--node", kNode, csv.string()});
    ASSERT_EQ(code, 0) << text;
    const std::string rows = read_text(csv);
    ASSERT_EQ(rows.rfind("key,value,type,space,address,size\r\n", 0), 0u) << rows;
    EXPECT_NE(rows.find("\r\nSettings.Trim,65531,int,253,"), std::string::npos) << rows;
    std::tie(code, text) = conform_all({"diff", csv.string(), base_.string()});
    EXPECT_EQ(code, 0) << text;

    const fs::path edited =
        file("edited.csv", replaced(rows, "Settings.Trim,65531,", "Settings.Trim,-9,"));
    std::tie(code, text) = run({"restore", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("restore: 1 variable(s) written"), std::string::npos) << text;
    EXPECT_EQ(current(), replaced(saved_, "Settings.Trim=65531", "Settings.Trim=65527"));
}

TEST_F(LccConformBackup, AFileForAnotherNodeTypeExits1AndWritesNothing) {
    const fs::path other =
        file("other.txt", "seg5.User Name=x\nseg7.Internal data.Version=3\nSettings.Trim=1\n");
    const auto images = snapshot_images(sim_.images.path());
    const auto [code, text] = run({"restore", "--node", kNode, other.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("is for another node type: it matches 1 of the"), std::string::npos)
        << text;
    EXPECT_NE(text.find("nothing written"), std::string::npos) << text;
    EXPECT_NE(text.find("\n  line 1: seg5.User Name\n"), std::string::npos) << text;
    EXPECT_EQ(snapshot_images(sim_.images.path()), images);
    EXPECT_EQ(current(), saved_);
}

TEST_F(LccConformBackup, UnknownKeysExit1UnlessAllowedBadValuesAlways) {
    const fs::path unknown = file("unknown.txt", replaced(saved_, "Settings.Trim=65531\n",
                                                          "Settings.Trim=65531\nNo.Such=1\n"));
    auto [code, text] = run({"restore", unknown.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("unknown    line "), std::string::npos) << text;
    EXPECT_NE(text.find(": No.Such"), std::string::npos) << text;
    EXPECT_NE(text.find("--allow-unknown accepts them"), std::string::npos) << text;
    std::tie(code, text) = run({"restore", "--allow-unknown", unknown.string()});
    EXPECT_EQ(code, 0) << text;

    // A value no 2-byte int holds is refused, --allow-unknown or not: it is no unknown key.
    const fs::path bad = file(
        "bad.txt", replaced(saved_, "Settings.Trim=65531\n", "Settings.Trim=70000\nNo.Such=1\n"));
    std::tie(code, text) = run({"restore", "--allow-unknown", bad.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("refused    line "), std::string::npos) << text;
    EXPECT_NE(text.find("out of range"), std::string::npos) << text;
    EXPECT_EQ(current(), saved_);  // the bad value was not written
}

// What a user hand-edits into a JMRI backup (issue 33): a value above the CDI's <max>, one not
// in its <map>, a string with no room for its NUL and a malformed event ID, beside one good
// change. Settings.Trim is the <int> on line 24 of scenarios/default.xml.
std::string forbidden_edits(const std::string& saved) {
    std::string t = replaced(saved, "Settings.Trim=65531", "Settings.Trim=2000");
    t = replaced(t, "Settings.Mode=2", "Settings.Mode=7");
    t = replaced(t, "Settings.Label=", "Settings.Label=0123456789abcdef");
    t = replaced(t, "Settings.Port(0).On event=", "Settings.Port(0).On event=05.01.01.01.22.0\n#");
    return replaced(t, "Settings.Delay (ms)=250", "Settings.Delay (ms)=300");
}

TEST_F(LccConformBackup, ValuesTheCdiForbidsAreRefusedAndOnlyForceWritesThem) {
    const fs::path csv = out_.path() / "places.csv";
    ASSERT_EQ(run({"backup", "--csv", "--node", kNode, csv.string()}).first, 0);
    const std::string places = read_text(csv);
    const fs::path edited = file("edited.txt", forbidden_edits(saved_));
    const auto before = snapshot_images(sim_.images.path());

    auto [code, text] = run({"restore", "--dry-run", edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("restore --dry-run: 1 change(s) to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find(", 4 refused; nothing written"), std::string::npos) << text;
    EXPECT_NE(text.find("  refused    line 6: Settings.Trim=\"2000\": out-of-range: value 2000 "
                        "above max 1000 of 'Trim' (<int> at CDI line 24; CDI §5.1.4.2: invalid "
                        "values shall not be written)"),
              std::string::npos)
        << text;
    EXPECT_EQ(snapshot_images(sim_.images.path()), before);

    std::tie(code, text) = run({"restore", edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("restore: 1 variable(s) written to node 05.01.01.01.22.00"),
              std::string::npos)
        << text;
    for (const char* rule :
         {"Settings.Trim=\"2000\": out-of-range", "Settings.Mode=\"7\": not-in-map",
          "Settings.Label=\"0123456789abcdef\": too-long",
          "Settings.Port(0).On event=\"05.01.01.01.22.0\": malformed"}) {
        EXPECT_NE(text.find(std::string("  refused    line ")), std::string::npos) << text;
        EXPECT_NE(text.find(rule), std::string::npos) << rule << "\n" << text;
    }
    EXPECT_NE(text.find("restore: 4 value(s) refused (the node's CDI forbids them, or they are "
                        "no value of their variable), so nothing was written for them; --force "
                        "writes the 3 that have bytes anyway"),
              std::string::npos)
        << text;
    const auto after =
        images_once(sim_.images.path(), place_in_csv(places, "Settings.Delay (ms)"), delay_300());
    for (const char* key :
         {"Settings.Trim", "Settings.Mode", "Settings.Label", "Settings.Port(0).On event"}) {
        EXPECT_EQ(image_bytes(after, place_in_csv(places, key)),
                  image_bytes(before, place_in_csv(places, key)))
            << key;
    }
    EXPECT_EQ(image_bytes(after, place_in_csv(places, "Settings.Delay (ms)")), delay_300());

    std::tie(code, text) = run({"diff", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("0 change(s) a restore would write, 4 refused by the node's CDI"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  refused    line 9: Settings.Mode=\"7\": not-in-map"), std::string::npos)
        << text;

    std::tie(code, text) = run({"restore", "--force", edited.string()});
    EXPECT_EQ(code, 1) << text;  // the malformed event ID has no bytes to force
    EXPECT_NE(text.find("restore: 3 variable(s) written to node 05.01.01.01.22.00, 23 already "
                        "equal, 3 forced, 1 refused"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("  forced     line 6: Settings.Trim=\"2000\": out-of-range"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("restore: 3 value(s) the node's CDI forbids written anyway (--force)"),
              std::string::npos)
        << text;
    const std::string now = current();
    for (const char* line :
         {"\nSettings.Trim=2000\n", "\nSettings.Mode=7\n", "\nSettings.Label=0123456789abcdef\n"}) {
        EXPECT_NE(now.find(line), std::string::npos) << line << now;
    }
}

TEST_F(LccConformBackup, ACsvRestoreKeepsTheSameRules) {
    const fs::path csv = out_.path() / "config.csv";
    ASSERT_EQ(run({"backup", "--csv", "--node", kNode, csv.string()}).first, 0);
    const std::string rows = read_text(csv);
    std::string edited_rows = replaced(rows, "Settings.Trim,65531,", "Settings.Trim,-1001,");
    edited_rows = replaced(edited_rows, "Settings.Mode,2,", "Settings.Mode,0,");
    edited_rows = replaced(edited_rows, "Settings.Delay (ms),250,", "Settings.Delay (ms),300,");
    const fs::path edited = file("edited.csv", edited_rows);
    const auto before = snapshot_images(sim_.images.path());
    auto [code, text] = run({"restore", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("restore: 1 variable(s) written"), std::string::npos) << text;
    EXPECT_NE(text.find("Settings.Trim=\"-1001\": out-of-range: value -1001 below min -1000"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("Settings.Mode=\"0\": not-in-map"), std::string::npos) << text;
    const auto after =
        images_once(sim_.images.path(), place_in_csv(rows, "Settings.Delay (ms)"), delay_300());
    for (const char* key : {"Settings.Trim", "Settings.Mode"}) {
        EXPECT_EQ(image_bytes(after, place_in_csv(rows, key)),
                  image_bytes(before, place_in_csv(rows, key)))
            << key;
    }
    EXPECT_EQ(image_bytes(after, place_in_csv(rows, "Settings.Delay (ms)")), delay_300());
    std::tie(code, text) = run({"restore", "--force", "--node", kNode, edited.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(current().find("\nSettings.Trim=64535\n"), std::string::npos);
}

// The first line of out: the cause, before any list.
std::string first_line(const std::string& out) {
    return out.substr(0, out.find('\n'));
}

TEST_F(LccConformBackup, AFileThatIsNoBackupGetsItsCauseFirstAndNoRawByte) {
    const auto before = snapshot_images(sim_.images.path());
    const std::string cut = saved_.substr(0, saved_.find("Settings.Trim=65531") + 16);
    const struct {
        fs::path path;
        int code;
        std::string cause;
    } cases[] = {
        {file("cut.txt", cut), 2, " is cut short: its last line (6) has no line end"},
        {"/bin/true", 2, " is not a text file: it holds "},
        {file("empty.txt", ""), 2, " is empty (0 bytes)"},
        {file("latin1.txt", replaced(saved_, "Settings.Trim", "Settings.Tr\xEEm")), 2,
         " is not UTF-8 text: 1 line(s) have bytes that are not UTF-8 outside a value"},
    };
    for (const auto& c : cases) {
        const auto [code, text] = run({"restore", "--node", kNode, c.path.string()});
        EXPECT_EQ(code, c.code) << c.path << "\n" << text;
        EXPECT_EQ(first_line(text).rfind("lcc-conform: " + c.path.string() + c.cause, 0), 0u)
            << text;
        EXPECT_TRUE(first_line(text).ends_with("; nothing written")) << text;
        expect_only_text(text);
        const auto [diff_code, diff_text] = run({"diff", "--node", kNode, c.path.string()});
        EXPECT_EQ(diff_code, 2) << diff_text;
        EXPECT_EQ(first_line(diff_text).rfind("lcc-conform: " + c.path.string() + c.cause, 0), 0u)
            << diff_text;
        expect_only_text(diff_text);
    }
    const auto [code, text] = conform_all({"diff", "/bin/true", base_.string()});
    EXPECT_EQ(code, 2) << text;
    expect_only_text(text);
    EXPECT_EQ(snapshot_images(sim_.images.path()), before);
}

TEST_F(LccConformBackup, AnotherNodesBackupSaysSoFirstThenTenKeysAndACount) {
    Simnode board(source_path("scenarios/io-board.ini"));
    ASSERT_NE(board.port, 0);
    const fs::path other = out_.path() / "board.txt";
    const auto [made, made_text] = conform_all(
        {"--connect", board.connect(), "backup", "--node", "05.01.01.01.22.10", other.string()});
    ASSERT_EQ(made, 0) << made_text;
    const auto before = snapshot_images(sim_.images.path());
    const auto [code, text] = run({"restore", "--node", kNode, other.string()});
    EXPECT_EQ(code, 1) << text;
    EXPECT_EQ(
        first_line(text).rfind("lcc-conform: " + other.string() +
                                   " is for another node type: it matches 2 of the 24 keys of "
                                   "node 05.01.01.01.22.00, and 99 of its keys are not "
                                   "the node's; nothing written",
                               0),
        0u)
        << text;
    EXPECT_NE(text.find("\n  ... and 89 more (99 in all)\n"), std::string::npos) << text;
    std::size_t listed = 0;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) listed += line.starts_with("  line ");
    EXPECT_EQ(listed, 10u) << text;
    expect_only_text(text);
    EXPECT_EQ(snapshot_images(sim_.images.path()), before);
}

TEST_F(LccConformBackup, AJmriFileWithoutNodeLineUsesTheOnlyNode) {
    const fs::path jmri = file(
        "jmri.txt", without_comments(replaced(saved_, "Settings.Trim=65531", "Settings.Trim=3")));
    const auto [code, text] = run({"restore", jmri.string()});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("using node 05.01.01.01.22.00, the only node on the bus"),
              std::string::npos)
        << text;
    EXPECT_NE(current().find("\nSettings.Trim=3\n"), std::string::npos);
}

TEST(LccConformBackupNodes, SeveralNodesAreListedAndNoneIsChosen) {
    TempDir dir("lcc-conform-backup-two");
    const fs::path ini = dir.path() / "two.ini";
    write_text(ini, "[node.pair]\nnode-id = 05.01.01.01.22.10\ncount = 2\ncdi = " +
                        source_path("scenarios/default.xml").string() + "\n");
    Simnode sim(ini);
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    const fs::path f = dir.path() / "jmri.txt";
    write_text(f, "Settings.Trim=3\n");
    const auto [code, text] = conform_all({"--connect", sim.connect(), "restore", f.string()});
    EXPECT_EQ(code, 2) << text;
    EXPECT_NE(text.find("2 nodes answer; say which with --node ID"), std::string::npos) << text;
    EXPECT_NE(text.find("05.01.01.01.22.10"), std::string::npos) << text;
    EXPECT_NE(text.find("05.01.01.01.22.11"), std::string::npos) << text;
}

// The client audit of simnode (docs/audit.md) on a restore of forbidden values: without --force
// lcc-conform writes nothing the CDI forbids, so only the note about Update Complete remains;
// with --force the audit names the values it wrote.
std::set<std::string> audited_rules(bool force) {
    TempDir dir("lcc-conform-restore-audit");
    const fs::path audit = dir.path() / "audit.json";
    Simnode sim(source_path("scenarios/default.ini"), {"--audit", audit.string()});
    EXPECT_NE(sim.port, 0);
    const fs::path saved = dir.path() / "saved.txt";
    auto [code, text] =
        conform_all({"--connect", sim.connect(), "backup", "--node", kNode, saved.string()});
    EXPECT_EQ(code, 0) << text;
    const fs::path edited = dir.path() / "edited.txt";
    write_text(edited, forbidden_edits(read_text(saved)));
    std::vector<std::string> args = {"--connect", sim.connect(), "restore", edited.string()};
    if (force) args.push_back("--force");
    std::tie(code, text) = conform_all(args);
    EXPECT_EQ(code, 1) << text;
    sim.child->signal(SIGTERM);
    EXPECT_TRUE(sim.child->wait_for(milliseconds(10000)));
    const auto report = nlohmann::json::parse(read_text(audit), nullptr, false);
    std::set<std::string> rules;
    if (report.is_discarded() || !report.contains("findings")) {
        ADD_FAILURE() << read_text(audit);
        return rules;
    }
    EXPECT_EQ(report["complete"], true);
    for (const auto& f : report["findings"]) rules.insert(f["rule"].get<std::string>());
    return rules;
}

TEST(LccConformBackupAudit, APlainRestoreWritesNothingTheCdiForbids) {
    EXPECT_EQ(audited_rules(false), std::set<std::string>{"memory.no-update-complete"});
    const std::set<std::string> forced = audited_rules(true);
    EXPECT_TRUE(forced.contains("cdi.int-out-of-range")) << ::testing::PrintToString(forced);
    EXPECT_TRUE(forced.contains("cdi.not-in-map")) << ::testing::PrintToString(forced);
    EXPECT_TRUE(forced.contains("cdi.string-invalid")) << ::testing::PrintToString(forced);
}

TEST(LccConformBackupUsage, TheUsageShowsNodeDryRunCsvAndDiff) {
    const auto [code, text] = conform_all({"--help"});
    EXPECT_EQ(code, 0);
    for (const char* s : {"restore [--node ID]", "--dry-run", "--allow-unknown", "--force", "--csv",
                          "diff A B", "diff [--node ID] FILE"}) {
        EXPECT_NE(text.find(s), std::string::npos) << s << "\n" << text;
    }
}

}  // namespace
}  // namespace olcb::e2e

#endif
