// Memory-config stream reads (MemoryConfigurationS §4.6-4.7 over StreamTransportS): the CDI read
// by stream matches the datagram download; the node waits for Data Proceed, keeps to the buffer
// lcc-conform granted, ends with a Data Complete of the right count, and refuses a read at the
// end of the space as a datagram read. A node that does not advertise streams SKIPs them all.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "base/error_codes.hpp"
#include "conformance/checks/checks.hpp"
#include "memory/memory_config_defs.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

// The windowed read: a small buffer, so a CDI spans several, each held before its Proceed.
constexpr std::uint16_t kProbeBuffer = 64;
constexpr std::uint32_t kProbeWindows = 2;
constexpr Duration kHold = std::chrono::milliseconds(200);

// A read of a few small buffers, each held kHold before lcc-conform's Proceed.
struct WindowedStream : StreamReadResult {
    static WindowedStream ask(CheckRun& run);
};

WindowedStream WindowedStream::ask(CheckRun& run) {
    StreamReadOptions o;
    o.buffer = kProbeBuffer;
    o.count = kProbeBuffer * kProbeWindows + kProbeBuffer / 2;
    o.hold = kHold;
    WindowedStream r{run.session().read_stream(run.node(), Space::kCdi, 0, o)};
    run.tally(r.mem);
    return r;
}

std::string outcome(const StreamReadResult& r) {
    if (r.cut) return std::to_string(r.mem.data.size()) + " bytes and more: the read was cut";
    if (r.mem.ok) return std::to_string(r.mem.data.size()) + " bytes";
    std::string s = describe(r.mem);
    if (!r.initiated) s += ", no Stream Initiate Request";
    if (r.initiated && !r.completed) s += ", no Data Complete";
    return s;
}

// SKIPs (and returns false) when the stream checks cannot run.
bool runnable(CheckRun& run, Verdict& v) {
    const StreamSupport& s = run.probe<StreamSupport>();
    if (!s.skip.empty()) {
        v.skip(s.skip);
        return false;
    }
    return true;
}

void stream_advertised(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    const StreamSupport& s = run.probe<StreamSupport>();
    if (run.options().no_stream) return v.skip("--no-stream");
    if (!s.pip && !s.options) return v.skip("node does not advertise streams");
    // Only write-lengths 0x01 is the standard's claim (§4.14); 0x1000 of the available commands
    // is reserved there (a proposal some stacks send), so it alone proves nothing.
    if (s.lengths && !s.pip) {
        return v.fail("Options write-lengths offer streams (0x01) but PIP has no Stream bit",
                      "PIP Stream bit with Options stream reads", "PIP without Stream");
    }
    if (s.options && !s.pip)
        return v.warn(
            "Options sets the reserved stream-reads bit 0x1000 but PIP has no Stream "
            "bit");
    v.pass(s.options ? "PIP Stream bit and Options stream reads agree"
                     : "PIP Stream bit; Options offers no stream reads (streams for other uses)");
}

void stream_cdi_read(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    if (!runnable(run, v)) return;
    const StreamReadResult& r = run.probe<CdiStream>();
    const CdiDownload& d = run.probe<CdiDownload>();
    if (!r.mem.ok) return v.fail("stream read of the CDI failed", "the CDI", outcome(r));
    if (!d.by_stream) {
        // The stream brought no NUL, so the datagram download was made: compare it all.
        const auto& dg = d.result.data;
        const auto& got = r.mem.data;
        if (got.size() < dg.size() || !std::equal(dg.begin(), dg.end(), got.begin())) {
            const auto diff = std::mismatch(dg.begin(), dg.end(), got.begin(), got.end());
            const auto at = static_cast<std::size_t>(diff.first - dg.begin());
            return v.fail(
                "stream bytes differ from the datagram download at offset " + std::to_string(at),
                std::to_string(dg.size()) + " datagram bytes",
                std::to_string(got.size()) + " stream bytes");
        }
        return v.pass(std::to_string(got.size()) + " bytes by stream, no NUL among them; the " +
                      std::to_string(dg.size()) + " of the datagram download first");
    }
    if (!d.datagram.ok) return v.skip("depends on cdi.read: the datagram reads to compare failed");
    if (!d.sample_difference.empty()) {
        return v.fail("stream and datagram reads of 0xFF differ " + d.sample_difference,
                      "the same bytes in " + d.sampled, d.sample_difference);
    }
    v.pass(std::to_string(d.result.data.size()) + " bytes by stream (buffer " +
           std::to_string(r.granted) + "); datagram reads of " + d.sampled + " agree");
}

