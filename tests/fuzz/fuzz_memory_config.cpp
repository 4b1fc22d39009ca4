// Fuzzes the Memory Configuration codec: decoding never crashes, and whatever decodes must
// re-encode to a payload that decodes to the same message. SNIP and ACDI decoders get the same
// bytes since they face the wire too.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "memory/acdi.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/snip.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::span<const std::uint8_t> bytes(data, size);
    using namespace olcb::memory;

    const DecodeResult first = decode(bytes);
    (void)describe(bytes);
    if (first.ok()) {
        const auto payload = encode(first.message);
        if (payload.size() > kMaxDatagram) std::abort();
        const DecodeResult second = decode(payload);
        if (!second.ok() || !(second.message == first.message)) std::abort();
        if (encode(second.message) != payload) std::abort();
    }

    const Snip snip = decode_snip(bytes);
    if (const auto complete = complete_snip_size(bytes); complete && *complete > size) {
        std::abort();
    }
    const auto snip_payload = encode_snip(snip);
    if (snip_payload.size() > kSnipMaxPayload || !is_complete_snip(snip_payload)) std::abort();
    if (encode_snip(decode_snip(snip_payload)) != snip_payload) std::abort();

    const Snip from_acdi = snip_from_acdi(bytes, bytes);
    if (decode_snip(encode_snip(from_acdi)) != from_acdi) std::abort();
    return 0;
}
