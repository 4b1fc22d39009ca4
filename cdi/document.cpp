#include "cdi/document.hpp"

namespace olcb::cdi {

Element::Element() = default;

std::string to_string(WideInt value) {
    if (value == 0) return "0";
    // Work on the unsigned magnitude so the most negative value does not overflow on negation.
    unsigned __int128 magnitude = value < 0 ? ~static_cast<unsigned __int128>(value) + 1
                                            : static_cast<unsigned __int128>(value);
    char digits[48];
    int n = 0;
    while (magnitude != 0) {
        digits[n++] = static_cast<char>('0' + static_cast<int>(magnitude % 10));
        magnitude /= 10;
    }
    std::string out;
    out.reserve(static_cast<std::size_t>(n) + 1);
    if (value < 0) out.push_back('-');
    while (n > 0) out.push_back(digits[--n]);
    return out;
}

const char* kind_name(ElementKind kind) {
    switch (kind) {
        case ElementKind::kGroup:
            return "group";
        case ElementKind::kInt:
            return "int";
        case ElementKind::kString:
            return "string";
        case ElementKind::kEventId:
            return "eventid";
        case ElementKind::kFloat:
            return "float";
        case ElementKind::kAction:
            return "action";
        case ElementKind::kBlob:
            return "blob";
        case ElementKind::kBit:
            return "bit";
        case ElementKind::kUnknown:
            return "unknown";
    }
    return "unknown";
}

}  // namespace olcb::cdi
