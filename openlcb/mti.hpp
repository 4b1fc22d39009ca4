// Message Type Indicators of MessageNetworkS (fact sheet 2.1, 3) and their bit fields.
#pragma once

#include <cstdint>
#include <string_view>

namespace olcb {

/// Every 16-bit MTI the fact sheet lists.
enum class Mti : std::uint16_t {
    kInitializationComplete = 0x0100,
    kInitializationCompleteSimple = 0x0101,
    kVerifyNodeIdAddressed = 0x0488,
    kVerifyNodeIdGlobal = 0x0490,
    kVerifiedNodeId = 0x0170,
    kVerifiedNodeIdSimple = 0x0171,
    kOptionalInteractionRejected = 0x0068,
    kTerminateDueToError = 0x00A8,
    kProtocolSupportInquiry = 0x0828,
    kProtocolSupportReply = 0x0668,
    kIdentifyConsumer = 0x08F4,
    kConsumerRangeIdentified = 0x04A4,
    kConsumerIdentifiedValid = 0x04C4,
    kConsumerIdentifiedInvalid = 0x04C5,
    kConsumerIdentifiedReserved = 0x04C6,
    kConsumerIdentifiedUnknown = 0x04C7,
    kIdentifyProducer = 0x0914,
    kProducerRangeIdentified = 0x0524,
    kProducerIdentifiedValid = 0x0544,
    kProducerIdentifiedInvalid = 0x0545,
    kProducerIdentifiedReserved = 0x0546,
    kProducerIdentifiedUnknown = 0x0547,
    kIdentifyEventsAddressed = 0x0968,
    kIdentifyEventsGlobal = 0x0970,
    kLearnEvent = 0x0594,
    kEventReport = 0x05B4,
    kEventReportWithPayload = 0x0F14,
    kSnipRequest = 0x0DE8,
    kSnipReply = 0x0A08,
    kDatagram = 0x1C48,
    kDatagramReceivedOk = 0x0A28,
    kDatagramRejected = 0x0A48,
    kStreamInitiateRequest = 0x0CC8,
    kStreamInitiateReply = 0x0868,
    kStreamDataSend = 0x1F88,
    kStreamDataProceed = 0x0888,
    kStreamDataComplete = 0x08A8,
    kTractionControlCommand = 0x05EB,
    kTractionControlReply = 0x01E9,
};

/// MTI bit fields (fact sheet 2.1).
namespace mti_bits {
inline constexpr std::uint16_t kReserved = 0xC000;  ///< always 0
inline constexpr std::uint16_t kSpecial = 0x2000;   ///< not forwarded by gateways
inline constexpr std::uint16_t kStreamOrDatagram = 0x1000;
inline constexpr std::uint16_t kPriority = 0x0C00;  ///< 0 = highest
inline constexpr std::uint16_t kTypeWithinPriority = 0x03E0;
inline constexpr std::uint16_t kSimpleProtocol = 0x0010;  ///< simple nodes must receive it
inline constexpr std::uint16_t kAddressPresent = 0x0008;
inline constexpr std::uint16_t kEventPresent = 0x0004;
inline constexpr std::uint16_t kModifier = 0x0003;
}  // namespace mti_bits

/// Raw 16-bit value of an MTI.
constexpr std::uint16_t to_u16(Mti mti) {
    return static_cast<std::uint16_t>(mti);
}
/// True when the message carries a destination (addressed message).
constexpr bool is_addressed(Mti mti) {
    return (to_u16(mti) & mti_bits::kAddressPresent) != 0;
}
/// True when the message's first 8 payload bytes are an event ID.
constexpr bool has_event_id(Mti mti) {
    return (to_u16(mti) & mti_bits::kEventPresent) != 0;
}
/// True for messages every simple node must receive.
constexpr bool is_simple(Mti mti) {
    return (to_u16(mti) & mti_bits::kSimpleProtocol) != 0;
}
/// True for datagram and stream data messages (bit 12), which CAN carries in formats 2-5 and 7.
constexpr bool is_stream_or_datagram(Mti mti) {
    return (to_u16(mti) & mti_bits::kStreamOrDatagram) != 0;
}
/// True for the Datagram MTI.
constexpr bool is_datagram(Mti mti) {
    return mti == Mti::kDatagram;
}
/// True for the Stream Data Send MTI.
constexpr bool is_stream_data(Mti mti) {
    return mti == Mti::kStreamDataSend;
}
/// True for messages gateways must not forward.
constexpr bool is_special(Mti mti) {
    return (to_u16(mti) & mti_bits::kSpecial) != 0;
}
/// Priority group 0 (highest) .. 3.
constexpr unsigned priority(Mti mti) {
    return (to_u16(mti) & mti_bits::kPriority) >> 10;
}

/// An MTI and its human-readable name.
struct MtiName {
    Mti mti;                ///< the message type
    std::string_view name;  ///< as decoders print it ("Verify Node ID Global")
};

/// The names of every MTI of the enum, in its order.
inline constexpr MtiName kMtiNames[] = {
    {Mti::kInitializationComplete, "Initialization Complete"},
    {Mti::kInitializationCompleteSimple, "Initialization Complete Simple"},
    {Mti::kVerifyNodeIdAddressed, "Verify Node ID Addressed"},
    {Mti::kVerifyNodeIdGlobal, "Verify Node ID Global"},
    {Mti::kVerifiedNodeId, "Verified Node ID"},
    {Mti::kVerifiedNodeIdSimple, "Verified Node ID Simple"},
    {Mti::kOptionalInteractionRejected, "Optional Interaction Rejected"},
    {Mti::kTerminateDueToError, "Terminate Due To Error"},
    {Mti::kProtocolSupportInquiry, "Protocol Support Inquiry"},
    {Mti::kProtocolSupportReply, "Protocol Support Reply"},
    {Mti::kIdentifyConsumer, "Identify Consumer"},
    {Mti::kConsumerRangeIdentified, "Consumer Range Identified"},
    {Mti::kConsumerIdentifiedValid, "Consumer Identified Valid"},
    {Mti::kConsumerIdentifiedInvalid, "Consumer Identified Invalid"},
    {Mti::kConsumerIdentifiedReserved, "Consumer Identified Reserved"},
    {Mti::kConsumerIdentifiedUnknown, "Consumer Identified Unknown"},
    {Mti::kIdentifyProducer, "Identify Producer"},
    {Mti::kProducerRangeIdentified, "Producer Range Identified"},
    {Mti::kProducerIdentifiedValid, "Producer Identified Valid"},
    {Mti::kProducerIdentifiedInvalid, "Producer Identified Invalid"},
    {Mti::kProducerIdentifiedReserved, "Producer Identified Reserved"},
    {Mti::kProducerIdentifiedUnknown, "Producer Identified Unknown"},
    {Mti::kIdentifyEventsAddressed, "Identify Events Addressed"},
    {Mti::kIdentifyEventsGlobal, "Identify Events Global"},
    {Mti::kLearnEvent, "Learn Event"},
    {Mti::kEventReport, "Producer/Consumer Event Report"},
    {Mti::kEventReportWithPayload, "Event Report With Payload"},
    {Mti::kSnipRequest, "Simple Node Ident Info Request"},
    {Mti::kSnipReply, "Simple Node Ident Info Reply"},
    {Mti::kDatagram, "Datagram"},
    {Mti::kDatagramReceivedOk, "Datagram Received OK"},
    {Mti::kDatagramRejected, "Datagram Rejected"},
    {Mti::kStreamInitiateRequest, "Stream Initiate Request"},
    {Mti::kStreamInitiateReply, "Stream Initiate Reply"},
    {Mti::kStreamDataSend, "Stream Data Send"},
    {Mti::kStreamDataProceed, "Stream Data Proceed"},
    {Mti::kStreamDataComplete, "Stream Data Complete"},
    {Mti::kTractionControlCommand, "Traction Control Command"},
    {Mti::kTractionControlReply, "Traction Control Reply"},
};

/// Human-readable name of a known MTI ("Verify Node ID Global"), or "" when unknown.
constexpr std::string_view mti_name(Mti mti) {
    for (const auto& [known, name] : kMtiNames) {
        if (known == mti) return name;
    }
    return "";
}

/// Name of a raw MTI value, or "" when it is not a known MTI.
constexpr std::string_view mti_name(std::uint16_t raw) {
    return mti_name(static_cast<Mti>(raw));
}

}  // namespace olcb
