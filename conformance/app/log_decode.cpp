#include "conformance/app/log_decode.hpp"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <string_view>

#include "base/hex.hpp"
#include "base/utf8.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_defs.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/candump_log.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/monitor.hpp"

namespace olcb::conform {

namespace {

// lcc-conform's status for a file it cannot read, as for every other usage error.
constexpr int kUnreadable = 2;
// SocketCAN's error-frame flag (linux/can.h CAN_ERR_FLAG): candump prints it inside the ID.
constexpr std::uint32_t kCanErrorFlag = 0x20000000;

enum class LineRead : std::uint8_t { kLine, kOverlong, kEnd };

// The next line of `in` without its line ending; only kMaxLogLine + 1 characters are kept, the
// rest of a longer line is read and dropped, so one huge line cannot fill memory.
LineRead read_line(std::istream& in, std::string& line) {
    line.clear();
    std::streambuf* buf = in.rdbuf();
    if (buf == nullptr) return LineRead::kEnd;
    using Traits = std::char_traits<char>;
    bool read_any = false;
    bool dropped = false;
    for (Traits::int_type c = buf->sbumpc(); !Traits::eq_int_type(c, Traits::eof());
         c = buf->sbumpc()) {
        read_any = true;
        if (c == '\n') break;
        if (line.size() <= kMaxLogLine) {
            line.push_back(Traits::to_char_type(c));
        } else {
            dropped = true;
        }
    }
    if (!read_any) return LineRead::kEnd;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return dropped || line.size() > kMaxLogLine ? LineRead::kOverlong : LineRead::kLine;
}

std::string_view trim(std::string_view s) {
    const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v'; };
    while (!s.empty() && space(s.front())) s.remove_prefix(1);
    while (!s.empty() && space(s.back())) s.remove_suffix(1);
    return s;
}

// The n-th word (from 0) of a line, words separated by spaces or tabs; empty when there is none.
std::string_view word(std::string_view s, std::size_t n) {
    for (std::size_t i = 0;; ++i) {
        const auto start = s.find_first_not_of(" \t");
        if (start == std::string_view::npos) return {};
        s.remove_prefix(start);
        const std::string_view w = s.substr(0, s.find_first_of(" \t"));
        if (i == n) return w;
        s.remove_prefix(w.size());
    }
}

// Why a line shaped like candump -L is not decoded; CAN FD and error frames are named because a
// user comparing with candump's own output looks for them.
std::string candump_reason(std::string_view line) {
    const std::string_view frame = word(line, 2);
    const auto hash = frame.find('#');
    if (hash != std::string_view::npos && frame.substr(hash).starts_with("##"))
        return "CAN FD frame (decode reads classic CAN frames only)";
    if (hash == 8) {
        std::uint32_t id = 0;
        bool hex = true;
        for (const char c : frame.substr(0, hash)) {
            const int v = base::hex_value(c);
            hex = hex && v >= 0;
            id = id << 4 | static_cast<std::uint32_t>(v < 0 ? 0 : v);
        }
        if (hex && (id & kCanErrorFlag) != 0) return "CAN error frame";
    }
    return "not a valid candump -L frame";
}

// The state of one decode: the monitor (aliases learnt, datagrams in progress) and the counts.
class LogDecoder {
public:
    LogDecoder(std::ostream& out, std::ostream& err) : out_(out), err_(err) {
        // Memory Configuration datagrams are most of a configuration tool's traffic; described,
        // they read as commands ("read FF @0x00000000 x64") instead of hex.
        monitor_.register_datagram_decoder(
            memory::kDatagramType,
            [](std::span<const std::uint8_t> bytes) { return memory::describe(bytes); });
    }

    void line(std::size_t number, std::string_view text) {
        text = trim(text);
        if (text.empty()) return;
        if (text.front() == '(') {
            candump_line(number, text);
        } else if (text.front() == ':') {
            const auto frame = gridconnect::parse_frame(text);
            if (!frame) return skip(number, "not a valid GridConnect frame");
            out_ << decoded(*frame) << '\n';
            ++counts_.frames;
        } else {
            skip(number, "neither a candump -L nor a GridConnect frame");
        }
    }

    void skip(std::size_t number, std::string_view reason) {
        ++counts_.skipped;
        if (counts_.skipped <= kMaxSkipReports)
            err_ << "decode: line " << number << ": " << reason << "\n";
    }

    DecodeCounts finish() {
        if (counts_.skipped > kMaxSkipReports)
            err_ << "decode: ... " << counts_.skipped - kMaxSkipReports << " more skipped lines\n";
        err_ << "decode: " << counts_.frames << " frames, " << counts_.skipped
             << " lines skipped\n";
        return counts_;
    }

private:
    void candump_line(std::size_t number, std::string_view text) {
        const auto entry = candump::parse(text);
        if (!entry) return skip(number, candump_reason(text));
        // The digits between the parentheses, as the log has them (parse() checked them).
        const std::string_view stamp = text.substr(1, text.find(')') - 1);
        // The interface name is untrusted text: no control byte of it reaches the terminal.
        out_ << stamp << ' ' << base::printable(entry->interface) << ' ' << decoded(entry->frame)
             << '\n';
        ++counts_.frames;
    }

    std::string decoded(const CanFrame& frame) {
        // Per-frame mode answers every frame; the bare frame text keeps one line per frame if not.
        auto text = monitor_.decode(frame);
        return text ? std::move(*text) : gridconnect::format(frame);
    }

    std::ostream& out_;
    std::ostream& err_;
    Monitor monitor_;
    DecodeCounts counts_;
};

}  // namespace

DecodeCounts decode_log(std::istream& in, std::ostream& out, std::ostream& err) {
    LogDecoder decoder(out, err);
    std::string line;
    std::size_t number = 0;
    for (;;) {
        const LineRead got = read_line(in, line);
        if (got == LineRead::kEnd) break;
        ++number;
        if (got == LineRead::kOverlong) {
            decoder.skip(
                number, "longer than " + std::to_string(kMaxLogLine) + " characters (not a frame)");
        } else {
            decoder.line(number, line);
        }
    }
    return decoder.finish();
}

int run_decode(const std::string& path, std::istream& standard_input, std::ostream& out,
               std::ostream& err) {
    if (path == "-") {
        decode_log(standard_input, out, err);
        return 0;
    }
    // A directory opens for reading but yields nothing: said as the system would say it.
    std::error_code ignored;
    if (std::filesystem::is_directory(path, ignored)) {
        err << "lcc-conform: cannot read " << path << ": " << std::strerror(EISDIR) << "\n";
        return kUnreadable;
    }
    errno = 0;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        const int why = errno;
        err << "lcc-conform: cannot read " << path << ": "
            << (why != 0 ? std::strerror(why) : "cannot be opened") << "\n";
        return kUnreadable;
    }
    decode_log(in, out, err);
    return 0;
}

}  // namespace olcb::conform
