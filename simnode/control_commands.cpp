#include "simnode/control_commands.hpp"

#include <algorithm>
#include <charconv>
#include <initializer_list>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "base/hex.hpp"
#include "base/number.hpp"
#include "openlcb/clock.hpp"

namespace olcb::simnode {
namespace {

using Json = ControlJson;

constexpr std::string_view kCommandList =
    "list, set-faults, clear-faults, read, write, reboot, add, remove";
// One request adds at most this many nodes: the io thread builds them all before it answers.
constexpr std::uint64_t kMaxAddedNodes = 1000;
// A value quoted back in an error is cut here: the error must stay readable.
constexpr std::size_t kMaxQuoted = 64;
constexpr std::size_t kMaxParseMessage = 200;
constexpr std::uint64_t kMaxAddress = 0xFFFF'FFFFu;
constexpr std::uint64_t kMaxSpace = 0xFF;

Json refused(std::string error) {
    Json out;
    out["ok"] = false;
    out["error"] = std::move(error);
    return out;
}

Json accepted(const Json& body = Json::object()) {
    Json out;
    out["ok"] = true;
    for (const auto& [key, value] : body.items()) out[key] = value;
    return out;
}

std::string quoted(const Json& value) {
    std::string text = value.is_string()
                           ? value.get<std::string>()
                           : value.dump(-1, ' ', false, Json::error_handler_t::replace);
    if (text.size() > kMaxQuoted) text = text.substr(0, kMaxQuoted) + "...";
    return "'" + text + "'";
}

std::string space_name(std::uint64_t number) {
    return "space " + std::to_string(number) + " (" + base::hex(number, 2) + ")";
}

Json alias_json(std::uint16_t alias) {
    if (alias == 0) return nullptr;
    return base::hex(alias, 3);
}

Json describe(const SimNode& node) {
    const NodeConfig& c = node.config();
    Json spaces = Json::array();
    for (const std::uint8_t number : node.memory().served_spaces()) {
        const memory::MemorySpace* s = node.memory().space(number);
        spaces.push_back({{"space", number}, {"size", s->size()}, {"writable", !s->read_only()}});
    }
    Json out;
    out["node_id"] = node.node_id().to_string();
    out["alias"] = alias_json(node.stack().alias());
    out["initialized"] = node.stack().initialized();
    out["cdi"] = c.cdi_file.empty() ? std::string("(inline)") : c.cdi_file.string();
    out["faults"] = to_names(c.faults);
    out["images"] = c.image_dir.empty() ? Json(nullptr) : Json(c.image_dir.string());
    out["spaces"] = std::move(spaces);
    return out;
}

std::string fault_text(const FaultSet& faults) {
    std::string out;
    for (const auto& name : to_names(faults)) out += (out.empty() ? "" : ",") + name;
    return out.empty() ? "none" : out;
}

// "a,b" and ["a", "b,c"] alike: one fault entry each.
std::vector<std::string> split_faults(const std::vector<std::string>& entries) {
    std::vector<std::string> out;
    for (const std::string& entry : entries) {
        std::string_view rest = entry;
        while (!rest.empty()) {
            const auto comma = rest.find(',');
            std::string_view item = rest.substr(0, comma);
            while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
            while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
            if (!item.empty()) out.emplace_back(item);
            rest = comma == std::string_view::npos ? std::string_view{} : rest.substr(comma + 1);
        }
    }
    return out;
}

std::string fault_name(std::string_view entry) {
    return std::string(entry.substr(0, entry.find('=')));
}

bool known_fault(std::string_view name) {
    const auto& catalog = fault_catalog();
    return std::any_of(catalog.begin(), catalog.end(),
                       [name](const FaultInfo& f) { return f.name == name; });
}

// The fields of one request, checked as they are taken; the first problem is kept.
class Fields {
public:
    Fields(const Json& request, std::string_view command,
           std::initializer_list<std::string_view> allowed)
        : request_(request) {
        for (const auto& [key, value] : request.items()) {
            if (key == "cmd" || key == "id") continue;
            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
            std::string names;
            for (const auto name : allowed)
                names += (names.empty() ? "" : ", ") + std::string(name);
            fail("unknown field '" + key + "' of " + std::string(command) +
                 " (fields: " + (names.empty() ? "none" : names) + ")");
            break;
        }
    }

    bool ok() const { return error_.empty(); }
    const std::string& error() const { return error_; }
    bool has(std::string_view name) const { return request_.contains(std::string(name)); }

