// Datagram transport as seen on the CDI reads, and the run's temporary rejects.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

// SKIPs (and returns false) when no datagram read of the CDI came back to judge.
bool datagram_read(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& d = run.probe<CdiDownload>();
    if (d.datagram.ok) return true;
    run.out(spec).skip("depends on cdi.read: no datagram read reply to judge (" +
                       describe(d.datagram) + ")");
    return false;
}

// Which reads were judged: all of the download, or the samples of a stream-read CDI.
std::string reads_judged(const CdiDownload& d) {
    return d.by_stream ? "the datagram reads of the CDI (" + d.sampled + ")" : "every CDI read";
}

void datagram_ok_before_reply(CheckRun& run, const CheckSpec& spec) {
    if (!datagram_read(run, spec)) return;
    const CdiDownload& d = run.probe<CdiDownload>();
    // Noted by the session over the whole run so far, not only the CDI reads.
    const NodeTrack t = run.session().track(run.node().id);
    if (t.never_acks)
        return run.out(spec).fail(
            "no Datagram Received OK or Rejected for " + std::to_string(t.unacknowledged) +
                " datagrams whose replies came (the first waited out the timeout; later replies "
                "were taken as they came)",
            "Datagram Received OK (or Rejected) for every datagram", "replies without any OK");
    if (d.datagram.datagram_ok_seen)
        return run.out(spec).pass("Datagram Received OK precedes the read reply in " +
                                  reads_judged(d));
    // Only MemoryConfigurationTN §2.4.5 orders them; a missing OK shows as a timeout elsewhere.
    run.out(spec).warn(
        "a read reply came before its Datagram Received OK (the technical note orders "
        "the OK first; tools that wait for it stall)");
}

void datagram_reply_pending(CheckRun& run, const CheckSpec& spec) {
    if (!datagram_read(run, spec)) return;
    const CdiDownload& d = run.probe<CdiDownload>();
    // An OK that came after its reply was not seen when the read ended: its flags are unknown.
    if (!d.datagram.datagram_ok_seen)
        return run.out(spec).skip(
            "depends on datagram.ok-before-reply: the Datagram Received OK "
            "came after the reply");
    const bool pending = d.datagram.reply_pending;
    run.out(spec).judge(pending,
                        pending ? "Datagram Received OK has Reply Pending in " + reads_judged(d)
                                : "Datagram Received OK without Reply Pending (flag 0x80 clear) "
                                  "in " +
                                      reads_judged(d) + ", yet a read reply followed",
                        "flag 0x80", "flags without 0x80");
}

void datagram_temporary_rejects(CheckRun& run, const CheckSpec& spec) {
    // Temporary rejects are legal (the retried request succeeded, or another check failed), but
    // a node that needs them on an idle bus is worth a look: warn, never fail.
    const unsigned n = run.heard().temporary_rejects;
    if (n == 0) return run.out(spec).pass("no datagram was rejected temporarily");
    run.out(spec).warn(std::to_string(n) + " datagrams rejected temporarily (0x2xxx) and retried");
}

}  // namespace

std::vector<CheckSpec> datagram_checks() {
    return {
        {"datagram.ok-before-reply", 130, Category::kDatagram,
         "DatagramTransportS §6; MemoryConfigurationS §4.4; MemoryConfigurationTN §2.4.5",
         Strength::kShall,
         "every datagram is answered with Datagram Received OK or Rejected (none at all FAILs); "
         "only the technical note orders the OK before the reply (a late OK WARNs)",
         "", "(every datagram read of the CDI) Datagram Received OK arrives before each read reply",
         datagram_ok_before_reply},
        {"datagram.reply-pending", 140, Category::kDatagram, "MemoryConfigurationS §4.4",
         Strength::kShall, "the Datagram Received OK to a Read carries Reply Pending", "",
         "(every datagram read of the CDI) the Datagram Received OK has Reply Pending",
         datagram_reply_pending},
        {"datagram.temporary-rejects", 750, Category::kDatagram, "DatagramTransportS §6.2",
         Strength::kMay, "a receiver may reject a datagram temporarily; the sender resends", "",
         "(whole run) PASS when no datagram was rejected temporarily; WARN with the count when "
         "some "
         "were and the retries succeeded",
         datagram_temporary_rejects},
    };
}

}  // namespace olcb::conform::checks
