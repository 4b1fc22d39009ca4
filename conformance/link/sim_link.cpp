// The runner's node on a SimNetwork, attached through a raw endpoint rather than add_stack so that
// injected frames bypass our own stack exactly as they do on a real transport.
#include <algorithm>
#include <optional>

#include "conformance/link/link.hpp"
#include "openlcb/sim_network.hpp"

namespace olcb::conform {
namespace {

class SimLink final : public Link {
public:
    SimLink(SimNetwork& network, NodeId tool_id, std::uint32_t assumed_bitrate)
        : network_(network), stack_(tool_stack_config(tool_id)), assumed_(assumed_bitrate) {
        port_ = &network_.add_endpoint([this](const CanFrame& frame, TimePoint at) {
            if (observer_) observer_(frame, at);
            stack_.on_frame(frame, at);
            pump();
        });
        stack_.start(network_.now());
        pump();
    }

    NodeStack& stack() override { return stack_; }
    TimePoint now() override { return network_.now(); }
    std::uint32_t bus_bitrate() override {
        return network_.bitrate() != 0 ? network_.bitrate() : assumed_;
    }

    bool run_until(const std::function<bool()>& pred, Duration max) override {
        const TimePoint limit = network_.now() + max;
        for (;;) {
            poll_due();
            if (pred && pred()) return true;
            if (network_.now() >= limit) return false;
            std::optional<TimePoint> deadline = stack_.next_deadline();
            const TimePoint until = deadline ? std::min(*deadline, limit) : limit;
            // Our deadline is not known to the network: stop there, poll, and go on.
            const Duration step = std::max(until - network_.now(), Duration::zero());
            network_.run_until([&] { return (pred && pred()) || stack_.has_output(); }, step);
            if (network_.step_limit_hit()) return pred && pred();
        }
    }

    void send_frame(const CanFrame& frame) override {
        if (observer_) observer_(frame, network_.now());
        port_->send(frame);
    }

    void set_frame_observer(FrameObserver observer) override { observer_ = std::move(observer); }

private:
    bool due() const {
        auto d = stack_.next_deadline();
        return d && *d <= network_.now();
    }

    void poll_due() {
        if (due()) stack_.poll(network_.now());
        pump();
    }

    void pump() {
        while (auto f = stack_.pop_frame()) {
            if (observer_) observer_(*f, network_.now());
            port_->send(*f);
        }
    }

    SimNetwork& network_;
    NodeStack stack_;
    std::uint32_t assumed_;  // the bus speed reported while the network is unpaced
    Transport* port_ = nullptr;
    FrameObserver observer_;
};

}  // namespace

NodeStackConfig tool_stack_config(NodeId tool_id) {
    NodeStackConfig config;
    config.node_id = tool_id;
    config.protocols =
        ProtocolSet{Protocol::kDatagram, Protocol::kMemoryConfiguration, Protocol::kSnip};
    // A node that rejects temporarily several times in a row is still conformant.
    config.datagram_sender.max_resends = 10;
    config.datagram_sender.resend_delay = std::chrono::milliseconds(20);
    // A node that never acks must not stall every later request for the full 3 s.
    config.datagram_sender.ack_timeout = std::chrono::milliseconds(1000);
    // Stream reads: only streams Session::read_stream announced are accepted.
    config.streams = true;
    config.stream.accept_unsolicited = false;
    return config;
}

std::unique_ptr<Link> make_sim_link(SimNetwork& network, NodeId tool_id,
                                    std::uint32_t assumed_bitrate) {
    return std::make_unique<SimLink>(network, tool_id, assumed_bitrate);
}

}  // namespace olcb::conform
