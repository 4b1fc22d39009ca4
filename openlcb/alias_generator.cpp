#include "openlcb/alias_generator.hpp"

namespace olcb {

std::uint16_t AliasGenerator::next() {
    if (started_) state_ = step(state_);
    started_ = true;
    std::uint16_t alias = alias_of(state_);
    // Terminates: a zero alias cannot repeat forever because the step is a full-period LCG.
    while (alias == 0) {
        state_ = step(state_);
        alias = alias_of(state_);
    }
    return alias;
}

}  // namespace olcb
