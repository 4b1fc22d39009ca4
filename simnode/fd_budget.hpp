// How many file descriptors a scenario needs, against the process's limit (RLIMIT_NOFILE), so
// one too large is refused before anything starts, with both numbers, instead of failing part
// way or leaving the process without a descriptor to accept a client with (docs/scenarios.md,
// "File descriptors").
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "simnode/scenario.hpp"

namespace olcb::simnode {

/// Held by a node with images while it runs: its image directory, which holds the lock of all
/// its images (memory/image_file.hpp); a node in RAM only holds none.
inline constexpr std::size_t kFdsPerImageNode = 1;
/// Held by every run: stdin, stdout, stderr; the io_context's epoll, eventfd and timerfd; the
/// signal set's pipe (2); one to spare.
inline constexpr std::size_t kFdsAlways = 9;
/// Open for moments: an image and its journal while one is opened or written, a file
/// base::write_file replaces and its directory, /proc reads, a node's past-end file; and a
/// connection accepted only to be refused because the listener is full (hub, control).
inline constexpr std::size_t kFdsMoments = 8;

/// What a run needs besides its nodes, and the limit: the check live control's add makes.
struct FdBudget {
    std::size_t fixed = 0;  ///< fixed_fds() of the scenario
    std::size_t limit = 0;  ///< fd_limit() (0 = unknown: no check)
};

/// Descriptors a run takes besides its nodes: kFdsAlways, kFdsMoments, and those of the
/// scenario's transports, listeners with every client they admit, and log files.
std::size_t fixed_fds(const Scenario& scenario);
/// Descriptors one node holds while it runs.
std::size_t node_fds(const NodeConfig& node);
/// Descriptors nodes hold while they run.
std::size_t node_fds(std::span<const NodeConfig> nodes);
/// The soft RLIMIT_NOFILE (0 when unknown or unlimited).
std::size_t fd_limit();
/// Raises the soft RLIMIT_NOFILE to the hard one; false (errno set) when that fails.
bool raise_fd_limit();
/// The sentence refusing a run that needs `need` descriptors when that is over budget.limit,
/// "" when it fits (or the limit is unknown). `what` names the need ("scenario", "adding node X").
std::string fd_shortage(const std::string& what, std::size_t need, const FdBudget& budget);

}  // namespace olcb::simnode
