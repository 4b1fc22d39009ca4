// Test support: pseudo-terminals standing in for USB serial adapters, and a null-modem relay
// between two of them that can "unplug" and "replug" either side. Linux only; link with util.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

namespace olcb::test {

/// A pseudo-terminal: the program under test opens slave_path(), the test drives master_fd().
class PtyPair {
public:
    /// Opens a pty in raw mode; throws std::runtime_error when the system has none left.
    PtyPair() {
        termios raw{};
        ::cfmakeraw(&raw);
        // Raw before anyone opens the slave: nothing echoed back or translated in between.
        if (::openpty(&master_, &slave_, nullptr, &raw, nullptr) != 0) {
            throw std::runtime_error(std::string("openpty: ") + std::strerror(errno));
        }
        std::array<char, 128> name{};
        if (::ptsname_r(master_, name.data(), name.size()) != 0) {
            const int error = errno;
            close();
            throw std::runtime_error(std::string("ptsname_r: ") + std::strerror(error));
        }
        slave_path_ = name.data();
        ::fcntl(master_, F_SETFL, ::fcntl(master_, F_GETFL) | O_NONBLOCK);
        // Programs the test starts must not inherit either end: a child holding the master
        // open would keep the line alive after close() ("unplug").
        ::fcntl(master_, F_SETFD, FD_CLOEXEC);
        ::fcntl(slave_, F_SETFD, FD_CLOEXEC);
    }
    /// Closes both ends.
    ~PtyPair() { close(); }
    PtyPair(const PtyPair&) = delete;
    PtyPair& operator=(const PtyPair&) = delete;

    /// The master end (non-blocking); -1 after close().
    int master_fd() const { return master_; }
    /// The slave device, e.g. /dev/pts/7.
    const std::string& slave_path() const { return slave_path_; }

    /// Writes all of `bytes` to the master, waiting at most `timeout` for room; returns the
    /// number of bytes written.
    std::size_t write_master(std::string_view bytes,
                             std::chrono::milliseconds timeout = std::chrono::seconds(2)) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        std::size_t done = 0;
        while (master_ >= 0 && done < bytes.size()) {
            const auto n = ::write(master_, bytes.data() + done, bytes.size() - done);
            if (n > 0) {
                done += static_cast<std::size_t>(n);
                continue;
            }
            if (n < 0 && errno != EAGAIN && errno != EINTR) break;
            const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) break;
            pollfd p{master_, POLLOUT, 0};
            ::poll(&p, 1, static_cast<int>(left.count()));
        }
        return done;
    }

    /// Returns what the program wrote to the slave so far, waiting at most `timeout` for the
    /// first byte; empty when nothing came.
    std::string read_master(std::chrono::milliseconds timeout = std::chrono::milliseconds(0)) {
        std::string out;
        if (master_ < 0) return out;
        pollfd p{master_, POLLIN, 0};
        if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return out;
        std::array<char, 4096> buf{};
        for (;;) {
            const auto n = ::read(master_, buf.data(), buf.size());
            if (n <= 0) break;
            out.append(buf.data(), static_cast<std::size_t>(n));
        }
        return out;
    }

    /// Closes master and slave: the program's reads and writes fail, as on an unplugged adapter.
    void close() {
        if (master_ >= 0) ::close(master_);
        if (slave_ >= 0) ::close(slave_);
        master_ = -1;
        slave_ = -1;
    }

private:
    int master_ = -1;
    // Kept open so the master never reads EIO merely because the program has not opened (or has
    // just closed) the slave.
    int slave_ = -1;
    std::string slave_path_;
};

/// Two ptys joined like a null-modem cable: a program opening path(Side::A) talks to one
/// opening path(Side::B). Either side can be unplugged and replugged under the same path.
class PtyRelay {
public:
    /// The two ends of the cable.
    enum class Side : std::uint8_t { A, B };
    /// schedule_unplug() downtime meaning "never replug".
    static constexpr std::chrono::milliseconds kNever{-1};

    /// Creates both ptys with symlinks dir/a and dir/b and starts relaying.
    explicit PtyRelay(std::filesystem::path dir) : dir_(std::move(dir)) {
        std::filesystem::create_directories(dir_);
        for (Side side : {Side::A, Side::B}) plug(side);
        thread_ = std::thread([this] { run(); });
    }
    /// Stops the relay thread, closes the ptys and removes the symlinks.
    ~PtyRelay() {
        stop_ = true;
        thread_.join();
        std::error_code ignored;
        for (Side side : {Side::A, Side::B}) std::filesystem::remove(path(side), ignored);
    }
    PtyRelay(const PtyRelay&) = delete;
    PtyRelay& operator=(const PtyRelay&) = delete;

    /// The stable path of a side (a symlink to its current pty).
    std::filesystem::path path(Side side) const { return dir_ / (side == Side::A ? "a" : "b"); }

