// A TCP address as the programs take it on the command line and in scenario files.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace olcb::base {

/// The GridConnect TCP port OpenLCB hubs use (JMRI, OpenMRN): the port when none is given.
inline constexpr std::uint16_t kDefaultPort = 12021;

/// A TCP address: a host (name or numeric address, IPv6 without brackets) and a port.
struct HostPort {
    std::string host = "127.0.0.1";     ///< 127.0.0.1 when only a port is given
    std::uint16_t port = kDefaultPort;  ///< 0 (listen only) lets the system pick a free port

    /// "HOST:PORT", an IPv6 host in brackets ("[::1]:12021").
    std::string to_string() const;
    /// Same host and port.
    friend bool operator==(const HostPort&, const HostPort&) = default;
};

/// Whether port 0 ("any free port") is allowed: only where the caller listens.
enum class PortZero : std::uint8_t {
    kRefused,  ///< a port to connect to: 1..65535
    kAllowed,  ///< a port to listen on: 0..65535
};

/// Parses "HOST:PORT", "[V6]:PORT", "HOST" or "[V6]" (port 12021) and a bare "PORT" (all digits;
/// host 127.0.0.1). An IPv6 address must be in brackets. Nullopt with `error` set to a sentence
/// naming the text and what is wrong.
std::optional<HostPort> parse_host_port(std::string_view text, std::string& error,
                                        PortZero zero = PortZero::kAllowed);

}  // namespace olcb::base
