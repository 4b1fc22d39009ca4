// libFuzzer target: bytes become a sequence of CAN frames (and clock steps) fed to the message
// assembler, the datagram receiver and sender; their invariants are asserted after every frame.
#include <cstdint>
#include <cstdlib>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_transport.hpp"

namespace {

void check(bool ok) {
    if (!ok) std::abort();
}

constexpr std::uint16_t kAliases[] = {0x343, 0x12C, 0x555, 0x001};
constexpr std::uint16_t kCanMtis[] = {0xA08, 0xA28, 0xA48, 0x068, 0xF16, 0xF15, 0xF14, 0x490};
constexpr std::size_t kMaxBuffers = 3;
constexpr std::size_t kMaxInProgress = 4;
constexpr std::size_t kMaxPayload = 40;

struct Reader {
    const std::uint8_t* data;
    std::size_t size;
    std::size_t pos = 0;
    bool more() const { return pos < size; }
    std::uint8_t next() { return pos < size ? data[pos++] : 0; }
};

}  // namespace

namespace olcb {
namespace {

// The next frame: a raw 29-bit header when kind's top bit is set, else a header of the frame
// format kind selects between the aliases (and MTIs) sel selects; then up to 8 data bytes.
CanFrame read_frame(Reader& in, std::uint8_t kind, std::uint8_t sel) {
    CanFrame frame;
    if (kind & 0x80) {
        frame.id = (std::uint32_t{in.next()} << 24 | std::uint32_t{in.next()} << 16 |
                    std::uint32_t{in.next()} << 8 | in.next()) &
                   can::kHeaderMask;
        frame.remote = (kind & 0x40) != 0;
    } else {
        const auto format = static_cast<can::FrameFormat>(kind & 7);
        const std::uint16_t src = kAliases[sel & 3];
        const std::uint16_t dst = kAliases[(sel >> 2) & 3];
        frame.id = format == can::FrameFormat::kGlobalAddressed
                       ? can::message_header(kCanMtis[(sel >> 4) & 7], src)
                       : can::addressed_header(format, dst, src);
    }
    frame.len = static_cast<std::uint8_t>(in.next() % 9);
    for (std::size_t i = 0; i < frame.len; ++i) frame.data[i] = in.next();
    return frame;
}

void check_message(const Message& m) {
    check(m.payload.size() <= (m.mti == Mti::kDatagram ? 72u : kMaxPcerPayload));
    check(m.payload.size() <= 8 || m.payload.size() <= kMaxPayload || m.mti == Mti::kDatagram);
}

// Takes every received datagram, answering it as sel says, and every frame and outcome queued.
void drain(DatagramReceiver& receiver, DatagramSender& sender, std::uint8_t sel) {
    while (auto d = receiver.pop_datagram()) {
        check(d->payload.size() <= datagram::kMaxSize);
        if (sel & 0x40) {
            receiver.accept(d->source_alias, sel);
        } else if (sel & 0x80) {
            receiver.reject(d->source_alias, 0x1042);
        }  // else left unanswered: holds a buffer
    }
    while (auto f = receiver.pop_frame()) check(f->len <= 8);
    while (auto f = sender.pop_frame()) check(f->len <= 8);
    while (sender.pop_outcome()) {
    }
}

}  // namespace
}  // namespace olcb

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace olcb;
    Reader in{data, size};
    MessageAssembler assembler({.max_in_progress = kMaxInProgress,
                                .max_payload = kMaxPayload,
                                .timeout = std::chrono::seconds(3),
                                .datagrams = true});
    DatagramReceiver receiver({.max_buffers = kMaxBuffers});
    receiver.set_alias(0x343);
    DatagramSender sender({.max_resends = 2, .max_queued = 8});
    sender.set_alias(0x343);
    TimePoint now{};

    while (in.more()) {
        const std::uint8_t kind = in.next();
        const std::uint8_t sel = in.next();
        const CanFrame frame = read_frame(in, kind, sel);
        now += std::chrono::milliseconds(in.next() * 20);

        if (auto m = assembler.on_frame(frame, now)) check_message(*m);
        receiver.on_frame(frame, now);
        sender.on_frame(frame, now);
        if (kind & 0x20) sender.send(kAliases[sel & 3], {frame.data.data(), frame.len}, now);
        assembler.poll(now);
        receiver.poll(now);
        sender.poll(now);

        drain(receiver, sender, sel);
        check(assembler.in_progress() <= kMaxInProgress);
        check(receiver.buffers_in_use() <= kMaxBuffers);
        check(sender.queued() <= 8);
    }
    return 0;
}
