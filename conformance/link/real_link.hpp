// A Link on real time: the runner's NodeStack driven by a StackDriver on any Transport, through a
// tap that records every frame and lets checks inject raw ones.
#pragma once

#include <memory>

#include "conformance/link/link.hpp"
#include "openlcb/asio.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/transport.hpp"

namespace olcb::conform {

/// Wraps a transport: every frame in or out goes to the observer first.
class TapTransport final : public Transport {
public:
    /// Taps `inner`, which must outlive the tap.
    explicit TapTransport(Transport& inner);
    /// Forwards to the inner transport after observing.
    void send(const CanFrame& frame) override;
    /// Receives the inner transport's frames after observing.
    void set_handler(FrameHandler handler) override;
    /// Sets the observer.
    void set_observer(FrameObserver observer) { observer_ = std::move(observer); }

private:
    Transport& inner_;
    FrameHandler handler_;
    FrameObserver observer_;
};

/// Real-time link over a transport owned by the caller's subclass.
class RealLink : public Link {
public:
    /// The io_context must outlive the link; call attach() once the transport exists.
    RealLink(std::unique_ptr<boost::asio::io_context> io, NodeId tool_id);
    ~RealLink() override;
    /// Wires the tap and driver to `transport` and starts the stack.
    void attach(Transport& transport);
    /// Unwires the transport; subclasses call it before their transport dies.
    void detach();
    /// The io_context everything runs on.
    boost::asio::io_context& io() { return *io_; }

    NodeStack& stack() override { return stack_; }
    TimePoint now() override { return Clock::now(); }
    bool run_until(const std::function<bool()>& pred, Duration max) override;
    void send_frame(const CanFrame& frame) override;
    void set_frame_observer(FrameObserver observer) override;
    bool up() override { return up_; }
    std::uint64_t losses() override { return losses_; }
    std::string loss_reason() override { return loss_reason_; }

protected:
    /// Subclasses report their transport going away (with the reason) and coming back.
    void set_up(bool up, const std::string& reason = {});

private:
    bool up_ = true;
    std::uint64_t losses_ = 0;
    std::string loss_reason_;
    std::unique_ptr<boost::asio::io_context> io_;
    NodeStack stack_;
    std::unique_ptr<TapTransport> tap_;
    std::unique_ptr<StackDriver> driver_;
    Transport* inner_ = nullptr;
    FrameObserver observer_;
};

}  // namespace olcb::conform
