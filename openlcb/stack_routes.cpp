#include "openlcb/stack_routes.hpp"

#include <algorithm>
#include <span>

#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"

namespace olcb {
namespace {

void insert_slot(std::vector<std::size_t>& slots, std::size_t slot) {
    slots.push_back(slot);
}

// Order does not matter: route() sorts what it collects.
void erase_slot(std::vector<std::size_t>& slots, std::size_t slot) {
    const auto it = std::find(slots.begin(), slots.end(), slot);
    if (it == slots.end()) return;
    *it = slots.back();
    slots.pop_back();
}

void set_member(std::vector<std::size_t>& slots, std::size_t slot, bool& member, bool now) {
    if (member == now) return;
    member = now;
    if (now) {
        insert_slot(slots, slot);
    } else {
        erase_slot(slots, slot);
    }
}

constexpr std::uint16_t cmti_of(Mti mti) {
    return to_u16(mti) & 0xFFF;
}

}  // namespace

StackRoutes::StackRoutes(bool share_alias_cache) {
    if (share_alias_cache) shared_ = std::make_shared<AliasCache>();
}

StackRoutes::~StackRoutes() = default;

std::size_t StackRoutes::add(NodeStack& stack) {
    const std::size_t slot = entries_.size();
    entries_.push_back({});
    Entry& e = entries_.back();
    e.stack = &stack;
    ++live_;
    by_node_[stack.node_id()].push_back(slot);
    if (shared_) {
        stack.share_alias_cache(shared_);
    } else {
        insert_slot(learners_, slot);
    }
    refresh(slot);
    return slot;
}

void StackRoutes::remove(std::size_t slot) {
    Entry& e = entries_[slot];
    if (!e.stack) return;
    index(slot, e, false);
    erase_slot(by_node_[e.stack->node_id()], slot);
    erase_slot(learners_, slot);
    if (shared_) e.stack->share_alias_cache(nullptr);
    e = Entry{};
    --live_;
}

void StackRoutes::refresh(std::size_t slot) {
    Entry& e = entries_[slot];
    if (!e.stack) return;
    const NodeStack& s = *e.stack;
    if (const std::uint16_t alias = s.alias(); alias != e.alias) {
        if (e.alias != 0) erase_slot(by_alias_[e.alias], slot);
        if (alias != 0) insert_slot(by_alias_[alias], slot);
        e.alias = alias;
    }
    set_member(filtered_, slot, e.filtered, s.has_inbound_filter());
    set_member(sending_, slot, e.sending, s.sending_datagrams());
    const auto& globals = s.global_can_mtis();
    if (globals ? (e.all_globals || *globals != e.globals) : !e.all_globals) {
        index_globals(slot, e, false);
        e.all_globals = !globals;
        e.globals = globals ? *globals : std::vector<std::uint16_t>{};
        index_globals(slot, e, true);
    }
}

// Takes the slot into (or out of) every index its entry says it belongs to.
void StackRoutes::index(std::size_t slot, Entry& e, bool on) {
    if (e.alias != 0) {
        if (on) {
            insert_slot(by_alias_[e.alias], slot);
        } else {
            erase_slot(by_alias_[e.alias], slot);
        }
    }
    index_globals(slot, e, on);
    if (on) return;
    set_member(filtered_, slot, e.filtered, false);
    set_member(sending_, slot, e.sending, false);
}

void StackRoutes::index_globals(std::size_t slot, const Entry& e, bool on) {
    if (e.all_globals) {
        if (on) {
            insert_slot(all_globals_, slot);
        } else {
            erase_slot(all_globals_, slot);
        }
        return;
    }
    for (const std::uint16_t cmti : e.globals) {
        if (on) {
            insert_slot(globals_[cmti], slot);
        } else {
            erase_slot(globals_[cmti], slot);
        }
    }
}

const std::vector<std::size_t>& StackRoutes::route(const CanFrame& frame, std::size_t sender) {
    // Learned before any stack sees the frame, as a stack with its own cache learns it first.
    if (shared_) shared_->learn(frame);
    hits_.clear();
    everyone_ = false;
    add(filtered_);
    if (can::is_openlcb_frame(frame) && frame.len <= 8) {
        add(by_alias_[can::source_alias(frame.id)]);
        if (can::is_control(frame.id)) {
            route_control(frame);
        } else {
            route_message(frame);
        }
    }
    if (everyone_) {
        hits_.clear();
        for (std::size_t i = 0; i < entries_.size(); ++i) {
            if (entries_[i].stack && i != sender) hits_.push_back(i);
        }
        return hits_;
    }
    std::sort(hits_.begin(), hits_.end());
    hits_.erase(std::unique(hits_.begin(), hits_.end()), hits_.end());
    if (const auto it = std::lower_bound(hits_.begin(), hits_.end(), sender);
        it != hits_.end() && *it == sender) {
        hits_.erase(it);
    }
    return hits_;
}

void StackRoutes::route_control(const CanFrame& frame) {
    switch (can::classify_control(frame.id)) {
        case can::ControlFrame::kAmd:
            add_carried(frame);
            add(sending_);
            add(learners_);
            break;
        case can::ControlFrame::kAmr:
            add(learners_);
            break;
        case can::ControlFrame::kAme:
            // A global AME asks everyone; any AME marks the time AMDs answering it start.
            everyone_ = true;
            break;
        default:
            break;  // CID, RID, error information: only for the holder of the source alias
    }
}

void StackRoutes::route_message(const CanFrame& frame) {
    switch (can::frame_format(frame.id)) {
        case can::FrameFormat::kGlobalAddressed:
            if (!is_addressed(static_cast<Mti>(can::can_mti(frame.id)))) {
                route_global(frame);
            } else if (frame.len >= 2) {
                add(by_alias_[can::addressed_dest(frame.data[0], frame.data[1])]);
            }
            break;
        case can::FrameFormat::kDatagramOnly:
        case can::FrameFormat::kDatagramFirst:
        case can::FrameFormat::kDatagramMiddle:
        case can::FrameFormat::kDatagramLast:
        case can::FrameFormat::kStreamData:
            add(by_alias_[can::dest_alias(frame.id)]);
            break;
        default:
            break;
    }
}

void StackRoutes::route_global(const CanFrame& frame) {
    const std::uint16_t cmti = can::can_mti(frame.id);
    if (cmti == cmti_of(Mti::kVerifyNodeIdGlobal)) {
        everyone_ = true;  // the built-in answer needs no handler
        return;
    }
    add(all_globals_);
    if (const auto it = globals_.find(cmti); it != globals_.end()) add(it->second);
    switch (cmti) {
        case cmti_of(Mti::kInitializationComplete):
        case cmti_of(Mti::kInitializationCompleteSimple):
            add(sending_);
            add(learners_);
            break;
        case cmti_of(Mti::kVerifiedNodeId):
        case cmti_of(Mti::kVerifiedNodeIdSimple):
            add_carried(frame);
            add(learners_);
            break;
        default:
            break;
    }
}

// The stacks with the node ID the frame carries (a duplicate of theirs, or an AME for them).
void StackRoutes::add_carried(const CanFrame& frame) {
    const auto id = NodeId::from_bytes(std::span(frame.data.data(), frame.len));
    if (!id) return;
    if (const auto it = by_node_.find(*id); it != by_node_.end()) add(it->second);
}

}  // namespace olcb
