// The simnode program as a child process of a benchmark: started on a free loopback port with
// fresh images, its stdout read for the "listening on" and "initialized" lines, killed at the end.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace olcb::bench {

/// simnode on scenarios/default.ini, listening on 127.0.0.1:<free port>, plus `extra` options.
class SimnodeProcess {
public:
    explicit SimnodeProcess(const std::vector<std::string>& extra) {
        namespace fs = std::filesystem;
        const fs::path source = OLCB_SOURCE_DIR;  // not __FILE__: ccache may make it relative
        images_ = fs::temp_directory_path() / ("bench-simnode-hub-" + std::to_string(::getpid()) +
                                               "-" + std::to_string(std::random_device{}()));
        std::vector<std::string> args = {
            SIMNODE_PATH,     "--scenario",  (source / "scenarios/default.ini").string(),
            "--listen",       "127.0.0.1:0", "--image-dir",
            images_.string(), "--run-for",   "600"};
        args.insert(args.end(), extra.begin(), extra.end());
        spawn(args);
        const std::string listening = wait_line("simnode: listening on ");
        port_ = static_cast<std::uint16_t>(std::stoi(listening.substr(listening.rfind(':') + 1)));
        wait_line("simnode: 1 node(s) initialized");
    }
    ~SimnodeProcess() {
        if (pid_ > 0) {
            ::kill(pid_, SIGKILL);
            int status = 0;
            ::waitpid(pid_, &status, 0);
        }
        if (out_ >= 0) ::close(out_);
        std::error_code ec;
        std::filesystem::remove_all(images_, ec);
    }
    SimnodeProcess(const SimnodeProcess&) = delete;
    SimnodeProcess& operator=(const SimnodeProcess&) = delete;

    /// The hub's port on 127.0.0.1.
    std::uint16_t port() const { return port_; }

private:
    void spawn(std::vector<std::string>& args) {
        int fds[2];
        if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
        std::vector<char*> argv;
        argv.reserve(args.size() + 1);
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        pid_ = ::fork();
        if (pid_ < 0) throw std::runtime_error("fork failed");
        if (pid_ == 0) {
            ::dup2(fds[1], STDOUT_FILENO);
            ::execv(argv[0], argv.data());
            ::_exit(127);
        }
        ::close(fds[1]);
        out_ = fds[0];
    }

    // The first line starting with prefix (within 20 s), else an exception with the output.
    std::string wait_line(const std::string& prefix) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        for (;;) {
            for (auto nl = buffer_.find('\n'); nl != std::string::npos; nl = buffer_.find('\n')) {
                std::string line = buffer_.substr(0, nl);
                buffer_.erase(0, nl + 1);
                seen_ += line + "\n";
                if (line.starts_with(prefix)) return line;
            }
            if (std::chrono::steady_clock::now() > deadline) break;
            pollfd p{out_, POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) continue;
            char chunk[4096];
            const ssize_t n = ::read(out_, chunk, sizeof chunk);
            if (n <= 0) break;
            buffer_.append(chunk, static_cast<std::size_t>(n));
        }
        throw std::runtime_error("simnode did not print '" + prefix + "':\n" + seen_);
    }

    pid_t pid_ = -1;
    int out_ = -1;
    std::uint16_t port_ = 0;
    std::filesystem::path images_;
    std::string buffer_;
    std::string seen_;
};

}  // namespace olcb::bench
