#include "openlcb/tcp_listener.hpp"

#include <cerrno>

namespace olcb {

using boost::asio::ip::tcp;

boost::system::error_code listen_on(tcp::acceptor& acceptor, const std::string& address,
                                    std::uint16_t port) {
    boost::system::error_code ec;
    const auto ip = boost::asio::ip::make_address(address, ec);
    if (ec) return ec;
    const tcp::endpoint endpoint(ip, port);
    if (acceptor.is_open()) return boost::asio::error::already_open;
    if (acceptor.open(endpoint.protocol(), ec)) return ec;
    // Lets a restarted program bind its port again while old connections sit in TIME_WAIT.
    if (acceptor.set_option(tcp::acceptor::reuse_address(true), ec)) return ec;
    if (acceptor.bind(endpoint, ec) || acceptor.listen(tcp::socket::max_listen_connections, ec)) {
        boost::system::error_code ignored;
        acceptor.close(ignored);
        return ec;
    }
    return {};
}

std::chrono::milliseconds accept_retry_delay(const boost::system::error_code& ec) {
    if (ec.category() != boost::system::system_category()) return {};
    switch (ec.value()) {
        case EMFILE:
        case ENFILE:
        case ENOBUFS:
        case ENOMEM:
            return kAcceptRetryDelay;
        default:
            return {};
    }
}

std::uint16_t listening_port(const tcp::acceptor& acceptor) {
    boost::system::error_code ec;
    if (!acceptor.is_open()) return 0;
    const auto endpoint = acceptor.local_endpoint(ec);
    return ec ? 0 : endpoint.port();
}

}  // namespace olcb
