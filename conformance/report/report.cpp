#include "conformance/report/report.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ostream>

namespace olcb::conform {
namespace {

std::string format_duration(double seconds) {
    if (seconds < 0) seconds = 0;
    const long long total = std::llround(seconds);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%lld:%02lld", total / 60, total % 60);
    return buf;
}

}  // namespace

Summary summarize(const std::vector<NodeReport>& reports) {
    Summary s;
    for (const NodeReport& r : reports) {
        s.pass += r.count(Status::kPass);
        s.fail += r.count(Status::kFail);
        s.warn += r.count(Status::kWarn);
        s.skip += r.count(Status::kSkip);
    }
    return s;
}

bool is_terminal(int fd) {
    return ::isatty(fd) == 1;
}

void ProgressBar::start(std::string label, std::size_t total,
                        std::chrono::steady_clock::time_point now) {
    label_ = std::move(label);
    total_ = total;
    started_ = now;
}

std::string ProgressBar::render(std::size_t done, std::chrono::steady_clock::time_point now) const {
    constexpr std::size_t kWidth = 30;
    double elapsed = std::chrono::duration<double>(now - started_).count();
    std::string line = label_ + " ";
    if (total_ > 0) {
        std::size_t shown = done > total_ ? total_ : done;
        const auto filled = static_cast<std::size_t>(
            static_cast<double>(shown) * static_cast<double>(kWidth) / static_cast<double>(total_));
        line += "[" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] ";
        line += std::to_string(shown) + "/" + std::to_string(total_) + " B";
        if (shown > 0 && elapsed > 0) {
            double rate = static_cast<double>(shown) / elapsed;
            line += " ETA " + format_duration(static_cast<double>(total_ - shown) / rate);
        } else {
            line += " ETA --:--";
        }
    } else {
        line += std::to_string(done) + " B";
    }
    if (elapsed > 0 && done > 0) {
        line += " (" + std::to_string(std::llround(static_cast<double>(done) / elapsed)) + " B/s)";
    }
    return line;
}

void ProgressBar::update(std::size_t done, std::chrono::steady_clock::time_point now) {
    if (!enabled_) return;
    out_ << '\r' << render(done, now) << "\033[K" << std::flush;
    drawn_ = true;
}

void ProgressBar::finish() {
    if (!enabled_ || !drawn_) return;
    out_ << "\r\033[K" << std::flush;
    drawn_ = false;
}

}  // namespace olcb::conform
