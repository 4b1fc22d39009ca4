#include "simnode/control_client.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

#include "base/hex.hpp"
#include "base/number.hpp"
#include "openlcb/asio.hpp"

namespace olcb::simnode {
namespace {

namespace fs = std::filesystem;
using Json = ControlJson;
using Args = std::span<const std::string>;

// Bounds a response line: a list of a thousand nodes is far below.
constexpr std::size_t kMaxResponseBytes = std::size_t{64} << 20;
constexpr std::size_t kDumpBytesPerLine = 16;

bool count_is(Args args, std::size_t min, std::size_t max, const char* usage, std::string& error) {
    if (args.size() >= min && args.size() <= max) return true;
    error = std::string("usage: simnode ctl HOST:PORT ") + usage;
    return false;
}

// SPACE ADDRESS [COUNT] as numbers (decimal or 0x hex) into request.
bool numbers(Args args, std::span<const char* const> names, Json& request, std::string& error) {
    for (std::size_t i = 0; i < names.size(); ++i) {
        const auto n = base::parse_unsigned(args[i]);
        if (!n) {
            error =
                std::string(names[i]) + " '" + args[i] + "' is not a number (decimal or 0x hex)";
            return false;
        }
        request[names[i]] = *n;
    }
    return true;
}

std::optional<Json> list_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 0, 0, "list", error)) return std::nullopt;
    return Json{{"cmd", "list"}};
}

std::optional<Json> node_request(const char* cmd, Args args, std::string& error) {
    if (!count_is(args, 1, 1, (std::string(cmd) + " NODE").c_str(), error)) return std::nullopt;
    return Json{{"cmd", cmd}, {"node", args[0]}};
}

std::optional<Json> reboot_request(Args args, const fs::path&, std::string& error) {
    return node_request("reboot", args, error);
}

std::optional<Json> remove_request(Args args, const fs::path&, std::string& error) {
    return node_request("remove", args, error);
}

std::optional<Json> set_faults_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 2, SIZE_MAX, "set-faults NODE FAULT[=PARAM]...", error)) {
        return std::nullopt;
    }
    return Json{{"cmd", "set-faults"},
                {"node", args[0]},
                {"faults", std::vector<std::string>(args.begin() + 1, args.end())}};
}

std::optional<Json> clear_faults_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 1, SIZE_MAX, "clear-faults NODE [FAULT...]", error)) return std::nullopt;
    Json request{{"cmd", "clear-faults"}, {"node", args[0]}};
    if (args.size() > 1) request["faults"] = std::vector<std::string>(args.begin() + 1, args.end());
    return request;
}

std::optional<Json> read_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 4, 4, "read NODE SPACE ADDRESS COUNT", error)) return std::nullopt;
    Json request{{"cmd", "read"}, {"node", args[0]}};
    static constexpr const char* kNames[] = {"space", "address", "count"};
    if (!numbers(args.subspan(1), kNames, request, error)) return std::nullopt;
    return request;
}

std::optional<Json> write_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 4, 4, "write NODE SPACE ADDRESS HEX", error)) return std::nullopt;
    Json request{{"cmd", "write"}, {"node", args[0]}};
    static constexpr const char* kNames[] = {"space", "address"};
    if (!numbers(args.subspan(1, 2), kNames, request, error)) return std::nullopt;
    request["data"] = args[3];
    return request;
}

// KEY=VALUE pairs: scenario node keys; fault may repeat.
std::optional<Json> add_request(Args args, const fs::path& cwd, std::string& error) {
    if (!count_is(args, 1, SIZE_MAX, "add node-id=ID cdi=FILE [KEY=VALUE...]", error)) {
        return std::nullopt;
    }
    Json request{{"cmd", "add"}};
    for (const std::string& arg : args) {
        const auto eq = arg.find('=');
        if (eq == std::string::npos || eq == 0) {
            error = "add: '" + arg + "' is not KEY=VALUE (keys as in docs/scenarios.md)";
            return std::nullopt;
        }
        const std::string key = arg.substr(0, eq);
        std::string value = arg.substr(eq + 1);
        if ((key == "cdi" || key == "image-dir") && !value.empty() && fs::path(value).is_relative())
            value = (cwd / value).lexically_normal().string();
        if (key == "fault") {
            request[key].push_back(value);
        } else if (request.contains(key)) {
            error = "add: '" + key + "' is given twice";
            return std::nullopt;
        } else {
            request[key] = value;
        }
    }
    return request;
}

std::optional<Json> raw_request(Args args, const fs::path&, std::string& error) {
    if (!count_is(args, 1, 1, "request JSON", error)) return std::nullopt;
    try {
        return Json::parse(args[0]);
    } catch (const Json::exception& e) {
        error = std::string("request: not JSON: ") + e.what();
        return std::nullopt;
    }
}

