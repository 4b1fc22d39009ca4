// The one transport interface: a port on a CAN segment, whatever carries the segment.
#pragma once

#include <functional>
#include <utility>

#include "openlcb/can_frame.hpp"

namespace olcb {

/// Called with each frame another port of the segment sent.
using FrameHandler = std::function<void(const CanFrame&)>;

/// Holds a port's handler so that the handler may replace itself (or be replaced) while it runs.
class HandlerSlot {
public:
    /// Sets the handler; takes effect after the running call, if any.
    void set(FrameHandler handler) {
        if (calling_) {
            next_ = std::move(handler);
            replace_ = true;
        } else {
            handler_ = std::move(handler);
        }
    }
    /// Calls the handler, if any, with `frame`.
    void operator()(const CanFrame& frame) {
        if (!handler_) return;
        Call call(*this);
        handler_(frame);
    }

private:
    // Ends a call even when the handler throws.
    class Call {
    public:
        explicit Call(HandlerSlot& slot) : slot_(slot), outer_(slot.calling_) {
            slot_.calling_ = true;
        }
        ~Call() {
            slot_.calling_ = outer_;
            if (!outer_ && slot_.replace_) {
                slot_.handler_ = std::move(slot_.next_);
                slot_.replace_ = false;
            }
        }
        Call(const Call&) = delete;
        Call& operator=(const Call&) = delete;

    private:
        HandlerSlot& slot_;
        bool outer_;
    };

    FrameHandler handler_;
    FrameHandler next_;
    bool calling_ = false;
    bool replace_ = false;
};

/// A port on one CAN segment: frames sent here reach every other port, never this one.
class Transport {
public:
    virtual ~Transport() = default;

    /// Queues a frame for every other port of the segment; never blocks.
    virtual void send(const CanFrame& frame) = 0;

    /// Sets who receives the frames other ports send (replaces any previous handler; safe to call
    /// from inside the handler, taking effect after it returns).
    virtual void set_handler(FrameHandler handler) = 0;
};

}  // namespace olcb
