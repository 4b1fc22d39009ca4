#include "conformance/backup/config_restore.hpp"

#include <map>
#include <sstream>

#include "base/hex.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

std::string at_line(const BackupRecord& r) {
    return "line " + std::to_string(r.line) + ": " + r.key;
}

std::string place_text(const std::string& type, std::uint32_t space, std::uint64_t address,
                       std::uint64_t size) {
    return type + " of " + std::to_string(size) + " byte(s) at space " + std::to_string(space) +
           " address " + std::to_string(address);
}

// Why a CSV row's place is not the entry's, or "" when it is.
std::string place_mismatch(const ConfigEntry& e, const std::optional<BackupPlace>& place) {
    if (!place) return {};
    const BackupPlace mine{backup_type_name(*e.element), e.space, e.address, e.size};
    if (*place == mine) return {};
    return "a key of another CDI: the file's variable is " +
           place_text(place->type, place->space, place->address, place->size) + ", the node's " +
           place_text(mine.type, mine.space, mine.address, mine.size);
}

bool counts_as_node_key(const ConfigEntry& e, bool floats_count) {
    return floats_count || e.element->kind != cdi::ElementKind::kFloat;
}

}  // namespace

RestorePlan plan_restore(const std::vector<ConfigEntry>& entries, const BackupFile& file,
                         const std::vector<ConfigValue>& node_values) {
    RestorePlan plan;
    plan.file_errors = file.errors;
    std::map<std::string, std::vector<std::size_t>, std::less<>> by_key;
    for (std::size_t i = 0; i < entries.size(); ++i) by_key[entries[i].key].push_back(i);
    // OpenLCB_Java writes no floats, so they do not count towards "the node's keys" (unless the
    // node has nothing else).
    bool floats_count = true;
    for (const ConfigEntry& e : entries) {
        if (e.element->kind != cdi::ElementKind::kFloat) floats_count = false;
    }
    for (const ConfigEntry& e : entries) plan.node_keys += counts_as_node_key(e, floats_count);
    std::vector<bool> matched(entries.size(), false);
    std::map<std::string, std::size_t, std::less<>> seen;
    for (const BackupRecord& r : file.records) {
        const auto it = by_key.find(r.key);
        const std::size_t nth = it == by_key.end() ? 0 : seen[r.key]++;
        if (it == by_key.end() || nth >= it->second.size()) {
            plan.unknown_keys.push_back(at_line(r));
            continue;
        }
        const std::size_t i = it->second[nth];
        const ConfigEntry& e = entries[i];
        if (std::string why = place_mismatch(e, r.place); !why.empty()) {
            plan.unknown_keys.push_back(at_line(r) + " (" + why + ")");
            continue;
        }
        matched[i] = true;
        plan.matched += counts_as_node_key(e, floats_count);
        std::string error;
        auto bytes = parse_backup_value(*e.element, r.value, error);
        std::optional<std::string> canonical;
        if (bytes) canonical = format_backup_value(*e.element, *bytes, error);
        if (!canonical) {
            plan.bad_values.push_back(at_line(r) + "=" + escape_backup_text(r.value) + ": " +
                                      error);
            continue;
        }
        const std::optional<std::string>& node =
            i < node_values.size() ? node_values[i].text : std::nullopt;
        if (node && *node == *canonical) {
            ++plan.unchanged;
            continue;
        }
        plan.changes.push_back({&e, node, r.value, std::move(*bytes)});
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!matched[i]) plan.missing.push_back(&entries[i]);
    }
    return plan;
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

ConfigRestoreOutcome apply_restore(const RestorePlan& plan, MemoryAccess& memory) {
    ConfigRestoreOutcome out;
    std::vector<ConfigEntry> written;
    std::vector<const ValueChange*> kept;
    for (const ValueChange& c : plan.changes) {
        const ConfigEntry& e = *c.entry;
        AccessResult w = memory.write(static_cast<std::uint8_t>(e.space),
                                      static_cast<std::uint32_t>(e.address), c.bytes);
        if (!w.ok) {
            out.errors.push_back(e.key + ": write failed (error " + base::hex(w.error) + ")");
            continue;
        }
        written.push_back(e);
        kept.push_back(&c);
    }
    // Read back: a node may refuse a value silently, or clamp it.
    const std::vector<ConfigValue> now = read_config_values(written, memory);
    for (std::size_t i = 0; i < written.size(); ++i) {
        std::string error;
        const auto want = format_backup_value(*written[i].element, kept[i]->bytes, error);
        if (now[i].text && now[i].text == want) {
            ++out.written;
        } else {
            out.errors.push_back(written[i].key + ": wrote " + shown_value(want) +
                                 ", the node holds " + shown_value(now[i].text));
        }
    }
    return out;
}

ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text) {
    const std::vector<ConfigEntry> entries = config_entries(layout);
    const RestorePlan plan =
        plan_restore(entries, parse_backup_file(text), read_config_values(entries, memory));
    ConfigRestoreOutcome out = apply_restore(plan, memory);
    out.unknown_keys = plan.unknown_keys;
    out.errors.insert(out.errors.begin(), plan.bad_values.begin(), plan.bad_values.end());
    out.errors.insert(out.errors.begin(), plan.file_errors.begin(), plan.file_errors.end());
    return out;
}

std::string shown_value(const std::optional<std::string>& value) {
    return value ? "\"" + escape_backup_text(*value) + "\"" : "(unreadable)";
}

}  // namespace olcb::conform