using RequestBuilder = std::optional<Json> (*)(Args, const fs::path&, std::string&);
constexpr std::pair<std::string_view, RequestBuilder> kBuilders[] = {
    {"list", &list_request},
    {"set-faults", &set_faults_request},
    {"clear-faults", &clear_faults_request},
    {"read", &read_request},
    {"write", &write_request},
    {"reboot", &reboot_request},
    {"add", &add_request},
    {"remove", &remove_request},
    {"request", &raw_request},
};

std::string text_of(const Json& value) {
    if (value.is_string()) return value.get<std::string>();
    if (value.is_null()) return "none";
    return value.dump();
}

std::string node_line(const Json& node) {
    std::string faults;
    for (const auto& f : node.value("faults", Json::array())) {
        faults += (faults.empty() ? "" : ",") + text_of(f);
    }
    std::string line = "node " + text_of(node["node_id"]) + " alias " + text_of(node["alias"]) +
                       " cdi " + text_of(node["cdi"]) + " faults " +
                       (faults.empty() ? "none" : faults) + " images " + text_of(node["images"]);
    if (!node.value("initialized", false)) line += " (not initialized yet)";
    return line + "\n";
}

std::string dump_lines(const Json& response) {
    const std::string hex = text_of(response["data"]);
    const std::uint64_t address = response.value("address", std::uint64_t{0});
    std::string out;
    for (std::size_t i = 0; i < hex.size(); i += 2 * kDumpBytesPerLine) {
        out += base::hex(address + i / 2, 8) + ":";
        for (std::size_t j = i; j < std::min(hex.size(), i + 2 * kDumpBytesPerLine); j += 2) {
            out += ' ';
            out += hex.substr(j, 2);
        }
        out += '\n';
    }
    return out;
}

std::string faults_line(const Json& response) {
    return node_line(response) + (response.value("restarted", false)
                                      ? "(restarted with these faults)\n"
                                      : "(faults unchanged, not restarted)\n");
}

std::string added_lines(const Json& response) {
    std::string out;
    for (const auto& node : response.value("added", Json::array())) out += node_line(node);
    for (const auto& w : response.value("warnings", Json::array())) {
        out += "warning: " + text_of(w) + "\n";
    }
    return out;
}

}  // namespace

std::string ctl_usage() {
    return "usage: simnode ctl [--json] [--timeout SECONDS] HOST:PORT COMMAND [ARGS...]\n"
           "Sends one request to the --control address of a running simnode (docs/control.md).\n"
           "  list                                   every node: ID, alias, CDI, faults, images\n"
           "  set-faults NODE FAULT[=PARAM]...       add faults (the node restarts with them)\n"
           "  clear-faults NODE [FAULT...]           remove these faults, or all\n"
           "  read NODE SPACE ADDRESS COUNT          read memory (numbers: decimal or 0x hex)\n"
           "  write NODE SPACE ADDRESS HEX           write memory, e.g. write NODE 253 0 01ff\n"
           "  reboot NODE                            restart the node\n"
           "  add KEY=VALUE...                       add nodes: scenario node keys, e.g.\n"
           "                                         node-id=05.01.01.01.22.10 cdi=my.xml\n"
           "  remove NODE                            take the node off the bus (AMR)\n"
           "  request JSON                           send a request object as it is\n"
           "--json prints the response line as it came. Exit status: 0 done, 1 refused,\n"
           "2 usage error, no connection or no answer.\n";
}

std::optional<CtlInvocation> parse_ctl_arguments(Args args, const fs::path& cwd,
                                                 std::string& error) {
    CtlInvocation out;
    std::vector<std::string> positional;
    for (std::size_t i = 0; i < args.size(); ++i) {
        if (args[i] == "--json") {
            out.json = true;
        } else if (args[i] == "--timeout" && i + 1 < args.size()) {
            char* end = nullptr;
            const double seconds = std::strtod(args[++i].c_str(), &end);
            if (end == args[i].c_str() || *end != '\0' || !(seconds > 0) || seconds > 3600) {
                error = "--timeout '" + args[i] + "' must be seconds, 0 < S <= 3600";
                return std::nullopt;
            }
            out.timeout = std::chrono::milliseconds(std::llround(seconds * 1000));
        } else if (args[i].starts_with("--") && positional.size() < 2) {
            error = "unknown option '" + args[i] + "'";
            return std::nullopt;
        } else {
            positional.push_back(args[i]);
        }
    }
    if (positional.size() < 2) {
        error = "give HOST:PORT and a command";
        return std::nullopt;
    }
    const auto where = base::parse_host_port(positional[0], error, base::PortZero::kRefused);
    if (!where) return std::nullopt;
    out.where = *where;
    const Args rest = Args(positional).subspan(2);
    for (const auto& [name, build] : kBuilders) {
        if (name != positional[1]) continue;
        auto request = build(rest, cwd, error);
        if (!request) return std::nullopt;
        out.request = std::move(*request);
        return out;
    }
    error = "unknown command '" + positional[1] + "'";
    return std::nullopt;
}

