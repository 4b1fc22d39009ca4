// The exchanges with a clock generator that the clock checks judge, each a probe asked once per
// clock and run: the Query that saves its state (ClockQuery), the Set exchange and the run
// through midnight, each followed by the saved state set back (SetSession, RunSession), and the
// node's start-up (Startup). A session that sets a clock runs only when its state was saved.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "conformance/checks/clock_observer.hpp"

namespace olcb::conform::checks::clocks {

/// The clock's state from a Query, saved before anything is set (clock.query judges it).
struct ClockQuery {
    using Key = std::uint64_t;  ///< the clock's 6-byte ID
    Sync sync;
    TimePoint sent{};
    bool next_awaited = false;  ///< item 6 was waited for (the next minute was near enough)
    Duration next_wait{};

    static ClockQuery ask(CheckRun& run, Key clock);
};

/// Waits for item 6 of a sequence read from the clock's messages since mark when it is owed and
/// near: at most a fast minute at its rate plus the answer window, if that is within 10 s
/// (--thorough: 65 s). `awaited` and `waited` say whether and how long.
Sync await_next(CheckRun& run, NodeId clock, std::size_t mark, Sync sync, bool& awaited,
                Duration& waited);

/// A Set sent and the Report the node produced for it (§6.5).
struct Echo {
    ClockEvent asked;
    std::optional<ClockEvent> got;  ///< the first Report of the same form after it
    Duration after{};               ///< how long after the Set it came
};

/// What the running exchange saw: 23:59 and 00:00 asked for by Consumer Identified, the clock set
/// to 2023-12-31 23:58 at kRunQuarters (or the rate it took instead) and started.
struct RunSeen {
    std::string not_run;         ///< why the clock was not run ("" when it was)
    int rate = 0;                ///< the effective rate (the Set Rate's report)
    TimePoint started{};         ///< Start sent
    std::vector<ClockMsg> msgs;  ///< the clock's messages from the first Set on
};

/// Sets of the saved state (advanced by the time passed) and what a Query then showed.
struct Restore {
    std::string to;       ///< what was set back ("" when nothing was)
    std::string problem;  ///< "" when the clock came back as it was
};

/// The Set exchange: the clock stopped at 2023-07-22 01:23 and rate 4.00, Set Rate a second after
/// the others; then Set Date 02-30 and a Query; then the saved state back.
struct SetSession {
    using Key = std::uint64_t;  ///< the clock's 6-byte ID
    std::string not_run;        ///< why nothing was set ("" when the session ran)
    std::vector<Echo> echoes;
    TimePoint first_set{}, last_set{}, set_end{};
    std::vector<ClockMsg> set_msgs;  ///< the clock's messages from the first Set to set_end
    Echo odd_date;                   ///< Set Date 02-30 and its report
    Sync odd_sync;                   ///< the sequence a Query brought right after it
    Restore restore;

    static SetSession ask(CheckRun& run, Key clock);
};

/// The running exchange (RunSeen), then the saved state back.
struct RunSession {
    using Key = std::uint64_t;
    std::string not_run;
    RunSeen run;
    Restore restore;

    static RunSession ask(CheckRun& run, Key clock);
};

const ClockQuery& query_of(CheckRun& run, NodeId clock);
const SetSession& set_session(CheckRun& run, NodeId clock);
const RunSession& run_session(CheckRun& run, NodeId clock);

/// The sessions that set the clock in this run, whichever the selected checks made (nullptr:
/// not made); when neither was, the Set exchange is made now. For the checks that judge every
/// session (clock.report-frequency, clock.restored), so that a selection of the Set checks or
/// of the midnight checks does not also make the other session.
struct SessionsMade {
    const SetSession* set = nullptr;
    const RunSession* running = nullptr;
    /// Why nothing was set ("" when a session ran).
    std::string not_run() const;
};
SessionsMade sessions_made(CheckRun& run, NodeId clock);

/// Where the node's last start-up begins in the session's messages (its Initialization
/// Complete); with --reboot and none seen yet, a Reset/Reboot is sent for it.
struct Startup {
    std::optional<std::size_t> mark;  ///< nullopt: no start-up seen
    std::string refused;              ///< why the node did not restart ("" when not refused)
    static Startup ask(CheckRun& run);
};

/// Why a start-up check cannot judge ("" when a start-up was seen).
std::string startup_gate(CheckRun& run);

}  // namespace olcb::conform::checks::clocks
