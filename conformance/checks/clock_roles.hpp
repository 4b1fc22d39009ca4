// Which Broadcast Time checks apply to a node and how each clock's verdict is reported: the gates
// (a generator, a consumer, a node the user named) and one result for every clock of the node.
// ClockRoles itself is declared in checks.hpp (message.cpp asks it too).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks::clocks {

/// Why a generator check does not apply ("" when the node generates a clock).
std::string generator_gate(CheckRun& run);
/// Why a consumer check does not apply ("" when the node consumes a clock it does not generate).
std::string consumer_gate(CheckRun& run);
/// Why a check that sets a clock (or feeds a consumer a time) does not run ("" when it does):
/// --read-only, or the node not named with --node.
std::string disruptive_gate(CheckRun& run);

/// The answer window, at least a second (clock timers are coarse).
Duration answer_window(CheckRun& run);

/// One clock's verdict of a check judging every clock of the node.
struct PerClock {
    Status status = Status::kPass;
    std::string message, expected, seen;
};

PerClock pass(std::string message);
PerClock fail(std::string message, std::string expected, std::string seen);
PerClock warn(std::string message);
PerClock skip(std::string why);

/// Judges each clock with one(), then reports one result: the worst verdict, each clock's line.
void judge_clocks(CheckRun& run, const CheckSpec& spec, const std::vector<NodeId>& clocks,
                  const std::function<PerClock(NodeId)>& one);
/// Runs one() on every clock the node generates, or SKIPs saying why it is no generator (or,
/// `disruptive`, why it may not be set).
void each_generated(CheckRun& run, const CheckSpec& spec, bool disruptive,
                    const std::function<PerClock(NodeId)>& one);

}  // namespace olcb::conform::checks::clocks