std::string format_ctl_response(const Json& request, const Json& response) {
    const std::string cmd = request.is_object() ? request.value("cmd", std::string()) : "";
    if (cmd == "list") {
        std::string out;
        for (const auto& node : response.value("nodes", Json::array())) out += node_line(node);
        return out;
    }
    if (cmd == "read") return dump_lines(response);
    if (cmd == "write") {
        return "node " + text_of(response["node"]) + ": wrote " + text_of(response["written"]) +
               " byte(s) to space " + text_of(response["space"]) + " at " +
               text_of(response["address"]) + "\n";
    }
    if (cmd == "set-faults" || cmd == "clear-faults") return faults_line(response);
    if (cmd == "reboot") return "node " + text_of(response["node"]) + " rebooting\n";
    if (cmd == "add") return added_lines(response);
    if (cmd == "remove") {
        return "node " + text_of(response["node"]) + " removed (AMR for alias " +
               text_of(response["alias"]) + ")\n";
    }
    return response.dump() + "\n";
}

std::optional<std::string> ctl_exchange(const HostPort& where, const std::string& line,
                                        std::chrono::milliseconds timeout, std::string& error) {
    using boost::asio::ip::tcp;
    boost::system::error_code ec;
    const auto ip = boost::asio::ip::make_address(where.host, ec);
    if (ec) {
        error = "'" + where.host + "' is not a numeric address";
        return std::nullopt;
    }
    boost::asio::io_context io;
    tcp::socket socket(io);
    boost::asio::streambuf input(kMaxResponseBytes);
    const std::string output = line + "\n";
    std::optional<std::string> answer;
    const auto failed = [&](const char* what, const boost::system::error_code& e) {
        error = std::string(what) + " " + where.to_string() + ": " + e.message();
    };
    const auto on_read = [&](const boost::system::error_code& e, std::size_t n) {
        if (e) return failed("no answer from", e);
        const auto begin = boost::asio::buffers_begin(input.data());
        answer.emplace(begin, begin + static_cast<std::ptrdiff_t>(n - 1));
    };
    const auto on_write = [&](const boost::system::error_code& e, std::size_t) {
        if (e) return failed("cannot send to", e);
        boost::asio::async_read_until(socket, input, '\n', on_read);
    };
    socket.async_connect(tcp::endpoint(ip, where.port), [&](const boost::system::error_code& e) {
        if (e) return failed("cannot connect to", e);
        boost::asio::async_write(socket, boost::asio::buffer(output), on_write);
    });
    io.run_for(timeout);
    if (!answer && error.empty()) {
        error = "no answer from " + where.to_string() + " within " +
                std::to_string(timeout.count()) + " ms";
    }
    return answer;
}

int run_ctl(Args args, std::ostream& out, std::ostream& err) {
    for (const auto& arg : args) {
        if (arg == "--help" || arg == "-h") {
            out << ctl_usage();
            return kCtlOk;
        }
    }
    std::string error;
    std::error_code ec;
    const auto invocation = parse_ctl_arguments(args, fs::current_path(ec), error);
    if (!invocation) {
        err << "simnode ctl: " << error << "\n(simnode ctl --help lists the commands)\n";
        return kCtlUsage;
    }
    const auto line =
        ctl_exchange(invocation->where, invocation->request.dump(), invocation->timeout, error);
    if (!line) {
        err << "simnode ctl: " << error << "\n";
        return kCtlUsage;
    }
    Json response;
    try {
        response = Json::parse(*line);
    } catch (const Json::exception& e) {
        err << "simnode ctl: the answer is not JSON: " << e.what() << "\n";
        return kCtlUsage;
    }
    const bool ok = response.is_object() && response.contains("ok") && response["ok"] == true;
    if (invocation->json) {
        out << *line << "\n";
    } else if (ok) {
        try {
            out << format_ctl_response(invocation->request, response);
        } catch (const Json::exception& e) {
            err << "simnode ctl: unexpected answer " << *line << ": " << e.what() << "\n";
            return kCtlUsage;
        }
    } else {
        const bool has_error = response.is_object() && response.contains("error");
        err << "simnode ctl: refused: " << (has_error ? text_of(response["error"]) : *line) << "\n";
    }
    return ok ? kCtlOk : kCtlRefused;
}

}  // namespace olcb::simnode
