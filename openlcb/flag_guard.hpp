// Keeps a re-entrancy flag set for a scope, even when a handler throws.
#pragma once

namespace olcb {

/// Sets `flag` on construction and clears it on destruction.
class FlagGuard {
public:
    /// Sets the flag.
    explicit FlagGuard(bool& flag) : flag_(flag) { flag_ = true; }
    /// Clears the flag.
    ~FlagGuard() { flag_ = false; }
    FlagGuard(const FlagGuard&) = delete;
    FlagGuard& operator=(const FlagGuard&) = delete;

private:
    bool& flag_;
};

}  // namespace olcb
