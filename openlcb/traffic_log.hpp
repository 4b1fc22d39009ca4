// A sink recording every frame of a segment as GridConnect lines and/or candump -L lines.
#pragma once

#include <chrono>
#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "openlcb/can_frame.hpp"

namespace olcb {

/// An append-only log file with an optional size bound: before a write would take it past
/// max_bytes it is renamed to PATH.1 (replacing an older one) and PATH starts empty, so about
/// 2 * max_bytes stay on disk. Writes are flushed at once so a log survives a crash.
class RotatingFile {
public:
    /// Opens path for appending (its current size counts); max_bytes 0 = never rotate. "-" is
    /// standard output (never rotated). False if it cannot be opened.
    bool open(const std::string& path, std::uint64_t max_bytes = 0);
    /// Appends text, which stays whole in one file (a text longer than max_bytes fills one alone).
    void write(std::string_view text);
    /// True after a successful open().
    bool is_open() const { return stdout_ || file_.is_open(); }
    /// False once a write or a rotation failed.
    bool ok() const { return !failed_ && (stdout_ || static_cast<bool>(file_)); }
    /// Bytes in the current file.
    std::uint64_t size() const { return size_; }
    /// Times the file was rotated.
    std::uint64_t rotations() const { return rotations_; }

private:
    void rotate();

    std::string path_;
    std::uint64_t max_bytes_ = 0;
    std::uint64_t size_ = 0;
    std::uint64_t rotations_ = 0;
    bool failed_ = false;
    bool stdout_ = false;  ///< writing to standard output ("-")
    std::ofstream file_;
};

/// Writes each recorded frame to every attached output, one line per frame.
///
/// GridConnect outputs get `:X19490343N;` lines (what the hub and the tests speak); candump
/// outputs get `(1700000000.123456) vcan0 19490343#` lines that canplayer replays. Lines are
/// flushed as written so a log survives a crash of the program that writes it.
class TrafficLog {
public:
    /// Microseconds since the Unix epoch; replaceable for deterministic tests.
    using Clock = std::function<std::chrono::microseconds()>;

    /// A log with no outputs, stamping candump lines with the system clock.
    TrafficLog();
    /// A log stamping candump lines with `clock`.
    explicit TrafficLog(Clock clock);

    /// Appends GridConnect lines to the file at `path`, rotated past max_bytes (0 = never, see
    /// RotatingFile); false if it cannot be opened.
    bool add_gridconnect_file(const std::string& path, std::uint64_t max_bytes = 0);
    /// Appends candump -L lines naming `interface` to the file at `path`, rotated past max_bytes
    /// (0 = never); false if not opened.
    bool add_candump_file(const std::string& path, const std::string& interface = "vcan0",
                          std::uint64_t max_bytes = 0);
    /// Writes GridConnect lines to a caller-owned stream that outlives the log.
    void add_gridconnect_stream(std::ostream& out);
    /// Writes candump lines to a caller-owned stream that outlives the log.
    void add_candump_stream(std::ostream& out, const std::string& interface = "vcan0");

    /// Writes `frame` to every output, stamped with the clock.
    void record(const CanFrame& frame);
    /// Writes `frame` to every output with an explicit timestamp.
    void record(const CanFrame& frame, std::chrono::microseconds timestamp);

    /// False once any output failed to write.
    bool ok() const;
    /// Lines written per output so far.
    std::uint64_t frames_recorded() const { return frames_; }
    /// Rotations of all file outputs so far.
    std::uint64_t rotations() const;

private:
    struct Output {
        std::ostream* stream;  // null for a file output
        RotatingFile* file;    // null for a stream output
        bool candump;
        std::string interface;
    };
    bool add_file(const std::string& path, bool candump, const std::string& interface,
                  std::uint64_t max_bytes);

    Clock clock_;
    std::vector<std::unique_ptr<RotatingFile>> files_;
    std::vector<Output> outputs_;
    std::string line_;
    std::uint64_t frames_ = 0;
};

}  // namespace olcb
