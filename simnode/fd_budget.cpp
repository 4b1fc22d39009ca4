#include "simnode/fd_budget.hpp"

#include <sys/resource.h>

#include "simnode/control_server.hpp"

namespace olcb::simnode {

std::size_t fixed_fds(const Scenario& scenario) {
    std::size_t fds = kFdsAlways + kFdsMoments;
    // The hub's listener and every client it admits.
    if (scenario.listen) fds += 1 + scenario.max_clients;
    if (scenario.control) fds += 1 + kMaxControlClients;
    if (scenario.connect) ++fds;
    if (!scenario.socketcan.empty()) ++fds;
    if (!scenario.serial.empty()) ++fds;
    if (!scenario.trace.empty()) ++fds;
    if (!scenario.candump.empty()) ++fds;
    return fds;
}

std::size_t node_fds(const NodeConfig& node) {
    return node.image_dir.empty() ? 0 : kFdsPerImageNode;
}

std::size_t node_fds(std::span<const NodeConfig> nodes) {
    std::size_t fds = 0;
    for (const NodeConfig& node : nodes) fds += node_fds(node);
    return fds;
}

std::size_t fd_limit() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
    return static_cast<std::size_t>(limit.rlim_cur);
}

bool raise_fd_limit() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_NOFILE, &limit) != 0) return false;
    if (limit.rlim_cur == limit.rlim_max) return true;
    limit.rlim_cur = limit.rlim_max;
    return ::setrlimit(RLIMIT_NOFILE, &limit) == 0;
}

std::string fd_shortage(const std::string& what, std::size_t need, const FdBudget& budget) {
    if (budget.limit == 0 || need <= budget.limit) return "";
    return what + " needs about " + std::to_string(need) + " file descriptors, the limit is " +
           std::to_string(budget.limit) + " (ulimit -n; " + std::to_string(budget.fixed) +
           " for listeners, clients and files, " + std::to_string(kFdsPerImageNode) +
           " per node with images)";
}

}  // namespace olcb::simnode
