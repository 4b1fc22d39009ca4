// The safety promise end to end, programs run as a user would over GridConnect TCP: against the
// OpenMRN-like node (Version in "Internal data", abort-on-value, factory-reset-on-version-change)
// a full --reboot run neither kills nor resets it; a node that restarts mid-run is reported with
// the variable written last; a node that never comes back leaves a backup whose printed restore
// command works afterwards; the image files are byte-identical whenever the run says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

std::vector<std::string> run_args(const Simnode& n, const TempDir& out,
                                  std::vector<std::string> extra = {},
                                  const std::string& node = kNode) {
    std::vector<std::string> args = {
        "--connect", n.connect(), "--node", node, "--backup", (out.path() / "safety.txt").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

std::string status_of(const std::string& text, const std::string& id) {
    for (const auto& [status, check] : check_lines(text)) {
        if (check == id) return status;
    }
    return "";
}

TEST(LccConformSafety, OpenMrnLikeNodeSurvivesAFullRebootRunUnchanged) {
    Simnode n(source_path("scenarios/faults/openmrn-like.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot"}));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "encoding.persist-after-reboot"), "PASS") << text;
    EXPECT_NE(text.find("SKIP  encoding.protected  seg7.Internal data.Version"), std::string::npos)
        << text;
    EXPECT_EQ(text.find("node."), std::string::npos) << text;  // never died, never restarted
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, WriteProtectedProbesInternalDataAndTheNodeStillSurvives) {
    Simnode n(source_path("scenarios/faults/openmrn-like.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot", "--write-protected"}));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "encoding.protected"), "") << text;
    EXPECT_EQ(text.find("node."), std::string::npos) << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, ARestartMidRunNamesTheVariableAndTheMemoryEndsIdentical) {
    // The 7th stored write: write-under-mask makes 2 before the encoding checks, whose 5th write
    // is the original going back into the first variable after its 4 test values.
    Simnode n(source_path("scenarios/default.ini"), {"--fault", "reboot-on-write=7"});
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out));
    // No clause forbids a restart (WARN), but the checks after it were not run: incomplete.
    EXPECT_EQ(code, 2) << text;
    EXPECT_EQ(status_of(text, "node.rebooted"), "WARN") << text;
    EXPECT_NE(text.find("INCOMPLETE: the node restarted"), std::string::npos) << text;
    EXPECT_NE(text.find("restoring Node identity.User Name"), std::string::npos) << text;
    EXPECT_NE(text.find("last test value written"), std::string::npos) << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "PASS") << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

// The "run: lcc-conform ... restore FILE" command the report printed, as arguments.
std::vector<std::string> printed_restore(const std::string& text) {
    const auto at = text.find("run: lcc-conform ");
    if (at == std::string::npos) return {};
    std::istringstream words(text.substr(at + 17, text.find('\n', at) - at - 17));
    std::vector<std::string> args;
    for (std::string w; words >> w;) args.push_back(w);
    return args;
}

TEST(LccConformSafety, ANodeThatNeverComesBackLeavesAWorkingRestoreCommand) {
    Simnode n(source_path("scenarios/default.ini"),
              {"--fault", "abort-on-value=12000", "--watch-variable", "Node identity.User Name"});
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--write-protected", "--node-wait", "1"}));
    EXPECT_EQ(code, 2) << text;
    EXPECT_EQ(status_of(text, "node.stopped-answering"), "FAIL") << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "FAIL") << text;
    const auto command = printed_restore(text);
    ASSERT_GE(command.size(), 4u) << text;
    EXPECT_EQ(command.back(), fs::absolute(out.path() / "safety.txt").string());
    EXPECT_TRUE(fs::exists(command.back()));
    EXPECT_NE(snapshot_images(n.images.path()), before);  // the test name is still in the node

    // Once the node is back (12 s of silence), the printed command puts everything back.
    int restored = -1;
    std::string restore_text;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (restored != 0 && std::chrono::steady_clock::now() < deadline) {
        std::tie(restored, restore_text) = conform(command);
    }
    EXPECT_EQ(restored, 0) << restore_text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