    /// Closes that side's pty and removes its path: the program on that side sees its device fail.
    void unplug(Side side) {
        std::lock_guard lock(mutex_);
        unplug_locked(side);
    }
    /// Gives that side a new pty and points its symlink there.
    void replug(Side side) {
        std::lock_guard lock(mutex_);
        plug(side);
    }
    /// Unplugs `side` once `after_bytes_total` bytes have been relayed (both directions
    /// together), and replugs it `downtime` later (never for a negative downtime).
    void schedule_unplug(Side side, std::size_t after_bytes_total,
                         std::chrono::milliseconds downtime) {
        std::lock_guard lock(mutex_);
        auto& e = end(side);
        e.unplug_scheduled = true;
        e.unplug_after = after_bytes_total;
        e.downtime = downtime;
    }
    /// Bytes copied so far, both directions together.
    std::size_t bytes_relayed() const {
        std::lock_guard lock(mutex_);
        return bytes_relayed_;
    }
    /// True while that side is unplugged.
    bool unplugged(Side side) const {
        std::lock_guard lock(mutex_);
        return end(side).pty == nullptr;
    }

private:
    using SteadyClock = std::chrono::steady_clock;
    // Bytes waiting for room in a master's input: beyond this the relay stops reading the
    // other side (flow control), so memory stays bounded.
    static constexpr std::size_t kMaxBuffered = std::size_t{64} * 1024;

    struct End {
        std::unique_ptr<PtyPair> pty;
        std::string to_master;  // bytes from the other side not yet written to this master
        bool unplug_scheduled = false;
        std::size_t unplug_after = 0;
        std::chrono::milliseconds downtime{0};
        bool replug_scheduled = false;
        SteadyClock::time_point replug_at{};
    };

    End& end(Side side) { return side == Side::A ? a_ : b_; }
    const End& end(Side side) const { return side == Side::A ? a_ : b_; }

    // Requires mutex_ or the constructor.
    void plug(Side side) {
        auto& e = end(side);
        e.pty = std::make_unique<PtyPair>();
        e.replug_scheduled = false;
        // Atomic re-pointing: a program reopening the path sees the old or the new pty.
        const auto link = path(side);
        auto temp = link;
        temp += ".tmp";
        std::error_code ignored;
        std::filesystem::remove(temp, ignored);
        std::filesystem::create_symlink(e.pty->slave_path(), temp);
        std::filesystem::rename(temp, link);
    }

    void unplug_locked(Side side) {
        auto& e = end(side);
        // The path goes away with the device, as /dev/ttyACM0 does: a program reopening it
        // must never reach a stranger's pty that happens to get the freed /dev/pts number.
        std::error_code ignored;
        std::filesystem::remove(path(side), ignored);
        e.pty.reset();
        e.to_master.clear();
        e.replug_scheduled = false;
    }

    void run() {
        while (!stop_) {
            std::array<pollfd, 2> fds{};
            {
                std::lock_guard lock(mutex_);
                fds[0] = poll_entry(a_, b_);
                fds[1] = poll_entry(b_, a_);
            }
            // A descriptor closed meanwhile only makes poll return early: every read and write
            // below happens under the mutex on the current descriptors.
            ::poll(fds.data(), fds.size(), 20);
            std::lock_guard lock(mutex_);
            pump(a_, b_);
            pump(b_, a_);
            check_schedule(Side::A);
            check_schedule(Side::B);
        }
    }

    static pollfd poll_entry(const End& self, const End& other) {
        pollfd p{-1, 0, 0};
        if (!self.pty) return p;
        p.fd = self.pty->master_fd();
        if (other.to_master.size() < kMaxBuffered) p.events |= POLLIN;
        if (!self.to_master.empty()) p.events |= POLLOUT;
        return p;
    }

    // Moves what `from`'s program wrote towards `to`'s program, and flushes `from`'s backlog.
    void pump(End& from, End& to) {
        if (!from.pty) return;
        const int fd = from.pty->master_fd();
        std::array<char, 4096> buf{};
        while (to.to_master.size() < kMaxBuffered) {
            const auto n = ::read(fd, buf.data(), buf.size());
            if (n <= 0) break;
            if (!to.pty) continue;  // nobody on the other end of the cable
            to.to_master.append(buf.data(), static_cast<std::size_t>(n));
            bytes_relayed_ += static_cast<std::size_t>(n);
        }
        while (!from.to_master.empty()) {
            const auto n = ::write(fd, from.to_master.data(), from.to_master.size());
            if (n <= 0) break;
            from.to_master.erase(0, static_cast<std::size_t>(n));
        }
    }

    void check_schedule(Side side) {
        auto& e = end(side);
        const auto now = SteadyClock::now();
        if (e.unplug_scheduled && bytes_relayed_ >= e.unplug_after) {
            e.unplug_scheduled = false;
            const auto downtime = e.downtime;
            unplug_locked(side);
            if (downtime >= std::chrono::milliseconds(0)) {
                e.replug_scheduled = true;
                e.replug_at = now + downtime;
            }
        } else if (e.replug_scheduled && !e.pty && now >= e.replug_at) {
            plug(side);
        }
    }

    std::filesystem::path dir_;
    mutable std::mutex mutex_;
    End a_;
    End b_;
    std::size_t bytes_relayed_ = 0;
    std::atomic<bool> stop_{false};
    std::thread thread_;  // last: started after everything it touches exists
};

}  // namespace olcb::test