    SimNode* node(const NodeRegistry& registry) {
        const Json* v = get("node");
        if (v == nullptr) return nullptr;
        std::string why;
        const auto id = v->is_string() ? NodeId::parse(v->get<std::string>(), &why) : std::nullopt;
        if (!id) {
            fail("\"node\" " + quoted(*v) + " is not a node ID such as 05.01.01.01.22.00");
            return nullptr;
        }
        SimNode* found = registry.find(*id);
        if (found == nullptr) fail("no node " + id->to_string() + " (list shows the nodes)");
        return found;
    }

    std::optional<std::uint64_t> number(std::string_view name, std::uint64_t min,
                                        std::uint64_t max) {
        const Json* v = get(name);
        if (v == nullptr) return std::nullopt;
        std::optional<std::uint64_t> n;
        if (v->is_number_integer() && v->get<std::int64_t>() >= 0) {
            n = v->get<std::uint64_t>();
        } else if (v->is_string()) {
            n = base::parse_unsigned(v->get<std::string>());
        }
        if (!n || *n < min || *n > max) {
            fail("\"" + std::string(name) + "\" " + quoted(*v) + " must be a whole number " +
                 std::to_string(min) + ".." + std::to_string(max) + " (or a \"0x\" hex string)");
            return std::nullopt;
        }
        return n;
    }

    std::optional<std::vector<std::string>> strings(std::string_view name) {
        const Json* v = get(name);
        if (v == nullptr) return std::nullopt;
        std::vector<std::string> out;
        if (v->is_string()) {
            out.push_back(v->get<std::string>());
            return out;
        }
        if (v->is_array()) {
            for (const Json& item : *v) {
                if (!item.is_string()) break;
                out.push_back(item.get<std::string>());
            }
            if (out.size() == v->size()) return out;
        }
        fail("\"" + std::string(name) + "\" must be a string or a list of strings");
        return std::nullopt;
    }

    std::optional<std::vector<std::uint8_t>> hex(std::string_view name) {
        const Json* v = get(name);
        if (v == nullptr) return std::nullopt;
        std::string digits;
        if (v->is_string()) {
            for (const char c : v->get<std::string>()) {
                if (c != ' ') digits.push_back(c);
            }
        }
        std::vector<std::uint8_t> out(digits.size() / 2);
        bool good = v->is_string() && digits.size() % 2 == 0 && !out.empty() &&
                    out.size() <= kMaxControlBytes;
        for (std::size_t i = 0; good && i < out.size(); ++i) {
            const auto [end, ec] =
                std::from_chars(digits.data() + 2 * i, digits.data() + 2 * i + 2, out[i], 16);
            good = ec == std::errc() && end == digits.data() + 2 * i + 2;
        }
        if (!good) {
            fail("\"" + std::string(name) + "\" must be 1.." + std::to_string(kMaxControlBytes) +
                 " bytes as hex digits, e.g. \"01ff\"");
            return std::nullopt;
        }
        return out;
    }

private:
    const Json* get(std::string_view name) {
        const auto it = request_.find(std::string(name));
        if (it != request_.end()) return &*it;
        fail("the request needs \"" + std::string(name) + "\"");
        return nullptr;
    }
    void fail(std::string message) {
        if (error_.empty()) error_ = std::move(message);
    }

