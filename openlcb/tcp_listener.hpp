// Opening a TCP listener: the steps the hub and simnode's control server take alike.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include "openlcb/asio.hpp"

namespace olcb {

/// Opens acceptor on a numeric address and port (0: any free port) and listens, reusing the
/// address; an error when it cannot (a failed bind or listen closes acceptor again), already_open
/// when acceptor is open already.
boost::system::error_code listen_on(boost::asio::ip::tcp::acceptor& acceptor,
                                    const std::string& address, std::uint16_t port);

/// How long a listener rests after an accept that failed with a process or system out of
/// descriptors or memory: accepting again at once would fail at once, a busy loop.
inline constexpr std::chrono::milliseconds kAcceptRetryDelay{100};

/// The delay before accepting again after an accept failed with ec: kAcceptRetryDelay when it
/// would fail again at once (EMFILE, ENFILE, ENOBUFS, ENOMEM), 0 for an error of one connection
/// (one reset before it was taken).
std::chrono::milliseconds accept_retry_delay(const boost::system::error_code& ec);

/// The port acceptor listens on (0 when it is not listening).
std::uint16_t listening_port(const boost::asio::ip::tcp::acceptor& acceptor);

}  // namespace olcb
