#include "conformance/config_backup.hpp"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>

#include "cdi/parser.hpp"
#include "cdi/value_codec.hpp"
#include "conformance/report.hpp"
#include "conformance/runner.hpp"
#include "conformance/session.hpp"

namespace olcb::conform {

namespace {

// A space extent larger than this is read variable by variable: a bad CDI must not make the
// tool allocate without bound.
constexpr std::uint64_t kMaxExtentRead = 1u << 20;
constexpr std::uint32_t kMaxCdiBytes = 1u << 24;

template <class Container>
std::size_t index_in(const Container& siblings, const cdi::Element& e) {
    return static_cast<std::size_t>(&e - siblings.data());
}

std::string part_name(const std::string& name, std::size_t index) {
    return name.empty() ? "child" + std::to_string(index) : escape_backup_text(name);
}

bool backed_up(const cdi::Element& e) {
    return e.kind != cdi::ElementKind::kAction && cdi::value_kind_of(e).has_value();
}

}  // namespace

std::string backup_key(const cdi::Layout& layout, const cdi::Cursor& c) {
    const cdi::Segment& seg = layout.document().segments[c.segment_index()];
    std::string key =
        seg.name.empty() ? "seg" + std::to_string(c.segment_index()) : escape_backup_text(seg.name);
    const std::vector<cdi::Element>* siblings = &seg.children;
    for (std::size_t level = 0; level < c.group_depth(); ++level) {
        const cdi::Element& g = c.group(level);
        key += "." + part_name(g.name, index_in(*siblings, g));
        if (g.replication > 1) key += "(" + std::to_string(c.replica(level)) + ")";
        siblings = &g.children;
    }
    const cdi::Element& v = c.element();
    key += "." + part_name(v.name, index_in(*siblings, v));
    return key;
}

namespace {

void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
        out += static_cast<char>(cp);
    } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
    }
}

// Decodes the UTF-8 sequence at text[i]; its code point and length, or length 0 when invalid.
std::pair<std::uint32_t, std::size_t> decode_utf8(std::string_view text, std::size_t i) {
    const auto b0 = static_cast<unsigned char>(text[i]);
    std::size_t len = b0 < 0x80         ? 1
                      : (b0 >> 5) == 6  ? 2
                      : (b0 >> 4) == 14 ? 3
                      : (b0 >> 3) == 30 ? 4
                                        : 0;
    if (len == 0 || i + len > text.size()) return {0, 0};
    std::uint32_t cp = len == 1 ? b0 : b0 & (0x7F >> len);
    for (std::size_t k = 1; k < len; ++k) {
        const auto b = static_cast<unsigned char>(text[i + k]);
        if ((b & 0xC0) != 0x80) return {0, 0};
        cp = (cp << 6) | (b & 0x3F);
    }
    return {cp, len};
}

bool needs_escape(std::uint32_t cp) {
    return cp == '=' || cp == '\\' || cp < 0x20 || (cp >= 0x7F && cp <= 0x9F) ||
           (cp >= 0xD800 && cp <= 0xDFFF) || cp == 0xFFFE || cp == 0xFFFF;
}

std::string hex4(std::uint32_t v) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string s = "\\x";
    for (int shift = 12; shift >= 0; shift -= 4) s += kHex[(v >> shift) & 0xF];
    return s;
}

std::string_view trim_line(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

// An integer written unsigned (OpenLCB_Java's reading) of a signed variable: its raw bytes.
std::optional<std::vector<std::uint8_t>> unsigned_int_bytes(const cdi::Element& e,
                                                            std::string_view text) {
    while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    std::uint64_t v = 0;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    if (e.size == 0 || e.size > 8) return std::nullopt;
    if (e.size < 8 && v >> (8 * e.size) != 0) return std::nullopt;
    std::vector<std::uint8_t> bytes(e.size);
    for (std::size_t k = 0; k < e.size; ++k) bytes[e.size - 1 - k] = (v >> (8 * k)) & 0xFF;
    return bytes;
}

// The bytes of one entry's value text, or an error message.
std::optional<std::vector<std::uint8_t>> value_bytes(const cdi::Element& e, std::string_view text,
                                                     std::string& error) {
    const bool is_string = e.kind == cdi::ElementKind::kString;
    const std::string raw = is_string ? unescape_backup_text(text) : std::string(text);
    auto value = cdi::parse_value_text(e, raw);
    if (value) {
        auto bytes = cdi::encode(e, *value);
        if (bytes) return std::move(bytes).value();
        error = bytes.error().message;
    } else {
        error = value.error().message;
    }
    if (cdi::value_kind_of(e) == cdi::ValueKind::kInt) {
        if (auto bytes = unsigned_int_bytes(e, raw)) return bytes;
    }
    return std::nullopt;
}

}  // namespace

std::vector<ConfigEntry> config_entries(const cdi::Layout& layout) {
    std::vector<ConfigEntry> out;
    layout.visit([&](const cdi::Cursor& c) {
        if (!backed_up(c.element())) return;
        out.push_back({backup_key(layout, c), &c.element(), c.space(), c.address()});
    });
    return out;
}