TEST(LccConformSafety, OneLineCdiHasACorrectXmlDeclaration) {
    Simnode n(source_path("scenarios/one-line.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto [code, text] = conform(run_args(n, out));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "cdi.xml-declaration"), "PASS") << text;
}

TEST(LccConformSafety, IoBoardScenarioHasNoFalseFailure) {
    Simnode n(source_path("scenarios/io-board.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--reboot"}, "05.01.01.01.22.10"));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

// ---- issue 28: every write restored or accounted for ----

// A node that ignores Write Under Mask's mask and then is silent for 5 s: the byte it changed is
// put back when it answers again, and the checks missed while it was silent make the run
// incomplete (exit 2), never a green run.
TEST(LccConformSafety, AMaskIgnoringNodeSilentFor5sIsRestoredWhenItAnswers) {
    Simnode n(source_path("scenarios/faults/mask-ignored.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const std::string json = (out.path() / "r.json").string();
    const auto [code, text] = conform(run_args(n, out, {"--json", json}), milliseconds(120000));
    EXPECT_EQ(code, 2) << text;
    EXPECT_EQ(status_of(text, "memory.write-under-mask"), "FAIL") << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "PASS") << text;
    EXPECT_NE(text.find("INCOMPLETE: "), std::string::npos) << text;
    const auto j = read_report(json);
    EXPECT_TRUE(j["nodes"][0]["incomplete"].get<bool>());
    EXPECT_GE(j["nodes"][0]["writes"]["sent"].get<int>(), 2) << text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

// The same node silent for 40 s, longer than --node-wait: no PASS restore over the changed byte;
// exit 2, the backup kept and the printed restore command puts the byte back later.
TEST(LccConformSafety, AMaskIgnoringNodeSilentFor40sKeepsTheBackupAndTheCommandWorks) {
    Simnode n(source_path("scenarios/faults/mask-ignored.ini"), {"--fault", "mask-ignored=40000"});
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] = conform(run_args(n, out, {"--node-wait", "5"}), milliseconds(120000));
    EXPECT_EQ(code, 2) << text;
    EXPECT_NE(status_of(text, "encoding.restore"), "PASS") << text;
    EXPECT_EQ(text.find("byte-identical"), std::string::npos) << text;
    const auto command = printed_restore(text);
    ASSERT_GE(command.size(), 4u) << text;
    EXPECT_TRUE(fs::exists(command.back())) << text;
    EXPECT_NE(snapshot_images(n.images.path()), before) << "the node kept the byte it changed";
    int restored = -1;
    std::string restore_text;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (restored != 0 && std::chrono::steady_clock::now() < deadline) {
        std::tie(restored, restore_text) = conform(command);
    }
    EXPECT_EQ(restored, 0) << restore_text;
    EXPECT_EQ(settled_images(n.images.path(), before), before);
}

// Every "write SP @0xADDR xN" of simnode's trace that runs past the end of its space, whose size
// is its image file's.
std::vector<std::string> crossing_writes(const fs::path& trace, const fs::path& images) {
    std::map<unsigned long, std::uintmax_t> size;
    const std::regex image(R"(space-([0-9]+)\.img)");
    for (const auto& e : fs::recursive_directory_iterator(images)) {
        std::smatch m;
        const std::string name = e.path().filename().string();
        if (std::regex_match(name, m, image)) size[std::stoul(m[1])] = fs::file_size(e.path());
    }
    const std::regex write(R"(\| write ([0-9A-F]{2}) @0x([0-9A-F]+) x([0-9]+))");
    std::vector<std::string> out;
    std::istringstream in(read_text(trace));
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, write)) continue;
        const unsigned long sp = std::stoul(m[1], nullptr, 16);
        const unsigned long end = std::stoul(m[2], nullptr, 16) + std::stoul(m[3]);
        if (size.count(sp) && end > size[sp]) out.push_back(line);
    }
    return out;
}

// --write-past-end on a node that keeps the byte (OpenMRN's file): a WARN naming it and a restore
// line that says so; never "byte-identical". Without the option no write crosses an end.
TEST(LccConformSafety, WritePastEndIsItsOwnOptionAndItsByteIsNamed) {
    TempDir out("lcc-conform-safety-out");
    const fs::path trace = out.path() / "trace.txt";
    Simnode n(source_path("scenarios/faults/write-past-end-grows.ini"),
              {"--trace", trace.string()});
    ASSERT_NE(n.port, 0);
    const auto before = snapshot_images(n.images.path());
    // Without the option: a thorough run, and not one write past an end.
    auto [code, text] = conform(run_args(n, out, {"--thorough"}), milliseconds(120000));
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find("add --write-past-end"), std::string::npos) << text;
    EXPECT_TRUE(crossing_writes(trace, n.images.path()).empty())
        << crossing_writes(trace, n.images.path()).front();
    EXPECT_EQ(settled_images(n.images.path(), before), before);
    // With it: the node keeps a byte past the end of 0xFD; the run says so.
    std::tie(code, text) = conform(run_args(n, out, {"--write-past-end"}), milliseconds(120000));
    EXPECT_EQ(status_of(text, "memory.write-past-end.fd"), "WARN") << text;
    EXPECT_NE(text.find("may have stored 1 byte past the end of space 0xFD"), std::string::npos)
        << text;
    EXPECT_EQ(text.find("byte-identical"), std::string::npos) << text;
    EXPECT_NE(text.find("restore: node memory identical to before except 2 unrestorable bytes "
                        "past the end"),
              std::string::npos)
        << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "WARN") << text;
    EXPECT_FALSE(crossing_writes(trace, n.images.path()).empty());
    // Every byte a tool can read is as before; the kept bytes sit beside the images.
    auto after = settled_images(n.images.path(), before);
    for (auto it = after.begin(); it != after.end();)
        it = it->first.ends_with(".past-end") ? after.erase(it) : std::next(it);
    EXPECT_EQ(after, before);
}

