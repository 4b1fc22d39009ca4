#include "simnode/node_registry.hpp"

#include <algorithm>
#include <filesystem>
#include <system_error>
#include <utility>

#include "openlcb/asio.hpp"
#include "openlcb/stack_driver.hpp"

namespace olcb::simnode {

NodeRegistry::NodeRegistry(std::vector<std::unique_ptr<SimNode>>& nodes, StackDriver& driver)
    : nodes_(nodes), driver_(driver) {
    for (const auto& node : nodes_) {
        node_fds_ += node_fds(node->config());
        create_trains_for(*node);
    }
}

SimNode* NodeRegistry::find(NodeId id) const {
    for (const auto& node : nodes_) {
        if (node->node_id() == id) return node.get();
    }
    return nullptr;
}

void NodeRegistry::start_all() {
    started_ = true;
    driver_.start_all();
}

std::unique_ptr<SimNode> NodeRegistry::create(const NodeConfig& config, std::string& error) const {
    std::error_code ec;
    if (!config.image_dir.empty() && !std::filesystem::create_directories(config.image_dir, ec) &&
        ec) {
        error = "cannot create image directory " + config.image_dir.string() + ": " + ec.message();
        return nullptr;
    }
    return SimNode::create(config, error);
}

void NodeRegistry::create_trains_for(SimNode& node) {
    if (!node.config().command_station) return;
    // The station decides inside the driver's callbacks, where no node may be added: the train
    // joins from the io_context right after.
    node.set_train_factory([this](const NodeConfig& config) {
        if (find(config.node_id) != nullptr) return false;
        boost::asio::post(driver_.io(), [this, config] {
            std::string error;
            if (find(config.node_id) == nullptr && add(config, error) == nullptr && log_)
                log_("train " + config.node_id.to_string() + " not created: " + error);
        });
        return true;
    });
}

void NodeRegistry::run(SimNode& node) {
    create_trains_for(node);
    driver_.attach(node.stack());
    // Before start_all() the node waits with the others (a --connect hub not reached yet).
    if (started_) node.stack().start(Clock::now());
}

SimNode* NodeRegistry::add(const NodeConfig& config, std::string& error) {
    if (find(config.node_id) != nullptr) {
        error = "node " + config.node_id.to_string() + " is already running";
        return nullptr;
    }
    // Refused before it opens anything: a process out of descriptors cannot accept a client.
    const std::size_t need = fds_needed() + node_fds(config);
    error = fd_shortage("not added: simnode", need, budget_);
    if (!error.empty()) return nullptr;
    auto node = create(config, error);
    if (!node) return nullptr;
    node_fds_ += node_fds(config);
    nodes_.push_back(std::move(node));
    if (added_) added_(*nodes_.back());
    run(*nodes_.back());
    return nodes_.back().get();
}

bool NodeRegistry::remove(NodeId id) {
    const auto it = std::find_if(nodes_.begin(), nodes_.end(),
                                 [id](const auto& node) { return node->node_id() == id; });
    if (it == nodes_.end()) return false;
    NodeStack& stack = (*it)->stack();
    stack.release(Clock::now());
    driver_.flush();  // the AMR leaves before the stack does
    driver_.detach(stack);
    node_fds_ -= node_fds((*it)->config());
    nodes_.erase(it);
    return true;
}

SimNode* NodeRegistry::set_faults(NodeId id, const FaultSet& faults, std::string& error) {
    const auto it = std::find_if(nodes_.begin(), nodes_.end(),
                                 [id](const auto& node) { return node->node_id() == id; });
    if (it == nodes_.end()) {
        error = "no node " + id.to_string();
        return nullptr;
    }
    const NodeConfig before = (*it)->config();
    NodeConfig config = before;
    config.faults = faults;
    // The old node holds its images locked: it goes first. A restart sends no AMR.
    driver_.detach((*it)->stack());
    it->reset();
    *it = create(config, error);
    if (!*it) {
        std::string ignored;
        *it = create(before, ignored);
        if (!*it) {
            node_fds_ -= node_fds(before);
            nodes_.erase(it);
            error += "; the node could not be restarted as before either and is gone";
            return nullptr;
        }
        run(**it);
        return nullptr;
    }
    run(**it);
    return it->get();
}

}  // namespace olcb::simnode
