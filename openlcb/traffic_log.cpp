#include "openlcb/traffic_log.hpp"

#include <filesystem>
#include <iostream>
#include <system_error>
#include <utility>

#include "openlcb/candump_log.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb {

namespace {
std::chrono::microseconds system_now() {
    return std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::system_clock::now().time_since_epoch());
}
}  // namespace

TrafficLog::TrafficLog() : clock_(system_now) {}

TrafficLog::TrafficLog(Clock clock) : clock_(clock ? std::move(clock) : Clock(system_now)) {}

bool RotatingFile::open(const std::string& path, std::uint64_t max_bytes) {
    path_ = path;
    max_bytes_ = max_bytes;
    failed_ = false;
    // "-" is standard output, as for most Unix tools: a pipe cannot be rotated.
    stdout_ = path == "-";
    if (stdout_) {
        max_bytes_ = 0;
        return true;
    }
    file_.open(path, std::ios::app);
    if (!file_) return false;
    std::error_code ec;
    // A FIFO or device (--trace /dev/null) is a stream: renaming it would move the device node.
    if (!std::filesystem::is_regular_file(path, ec)) max_bytes_ = 0;
    const auto existing = std::filesystem::file_size(path, ec);
    size_ = ec ? 0 : existing;
    return true;
}

void RotatingFile::write(std::string_view text) {
    if (stdout_) {
        std::cout.write(text.data(), static_cast<std::streamsize>(text.size()));
        std::cout.flush();
        if (!std::cout) failed_ = true;
        size_ += text.size();
        return;
    }
    if (!file_.is_open()) return;
    if (max_bytes_ != 0 && size_ != 0 && size_ + text.size() > max_bytes_) rotate();
    file_.write(text.data(), static_cast<std::streamsize>(text.size()));
    file_.flush();
    if (!file_) failed_ = true;
    size_ += text.size();
}

void RotatingFile::rotate() {
    file_.close();
    std::error_code ec;
    std::filesystem::rename(path_, path_ + ".1", ec);  // replaces an older PATH.1
    if (ec) {
        // Keep logging unbounded rather than lose the file; retrying every line would only
        // repeat the same failure.
        failed_ = true;
        max_bytes_ = 0;
        file_.open(path_, std::ios::app);
        return;
    }
    file_.open(path_, std::ios::trunc);
    if (!file_) failed_ = true;
    size_ = 0;
    ++rotations_;
}

bool TrafficLog::add_file(const std::string& path, bool candump, const std::string& interface,
                          std::uint64_t max_bytes) {
    auto file = std::make_unique<RotatingFile>();
    if (!file->open(path, max_bytes)) return false;
    outputs_.push_back({nullptr, file.get(), candump, interface});
    files_.push_back(std::move(file));
    return true;
}

bool TrafficLog::add_gridconnect_file(const std::string& path, std::uint64_t max_bytes) {
    return add_file(path, false, {}, max_bytes);
}

bool TrafficLog::add_candump_file(const std::string& path, const std::string& interface,
                                  std::uint64_t max_bytes) {
    return add_file(path, true, interface, max_bytes);
}

void TrafficLog::add_gridconnect_stream(std::ostream& out) {
    outputs_.push_back({&out, nullptr, false, {}});
}

void TrafficLog::add_candump_stream(std::ostream& out, const std::string& interface) {
    outputs_.push_back({&out, nullptr, true, interface});
}

void TrafficLog::record(const CanFrame& frame) {
    if (outputs_.empty()) return;
    record(frame, clock_());
}

void TrafficLog::record(const CanFrame& frame, std::chrono::microseconds timestamp) {
    ++frames_;
    for (const Output& out : outputs_) {
        if (out.candump) {
            line_ = candump::format(frame, timestamp, out.interface);
        } else {
            line_.clear();
            gridconnect::format_to(frame, line_);
        }
        line_.push_back('\n');
        if (out.file != nullptr) {
            out.file->write(line_);
            continue;
        }
        out.stream->write(line_.data(), static_cast<std::streamsize>(line_.size()));
        out.stream->flush();
    }
}

bool TrafficLog::ok() const {
    for (const Output& out : outputs_) {
        if (out.file != nullptr ? !out.file->ok() : !*out.stream) return false;
    }
    return true;
}

std::uint64_t TrafficLog::rotations() const {
    std::uint64_t n = 0;
    for (const auto& file : files_) n += file->rotations();
    return n;
}

}  // namespace olcb
