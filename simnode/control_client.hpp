// `simnode ctl HOST:PORT COMMAND [ARGS...]`: sends one live-control request to a running simnode
// (docs/control.md) and prints its response.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <ostream>
#include <span>
#include <string>

#include "simnode/control_commands.hpp"
#include "simnode/scenario.hpp"

namespace olcb::simnode {

/// Exit status of `simnode ctl`: the request was done.
inline constexpr int kCtlOk = 0;
/// Exit status of `simnode ctl`: simnode refused the request.
inline constexpr int kCtlRefused = 1;
/// Exit status of `simnode ctl`: bad arguments, no connection or no answer.
inline constexpr int kCtlUsage = 2;

/// What one `simnode ctl` run asks.
struct CtlInvocation {
    HostPort where;                            ///< simnode's control address
    ControlJson request;                       ///< the request to send
    bool json = false;                         ///< print the response line as it came
    std::chrono::milliseconds timeout{10000};  ///< for connecting and the answer together
};

/// The usage text of `simnode ctl`.
std::string ctl_usage();

/// Parses the arguments after "ctl"; relative cdi and image-dir paths of add are made absolute
/// against cwd (simnode may run elsewhere). nullopt with error when they are wrong.
std::optional<CtlInvocation> parse_ctl_arguments(std::span<const std::string> args,
                                                 const std::filesystem::path& cwd,
                                                 std::string& error);

/// The readable form of a successful response to request, one or more lines.
std::string format_ctl_response(const ControlJson& request, const ControlJson& response);

/// Sends line (one request, no newline) to where and returns the response line; nullopt with
/// error when it cannot connect or no answer came within timeout.
std::optional<std::string> ctl_exchange(const HostPort& where, const std::string& line,
                                        std::chrono::milliseconds timeout, std::string& error);

/// Runs `simnode ctl` with the arguments after "ctl"; kCtlOk, kCtlRefused or kCtlUsage.
int run_ctl(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace olcb::simnode
