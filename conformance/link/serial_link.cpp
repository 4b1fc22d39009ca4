// The link through a USB/serial GridConnect adapter: a RealLink that owns its SerialPort.
#include "conformance/link/real_link.hpp"
#include "openlcb/serial_port.hpp"

namespace olcb::conform {
namespace {

class SerialLink final : public RealLink {
public:
    SerialLink(std::unique_ptr<boost::asio::io_context> io, const std::string& device,
               SerialOptions options, NodeId tool_id)
        : RealLink(std::move(io), tool_id), port_(this->io(), device, options) {
        port_.set_connection_handler(
            [this](bool up, const std::string& reason) { set_up(up, reason); });
    }
    ~SerialLink() override {
        detach();
        port_.close();
    }
    SerialPort& port() { return port_; }

private:
    SerialPort port_;
};

}  // namespace

std::unique_ptr<Link> open_serial(const std::string& device, SerialSettings settings,
                                  NodeId tool_id, std::string& error) {
    SerialOptions options;
    options.baud = settings.baud;
    options.rtscts = settings.rtscts;
    auto link = std::make_unique<SerialLink>(std::make_unique<boost::asio::io_context>(), device,
                                             options, tool_id);
    if (auto failure = link->port().open()) {
        error = *failure;
        return nullptr;
    }
    link->attach(link->port());
    return link;
}

}  // namespace olcb::conform
