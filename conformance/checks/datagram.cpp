// Datagram transport as seen on the CDI reads, and the run's temporary rejects.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

void datagram_ok_before_reply(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& d = run.probe<CdiDownload>();
    if (!d.read_ok) return run.out(spec).skip("depends on cdi.read: no read reply to judge");
    if (d.result.datagram_ok_seen)
        return run.out(spec).pass("Datagram Received OK precedes every read reply");
    // Only MemoryConfigurationTN §2.4.5 orders them; a missing OK shows as a timeout elsewhere.
    run.out(spec).warn(
        "a read reply came before its Datagram Received OK (the technical note orders "
        "the OK first; tools that wait for it stall)");
}

void datagram_reply_pending(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& d = run.probe<CdiDownload>();
    if (!d.read_ok) return run.out(spec).skip("depends on cdi.read: no read reply to judge");
    // An OK that came after its reply was not seen when the read ended: its flags are unknown.
    if (!d.result.datagram_ok_seen)
        return run.out(spec).skip(
            "depends on datagram.ok-before-reply: the Datagram Received OK "
            "came after the reply");
    run.out(spec).judge(d.result.reply_pending, "Datagram Received OK of a read has Reply Pending",
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
         "every datagram is answered with Datagram Received OK or Rejected; only the technical "
         "note "
         "orders the OK before the reply (a late OK WARNs)",
         "", "(every CDI read) Datagram Received OK arrives before each read reply",
         datagram_ok_before_reply},
        {"datagram.reply-pending", 140, Category::kDatagram, "MemoryConfigurationS §4.4",
         Strength::kShall, "the Datagram Received OK to a Read carries Reply Pending", "",
         "(every CDI read) the Datagram Received OK has Reply Pending", datagram_reply_pending},
        {"datagram.temporary-rejects", 750, Category::kDatagram, "DatagramTransportS §6.2",
         Strength::kMay, "a receiver may reject a datagram temporarily; the sender resends", "",
         "(whole run) PASS when no datagram was rejected temporarily; WARN with the count when "
         "some "
         "were and the retries succeeded",
         datagram_temporary_rejects},
    };
}

}  // namespace olcb::conform::checks
