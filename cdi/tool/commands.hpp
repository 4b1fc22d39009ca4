// The subcommands of lcc-cdi; each takes the arguments after the command name.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace olcb::cdi::tool {

/// Exit status: every file clean (warnings allowed).
constexpr int kExitOk = 0;
/// Exit status: a file has errors (or can't be read).
constexpr int kExitErrors = 1;
/// Exit status: bad command line.
constexpr int kExitUsage = 2;

/// `lcc-cdi validate FILE...`.
int run_validate(const std::vector<std::string>& args);
/// `lcc-cdi layout FILE [--json]`.
int run_layout(const std::vector<std::string>& args);
/// `lcc-cdi render [--html] FILE`.
int run_render(const std::vector<std::string>& args);

}  // namespace olcb::cdi::tool
