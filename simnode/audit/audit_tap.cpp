#include "simnode/audit/audit_tap.hpp"

#include <chrono>
#include <utility>

#include "base/file.hpp"
#include "simnode/audit/audit_report.hpp"
#include "simnode/audit/node_profile.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::simnode::audit {
namespace {

// How often time limits are judged and new findings written: a killed simnode loses at most
// this much, and a flood of findings does not rewrite the files per frame.
constexpr auto kTick = std::chrono::milliseconds(200);
// The connection frames from an in-process segment's other ports (bridges) are counted on.
constexpr std::uint64_t kBridgeConnection = 0;

}  // namespace

// Without a hub nobody else knows which frames are the nodes': the nodes' own port tells.
class AuditTap::NodePort final : public Transport {
public:
    NodePort(Transport& inner, ClientAudit& audit) : inner_(inner), audit_(audit) {}

    void send(const CanFrame& frame) override {
        audit_.on_frame(frame, Direction::kFromNode, kBridgeConnection, Clock::now());
        inner_.send(frame);
    }
    void set_handler(FrameHandler handler) override {
        if (!handler) {
            inner_.set_handler({});
            return;
        }
        inner_.set_handler([this, handler = std::move(handler)](const CanFrame& frame) {
            audit_.on_frame(frame, Direction::kFromClient, kBridgeConnection, Clock::now());
            handler(frame);
        });
    }

private:
    Transport& inner_;
    ClientAudit& audit_;
};

AuditTap::AuditTap(boost::asio::io_context& io, AuditFiles files)
    : audit_(Clock::now()), timer_(io), files_(std::move(files)), started_(utc_now()) {}

std::unique_ptr<AuditTap> AuditTap::open(boost::asio::io_context& io, AuditFiles files,
                                         std::string& error) {
    std::unique_ptr<AuditTap> tap(new AuditTap(io, std::move(files)));
    if (!tap->write(error)) return nullptr;
    tap->tick();
    return tap;
}

AuditTap::~AuditTap() {
    if (hub_ != nullptr) {
        hub_->set_frame_observer({});
        hub_->set_disconnect_handler({});
    }
}

void AuditTap::add_node(const SimNode& node) {
    audit_.add_node(profile_of(node));
}

Transport& AuditTap::attach(Transport& node_port, TcpHubServer* hub) {
    if (hub == nullptr) {
        port_ = std::make_unique<NodePort>(node_port, audit_);
        return *port_;
    }
    hub_ = hub;
    // Every connection number is a valid one, so a port the hub does not know matches none.
    node_connection_ = hub->connection_of(node_port).value_or(~std::uint64_t{0});
    hub->set_frame_observer([this](const CanFrame& frame, const TcpHubServer::FrameSource& s) {
        on_hub_frame(frame, s);
    });
    hub->set_disconnect_handler([this](std::uint64_t connection, const std::string&) {
        audit_.on_disconnect(connection, Clock::now());
    });
    return node_port;
}

void AuditTap::on_hub_frame(const CanFrame& frame, const TcpHubServer::FrameSource& source) {
    const TimePoint now = Clock::now();
    if (source.connection == node_connection_) {
        audit_.on_frame(frame, Direction::kFromNode, kBridgeConnection, now);
        return;
    }
    // A local endpoint other than the nodes' is a bridged bus: it stays unnamed.
    if (!source.remote.empty() && named_.insert(source.connection).second) {
        audit_.name_connection(source.connection, std::string(source.remote),
                               ConnectionKind::kHubClient);
    }
    audit_.on_frame(frame, Direction::kFromClient, source.connection, now);
}

void AuditTap::tick() {
    timer_.expires_after(kTick);
    timer_.async_wait([this](const boost::system::error_code& ec) {
        if (ec || finished_) return;
        audit_.poll(Clock::now());
        if (audit_.log().revision() != written_revision_) {
            std::string ignored;  // the final write reports a file that cannot be written
            write(ignored);
        }
        tick();
    });
}

bool AuditTap::write(std::string& error) {
    const ReportInfo info{started_, audit_.finished()};
    const FindingLog& log = audit_.log();
    written_revision_ = log.revision();
    bool ok = true;
    if (!files_.json.empty()) ok = base::write_file(files_.json, audit_json(log, info), error);
    if (!files_.junit.empty())
        ok = base::write_file(files_.junit, audit_junit(log, info), error) && ok;
    return ok;
}

std::string AuditTap::finish() {
    if (finished_) return {};
    finished_ = true;
    timer_.cancel();
    audit_.finish(Clock::now());
    std::string error;
    write(error);
    return error;
}

}  // namespace olcb::simnode::audit
