// libFuzzer target: arbitrary bytes into the GridConnect streaming parser and parse_frame; every
// frame they accept must survive format -> parse unchanged.
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "openlcb/gridconnect.hpp"

namespace {

void check(bool ok) {
    if (!ok) std::abort();
}

void check_round_trip(const olcb::CanFrame& frame) {
    check(frame.len <= 8);
    check(frame.id <= (frame.extended ? 0x1FFFFFFFu : 0x7FFu));
    const std::string text = olcb::gridconnect::format(frame);
    check(text.size() <= olcb::gridconnect::kMaxFormattedSize);
    const auto again = olcb::gridconnect::parse_frame(text);
    check(again.has_value() && *again == frame);
    check(olcb::gridconnect::format(*again) == text);
    olcb::gridconnect::Parser p;
    int n = 0;
    p.feed(text, [&](const olcb::CanFrame& f) {
        check(f == frame);
        ++n;
    });
    check(n == 1 && p.errors() == 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);

    if (auto frame = olcb::gridconnect::parse_frame(bytes)) check_round_trip(*frame);

    // The same stream fed whole and in uneven chunks must give the same frames.
    olcb::gridconnect::Parser whole;
    std::string seen_whole;
    whole.feed(bytes, [&](const olcb::CanFrame& f) {
        check_round_trip(f);
        olcb::gridconnect::format_to(f, seen_whole);
    });
    olcb::gridconnect::Parser chunked;
    std::string seen_chunked;
    std::size_t pos = 0;
    std::size_t step = 1;
    while (pos < bytes.size()) {
        const auto chunk = bytes.substr(pos, step);
        chunked.feed(
            chunk, [&](const olcb::CanFrame& f) { olcb::gridconnect::format_to(f, seen_chunked); });
        pos += chunk.size();
        step = step % 7 + 1;
    }
    check(seen_whole == seen_chunked);
    check(whole.frames() == chunked.frames() && whole.errors() == chunked.errors());
    check(whole.frames() + whole.errors() <= size);
    return 0;
}