std::string escape_backup_text(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size();) {
        auto [cp, len] = decode_utf8(text, i);
        if (len == 0) {  // not UTF-8: keep the byte visible and reversible
            out += hex4(static_cast<unsigned char>(text[i]));
            ++i;
            continue;
        }
        if (needs_escape(cp)) {
            out += hex4(cp);
        } else {
            out.append(text.substr(i, len));
        }
        i += len;
    }
    return out;
}

std::string unescape_backup_text(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\\' && i + 5 < text.size() && text[i + 1] == 'x') {
            std::uint32_t cp = 0;
            auto [end, ec] = std::from_chars(text.data() + i + 2, text.data() + i + 6, cp, 16);
            if (ec == std::errc() && end == text.data() + i + 6) {
                append_utf8(out, cp);
                i += 5;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

std::string make_config_backup(const cdi::Layout& layout, MemoryAccess& memory,
                               const std::string& node_id, std::vector<std::string>& errors) {
    // One read per space extent when it is small enough; otherwise per variable.
    std::map<std::uint32_t, std::pair<std::uint64_t, std::vector<std::uint8_t>>> images;
    for (const cdi::SpaceExtent& x : layout.extents()) {
        if (x.space > 0xFF || x.end <= x.begin || x.end - x.begin > kMaxExtentRead ||
            x.end > 0x1'0000'0000ull)
            continue;
        AccessResult r = memory.read(static_cast<std::uint8_t>(x.space),
                                     static_cast<std::uint32_t>(x.begin), x.end - x.begin);
        if (r.ok) images[x.space] = {x.begin, std::move(r.data)};
    }
    std::ostringstream text;
    text << "# OpenLCB configuration backup of node " << node_id << " (lcc-conform)\n";
    text << "# node " << node_id << "\n";
    for (const ConfigEntry& e : config_entries(layout)) {
        const std::uint64_t size =
            e.element->kind == cdi::ElementKind::kEventId ? 8 : e.element->size;
        std::vector<std::uint8_t> bytes;
        auto img = images.find(e.space);
        if (img != images.end() && e.address >= img->second.first &&
            e.address + size <= img->second.first + img->second.second.size()) {
            auto from = img->second.second.begin() +
                        static_cast<std::ptrdiff_t>(e.address - img->second.first);
            bytes.assign(from, from + static_cast<std::ptrdiff_t>(size));
        } else if (e.space <= 0xFF && e.address + size <= 0x1'0000'0000ull && size <= 0xFFFF) {
            AccessResult r = memory.read(static_cast<std::uint8_t>(e.space),
                                         static_cast<std::uint32_t>(e.address), size);
            if (!r.ok || r.data.size() != size) {
                std::ostringstream m;
                m << e.key << ": read failed (error 0x" << std::hex << r.error << ")";
                errors.push_back(m.str());
                continue;
            }
            bytes = std::move(r.data);
        } else {
            errors.push_back(e.key + ": outside any readable address");
            continue;
        }
        auto value = cdi::decode(*e.element, bytes, cdi::CodecMode::kLenient);
        if (!value) {
            errors.push_back(e.key + ": " + value.error().message);
            continue;
        }
        std::string shown = cdi::format_value(*e.element, *value);
        if (e.element->kind == cdi::ElementKind::kString) shown = escape_backup_text(shown);
        text << e.key << "=" << shown << "\n";
    }
    return text.str();
}

std::string ConfigRestoreOutcome::summary() const {
    std::ostringstream s;
    s << written << " variable(s) written";
    if (!unknown_keys.empty()) s << ", " << unknown_keys.size() << " unknown key(s) skipped";
    if (!errors.empty()) s << ", " << errors.size() << " error(s)";
    for (const auto& k : unknown_keys) s << "\n  unknown key: " << k;
    for (const auto& e : errors) s << "\n  error: " << e;
    return s.str();
}

ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text) {
    ConfigRestoreOutcome out;
    // Keys may repeat (siblings with one name): the n-th line of a key is its n-th variable.
    std::map<std::string, std::vector<const ConfigEntry*>, std::less<>> by_key;
    const std::vector<ConfigEntry> entries = config_entries(layout);
    for (const ConfigEntry& e : entries) by_key[e.key].push_back(&e);
    std::map<std::string, std::size_t, std::less<>> seen;
    std::size_t line_no = 0;
    while (!text.empty()) {
        const auto nl = text.find('\n');
        std::string_view line = trim_line(text.substr(0, nl));
        text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
        ++line_no;
        if (line.empty() || line.front() == '#') continue;
        const auto eq = line.find('=');
        if (eq == std::string_view::npos) {
            out.errors.push_back("line " + std::to_string(line_no) + ": no '='");
            continue;
        }
        const std::string_view key = line.substr(0, eq);
        const auto it = by_key.find(key);
        const std::size_t nth = it == by_key.end() ? 0 : seen[it->first]++;
        if (it == by_key.end() || nth >= it->second.size()) {
            out.unknown_keys.emplace_back(key);
            continue;
        }
        const ConfigEntry& e = *it->second[nth];
        std::string error;
        auto bytes = value_bytes(*e.element, line.substr(eq + 1), error);
        if (!bytes) {
            out.errors.push_back(e.key + ": " + error);
            continue;
        }
        AccessResult w = memory.write(static_cast<std::uint8_t>(e.space),
                                      static_cast<std::uint32_t>(e.address), *bytes);
        if (!w.ok) {
            std::ostringstream m;
            m << e.key << ": write failed (error 0x" << std::hex << w.error << ")";
            out.errors.push_back(m.str());
            continue;
        }
        ++out.written;
    }
    return out;
}

std::optional<std::string> config_backup_node(std::string_view text) {
    constexpr std::string_view kPrefix = "# node ";
    while (!text.empty() && text.front() == '#') {
        const auto nl = text.find('\n');
        std::string_view line = trim_line(text.substr(0, nl));
        if (line.starts_with(kPrefix)) return std::string(line.substr(kPrefix.size()));
        if (nl == std::string_view::npos) break;
        text.remove_prefix(nl + 1);
    }
    return std::nullopt;
}

bool load_node_config(Session& session, const NodeInfo& node, NodeConfig& config,
                      std::string& error) {
    MemResult cdi = session.read_range(node, memory::Space::kCdi, 0, kMaxCdiBytes, true);
    if (cdi.data.empty()) {
        std::ostringstream m;
        m << "could not read the CDI (space 0xFF, error 0x" << std::hex << cdi.error << ")";
        error = m.str();
        return false;
    }
    std::string_view xml(reinterpret_cast<const char*>(cdi.data.data()), cdi.data.size());
    if (auto nul = xml.find('\0'); nul != std::string_view::npos) xml = xml.substr(0, nul);
    cdi::ParseResult parsed = cdi::parse(xml);
    if (!parsed.document) {
        error = "the CDI does not parse";
        return false;
    }
    config.document = std::make_unique<cdi::Document>(std::move(*parsed.document));
    cdi::LayoutResult laid = cdi::build_layout(*config.document);
    if (!laid.layout) {
        error = "the CDI has no valid address layout";
        return false;
    }
    config.layout.emplace(std::move(*laid.layout));
    return true;
}

namespace {

std::optional<NodeInfo> find(Session& session, const std::string& id_text, std::ostream& err) {
    std::string error;
    auto id = NodeId::parse(id_text, &error);
    if (!id) {
        err << "lcc-conform: node ID '" << id_text << "': " << error << "\n";
        return std::nullopt;
    }
    auto node = session.find_node(*id);
    if (!node) err << "lcc-conform: node " << id->to_string() << " does not answer\n";
    return node;
}

}  // namespace

int run_config_backup(Session& session, const std::string& node_id, const std::string& path,
                      std::ostream& out, std::ostream& err) {
    auto node = find(session, node_id, err);
    if (!node) return 2;
    NodeConfig config;
    std::string error;
    if (!load_node_config(session, *node, config, error)) {
        err << "lcc-conform: " << error << "\n";
        return 2;
    }
    SessionMemory memory(session, *node);
    std::vector<std::string> errors;
    const std::string text =
        make_config_backup(*config.layout, memory, node->id.to_string(), errors);
    if (!write_file(path, text, error)) {
        err << "lcc-conform: " << error << "\n";
        return 2;
    }
    const auto lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
    out << "backup: " << (lines - 2) << " variable(s) of node " << node->id.to_string()
        << " written to " << path << "\n";
    for (const auto& e : errors) err << "backup: " << e << "\n";
    return errors.empty() ? 0 : 1;
}

int run_restore(Session& session, const std::string& path, const std::string& node_id,
                std::ostream& out, std::ostream& err) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        err << "lcc-conform: cannot read " << path << "\n";
        return 2;
    }
    std::ostringstream buf;
    buf << in.rdbuf();
    const std::string text = buf.str();
    std::string error;
    if (SafetyBackup::is_safety_backup(text)) {
        auto outcome = restore_file(session, path, error);
        if (!outcome) {
            err << "lcc-conform: " << error << "\n";
            return 2;
        }
        out << "restore: " << outcome->summary() << "\n";
        return outcome->identical ? 0 : 1;
    }
    std::string id = node_id;
    if (id.empty()) id = config_backup_node(text).value_or("");
    if (id.empty()) {
        err << "lcc-conform: " << path << " names no node: pass --node ID\n";
        return 2;
    }
    auto node = find(session, id, err);
    if (!node) return 2;
    NodeConfig config;
    if (!load_node_config(session, *node, config, error)) {
        err << "lcc-conform: " << error << "\n";
        return 2;
    }
    SessionMemory memory(session, *node);
    ConfigRestoreOutcome outcome = restore_config(*config.layout, memory, text);
    out << "restore: " << outcome.summary() << "\n";
    return outcome.ok() ? 0 : 1;
}

}  // namespace olcb::conform