void stream_complete(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    if (!runnable(run, v)) return;
    const StreamReadResult& r = run.probe<CdiStream>();
    if (!r.initiated) return v.fail("no stream was opened", "Stream Initiate Request", outcome(r));
    if (!r.completed) return v.fail("the stream never ended", "Data Complete", outcome(r));
    if (!r.reply) return v.fail("no Read Stream Reply OK", "Read Stream Reply OK", outcome(r));
    const std::size_t n = r.mem.data.size();
    if (r.complete_count && *r.complete_count != n) {
        return v.fail("Data Complete's count disagrees with the bytes sent",
                      std::to_string(n) + " bytes", std::to_string(*r.complete_count));
    }
    if (r.reply->count != 0 && r.reply->count < n && r.reply->count != kStreamToEnd) {
        return v.fail("more bytes than the Read Stream Reply's count", std::to_string(n),
                      std::to_string(r.reply->count));
    }
    v.pass("Data Complete after " + std::to_string(n) + " bytes" +
           (r.complete_count ? ", count " + std::to_string(*r.complete_count) : ", no count"));
}

void stream_buffer_negotiation(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    if (!runnable(run, v)) return;
    const StreamReadResult& r = run.probe<WindowedStream>();
    if (!r.initiated) return v.fail("no stream was opened", "Stream Initiate Request", outcome(r));
    if (r.proposed == 0) return v.fail("the node proposed a buffer of 0", "> 0", "0");
    const std::uint64_t granted = r.granted;
    if (r.max_in_window > granted) {
        return v.fail("the node sent more than the granted buffer before a Proceed",
                      "<= " + std::to_string(granted) + " bytes per Proceed",
                      std::to_string(r.max_in_window) + " bytes");
    }
    v.pass("proposed " + std::to_string(r.proposed) + ", granted " + std::to_string(granted) +
           ", at most " + std::to_string(r.max_in_window) + " bytes per Proceed");
}

void stream_proceed(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    if (!runnable(run, v)) return;
    const StreamReadResult& r = run.probe<WindowedStream>();
    if (!r.initiated) return v.fail("no stream was opened", "Stream Initiate Request", outcome(r));
    if (r.during_hold > 0) {
        return v.fail("data kept coming while a full buffer waited for our Proceed",
                      "nothing until Data Proceed",
                      std::to_string(r.during_hold) + " bytes in " + std::to_string(r.proceeds) +
                          " held buffers");
    }
    if (!r.mem.ok) return v.fail("the windowed read did not finish", "Data Complete", outcome(r));
    // The CDI as downloaded (by the whole stream or by datagrams).
    const std::vector<std::uint8_t>& dg = run.probe<CdiDownload>().result.data;
    const std::size_t n = std::min(r.mem.data.size(), dg.size());
    if (!std::equal(r.mem.data.begin(), r.mem.data.begin() + static_cast<std::ptrdiff_t>(n),
                    dg.begin())) {
        return v.fail("windowed stream bytes differ from the CDI download", "same bytes",
                      "different bytes");
    }
    v.pass(std::to_string(r.mem.data.size()) + " bytes in buffers of " + std::to_string(r.granted) +
           ", each held " + std::to_string(kHold.count() / 1'000'000) +
           " ms: nothing came before our Proceed");
}

