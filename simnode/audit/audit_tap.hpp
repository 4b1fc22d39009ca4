// simnode's side of the client audit: feeds ClientAudit the segment's frames (from the hub,
// which knows each client's connection, or from the node port of an in-process segment), polls
// it on the io_context and keeps the JSON and JUnit files up to date.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <unordered_set>

#include "openlcb/asio.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/transport.hpp"
#include "simnode/audit/client_audit.hpp"

namespace olcb::simnode {
class SimNode;
}

namespace olcb::simnode::audit {

/// Where the audit is written (an empty path: that file is not written).
struct AuditFiles {
    std::filesystem::path json;   ///< --audit
    std::filesystem::path junit;  ///< --audit-junit
};

/// The running audit of one simnode process.
class AuditTap {
public:
    /// An audit writing files (both files are written at once, empty, so a path that cannot be
    /// written fails here); nullptr with error set on failure.
    static std::unique_ptr<AuditTap> open(boost::asio::io_context& io, AuditFiles files,
                                          std::string& error);
    /// Stops observing the hub (it may outlive the tap).
    ~AuditTap();
    AuditTap(const AuditTap&) = delete;
    AuditTap& operator=(const AuditTap&) = delete;

    /// Adds one of simnode's nodes, before its first frame (NodeRegistry's added handler calls
    /// it for the nodes live control adds).
    void add_node(const SimNode& node);
    /// Starts auditing the segment the nodes use through node_port. With a hub (node_port one
    /// of its local endpoints) the hub's frames are observed and node_port is returned; without
    /// one the returned port wraps node_port: give it to the StackDriver instead.
    Transport& attach(Transport& node_port, TcpHubServer* hub);
    /// The end of the run: the last judgements, then both files, marked complete; "" or why a
    /// file could not be written. Only the first call does anything.
    std::string finish();

private:
    class NodePort;
    AuditTap(boost::asio::io_context& io, AuditFiles files);
    void on_hub_frame(const CanFrame& frame, const TcpHubServer::FrameSource& source);
    void tick();
    bool write(std::string& error);

    ClientAudit audit_;
    boost::asio::steady_timer timer_;
    AuditFiles files_;
    std::string started_;
    std::uint64_t written_revision_ = 0;
    TcpHubServer* hub_ = nullptr;
    std::uint64_t node_connection_ = 0;
    std::unordered_set<std::uint64_t> named_;  // hub connections told to the audit
    std::unique_ptr<NodePort> port_;
    bool finished_ = false;
};

}  // namespace olcb::simnode::audit
