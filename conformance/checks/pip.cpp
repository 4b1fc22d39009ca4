// The Protocol Support Reply against what the node actually answers.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

void bit_agrees(CheckRun& run, Protocol bit, bool works, const std::string& what) {
    const auto& pip = run.pip();
    if (!pip) return run.out().skip("depends on message.pip-answered: no Protocol Support Reply");
    const bool set = pip->has(bit);
    run.out().judge(set == works, what, works ? "bit set" : "bit clear",
                    set ? "bit set" : "bit clear");
}

}  // namespace

void pip_snip_bit(CheckRun& run) {
    bit_agrees(run, Protocol::kSnip, run.snip_raw().has_value(),
               "PIP SNIP bit agrees with the SNIP answer");
}

void pip_datagram_bit(CheckRun& run) {
    bit_agrees(run, Protocol::kDatagram, run.datagrams_answered(),
               "PIP Datagram bit agrees with datagram answers");
}

void pip_memory_config_bit(CheckRun& run) {
    bit_agrees(run, Protocol::kMemoryConfiguration, run.memory_works(),
               "PIP Memory Configuration bit agrees with memory answers");
}

void pip_cdi_bit(CheckRun& run) {
    bit_agrees(run, Protocol::kCdi, run.cdi().read_ok, "PIP CDI bit agrees with space 0xFF");
}

void pip_acdi_bit(CheckRun& run) {
    run.cdi();
    if (!run.ctx().document) return run.out().skip("depends on cdi.well-formed: no CDI document");
    bit_agrees(run, Protocol::kAcdi, run.ctx().document->acdi.has_value(),
               "PIP ACDI bit iff the CDI has <acdi/>");
}

}  // namespace olcb::conform::checks
