#include "cdi/value.hpp"

namespace olcb::cdi {

const char* value_kind_name(ValueKind kind) {
    switch (kind) {
        case ValueKind::kInt:
            return "int";
        case ValueKind::kFloat:
            return "float";
        case ValueKind::kString:
            return "string";
        case ValueKind::kEventId:
            return "eventid";
    }
    return "unknown";
}

}  // namespace olcb::cdi
