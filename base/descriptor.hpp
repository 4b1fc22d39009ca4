// A file descriptor closed on every way out of the scope that owns it.
#pragma once

#include <unistd.h>

#include <utility>

namespace olcb::base {

/// Owns one descriptor (-1: none) and closes it when destroyed, unless released.
class Descriptor {
public:
    explicit Descriptor(int fd = -1) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;

    /// The descriptor (-1: none).
    int get() const { return fd_; }
    /// Gives the descriptor up to the caller, who closes it.
    int release() { return std::exchange(fd_, -1); }
    /// Closes the one held, if any, and holds fd.
    void reset(int fd) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = fd;
    }
    /// Closes now and returns close()'s result: some file systems (NFS) report a write error
    /// only then.
    int close() { return ::close(std::exchange(fd_, -1)); }

private:
    int fd_;
};

}  // namespace olcb::base
