// The nodes of one running simnode process, changeable while it runs (live control): nodes are
// added, removed and rebuilt with other faults on the segment of one StackDriver, so every hub
// connection stays up.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/node_id.hpp"
#include "simnode/faults.hpp"
#include "simnode/fd_budget.hpp"
#include "simnode/sim_node.hpp"

namespace olcb {
class StackDriver;
}  // namespace olcb

namespace olcb::simnode {

/// The running nodes and the driver they are attached to. Single-threaded: call it only from the
/// driver's io_context, outside the driver's own callbacks (a control request handler is).
class NodeRegistry {
public:
    /// The nodes of nodes (already attached to driver); both must outlive the registry, which
    /// adds to and erases from the vector.
    NodeRegistry(std::vector<std::unique_ptr<SimNode>>& nodes, StackDriver& driver);

    /// Every node: the scenario's in order, then the added ones.
    const std::vector<std::unique_ptr<SimNode>>& nodes() const { return nodes_; }
    /// The node with this ID, or null.
    SimNode* find(NodeId id) const;
    /// What the run needs besides its nodes, and the descriptor limit add() keeps to (none
    /// until set).
    void set_fd_budget(const FdBudget& budget) { budget_ = budget; }
    /// Told a line (without "simnode: ") when a command station's train cannot be created.
    void set_log_handler(std::function<void(const std::string&)> log) { log_ = std::move(log); }
    /// Descriptors the run needs now: the budget's fixed part and what the nodes hold.
    std::size_t fds_needed() const { return budget_.fixed + node_fds_; }
    /// Starts every node (StackDriver::start_all); nodes added later start at once.
    void start_all();
    /// True once start_all() ran.
    bool started() const { return started_; }
    /// Called with every node add() creates, before its first frame (the client audit learns it
    /// there: without it the node's exchanges would be judged as no node's).
    void set_added_handler(std::function<void(const SimNode&)> handler) {
        added_ = std::move(handler);
    }

    /// Creates the node (its image directory too), attaches it and starts it when the others
    /// run; null with error set (a running node ID, a bad CDI, an unusable image directory, or
    /// the descriptors it would hold passing the budget's limit).
    SimNode* add(const NodeConfig& config, std::string& error);
    /// Takes the node off the segment: AMR for its alias (sent before this returns), then it is
    /// destroyed (its images stay on disk); false when no node has this ID.
    bool remove(NodeId id);
    /// Rebuilds the node with other faults, as firmware with the bugs flashed onto it: the same
    /// node ID, CDI and images, a restart (alias reservation, Initialization Complete). Null with
    /// error set when it cannot be rebuilt; the node then runs again as before, if it can.
    SimNode* set_faults(NodeId id, const FaultSet& faults, std::string& error);

private:
    std::unique_ptr<SimNode> create(const NodeConfig& config, std::string& error) const;
    void run(SimNode& node);
    void create_trains_for(SimNode& node);

    std::vector<std::unique_ptr<SimNode>>& nodes_;
    StackDriver& driver_;
    FdBudget budget_;
    std::size_t node_fds_ = 0;  // what nodes_ hold (node_fds of their configs)
    bool started_ = false;
    std::function<void(const SimNode&)> added_;
    std::function<void(const std::string&)> log_;
};

}  // namespace olcb::simnode