void stream_read_past_end(CheckRun& run, const CheckSpec& spec) {
    Verdict v = run.out(spec);
    if (!runnable(run, v)) return;
    const SpaceInfo& info = run.probe<SpaceInfoProbe>(0xFF);
    if (!info.present) return v.skip("space 0xFF has no Space Info");
    // Past a too-small highest address the read is inside the space: that check's finding.
    if (const std::string why = highest_too_small(run, 0xFF); !why.empty()) return v.skip(why);
    const std::uint32_t end = info.highest_address + 1;
    StreamReadOptions o;
    o.count = kProbeBuffer;
    const StreamReadResult r = run.session().read_stream(run.node(), Space::kCdi, end, o);
    run.tally(r.mem);
    if (!r.mem.ok && r.mem.error == base::to_u16(base::ErrorCode::kOutOfBounds)) {
        return v.pass(std::string("refused 0x1082 at ") + hex(end, 8) +
                      (r.mem.rejected ? " (Datagram Rejected)" : " (Read Stream Reply Fail)"));
    }
    if (r.mem.ok && r.mem.data.empty()) {
        return v.warn("an empty stream at " + hex(end, 8) +
                      " instead of Read Stream Reply Fail 0x1082 (a datagram read fails there)");
    }
    // MemoryConfigurationS §4.7: a failure with an error code; the code is a recommendation.
    if (!r.mem.ok && !r.mem.timed_out && r.mem.error != 0)
        return v.warn("read at highest+1 of 0xFF refused with " + hex(r.mem.error) +
                      ", not the recommended 0x1082 (MemoryConfigurationTN §2.4.3)");
    v.fail("read at highest+1 of 0xFF not refused", "a failure with an error code (0x1082)",
           outcome(r));
}

}  // namespace

std::vector<CheckSpec> stream_checks() {
    return {
        {"stream.advertised", 670, Category::kStream,
         "MessageNetworkS §3.3.7; MemoryConfigurationS §4.14", Strength::kShall,
         "the PIP Stream bit is set when the node offers stream reads (write-lengths 0x01)", "cd20",
         "PIP Stream bit and Get Configuration Options stream reads (0x1000, or write-lengths "
         "0x01) agree: Options offering stream reads without the PIP bit fails; neither: SKIP",
         stream_advertised},
        {"stream.cdi-read", 680, Category::kStream, "MemoryConfigurationS §4.6, §4.7",
         Strength::kShall, "a Read Stream returns the space's bytes through a stream", "cd20",
         "Read Stream of 0xFF from 0 to the end (count 0xFFFFFFFF), lcc-conform granting the "
         "largest buffer, at most the CDI limit: it is how the CDI is read (up to its NUL), and "
         "datagram reads of its first and last 64 bytes agree byte for byte; a stream without a "
         "NUL is compared with the whole datagram download",
         stream_cdi_read},
        {"stream.complete", 690, Category::kStream, "StreamTransportS §6.4", Strength::kNone,
         "StreamTransportS is not adopted: its rules WARN", "",
         "(the same read) Read Stream Reply OK, Data Complete, its count (if any) equals the bytes "
         "the stream carried",
         stream_complete},
        {"stream.buffer-negotiation", 700, Category::kStream, "StreamTransportS §4.2, §6.3",
         Strength::kNone, "StreamTransportS is not adopted: its rules WARN", "",
         "Read Stream of 0xFF granting a 64-byte buffer: the node proposed > 0 and never sends "
         "more than 64 bytes before lcc-conform's Data Proceed",
         stream_buffer_negotiation},
        {"stream.proceed", 710, Category::kStream, "StreamTransportS §6.3", Strength::kNone,
         "StreamTransportS is not adopted: its rules WARN", "",
         "(the same read) each full buffer held 200 ms before the Proceed: no data meanwhile; "
         "the bytes match the datagram download",
         stream_proceed},
        {"stream.read-past-end", 720, Category::kStream,
         "MemoryConfigurationS §4.3, §4.7; MemoryConfigurationTN §2.4.3", Strength::kShall,
         "an error before the stream is set up is a Read Stream Reply failure with an error code; "
         "0x1082 is recommended (another code WARNs)",
         "",
         "Read Stream at highest+1 of 0xFF: refused 0x1082 (Read Stream Reply Fail, as a "
         "datagram read); an empty stream WARNs; data or no answer fails; SKIP \"depends on\" "
         "the check that found the highest address too small",
         stream_read_past_end},
    };
}

}  // namespace olcb::conform::checks
