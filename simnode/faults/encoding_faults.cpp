// Encoding faults: variables stored in another byte order, termination or width than CDI
// 5.1.4 says.
#include <algorithm>

#include "cdi/document.hpp"
#include "cdi/float_codec.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

template <cdi::ElementKind Kind>
void reversed(StoredValue& v, FaultValue) {
    if (v.element.kind == Kind) std::reverse(v.bytes.begin(), v.bytes.end());
}

void space_padded(StoredValue& v, FaultValue) {
    if (v.element.kind != cdi::ElementKind::kString) return;
    auto nul = std::find(v.bytes.begin(), v.bytes.end(), std::uint8_t{0});
    std::fill(nul, v.bytes.end(), std::uint8_t{' '});
}

void narrowed(StoredValue& v, FaultValue) {
    if (v.element.kind != cdi::ElementKind::kFloat) return;
    std::span<std::uint8_t> bytes = v.bytes;
    if (bytes.size() == 2) {
        bytes[1] &= 0xF8;  // no smaller float: drop the three lowest mantissa bits
        return;
    }
    const auto value = cdi::decode_float(bytes);
    if (!value) return;
    const double rounded = cdi::round_to_float_size(*value, bytes.size() / 2);
    const auto out = cdi::encode_float(rounded, bytes.size(), cdi::CodecMode::kLenient);
    if (out && out->size() == bytes.size()) std::copy(out->begin(), out->end(), bytes.begin());
}

}  // namespace

std::vector<FaultDecl> encoding_faults() {
    return {
        {
            .name = "int-byte-order",
            .order = 80,
            .summary = "<int> values stored little-endian",
            .rule_broken = "CDI 5.1.4.2: `<int>` values are stored big-endian (fact sheet "
                           "conventions)",
            .client_sees = "every `<int>` wholly inside a write is stored byte-reversed, "
                           "defaults too: a read-back differs from what was written (Trim "
                           "default −5 reads `FB FF`)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.int", "encoding.original-restored", "encoding.restore"},
            .hooks = {.store = reversed<cdi::ElementKind::kInt>},
        },
        {
            .name = "string-unterminated",
            .order = 90,
            .summary = "<string> values fill the field with spaces, no NUL",
            .rule_broken = "CDI 5.1.4.3: a `<string>` shorter than its size is NUL-terminated",
            .client_sees = "strings are padded with spaces to the full size, never a NUL (an "
                           "empty default reads as all spaces)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.stored-strings", "encoding.string"},
            .hooks = {.store = space_padded},
        },
        {
            .name = "eventid-byte-order",
            .order = 100,
            .summary = "<eventid> values stored little-endian",
            .rule_broken = "CDI 5.1.4.4 / Events: an `<eventid>` is 8 bytes big-endian (fact "
                           "sheet 9)",
            .client_sees = "event IDs stored byte-reversed; the node also advertises the "
                           "reversed IDs (it reads its own memory big-endian)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.eventid", "encoding.original-restored"},
            .hooks = {.store = reversed<cdi::ElementKind::kEventId>},
        },
        {
            .name = "float-width",
            .order = 110,
            .summary = "<float> values stored with the next smaller precision",
            .rule_broken = "CDI 5.1.4.5: a `<float>` of size 2/4/8 is IEEE-754 half/single/double",
            .client_sees = "a written double is stored with single precision, a single with half "
                           "precision, a half loses its 3 lowest mantissa bits: 0.1 reads back "
                           "as 0.100000001490116",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.float"},
            .hooks = {.store = narrowed},
        },
    };
}

}  // namespace olcb::simnode
