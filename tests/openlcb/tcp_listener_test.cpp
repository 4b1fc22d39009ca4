// listen_on and listening_port on real loopback sockets: a free port is picked and accepts, bad
// input and a taken port leave the acceptor closed, and a restart binds its port again.
#include "openlcb/tcp_listener.hpp"

#include <gtest/gtest.h>

#include <array>

namespace olcb {
namespace {

using boost::asio::ip::tcp;

tcp::endpoint loopback(std::uint16_t port) {
    return {boost::asio::ip::address_v4::loopback(), port};
}

TEST(TcpListener, PortZeroPicksAFreePortThatAcceptsAConnection) {
    boost::asio::io_context io;
    tcp::acceptor acceptor(io);
    ASSERT_FALSE(listen_on(acceptor, "127.0.0.1", 0));
    const std::uint16_t port = listening_port(acceptor);
    ASSERT_NE(port, 0);
    EXPECT_EQ(acceptor.local_endpoint().address().to_string(), "127.0.0.1");
    tcp::socket client(io);
    client.connect(loopback(port));
    tcp::socket served(io);
    acceptor.accept(served);
    EXPECT_EQ(served.remote_endpoint(), client.local_endpoint());
    boost::asio::write(client, boost::asio::buffer(std::string("ping")));
    std::array<char, 4> got{};
    boost::asio::read(served, boost::asio::buffer(got));
    EXPECT_EQ(std::string(got.data(), got.size()), "ping");
}

TEST(TcpListener, ANameOrGarbageIsNoNumericAddress) {
    boost::asio::io_context io;
    tcp::acceptor acceptor(io);
    EXPECT_TRUE(listen_on(acceptor, "localhost", 0));
    EXPECT_TRUE(listen_on(acceptor, "127.0.0.256", 0));
    EXPECT_FALSE(acceptor.is_open());
    EXPECT_EQ(listening_port(acceptor), 0);
}

TEST(TcpListener, AnOpenAcceptorIsAlreadyOpenAndKeepsItsPort) {
    boost::asio::io_context io;
    tcp::acceptor acceptor(io);
    ASSERT_FALSE(listen_on(acceptor, "127.0.0.1", 0));
    const std::uint16_t port = listening_port(acceptor);
    EXPECT_EQ(listen_on(acceptor, "127.0.0.1", 0), boost::asio::error::already_open);
    EXPECT_EQ(listening_port(acceptor), port);
}

TEST(TcpListener, APortSomeoneListensOnFailsAndLeavesTheAcceptorClosed) {
    boost::asio::io_context io;
    tcp::acceptor first(io);
    ASSERT_FALSE(listen_on(first, "127.0.0.1", 0));
    tcp::acceptor second(io);
    EXPECT_EQ(listen_on(second, "127.0.0.1", listening_port(first)),
              boost::asio::error::address_in_use);
    EXPECT_FALSE(second.is_open());
    EXPECT_EQ(listening_port(second), 0);
    EXPECT_FALSE(listen_on(second, "127.0.0.1", 0)) << "the failed acceptor can listen again";
}

TEST(TcpListener, ARestartBindsItsPortWhileAnOldConnectionIsInTimeWait) {
    boost::asio::io_context io;
    tcp::acceptor acceptor(io);
    ASSERT_FALSE(listen_on(acceptor, "127.0.0.1", 0));
    const std::uint16_t port = listening_port(acceptor);
    {
        tcp::socket client(io);
        client.connect(loopback(port));
        tcp::socket served(io);
        acceptor.accept(served);
        served.close();  // the side that closes first keeps the port in TIME_WAIT
        std::array<char, 1> byte{};
        boost::system::error_code ec;
        boost::asio::read(client, boost::asio::buffer(byte), ec);
        EXPECT_EQ(ec, boost::asio::error::eof);
    }
    acceptor.close();
    tcp::acceptor restarted(io);
    EXPECT_FALSE(listen_on(restarted, "127.0.0.1", port));
    EXPECT_EQ(listening_port(restarted), port);
}

}  // namespace
}  // namespace olcb
