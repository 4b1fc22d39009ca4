// The requests of simnode's live control (docs/control.md), sans-I/O: one parsed JSON request
// and the node registry in, one JSON response out. ControlServer carries them over TCP.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "openlcb/can_defs.hpp"
#include "simnode/node_registry.hpp"
#include "simnode/scenario.hpp"

namespace olcb::simnode {

/// Requests and responses; ordered, so a response reads "ok" first.
using ControlJson = nlohmann::ordered_json;

/// Most bytes one read or write request moves.
inline constexpr std::size_t kMaxControlBytes = 4096;
/// Deepest nesting of arrays and objects a request line may have; a deeper one is refused
/// unparsed. Requests nest two levels; nlohmann copies, compares and prints JSON recursively.
inline constexpr std::size_t kMaxControlDepth = 32;
/// Most nodes `add` lets simnode run: one per alias of the segment, as a scenario may hold
/// (more would contend for an alias for ever).
inline constexpr std::size_t kMaxControlNodes = can::kAliasCount;

/// Answers control requests on the nodes of a registry.
class ControlCommands {
public:
    /// Told one line per change made (node added, faults set, ...), for simnode's output.
    using LogHandler = std::function<void(const std::string&)>;

    /// Requests act on registry; added nodes get the running scenario's image root and latency.
    ControlCommands(NodeRegistry& registry, const Scenario& running);

    /// Sets who is told of every change.
    void set_log_handler(LogHandler handler) { log_ = std::move(handler); }
    /// Sets how many nodes `add` lets simnode run at most (default kMaxControlNodes).
    void set_max_nodes(std::size_t max_nodes) { max_nodes_ = max_nodes; }
    /// The response to one request object: {"ok":true,...} or {"ok":false,"error":"..."}, with
    /// the request's "id" copied when it has one. Never throws.
    ControlJson handle(const ControlJson& request);
    /// The response to one line of text: handle() of its JSON, or a refusal of text that is not
    /// a JSON object or nests deeper than kMaxControlDepth.
    ControlJson handle_line(std::string_view line);

private:
    ControlJson dispatch(const ControlJson& request);
    ControlJson list(const ControlJson& request);
    ControlJson set_faults(const ControlJson& request);
    ControlJson clear_faults(const ControlJson& request);
    ControlJson read(const ControlJson& request);
    ControlJson write(const ControlJson& request);
    ControlJson reboot(const ControlJson& request);
    ControlJson add(const ControlJson& request);
    ControlJson remove(const ControlJson& request);
    ControlJson change_faults(SimNode& node, const FaultSet& faults);
    void log(const std::string& line) const;

    NodeRegistry& registry_;
    const Scenario& running_;
    LogHandler log_;
    std::size_t max_nodes_ = kMaxControlNodes;
};

}  // namespace olcb::simnode
