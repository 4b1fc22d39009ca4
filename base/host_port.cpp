#include "base/host_port.hpp"

#include <algorithm>
#include <charconv>

namespace olcb::base {

namespace {

bool all_digits(std::string_view text) {
    return !text.empty() &&
           std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void explain(std::string_view text, std::string_view why, std::string& error) {
    error = "'" + std::string(text) + "' is not HOST:PORT: " + std::string(why);
}

std::optional<HostPort> refuse(std::string_view text, std::string_view why, std::string& error) {
    explain(text, why, error);
    return std::nullopt;
}

// The port of `text` (all of it, or what follows the host and its colon).
std::optional<std::uint16_t> parse_port(std::string_view text, std::string_view port_text,
                                        PortZero zero, std::string& error) {
    unsigned port = 0;
    const auto [ptr, ec] =
        std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
    if (!all_digits(port_text) || ec != std::errc() || ptr != port_text.data() + port_text.size() ||
        port > 65535) {
        explain(text, "the port must be a number 0..65535", error);
        return std::nullopt;
    }
    if (port == 0 && zero == PortZero::kRefused) {
        explain(text, "port 0 only asks for a free port when listening; give 1..65535", error);
        return std::nullopt;
    }
    return static_cast<std::uint16_t>(port);
}

}  // namespace

std::string HostPort::to_string() const {
    const bool v6 = host.find(':') != std::string::npos;
    return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

std::optional<HostPort> parse_host_port(std::string_view text, std::string& error, PortZero zero) {
    HostPort hp;
    if (all_digits(text)) {
        // A bare port: the local host (HostPort's default).
        const auto port = parse_port(text, text, zero, error);
        if (!port) return std::nullopt;
        hp.port = *port;
        return hp;
    }
    std::string_view host = text;
    std::optional<std::string_view> port_text;
    if (text.starts_with('[')) {
        const auto close = text.find(']');
        if (close == std::string_view::npos) {
            return refuse(text, "no ']' after the IPv6 address", error);
        }
        host = text.substr(1, close - 1);
        const std::string_view rest = text.substr(close + 1);
        if (!rest.empty() && !rest.starts_with(':')) {
            return refuse(text, "':PORT' must follow ']'", error);
        }
        if (!rest.empty()) port_text = rest.substr(1);
    } else if (const auto colon = text.find(':'); colon != std::string_view::npos) {
        if (text.find(':', colon + 1) != std::string_view::npos) {
            return refuse(text, "an IPv6 address goes in brackets, as [::1]:12021", error);
        }
        host = text.substr(0, colon);
        port_text = text.substr(colon + 1);
    }
    if (host.empty()) return refuse(text, "the host is empty", error);
    hp.host = std::string(host);
    if (port_text) {
        const auto port = parse_port(text, *port_text, zero, error);
        if (!port) return std::nullopt;
        hp.port = *port;
    }
    return hp;
}

}  // namespace olcb::base
