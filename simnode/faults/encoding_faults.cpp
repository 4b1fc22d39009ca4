// Encoding faults: variables stored in another byte order, termination or width than CDI
// 5.1.4 says.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

std::vector<FaultDecl> encoding_faults() {
    return {
        {
            .name = "int-byte-order",
            .order = 80,
            .access = flag_field<&FaultSet::int_byte_order>(),
            .summary = "<int> values stored little-endian",
            .rule_broken = "CDI 5.1.4.2: `<int>` values are stored big-endian (fact sheet "
                           "conventions)",
            .client_sees = "every `<int>` wholly inside a write is stored byte-reversed, "
                           "defaults too: a read-back differs from what was written (Trim "
                           "default −5 reads `FB FF`)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.int", "encoding.original-restored", "encoding.restore"},
        },
        {
            .name = "string-unterminated",
            .order = 90,
            .access = flag_field<&FaultSet::string_unterminated>(),
            .summary = "<string> values fill the field with spaces, no NUL",
            .rule_broken = "CDI 5.1.4.3: a `<string>` shorter than its size is NUL-terminated",
            .client_sees = "strings are padded with spaces to the full size, never a NUL (an "
                           "empty default reads as all spaces)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.stored-strings", "encoding.string"},
        },
        {
            .name = "eventid-byte-order",
            .order = 100,
            .access = flag_field<&FaultSet::eventid_byte_order>(),
            .summary = "<eventid> values stored little-endian",
            .rule_broken = "CDI 5.1.4.4 / Events: an `<eventid>` is 8 bytes big-endian (fact "
                           "sheet 9)",
            .client_sees = "event IDs stored byte-reversed; the node also advertises the "
                           "reversed IDs (it reads its own memory big-endian)",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.eventid", "encoding.original-restored"},
        },
        {
            .name = "float-width",
            .order = 110,
            .access = flag_field<&FaultSet::float_width>(),
            .summary = "<float> values stored with the next smaller precision",
            .rule_broken = "CDI 5.1.4.5: a `<float>` of size 2/4/8 is IEEE-754 half/single/double",
            .client_sees = "a written double is stored with single precision, a single with half "
                           "precision, a half loses its 3 lowest mantissa bits: 0.1 reads back "
                           "as 0.100000001490116",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.float"},
        },
    };
}

}  // namespace olcb::simnode
