#include "openlcb/alias_cache.hpp"

#include <span>

#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"

namespace olcb {

void AliasCache::add(std::uint16_t alias, NodeId node) {
    alias &= 0xFFF;
    if (alias == 0 || node.is_zero()) return;
    if (by_alias_.empty()) by_alias_.assign(4096, 0);
    // Every Verified/AMD/Initialization Complete re-announces a known mapping; with 1,000 nodes
    // on a segment, re-inserting it each time dominated start-up (hash node freed and allocated).
    if (by_alias_[alias] == node.value()) return;
    remove_alias(alias);
    if (auto it = by_node_.find(node); it != by_node_.end()) {
        by_alias_[it->second] = 0;
        by_node_.erase(it);
    }
    by_alias_[alias] = node.value();
    by_node_[node] = alias;
}

void AliasCache::remove_alias(std::uint16_t alias) {
    alias &= 0xFFF;
    if (by_alias_.empty() || by_alias_[alias] == 0) return;
    by_node_.erase(NodeId(by_alias_[alias]));
    by_alias_[alias] = 0;
}

void AliasCache::clear() {
    by_alias_.clear();
    by_node_.clear();
}

std::optional<NodeId> AliasCache::node_of(std::uint16_t alias) const {
    alias &= 0xFFF;
    if (by_alias_.empty() || by_alias_[alias] == 0) return std::nullopt;
    return NodeId(by_alias_[alias]);
}

std::optional<std::uint16_t> AliasCache::alias_of(NodeId node) const {
    if (auto it = by_node_.find(node); it != by_node_.end()) return it->second;
    return std::nullopt;
}

namespace {

// The node ID an announcing global message carries, if it is one.
std::optional<NodeId> announced_by_message(const CanFrame& frame) {
    if (can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed) return std::nullopt;
    switch (can::can_mti(frame.id)) {
        case to_u16(Mti::kInitializationComplete):
        case to_u16(Mti::kInitializationCompleteSimple):
        case to_u16(Mti::kVerifiedNodeId):
        case to_u16(Mti::kVerifiedNodeIdSimple):
            return NodeId::from_bytes(std::span(frame.data.data(), frame.len));
        default:
            return std::nullopt;
    }
}

}  // namespace

void AliasCache::learn(const CanFrame& frame) {
    if (!can::is_openlcb_frame(frame) || frame.len > 8) return;
    const std::uint16_t src = can::source_alias(frame.id);
    if (!can::is_control(frame.id)) {
        if (const auto id = announced_by_message(frame)) add(src, *id);
        return;
    }
    switch (can::classify_control(frame.id)) {
        case can::ControlFrame::kAmd:
            if (const auto id = NodeId::from_bytes(std::span(frame.data.data(), frame.len))) {
                add(src, *id);
            }
            break;
        case can::ControlFrame::kAmr:
            remove_alias(src);
            break;
        case can::ControlFrame::kAme:
            if (frame.len == 0) clear();
            break;
        default:
            break;
    }
}

}  // namespace olcb
