// Opening a TCP listener: the steps the hub and simnode's control server take alike.
#pragma once

#include <cstdint>
#include <string>

#include "openlcb/asio.hpp"

namespace olcb {

/// Opens acceptor on a numeric address and port (0: any free port) and listens, reusing the
/// address; an error when it cannot (a failed bind or listen closes acceptor again), already_open
/// when acceptor is open already.
boost::system::error_code listen_on(boost::asio::ip::tcp::acceptor& acceptor,
                                    const std::string& address, std::uint16_t port);

/// The port acceptor listens on (0 when it is not listening).
std::uint16_t listening_port(const boost::asio::ip::tcp::acceptor& acceptor);

}  // namespace olcb
