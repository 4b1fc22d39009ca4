// The simnode command line: help, usage errors, inline nodes, [node.NAME] sections, the shipped
// scenarios (every fault has one) and a clean stop on SIGTERM.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

#ifdef SIMNODE_PATH
TEST(SimnodeCli, HelpListsEveryKey) {
    const auto [code, out] = run_program(SIMNODE_PATH, {"--help"});
    EXPECT_EQ(code, 0);
    for (const char* key :
         {"--scenario", "--node-id", "--count", "--cdi", "--image-dir", "--manufacturer", "--model",
          "--hardware-version", "--software-version", "--user-name", "--user-description",
          "--fault", "--listen", "--connect", "--socketcan", "--trace", "--candump", "--run-for"}) {
        EXPECT_NE(out.find(key), std::string::npos) << key;
    }
}

// Scenarios by name: this build's binary lists and runs the source tree's, from any directory.
TEST(SimnodeCli, ListsAndRunsScenariosByName) {
    const auto [code, out] = run_program(SIMNODE_PATH, {"--list-scenarios"});
    EXPECT_EQ(code, 0);
    const std::string line = out.substr(out.find("faults/int-byte-order "));
    EXPECT_TRUE(line.substr(0, line.find('\n'))
                    .ends_with(" " + source_path("scenarios/faults/int-byte-order.ini").string()))
        << out;
    TempDir images("simnode-by-name");
    const auto [rc, ran] =
        run_program(SIMNODE_PATH, {"--scenario", "io-board", "--image-dir", images.str(),
                                   "--listen", "127.0.0.1:0", "--run-for", "0.3"});
    EXPECT_EQ(rc, 0) << ran;
    EXPECT_NE(ran.find("cdi " + source_path("scenarios/io-board.xml").string()), std::string::npos)
        << ran;
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--scenario", "no-such-scenario"}).first, 2);
}

TEST(SimnodeCli, BadInputIsAUsageError) {
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--bogus"}).first, 2);
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--fault", "no-such-fault"}).first, 2);
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--listen", "1.2.3.4:99999"}).first, 2);
    EXPECT_EQ(run_program(SIMNODE_PATH, {"/nonexistent.ini"}).first, 2);
}

// A --connect hub that is not there at the start is a mistake said at once, not a silent wait.
TEST(SimnodeCli, ConnectingToNoHubIsOneLineAndExitTwo) {
    TempDir images("simnode-no-hub");
    const std::string where = "127.0.0.1:" + std::to_string(closed_port());
    const auto started = std::chrono::steady_clock::now();
    const auto [code, out] =
        run_merged(SIMNODE_PATH, {"--node-id", "05.01.01.01.22.78", "--cdi",
                                  source_path("scenarios/default.xml").string(), "--image-dir",
                                  images.str(), "--connect", where, "--run-for", "30"});
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("simnode: cannot connect to hub " + where + ": connection refused"),
              std::string::npos)
        << out;
    EXPECT_LT(std::chrono::steady_clock::now() - started, std::chrono::seconds(5));
}

TEST(SimnodeCli, RunsInlineWithoutAScenarioFile) {
    TempDir images("simnode-inline");
    const auto [code, out] =
        run_program(SIMNODE_PATH, {"--node-id", "05.01.01.01.22.77", "--cdi",
                                   source_path("scenarios/io-board.xml").string(), "--image-dir",
                                   images.str(), "--listen", "127.0.0.1:0", "--run-for", "0.6"});
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("simnode: listening on 127.0.0.1:"), std::string::npos) << out;
    EXPECT_NE(out.find("1 node(s) initialized"), std::string::npos) << out;
    EXPECT_TRUE(std::filesystem::is_directory(images.path() / "05.01.01.01.22.77"));
}

TEST(SimnodeCli, EveryFaultHasAScenarioThatRuns) {
    const auto [code, names] = run_program(SIMNODE_PATH, {"--list-faults"});
    ASSERT_EQ(code, 0);
    std::istringstream in(names);
    std::string name;
    EXPECT_NE(names.find("slow-reply                      reply datagrams sent MS milliseconds "
                         "late (parameter MS (default 1200))"),
              std::string::npos)
        << names;
    int count = 0;
    TempDir images("simnode-faults");
    std::string line;
    while (std::getline(in, line)) {
        name = line.substr(0, line.find(' '));  // "NAME   meaning (parameter ...)"
        if (name.empty()) continue;
        ++count;
        const auto file = source_path("scenarios/faults/" + name + ".ini");
        ASSERT_TRUE(std::filesystem::exists(file)) << file;
        // One image directory per scenario: they do not all serve the same CDI.
        const auto [rc, out] =
            run_program(SIMNODE_PATH, {file.string(), "--listen", "127.0.0.1:0", "--image-dir",
                                       (images.path() / name).string(), "--run-for", "0.3"});
        EXPECT_EQ(rc, 0) << name << "\n" << out;
    }
    EXPECT_GE(count, 21);
}

