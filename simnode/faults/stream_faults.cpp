// Stream faults: what the node does wrong as the source of a stream read.
#include "simnode/faults/fault_families.hpp"

#include "openlcb/stream_defs.hpp"

namespace olcb::simnode {

namespace {

// Data Complete with one byte more than the stream carried.
void count_one_more(StackHooks& hooks, FaultValue) {
    hooks.add_outbound([](Message& msg) {
        if (msg.mti != Mti::kStreamDataComplete) return true;
        auto complete = stream::decode_data_complete(msg.payload);
        if (!complete || !complete->total_bytes) return true;
        ++*complete->total_bytes;
        msg.payload = stream::encode(*complete);
        return true;
    });
}

void drop_complete(StackHooks& hooks, FaultValue) {
    hooks.add_outbound([](const Message& msg) { return msg.mti != Mti::kStreamDataComplete; });
}

void unlimited_window(StackHooks& hooks, FaultValue) {
    hooks.set_window([](std::uint16_t) { return StreamTransport::kUnlimitedWindow; });
}

void double_window(StackHooks& hooks, FaultValue) {
    hooks.set_window([](std::uint16_t buffer) { return 2ULL * buffer; });
}

}  // namespace

std::vector<FaultDecl> stream_faults() {
    return {
        {
            .name = "stream-wrong-count",
            .order = 430,
            .summary = "a stream read's Data Complete counts one byte more than the stream "
                       "carried",
            .rule_broken = "Stream: Data Complete's optional byte count is the number of bytes "
                           "the stream carried (StreamTransportS §6.4)",
            .client_sees = "every stream read ends with a Data Complete counting one byte more "
                           "than the stream sent (the data itself is right); `stream.complete` "
                           "fails",
            .verdict = Verdict::kWarn,
            .category = "stream",
            .checks = {"stream.complete"},
            .hooks = {.stack = count_one_more},
        },
        {
            .name = "stream-no-complete",
            .order = 440,
            .summary = "a stream read never ends with Data Complete",
            .rule_broken = "Stream: a stream read ends with Data Complete (StreamTransportS "
                           "§6.4; MemCfg §4.6)",
            .client_sees = "the stream read sends all its data and never the Data Complete, so "
                           "the reader waits until it gives up; `stream.cdi-read` and "
                           "`stream.complete` fail",
            .verdict = Verdict::kFail,
            .category = "stream",
            .checks = {"stream.cdi-read"},
            .hooks = {.stack = drop_complete},
        },
        {
            .name = "stream-ignore-proceed",
            .order = 450,
            .summary = "a stream read is sent whole, past the granted buffer, without waiting "
                       "for Proceed",
            .rule_broken = "Stream: the source sends at most the granted buffer, then waits for "
                           "Data Proceed (StreamTransportS §6.3)",
            .client_sees = "the whole read is sent at once, past the granted buffer, without "
                           "waiting for any Proceed; `stream.buffer-negotiation` and "
                           "`stream.proceed` fail",
            .verdict = Verdict::kWarn,
            .category = "stream",
            .checks = {"stream.buffer-negotiation"},
            .hooks = {.stack = unlimited_window},
        },
        {
            .name = "stream-exceed-buffer",
            .order = 460,
            .summary = "a stream read sends twice the granted buffer before waiting for each "
                       "Proceed",
            .rule_broken = "Stream: the buffer the sink grants is the most the source sends per "
                           "Proceed (StreamTransportS §4.2)",
            .client_sees = "twice the granted buffer is sent before each wait for Proceed (a "
                           "source using its own proposal, not the grant); "
                           "`stream.buffer-negotiation` fails",
            .verdict = Verdict::kWarn,
            .category = "stream",
            .checks = {"stream.buffer-negotiation"},
            .hooks = {.stack = double_window},
        },
    };
}

}  // namespace olcb::simnode
