// simnode and the file descriptor limit (docs/scenarios.md, "File descriptors"): a 3,000-node
// scenario is refused at once, with both numbers, when the hard limit is 1,024; it starts when
// only the soft limit is (simnode raises it); and a live-control add past the limit is refused
// while simnode goes on answering.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

#ifdef SIMNODE_PATH
namespace fs = std::filesystem;

// Runs simnode's arguments through sh with the limit set by `ulimit` (e.g. "-n 1024": soft and
// hard, "-Sn 1024": soft only), stderr merged into stdout.
std::vector<std::string> limited(const std::string& ulimit, std::vector<std::string> args) {
    std::vector<std::string> sh = {"-c", "ulimit " + ulimit + " && exec \"$0\" \"$@\" 2>&1",
                                   SIMNODE_PATH};
    sh.insert(sh.end(), args.begin(), args.end());
    return sh;
}

// Nodes with images, where their creation costs least: tmpfs when there is one (its fsync is
// free; thousands of images on a disk take minutes).
fs::path image_base() {
    std::error_code ec;
    return fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
}

std::vector<std::string> nodes(const fs::path& images, int count) {
    return {"--listen",
            "127.0.0.1:0",
            "--image-dir",
            images.string(),
            "--node.a.node-id=05.01.01.01.50.00",
            "--node.a.count=" + std::to_string(count),
            "--node.a.cdi=" + source_path("scenarios/one-line.xml").string()};
}

rlim_t hard_limit() {
    rlimit limit{};
    return ::getrlimit(RLIMIT_NOFILE, &limit) == 0 ? limit.rlim_max : 0;
}

TEST(SimnodeFdLimit, ThreeThousandNodesUnderAHardLimitOf1024AreRefusedAtOnce) {
    const TempDir base("simnode-fd");
    const fs::path images = base.path() / "images";
    const auto start = std::chrono::steady_clock::now();
    const auto [rc, out] = run_program("/bin/sh", limited("-n 1024", nodes(images, 3000)));
    const auto took = std::chrono::steady_clock::now() - start;
    EXPECT_EQ(rc, 2) << out;
    // One line: the hub's listener, its 64 clients and the process's own 17, one per node.
    EXPECT_EQ(out,
              "simnode: scenario needs about 3082 file descriptors, the limit is 1024 (ulimit -n; "
              "82 for listeners, clients and files, 1 per node with images); raise the limit or "
              "run fewer nodes\n");
    EXPECT_LT(took, std::chrono::seconds(5));
    EXPECT_FALSE(fs::exists(images)) << "refused before anything was made";
}

TEST(SimnodeFdLimit, ThreeThousandNodesStartWhenOnlyTheSoftLimitIs1024) {
    if (hard_limit() < 4096) GTEST_SKIP() << "the hard limit is below 4096";
    const TempDir images("simnode-fd", image_base());
    auto child = Child::spawn("/bin/sh", limited("-Sn 1024", nodes(images.path(), 3000)));
    ASSERT_TRUE(child);
    ASSERT_TRUE(child->wait_listening(milliseconds(120000))) << child->output();
    std::error_code ec;
    const auto fds =
        std::distance(fs::directory_iterator("/proc/" + std::to_string(child->pid()) + "/fd", ec),
                      fs::directory_iterator());
    EXPECT_GT(fds, 3000) << "one per node, past the soft limit simnode raised";
    EXPECT_LE(fds, 3082) << "within what simnode counted";
}

TEST(SimnodeFdLimit, LiveAddPastTheLimitIsRefusedAndSimnodeGoesOn) {
    const TempDir images("simnode-fd", image_base());
    std::vector<std::string> args = nodes(images.path(), 1);
    args.insert(args.end(), {"--control", "127.0.0.1:0"});
    auto child = Child::spawn("/bin/sh", limited("-n 200", args));
    ASSERT_TRUE(child);
    ASSERT_TRUE(child->wait_listening()) << child->output();
    const auto line = child->wait_line("simnode: control on 127.0.0.1:");
    ASSERT_TRUE(line) << child->output();
    const std::string where = "127.0.0.1:" + line->substr(line->rfind(':') + 1);
    // 99 for the process, the hub and 64 clients, control and its 16; 1 per node: 101 fit.
    auto [rc, out] = run_merged(
        SIMNODE_PATH, {"ctl", "--timeout", "60", where, "add", "node-id=05.01.01.01.60.00",
                       "count=150", "cdi=" + source_path("scenarios/one-line.xml").string()});
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("node 05.01.01.01.60.64: not added: simnode needs about 201 file "
                       "descriptors, the limit is 200"),
              std::string::npos)
        << out;
    std::tie(rc, out) = run_program(SIMNODE_PATH, {"ctl", "--json", where, "list"});
    EXPECT_EQ(rc, 0) << out;
    EXPECT_NE(out.find("05.01.01.01.60.63"), std::string::npos) << "the 100 added before run";
    EXPECT_EQ(out.find("05.01.01.01.60.64"), std::string::npos) << out;
}
#endif

}  // namespace
}  // namespace olcb::e2e