TEST(SimnodeCli, ShippedScenariosLoad) {
    TempDir images("simnode-shipped");
    for (const char* s : {"scenarios/default.ini", "scenarios/io-board.ini"}) {
        const auto [rc, out] =
            run_program(SIMNODE_PATH, {source_path(s).string(), "--listen", "127.0.0.1:0",
                                       "--image-dir", images.str(), "--run-for", "0.5"});
        EXPECT_EQ(rc, 0) << s << "\n" << out;
        EXPECT_NE(out.find("1 node(s) initialized"), std::string::npos) << s << "\n" << out;
    }
}

TEST(SimnodeCli, SectionsFromAFileWithRelativePaths) {
    TempDir dir("simnode-sections");
    std::filesystem::copy_file(source_path("scenarios/io-board.xml"), dir.path() / "board.xml");
    {
        std::ofstream ini(dir.path() / "layout.ini");
        ini << "listen = 127.0.0.1:0\nimage-dir = images\nuser-name = Board {n} {id}\n"
               "[node.a]\nnode-id = 05.01.01.01.50.00\ncount = 3\ncdi = board.xml\n"
               "[node.b]\nnode-id = 05.01.01.01.51.00\ncdi = board.xml\n"
               "fault = reply-form\n";
    }
    const auto [rc, out] =
        run_program(SIMNODE_PATH, {(dir.path() / "layout.ini").string(), "--run-for", "0.5"});
    EXPECT_EQ(rc, 0) << out;
    EXPECT_NE(out.find("4 node(s) initialized"), std::string::npos) << out;
    for (const char* id : {"05.01.01.01.50.00", "05.01.01.01.50.02", "05.01.01.01.51.00"}) {
        EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "images" / id)) << id;
    }
}

TEST(SimnodeCli, SectionsInlineAndDuplicateIds) {
    TempDir images("simnode-inline-sections");
    const auto board = source_path("scenarios/io-board.xml").string();
    const auto [rc, out] =
        run_program(SIMNODE_PATH, {"--listen", "0", "--image-dir", images.str(),
                                   "--node.a.node-id=05.01.01.01.50.00", "--node.a.count=2",
                                   "--node.a.cdi=" + board, "--node.b.node-id=05.01.01.01.51.00",
                                   "--node.b.cdi=" + board, "--run-for", "0.5"});
    EXPECT_EQ(rc, 0) << out;
    EXPECT_NE(out.find("3 node(s) initialized"), std::string::npos) << out;
    // 50.01 is both the second node of group a and the node of group b.
    EXPECT_EQ(run_program(SIMNODE_PATH,
                          {"--image-dir", images.str(), "--node.a.node-id=05.01.01.01.50.00",
                           "--node.a.count=2", "--node.a.cdi=" + board,
                           "--node.b.node-id=05.01.01.01.50.01", "--node.b.cdi=" + board})
                  .first,
              2);
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--node.a.bogus=1"}).first, 2);
    EXPECT_EQ(run_program(SIMNODE_PATH, {"--count", "0"}).first, 2);
}

TEST(SimnodeCli, SigtermStopsCleanly) {
    TempDir images("simnode-sigterm");
    auto child =
        Child::spawn(SIMNODE_PATH, {"--listen", "127.0.0.1:0", "--image-dir", images.str()});
    ASSERT_TRUE(child);
    ASSERT_TRUE(child->wait_listening());
    ASSERT_TRUE(child->wait_line("simnode: 1 node(s) initialized"));
    child->signal(SIGTERM);
    ASSERT_TRUE(child->wait_for(milliseconds(5000)));
    EXPECT_EQ(child->wait(), 0);
    EXPECT_TRUE(child->wait_line("simnode: stopped", milliseconds(1000)));
}
#endif

}  // namespace
}  // namespace olcb::e2e
