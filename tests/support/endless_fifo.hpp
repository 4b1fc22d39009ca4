// A FIFO fed without end: what a reader bounded by a size limit must give up on.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <string>
#include <thread>

namespace olcb::test_support {

/// Makes a FIFO at path and writes blocks of block_bytes into it from a thread until the reader
/// closes it (EPIPE: SIGPIPE is ignored while this lives). The destructor waits for the writer,
/// so the reader must have opened and closed the FIFO by then.
class EndlessFifo {
public:
    explicit EndlessFifo(std::filesystem::path path, std::size_t block_bytes = 4096)
        : path_(std::move(path)) {
        made_ = ::mkfifo(path_.c_str(), 0600) == 0;
        struct sigaction ignore {};
        ignore.sa_handler = SIG_IGN;
        ::sigaction(SIGPIPE, &ignore, &saved_);
        if (!made_) return;
        writer_ = std::thread([this, block_bytes] {
            const int fd = ::open(path_.c_str(), O_WRONLY | O_CLOEXEC);
            if (fd < 0) return;
            const std::string block(block_bytes, ' ');
            while (::write(fd, block.data(), block.size()) > 0) {
            }
            ::close(fd);
        });
    }
    ~EndlessFifo() {
        if (writer_.joinable()) writer_.join();
        ::sigaction(SIGPIPE, &saved_, nullptr);
    }
    EndlessFifo(const EndlessFifo&) = delete;
    EndlessFifo& operator=(const EndlessFifo&) = delete;

    /// False when the FIFO could not be made.
    bool made() const { return made_; }
    /// Where it is.
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
    bool made_ = false;
    struct sigaction saved_ {};
    std::thread writer_;
};

}  // namespace olcb::test_support
