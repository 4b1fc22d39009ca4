// GridConnect ASCII framing of CAN frames (fact sheet 8.1): the text every TCP hub and log uses.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>

#include "openlcb/can_frame.hpp"

namespace olcb::gridconnect {

/// ":X19490343N;" — uppercase, 8 ID digits for extended, 3 for standard (":S"), 'R' for remote,
/// no newline.
std::string format(const CanFrame& frame);

/// Appends format(frame) to out (no allocation when out has capacity).
void format_to(const CanFrame& frame, std::string& out);

/// Longest text format() can produce: ":X" + 8 + "N" + 16 + ";".
inline constexpr std::size_t kMaxFormattedSize = 28;

/// Writes format(frame) into buf (at least kMaxFormattedSize chars); returns the length written.
std::size_t format_into(const CanFrame& frame, char* buf);

/// Parses exactly one frame text such as ":x19490343n;" (any case, any ID digit count 1..8,
/// surrounding whitespace allowed); nullopt if invalid.
std::optional<CanFrame> parse_frame(std::string_view text);

/// Streaming parser: feed arbitrary byte chunks; skips whitespace/newlines/garbage and
/// resynchronises on ':'; a frame longer than kMaxFrameText characters is dropped (bounded memory).
class Parser {
public:
    /// Longest frame text accepted, ':' and ';' included; longer texts are counted as errors.
    static constexpr std::size_t kMaxFrameText = 64;

    /// Consumes bytes and calls on_frame(const CanFrame&) for each complete valid frame.
    template <class F>
    void feed(std::string_view bytes, F&& on_frame) {
        const char* p = bytes.data();
        const char* const end = p + bytes.size();
        while (p < end) {
            if (in_frame_) {
                feed_char(*p++, on_frame);
                continue;
            }
            const auto* colon =
                static_cast<const char*>(std::memchr(p, ':', static_cast<std::size_t>(end - p)));
            if (colon == nullptr) return;  // only garbage or whitespace left
            // Fast path: a whole clean frame inside this chunk is parsed in place, no copy.
            const char* limit =
                colon + std::min(end - colon, static_cast<std::ptrdiff_t>(kMaxFrameText));
            const char* q = colon + 1;
            while (q < limit && !kStopChar[static_cast<unsigned char>(*q)]) ++q;
            if (q < limit && *q == ';') {
                deliver(parse_frame(std::string_view(colon, q + 1)), on_frame);
                p = q + 1;
                continue;
            }
            feed_char(*colon, on_frame);
            p = colon + 1;
        }
    }

    /// Number of valid frames delivered so far.
    std::uint64_t frames() const { return frames_; }
    /// Number of frames dropped: invalid syntax, over-long, or interrupted by a new ':'.
    std::uint64_t errors() const { return errors_; }
    /// Forgets a partially received frame (e.g. after a reconnect).
    void reset() {
        in_frame_ = false;
        overflow_ = false;
        len_ = 0;
    }

private:
    // Characters that end the fast path's scan: the frame end, or what the slow path treats
    // specially (a restarting ':' and skipped whitespace).
    static constexpr auto kStopChar = [] {
        std::array<bool, 256> t{};
        for (const char c : {':', ';', ' ', '\t', '\r', '\n'}) {
            t[static_cast<unsigned char>(c)] = true;
        }
        return t;
    }();

    template <class F>
    void deliver(const std::optional<CanFrame>& frame, F& on_frame) {
        if (frame) {
            ++frames_;
            on_frame(*frame);
        } else {
            ++errors_;
        }
    }

    // Byte-at-a-time state machine for frames split across chunks or containing whitespace.
    template <class F>
    void feed_char(char c, F& on_frame) {
        if (c == ':') {
            if (in_frame_) ++errors_;  // a frame cut short by the next ':' is lost
            in_frame_ = true;
            overflow_ = false;
            len_ = 0;
            buf_[len_++] = c;
        } else if (!in_frame_ || c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            return;  // garbage between frames; whitespace is tolerated inside a frame too
        } else if (c == ';') {
            in_frame_ = false;
            if (overflow_ || len_ + 1 > kMaxFrameText) {
                ++errors_;
                return;
            }
            buf_[len_++] = c;
            deliver(parse_frame(std::string_view(buf_, len_)), on_frame);
        } else if (len_ < kMaxFrameText) {
            buf_[len_++] = c;
        } else {
            overflow_ = true;
        }
    }

    char buf_[kMaxFrameText]{};
    std::size_t len_ = 0;
    bool in_frame_ = false;
    bool overflow_ = false;
    std::uint64_t frames_ = 0;
    std::uint64_t errors_ = 0;
};

}  // namespace olcb::gridconnect
