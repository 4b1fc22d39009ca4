// Running a shell command line from a test and keeping what it printed.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace olcb::test_support {

/// What a command line did.
struct ShellResult {
    int status = -1;  ///< its exit status (-1: it did not exit normally)
    std::string out;  ///< its standard output (the line's redirections decide stderr)
};

/// Runs line with /bin/sh (the caller quotes) to its end.
inline ShellResult run_shell(const std::string& line) {
    ShellResult run;
    FILE* pipe = popen(line.c_str(), "r");
    if (pipe == nullptr) return run;
    std::array<char, 4096> buf{};
    std::size_t n = 0;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) run.out.append(buf.data(), n);
    const int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
}

}  // namespace olcb::test_support