// ---- hostile files: links planted where lcc-conform writes, a backup that cannot be written ----

// lcc-conform with args: exit code and stdout, its stderr in the file `err`.
std::pair<int, std::string> conform_stderr_to(const fs::path& err,
                                              const std::vector<std::string>& args) {
    std::vector<std::string> sh = {"-c", "err=$1; shift; exec \"$0\" \"$@\" 2>\"$err\"",
                                   LCC_CONFORM_PATH, err.string()};
    sh.insert(sh.end(), args.begin(), args.end());
    return run_program("/bin/sh", sh, milliseconds(120000));
}

// A link planted at BACKUP.tmp, the fixed temporary name of the older lcc-conform, had its target
// overwritten by a --backup run and by `backup FILE` (as root: any file of the system).
TEST(LccConformSafety, LinksPlantedWhereItWritesAreNeverWrittenThrough) {
    Simnode n(source_path("scenarios/default.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    TempDir elsewhere("lcc-conform-safety-target");
    const fs::path target = elsewhere.path() / "precious.txt";
    const std::string precious = "not lcc-conform's to write\n";
    std::ofstream(target, std::ios::binary) << precious;
    const fs::path backup = out.path() / "safety.txt";
    fs::create_symlink(target, backup.string() + ".tmp");
    const auto before = snapshot_images(n.images.path());
    auto [code, text] = conform({"--connect", n.connect(), "--node", kNode, "--backup",
                                 backup.string(), "--only", "encoding.*"});
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(status_of(text, "encoding.restore"), "PASS") << text;
    EXPECT_EQ(read_text(target), precious);
    EXPECT_EQ(fs::read_symlink(backup.string() + ".tmp"), target) << "left as it was";
    EXPECT_EQ(settled_images(n.images.path(), before), before);
    // `backup FILE`, with a link at FILE.tmp, then at FILE itself (rename replaces the link).
    const fs::path config = out.path() / "config.txt";
    fs::create_symlink(target, config.string() + ".tmp");
    for (int round = 0; round < 2; ++round) {
        if (round == 1) fs::create_symlink(target, config);
        std::tie(code, text) =
            conform({"--connect", n.connect(), "--node", kNode, "backup", config.string()});
        EXPECT_EQ(code, 0) << text;
        EXPECT_EQ(read_text(target), precious) << "round " << round;
        EXPECT_FALSE(fs::is_symlink(config));
        EXPECT_NE(read_text(config).find("\n# node 05.01.01.01.22.00\n"), std::string::npos)
            << read_text(config);
        fs::remove(config);
    }
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(out.path())) left.push_back(e.path().filename());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"config.txt.tmp", "safety.txt.tmp"}))
        << "no temporary file of lcc-conform's own is left";
}

// A backup file that cannot be written (a read-only directory, a full disk; /dev/null/x stops
// root too): nothing is written to the node, exit 2 with one line on stderr, and the reports say
// incomplete. It used to exit 0 with a report of SKIPs.
TEST(LccConformSafety, ABackupThatCannotBeWrittenWritesNothingAndExits2) {
    Simnode n(source_path("scenarios/default.ini"));
    ASSERT_NE(n.port, 0);
    TempDir out("lcc-conform-safety-out");
    const fs::path err = out.path() / "stderr.txt";
    const fs::path json = out.path() / "r.json";
    const auto before = snapshot_images(n.images.path());
    const auto [code, text] =
        conform_stderr_to(err, {"--connect", n.connect(), "--node", kNode, "--backup",
                                "/dev/null/safety.txt", "--json", json.string()});
    EXPECT_EQ(code, 2) << text << read_text(err);
    const std::string why =
        "the safety backup could not be written (cannot open /dev/null/safety.txt for writing: "
        "Not a directory), so nothing was written to the node";
    EXPECT_NE(read_text(err).find("\nlcc-conform: " + std::string(kNode) + ": " + why + "\n"),
              std::string::npos)
        << read_text(err);
    EXPECT_NE(text.find("INCOMPLETE: " + why + "\n"), std::string::npos) << text;
    for (const auto& [status, id] : check_lines(text))
        EXPECT_FALSE(status == "PASS" && id.starts_with("encoding.")) << id << "\n" << text;
    const auto j = read_report(json);
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["run"]["exit_code"], 2);
    EXPECT_TRUE(j["nodes"][0]["incomplete"].get<bool>());
    EXPECT_EQ(j["nodes"][0]["writes"]["sent"], 0);
    EXPECT_EQ(snapshot_images(n.images.path()), before);
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
