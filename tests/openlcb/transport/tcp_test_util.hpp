// Shared helpers of the TCP transport tests: bounded event-loop driving, raw loopback sockets.
#pragma once

#include <chrono>
#include <functional>
#include <string>

#include "openlcb/asio.hpp"
#include "openlcb/can_frame.hpp"

namespace olcb::test {

/// Runs `io` until `done()` holds or `limit` passes; returns done().
inline bool run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      std::chrono::milliseconds limit = std::chrono::seconds(20)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done() && std::chrono::steady_clock::now() < deadline) {
        if (io.stopped()) io.restart();
        io.run_one_for(std::chrono::milliseconds(20));
    }
    return done();
}

/// An extended frame whose ID carries `alias` and whose data carries `seq`.
inline CanFrame numbered_frame(std::uint16_t alias, std::uint32_t seq) {
    CanFrame f;
    f.id = 0x195B4000u | alias;
    f.len = 8;
    f.data = {0x05,
              0x01,
              0x01,
              0x01,
              static_cast<std::uint8_t>(seq >> 24),
              static_cast<std::uint8_t>(seq >> 16),
              static_cast<std::uint8_t>(seq >> 8),
              static_cast<std::uint8_t>(seq)};
    return f;
}

/// The sequence number numbered_frame() put into `f`.
inline std::uint32_t frame_seq(const CanFrame& f) {
    return std::uint32_t{f.data[4]} << 24 | std::uint32_t{f.data[5]} << 16 |
           std::uint32_t{f.data[6]} << 8 | f.data[7];
}

}  // namespace olcb::test
