#include "openlcb/traffic_log.hpp"

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

bool TrafficLog::add_gridconnect_file(const std::string& path) {
    auto file = std::make_unique<std::ofstream>(path, std::ios::app);
    if (!*file) return false;
    outputs_.push_back({file.get(), false, {}});
    files_.push_back(std::move(file));
    return true;
}

bool TrafficLog::add_candump_file(const std::string& path, const std::string& interface) {
    auto file = std::make_unique<std::ofstream>(path, std::ios::app);
    if (!*file) return false;
    outputs_.push_back({file.get(), true, interface});
    files_.push_back(std::move(file));
    return true;
}

void TrafficLog::add_gridconnect_stream(std::ostream& out) {
    outputs_.push_back({&out, false, {}});
}

void TrafficLog::add_candump_stream(std::ostream& out, const std::string& interface) {
    outputs_.push_back({&out, true, interface});
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
        out.stream->write(line_.data(), static_cast<std::streamsize>(line_.size()));
        out.stream->flush();
    }
}

bool TrafficLog::ok() const {
    for (const Output& out : outputs_) {
        if (!*out.stream) return false;
    }
    return true;
}

}  // namespace olcb
