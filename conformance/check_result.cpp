#include "conformance/check_result.hpp"

#include <algorithm>

namespace olcb::conform {

std::string_view status_name(Status status) {
    switch (status) {
        case Status::kPass:
            return "PASS";
        case Status::kFail:
            return "FAIL";
        case Status::kWarn:
            return "WARN";
        case Status::kSkip:
            return "SKIP";
    }
    return "?";
}

std::string_view category_name(Category category) {
    switch (category) {
        case Category::kFrame:
            return "frame";
        case Category::kMessage:
            return "message";
        case Category::kPip:
            return "pip";
        case Category::kSnip:
            return "snip";
        case Category::kDatagram:
            return "datagram";
        case Category::kMemory:
            return "memory";
        case Category::kCdi:
            return "cdi";
        case Category::kAcdi:
            return "acdi";
        case Category::kEncoding:
            return "encoding";
        case Category::kLink:
            return "link";
        case Category::kNode:
            return "node";
    }
    return "?";
}

std::size_t NodeReport::count(Status status) const {
    return static_cast<std::size_t>(
        std::count_if(checks.begin(), checks.end(),
                      [status](const CheckResult& c) { return c.status == status; }));
}

}  // namespace olcb::conform
