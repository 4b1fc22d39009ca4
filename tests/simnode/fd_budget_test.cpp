// The descriptor budget: what a scenario needs besides its nodes, what nodes hold, the limit and
// the sentence refusing a run over it.
#include "simnode/fd_budget.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "simnode/control_server.hpp"

namespace olcb::simnode {
namespace {

NodeConfig node(const char* image_dir) {
    NodeConfig c;
    c.image_dir = image_dir;
    return c;
}

TEST(FdBudget, FixedPartCountsEveryListenerClientAndFile) {
    Scenario bare;
    EXPECT_EQ(fixed_fds(bare), kFdsAlways + kFdsMoments);
    Scenario full = bare;
    full.listen = HostPort{"127.0.0.1", 0};
    full.max_clients = 64;
    full.control = HostPort{"127.0.0.1", 0};
    full.connect = HostPort{"127.0.0.1", 1};
    full.socketcan = "vcan0";
    full.serial = "/dev/ttyUSB0";
    full.trace = "trace.log";
    full.candump = "candump.log";
    EXPECT_EQ(fixed_fds(full), fixed_fds(bare) + (1 + 64) + (1 + kMaxControlClients) + 5);
    full.max_clients = 1000;
    EXPECT_EQ(fixed_fds(full), fixed_fds(bare) + (1 + 1000) + (1 + kMaxControlClients) + 5);
}

TEST(FdBudget, OnlyNodesWithImagesHoldDescriptors) {
    const std::vector<NodeConfig> nodes = {node("/tmp/a"), node(""), node("/tmp/b")};
    EXPECT_EQ(node_fds(nodes), 2 * kFdsPerImageNode);
    EXPECT_EQ(node_fds(node("")), 0u);
}

TEST(FdBudget, ShortageNamesNeedAndLimit) {
    const FdBudget budget{81, 1024};
    EXPECT_EQ(fd_shortage("scenario", 1024, budget), "");
    EXPECT_EQ(fd_shortage("scenario", 3081, budget),
              "scenario needs about 3081 file descriptors, the limit is 1024 (ulimit -n; 81 for "
              "listeners, clients and files, 1 per node with images)");
    EXPECT_EQ(fd_shortage("scenario", 1u << 30, FdBudget{81, 0}), "") << "unknown limit";
}

// In a child, whose limit it may change: the soft limit is raised to the hard one.
TEST(FdBudget, RaiseLiftsTheSoftLimitToTheHardOne) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        rlimit limit{};
        if (::getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_max < 64) ::_exit(2);
        limit.rlim_cur = 64;
        if (::setrlimit(RLIMIT_NOFILE, &limit) != 0 || fd_limit() != 64) ::_exit(3);
        if (!raise_fd_limit()) ::_exit(4);
        ::_exit(fd_limit() == limit.rlim_max ? 0 : 5);
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace olcb::simnode
