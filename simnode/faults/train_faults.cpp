// Train faults: a train node (train-address) that answers Traction Control wrong, or, where
// OlcbChecker and the standard disagree, differently but within the standard.
#include <utility>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

train::Speed swapped(train::Speed s) {
    const std::uint16_t b = s.bits();
    return train::Speed::from_bits(static_cast<std::uint16_t>((b << 8) | (b >> 8)));
}

// The speeds of a Query Speeds Reply in little-endian order, as a firmware storing the float16
// natively would send them.
void speed_byte_order(TrainReplyTurn& turn, FaultValue) {
    if (auto* r = std::get_if<train::SpeedsReply>(&turn.reply)) {
        r->set = swapped(r->set);
        r->commanded = swapped(r->commanded);
        r->actual = swapped(r->actual);
    }
}

void listener_lost(TrainForwardTurn& turn, FaultValue) {
    turn.drop = true;
}

void heartbeat_ignored(TrainBuild& build, FaultValue) {
    build.heartbeat_stops = false;
}

void no_fdi_space(TrainBuild& build, FaultValue) {
    build.fdi_space = false;
}

void reserve_exclusive(TrainBuild& build, FaultValue) {
    build.reserve_exclusive = true;
}

}  // namespace

std::vector<FaultDecl> train_faults() {
    return {
        {
            .name = "speed-byte-order",
            .order = 500,
            .summary = "a train's Query Speeds Reply carries its speeds little-endian",
            .rule_broken = "TrainControlS §4.4: the speeds are float16 in network byte order",
            .client_sees = "after Set Speed 0.75 reverse (`BA 00`), Query Speeds says `00 BA`, a "
                           "tiny forward speed",
            .verdict = Verdict::kFail,
            .category = "train",
            .checks = {"train.speed"},
            .hooks = {.train_reply = speed_byte_order},
        },
        {
            .name = "listener-not-forwarded",
            .order = 510,
            .summary = "a train forwards nothing to its listeners",
            .rule_broken = "TrainControlS §6.5: operations are forwarded to every listener as the "
                           "flags say, with the P bit set",
            .client_sees = "a listener is attached and listed, but another node's Set Speed never "
                           "reaches it",
            .verdict = Verdict::kFail,
            .category = "train",
            .checks = {"train.listener-forward"},
            .hooks = {.train_forward = listener_lost},
        },
        {
            .name = "heartbeat-ignored",
            .order = 520,
            .summary = "a train asks for heartbeats but keeps running when none comes",
            .rule_broken = "TrainControlS §6.6: no command from the controller by the deadline of "
                           "a Heartbeat Request is taken as Set Speed 0",
            .client_sees = "Heartbeat Requests (with `heartbeat = N`); left unanswered, the Set "
                           "Speed stays as it was",
            .verdict = Verdict::kFail,
            .category = "train",
            .checks = {"train.heartbeat"},
            .hooks = {.train = heartbeat_ignored},
        },
        {
            .name = "no-fdi-space",
            .order = 530,
            .summary = "a train claims FDI in its PIP but serves no space 0xFA",
            .rule_broken = "FunctionDescriptionInformationS §1, §3; TrainControlS §7.2: the FDI "
                           "is read from space 0xFA (OlcbChecker tr070: \"required space 0xFA not "
                           "present\")",
            .client_sees = "PIP FDI bit set; Space Info 0xFA says not present, reads of it fail "
                           "0x1081",
            .verdict = Verdict::kFail,
            .category = "fdi",
            .checks = {"fdi.space"},
            .hooks = {.train = no_fdi_space},
        },
        {
            .name = "reserve-exclusive",
            .order = 540,
            .summary = "a train refuses a second Reserve even from the node holding it",
            .rule_broken = "none: TrainControlS gives Reserve no rules beyond its reply (OpenMRN "
                           "does this; OlcbChecker tr100 fails it as \"second reserve from same "
                           "source rejected\")",
            .client_sees = "Reserve, Reserve: the second Reserve Reply says `01`",
            .verdict = Verdict::kNone,
            .category = "train",
            .checks = {"train.reserve"},
            .hooks = {.train = reserve_exclusive},
        },
    };
}

}  // namespace olcb::simnode