    const Json& request_;
    std::string error_;
};

// Why bytes [address, address + count) are not all in the space ("" when they are).
std::string range_problem(std::uint64_t number, const memory::MemorySpace& s, std::uint64_t address,
                          std::uint64_t count) {
    const std::uint64_t size = s.size();
    if (address >= s.lowest_address() && address + count <= size) return {};
    const std::string wanted = std::to_string(count) + " byte(s) at " + std::to_string(address);
    if (size <= s.lowest_address()) return space_name(number) + " holds no bytes; " + wanted;
    return space_name(number) + " holds addresses " + std::to_string(s.lowest_address()) + ".." +
           std::to_string(size - 1) + "; " + wanted + " do not fit";
}

// The space of node a read or write names, or null with why.
memory::MemorySpace* served_space(const SimNode& node, std::uint64_t number, std::string& why) {
    memory::MemorySpace* s = node.memory().space(static_cast<std::uint8_t>(number));
    if (s != nullptr) return s;
    std::string served;
    for (const std::uint8_t n : node.memory().served_spaces())
        served += (served.empty() ? "" : ", ") + std::to_string(n);
    why = "node " + node.node_id().to_string() + " serves no " + space_name(number) +
          " (it serves " + served + ")";
    return nullptr;
}

std::string write_failure(memory::WriteStatus status, std::uint64_t number) {
    switch (status) {
        case memory::WriteStatus::kReadOnly:
            return space_name(number) + " is read-only";
        case memory::WriteStatus::kOutOfBounds:
            return space_name(number) + ": the write does not fit";
        case memory::WriteStatus::kIoError:
            return space_name(number) + ": the image could not be written; nothing was stored";
        case memory::WriteStatus::kOk:
            break;
    }
    return {};
}

// A scenario node key's values from JSON: a string, a number, or a list of them.
std::optional<std::vector<std::string>> key_values(const Json& value) {
    const auto one = [](const Json& v) -> std::optional<std::string> {
        if (v.is_string()) return v.get<std::string>();
        if (v.is_number_integer()) return std::to_string(v.get<std::int64_t>());
        return std::nullopt;
    };
    std::vector<std::string> out;
    if (!value.is_array()) {
        auto v = one(value);
        if (!v) return std::nullopt;
        out.push_back(std::move(*v));
        return out;
    }
    for (const Json& item : value) {
        auto v = one(item);
        if (!v) return std::nullopt;
        out.push_back(std::move(*v));
    }
    return out;
}

// How deep arrays and objects nest in text, brackets inside strings not counted; counting stops
// past limit. Checked before parsing: the parse is iterative, but a quoted value is printed
// recursively, and 32,000 levels overflowed the stack under ASan.
std::size_t nesting_depth(std::string_view text, std::size_t limit) {
    std::size_t depth = 0;
    std::size_t deepest = 0;
    bool in_string = false;
    bool escaped = false;
    for (const char c : text) {
        if (in_string) {
            if (escaped) {
                escaped = false;
            } else if (c == '\\') {
                escaped = true;
            } else if (c == '"') {
                in_string = false;
            }
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
            if (deepest > limit) break;
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

// The count an add asks for when it is plainly too many, checked before the nodes' configs are
// built: each holds a copy of the CDI text, 100,000 of a 16 MiB CDI would exhaust memory.
std::optional<std::string> too_many_added(const std::vector<NodeKey>& keys) {
    for (const auto& [key, values] : keys) {
        if (key != "count" || values.size() != 1) continue;
        const std::string& text = values.front();
        std::uint64_t n = 0;
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
        if (end != text.data() + text.size() || text.empty()) return std::nullopt;
        if (ec == std::errc::result_out_of_range || n > kMaxAddedNodes) return text;
    }
    return std::nullopt;
}

}  // namespace

ControlCommands::ControlCommands(NodeRegistry& registry, const Scenario& running)
    : registry_(registry), running_(running) {}

void ControlCommands::log(const std::string& line) const {
    if (log_) log_(line);
}

Json ControlCommands::handle_line(std::string_view line) {
    if (nesting_depth(line, kMaxControlDepth) > kMaxControlDepth) {
        return refused("request nested deeper than " + std::to_string(kMaxControlDepth) +
                       " levels of arrays and objects");
    }
    Json request;
    try {
        request = Json::parse(line);
    } catch (const Json::exception& e) {
        // The parser quotes what it read last, which may be the whole line: cut it.
        std::string what = e.what();
        if (what.size() > kMaxParseMessage) what = what.substr(0, kMaxParseMessage) + "...";
        return refused("not JSON: " + what);
    }
    return handle(request);
}

Json ControlCommands::handle(const Json& request) {
    Json response;
    try {
        response = dispatch(request);
    } catch (const std::exception& e) {
        // A bug must cost one request, never the nodes and their hub connections.
        response = refused(std::string("internal error: ") + e.what());
    }
    // Scalars only: a nested "id" would be serialised back recursively.
    if (request.is_object()) {
        const auto id = request.find("id");
        if (id != request.end() && id->is_primitive()) response["id"] = *id;
    }
    return response;
}

Json ControlCommands::dispatch(const Json& request) {
    using Handler = Json (ControlCommands::*)(const Json&);
    static constexpr std::pair<std::string_view, Handler> kHandlers[] = {
        {"list", &ControlCommands::list},
        {"set-faults", &ControlCommands::set_faults},
        {"clear-faults", &ControlCommands::clear_faults},
        {"read", &ControlCommands::read},
        {"write", &ControlCommands::write},
        {"reboot", &ControlCommands::reboot},
        {"add", &ControlCommands::add},
        {"remove", &ControlCommands::remove},
    };
    if (!request.is_object()) {
        return refused("a request is a JSON object, e.g. {\"cmd\":\"list\"}");
    }
    const auto cmd = request.find("cmd");
    if (cmd == request.end() || !cmd->is_string()) {
        return refused(
            "the request needs \"cmd\", a string (commands: " + std::string(kCommandList) + ")");
    }
    const std::string name = cmd->get<std::string>();
    for (const auto& [command, handler] : kHandlers) {
        if (command == name) return (this->*handler)(request);
    }
    return refused("unknown command " + quoted(*cmd) + " (commands: " + std::string(kCommandList) +
                   ")");
}

Json ControlCommands::list(const Json& request) {
    Fields f(request, "list", {});
    if (!f.ok()) return refused(f.error());
    Json nodes = Json::array();
    for (const auto& node : registry_.nodes()) nodes.push_back(describe(*node));
    return accepted({{"nodes", std::move(nodes)}});
}

Json ControlCommands::change_faults(SimNode& node, const FaultSet& faults) {
    if (faults == node.config().faults) {
        Json body = describe(node);
        body["restarted"] = false;
        return accepted(body);
    }
    const NodeId id = node.node_id();  // node is destroyed by set_faults()
    std::string error;
    SimNode* fresh = registry_.set_faults(id, faults, error);
    if (fresh == nullptr) return refused("node " + id.to_string() + ": " + error);
    log("control: node " + id.to_string() + " faults " + fault_text(faults) + " (restarted)");
    Json body = describe(*fresh);
    body["restarted"] = true;
    return accepted(body);
}

Json ControlCommands::set_faults(const Json& request) {
    Fields f(request, "set-faults", {"node", "faults"});
    SimNode* node = f.node(registry_);
    const auto given = f.strings("faults");
    if (!f.ok()) return refused(f.error());
    std::string error;
    // The request's names alone first, so the error is about them.
    if (!parse_faults(*given, error)) return refused(error);
    std::vector<std::string> names = to_names(node->config().faults);
    names.insert(names.end(), given->begin(), given->end());
    const auto faults = parse_faults(names, error);
    if (!faults) return refused(error);
    return change_faults(*node, *faults);
}

Json ControlCommands::clear_faults(const Json& request) {
    Fields f(request, "clear-faults", {"node", "faults"});
    SimNode* node = f.node(registry_);
    std::optional<std::vector<std::string>> given;
    if (f.has("faults")) given = f.strings("faults");
    if (!f.ok()) return refused(f.error());
    FaultSet faults;
    if (given) {
        std::set<std::string> cleared;
        for (const auto& entry : split_faults(*given)) {
            const std::string name = fault_name(entry);
            if (!known_fault(name)) {
                return refused("unknown fault '" + name + "' (simnode --list-faults names them)");
            }
            cleared.insert(name);
        }
        std::vector<std::string> kept;
        for (const auto& entry : to_names(node->config().faults)) {
            if (!cleared.contains(fault_name(entry))) kept.push_back(entry);
        }
        std::string error;
        faults = parse_faults(kept, error).value_or(FaultSet{});
    }
    return change_faults(*node, faults);
}

Json ControlCommands::read(const Json& request) {
    Fields f(request, "read", {"node", "space", "address", "count"});
    const SimNode* node = f.node(registry_);
    const auto number = f.number("space", 0, kMaxSpace);
    const auto address = f.number("address", 0, kMaxAddress);
    const auto count = f.number("count", 1, kMaxControlBytes);
    if (!f.ok()) return refused(f.error());
    std::string why;
    const memory::MemorySpace* s = served_space(*node, *number, why);
    if (s == nullptr) return refused(why);
    if (auto problem = range_problem(*number, *s, *address, *count); !problem.empty()) {
        return refused(problem);
    }
    const auto bytes = node->memory().read(static_cast<std::uint8_t>(*number),
                                           static_cast<std::uint32_t>(*address),
                                           static_cast<std::uint32_t>(*count));
    return accepted({{"node", node->node_id().to_string()},
                     {"space", *number},
                     {"address", *address},
                     // Lowercase: the reply docs/control.md shows, which clients compare as text.
                     {"data", base::hex_bytes(bytes, "", base::HexCase::kLower)}});
}

Json ControlCommands::write(const Json& request) {
    Fields f(request, "write", {"node", "space", "address", "data"});
    SimNode* node = f.node(registry_);
    const auto number = f.number("space", 0, kMaxSpace);
    const auto address = f.number("address", 0, kMaxAddress);
    const auto data = f.hex("data");
    if (!f.ok()) return refused(f.error());
    std::string why;
    const memory::MemorySpace* s = served_space(*node, *number, why);
    if (s == nullptr) return refused(why);
    if (s->read_only()) return refused(space_name(*number) + " is read-only");
    if (auto problem = range_problem(*number, *s, *address, data->size()); !problem.empty()) {
        return refused(problem);
    }
    const auto status = node->write_memory(static_cast<std::uint8_t>(*number),
                                           static_cast<std::uint32_t>(*address), *data);
    if (status != memory::WriteStatus::kOk) {
        return refused(write_failure(status, *number));
    }
    log("control: node " + node->node_id().to_string() + ": wrote " + std::to_string(data->size()) +
        " byte(s) to " + space_name(*number) + " at " + std::to_string(*address));
    return accepted({{"node", node->node_id().to_string()},
                     {"space", *number},
                     {"address", *address},
                     {"written", data->size()}});
}

Json ControlCommands::reboot(const Json& request) {
    Fields f(request, "reboot", {"node"});
    SimNode* node = f.node(registry_);
    if (!f.ok()) return refused(f.error());
    if (!registry_.started()) {
        return refused("the nodes have not started yet (simnode waits for its hub)");
    }
    node->reboot(Clock::now());
    log("control: node " + node->node_id().to_string() + " rebooting");
    return accepted({{"node", node->node_id().to_string()}});
}

Json ControlCommands::add(const Json& request) {
    std::vector<NodeKey> keys;
    for (const auto& [key, value] : request.items()) {
        if (key == "cmd" || key == "id") continue;
        auto values = key_values(value);
        if (!values) return refused("\"" + key + "\" must be a string, a number or a list of them");
        keys.emplace_back(key, std::move(*values));
    }
    const std::string at_most =
        "one add makes at most " + std::to_string(kMaxAddedNodes) + " nodes";
    if (const auto count = too_many_added(keys))
        return refused(at_most + " (count " + *count + ")");
    std::string error;
    auto configs = parse_node_group(keys, running_, error);
    if (!configs) return refused(error);
    if (configs->size() > kMaxAddedNodes) return refused(at_most);
    const std::size_t running = registry_.nodes().size();
    if (running + configs->size() > max_nodes_) {
        return refused("simnode runs at most " + std::to_string(max_nodes_) + " nodes; " +
                       std::to_string(running) + " run now, so at most " +
                       std::to_string(max_nodes_ - std::min(running, max_nodes_)) +
                       " more can be added");
    }
    for (const auto& config : *configs) {
        if (registry_.find(config.node_id) != nullptr) {
            return refused("node " + config.node_id.to_string() + " is already running");
        }
    }
    Json added = Json::array();
    Json warnings = Json::array();
    for (const auto& config : *configs) {
        const std::string id = config.node_id.to_string();
        const SimNode* node = registry_.add(config, error);
        if (node == nullptr) {
            std::string message = "node " + id;
            message += ": ";
            message += error;
            Json out = refused(std::move(message));
            out["added"] = std::move(added);  // the ones before it run
            return out;
        }
        if (!node->cdi_problem().empty()) {
            warnings.push_back("node " + id +
                               " serves a CDI that is not valid: " + node->cdi_problem());
        }
        log("control: added node " + id + " cdi " + node->config().cdi_file.string() + " faults " +
            fault_text(node->config().faults));
        added.push_back(describe(*node));
    }
    return accepted({{"added", std::move(added)}, {"warnings", std::move(warnings)}});
}

Json ControlCommands::remove(const Json& request) {
    Fields f(request, "remove", {"node"});
    const SimNode* node = f.node(registry_);
    if (!f.ok()) return refused(f.error());
    const NodeId id = node->node_id();
    const Json alias = alias_json(node->stack().alias());
    registry_.remove(id);
    log("control: removed node " + id.to_string() +
        (alias.is_null() ? std::string() : " (AMR for alias " + alias.get<std::string>() + ")"));
    return accepted({{"node", id.to_string()}, {"alias", alias}});
}

}  // namespace olcb::simnode
