// libFuzzer target: parse, lay out, enumerate (bounded) and look up arbitrary CDI bytes.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace olcb::cdi;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    ParseResult parsed = parse(bytes);
    if (!parsed.document) return 0;
    LayoutOptions options;
    options.unsigned_offset =
        size % 2 == 0 ? UnsignedOffsetRule::kIgnore : UnsignedOffsetRule::kWrap32;
    LayoutResult laid = build_layout(*parsed.document, options);
    if (!laid.layout) return 0;
    const Layout& layout = *laid.layout;
    constexpr std::uint64_t kMaxVisited = 100000;
    std::uint64_t visited = 0;
    std::uint64_t checksum = 0;
    layout.visit([&](const Cursor& c) {
        checksum += c.address() + c.size() + c.ordinal();
        if (visited < 64) {
            checksum += c.path().size();
            // Every visited variable must be found again, and at() must agree.
            Cursor f = layout.find(c.space(), c.address());
            if (!f.valid() || f.address() > c.address() || f.ordinal() > c.ordinal())
                __builtin_trap();
            if (layout.at(c.ordinal()).address() != c.address()) __builtin_trap();
        }
        return ++visited < kMaxVisited;
    });
    if (layout.variable_count() < kMaxVisited && visited != layout.variable_count())
        __builtin_trap();
    for (const SpaceExtent& e : layout.extents()) {
        for (std::uint64_t a : {e.begin, e.end - 1, (e.begin + e.end) / 2, e.end}) {
            Cursor f = layout.find(e.space, a);
            if (f.valid() && (f.address() > a || f.address() + f.size() <= a)) __builtin_trap();
        }
    }
    (void)layout.at(layout.variable_count() / 2);
    (void)checksum;
    return 0;
}
