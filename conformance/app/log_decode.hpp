// `lcc-conform decode FILE`: a CAN traffic log (candump -L or GridConnect lines) read back as
// one decoded line per frame, with no link, so a user can read what their bus carried.
#pragma once

#include <cstddef>
#include <istream>
#include <ostream>
#include <string>

namespace olcb::conform {

/// Longest line decoded; a longer one is skipped (and read past without being kept, so a file
/// with no newline at all still takes bounded memory).
inline constexpr std::size_t kMaxLogLine = 4096;

/// Skipped lines reported one by one; the rest are only counted ("... N more").
inline constexpr std::size_t kMaxSkipReports = 20;

/// What decode_log() read.
struct DecodeCounts {
    std::size_t frames = 0;   ///< lines decoded, one output line each
    std::size_t skipped = 0;  ///< lines that are not a classic CAN frame
};

/// Decodes `in` line by line, each line's format found on its own: a candump -L line becomes
/// `SECONDS.MICROS IFACE MONITOR-LINE` (the timestamp's digits as the log has them), a
/// GridConnect line `MONITOR-LINE`, where MONITOR-LINE is olcb::Monitor's per-frame line (the
/// frame's GridConnect text, padded, then its meaning; Memory Configuration datagrams described).
/// Blank lines are ignored. Each skipped line (CAN FD, error frame, malformed, longer than
/// kMaxLogLine) is reported on `err` as `decode: line N: REASON`, at most kMaxSkipReports of them;
/// then `decode: ... K more skipped lines` and the summary `decode: F frames, S lines skipped`.
DecodeCounts decode_log(std::istream& in, std::ostream& out, std::ostream& err);

/// The command: decodes the file at `path` ("-" reads `standard_input`). 0 once the file was read
/// (skipped lines included), 2 (lcc-conform's usage status) when it cannot be opened.
int run_decode(const std::string& path, std::istream& standard_input, std::ostream& out,
               std::ostream& err);

}  // namespace olcb::conform
