// The Protocol Support Reply against what the node actually answers.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

// What the node showed of a protocol, either way, for a FAIL's headline: "PIP SNIP bit clear,
// but the node answers SNIP requests".
struct Behaviour {
    const char* name;  // the bit's
    const char* does;
    const char* does_not;
};

// what: the PASS message.
void bit_agrees(CheckRun& run, const CheckSpec& spec, Protocol bit, bool works,
                const std::string& what, const Behaviour& b) {
    const auto& pip = run.probe<PipProbe>().reply;
    if (!pip)
        return run.out(spec).skip("depends on message.pip-answered: no Protocol Support Reply");
    const bool set = pip->has(bit);
    const std::string state = set ? "bit set" : "bit clear";
    run.out(spec).judge(set == works,
                        set == works ? what
                                     : "PIP " + std::string(b.name) + (set ? " set" : " clear") +
                                           ", but " + (works ? b.does : b.does_not),
                        works ? "bit set" : "bit clear", state);
}

void pip_snip_bit(CheckRun& run, const CheckSpec& spec) {
    bit_agrees(run, spec, Protocol::kSnip, run.probe<SnipProbe>().raw.has_value(),
               "PIP SNIP bit agrees with the SNIP answer",
               {"SNIP bit", "the node answers SNIP requests", "the node does not answer SNIP"});
}

void pip_datagram_bit(CheckRun& run, const CheckSpec& spec) {
    bit_agrees(run, spec, Protocol::kDatagram, datagrams_answered(run),
               "PIP Datagram bit agrees with datagram answers",
               {"Datagram bit", "the node answers datagrams", "no datagram was answered"});
}

void pip_memory_config_bit(CheckRun& run, const CheckSpec& spec) {
    bit_agrees(run, spec, Protocol::kMemoryConfiguration, memory_works(run),
               "PIP Memory Configuration bit agrees with memory answers",
               {"Memory Configuration bit", "the node answers memory-config requests",
                "no memory-config request was answered"});
}

void pip_cdi_bit(CheckRun& run, const CheckSpec& spec) {
    bit_agrees(run, spec, Protocol::kCdi, run.probe<CdiDownload>().read_ok,
               "PIP CDI bit agrees with space 0xFF",
               {"CDI bit", "space 0xFF reads as a CDI", "space 0xFF could not be read"});
}

void pip_acdi_bit(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& cdi = run.probe<CdiDownload>();
    if (!cdi.document) return run.out(spec).skip("depends on cdi.well-formed: no CDI document");
    bit_agrees(run, spec, Protocol::kAcdi, cdi.document->acdi.has_value(),
               "PIP ACDI bit iff the CDI has <acdi/>",
               {"ACDI bit", "the CDI has <acdi/>", "the CDI has no <acdi/>"});
}

}  // namespace

std::vector<CheckSpec> pip_checks() {
    return {
        {"pip.snip-bit", 290, Category::kPip, "SimpleNodeInformationS §6.1; MessageNetworkS §3.3.7",
         Strength::kShall, "a node supporting SNIP sets the SNIP bit", "me30",
         "PIP SNIP bit set iff the node answered SNIP", pip_snip_bit},
        // §3.4.3: the reply "will" carry the bits of what the node implements; no clause says
        // "shall", so a disagreement WARNs (OpenMRN's train node answers datagrams, bit clear).
        {"pip.datagram-bit", 300, Category::kPip, "MessageNetworkS §3.3.7, §3.4.3", Strength::kNone,
         "the Datagram bit is set exactly when the node implements datagrams (any OK or Datagram "
         "Rejected shows it does); §3.4.3 says \"will\", not \"shall\"",
         "me30", "PIP Datagram bit set iff the node answered datagrams", pip_datagram_bit},
        {"pip.memory-config-bit", 310, Category::kPip, "MessageNetworkS §3.3.7, §3.4.3",
         Strength::kNone,
         "the Memory Configuration bit is set exactly when the node implements it; §3.4.3 says "
         "\"will\", not \"shall\"",
         "me30", "PIP Memory Configuration bit set iff memory configuration answered",
         pip_memory_config_bit},
        // MemoryConfigurationS §4.2 puts the CDI in space 0xFF; of the bit only §3.4.3's "will".
        {"pip.cdi-bit", 320, Category::kPip, "MessageNetworkS §3.3.7; MemoryConfigurationS §4.2",
         Strength::kNone,
         "the CDI bit is set exactly when the node provides a CDI; MessageNetworkS §3.4.3 says "
         "\"will\", not \"shall\"",
         "me30", "PIP CDI bit set iff space 0xFF returned data", pip_cdi_bit},
        {"pip.acdi-bit", 330, Category::kPip, "ConfigurationDescriptionInformationS §5.1.2",
         Strength::kShall, "<acdi/> is present exactly when the PIP ACDI bit is set", "",
         "PIP ACDI bit set iff the CDI has <acdi/>", pip_acdi_bit},
    };
}

}  // namespace olcb::conform::checks
