#include "conformance/backup/config_restore.hpp"

#include <map>
#include <sstream>

#include "base/hex.hpp"
#include "base/utf8.hpp"
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

// A file value matched to its variable: unchanged, a change, or refused by the CDI's rules.
void place_value(RestorePlan& plan, const ConfigEntry& e, const BackupRecord& r,
                 const std::optional<std::string>& node) {
    ValueVerdict verdict = judge_backup_value(*e.element, r.value);
    std::string error;
    std::optional<std::string> canonical;
    if (verdict.bytes) canonical = format_backup_value(*e.element, *verdict.bytes, error);
    if (node && canonical && *node == *canonical) {
        ++plan.unchanged;  // never written, so the rules do not apply
        return;
    }
    if (!canonical && verdict.allowed()) {  // bytes with no backup form: an int size JMRI lacks
        verdict.broken = ValueRule::kMalformed;
        verdict.why = error;
        verdict.bytes.reset();
    }
    if (!verdict.allowed()) {
        plan.refused.push_back({&e, r.line, r.value, node, std::move(verdict)});
        return;
    }
    plan.changes.push_back({&e, node, r.value, std::move(*verdict.bytes)});
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
        const std::optional<std::string>& node =
            i < node_values.size() ? node_values[i].text : std::nullopt;
        place_value(plan, e, r, node);
    }
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!matched[i]) plan.missing.push_back(&entries[i]);
    }
    return plan;
}

std::string refused_text(const RefusedValue& r) {
    const cdi::Element& e = *r.entry->element;
    std::string where =
        "<" + std::string(e.tag.empty() ? cdi::kind_name(e.kind) : e.tag.c_str()) + ">";
    if (e.pos.line != 0) where += " at CDI line " + std::to_string(e.pos.line);
    const std::string rule(rule_name(*r.verdict.broken));
    return base::printable("line " + std::to_string(r.line) + ": " + r.entry->key + "=" +
                           shown_value(r.file_value) + ": " + rule + ": " + r.verdict.why + " (" +
                           where + "; " + r.verdict.clause + ")");
}

std::size_t RestorePlan::forcible() const {
    std::size_t n = 0;
    for (const RefusedValue& r : refused) n += r.verdict.forcible();
    return n;
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

ConfigRestoreOutcome apply_restore(const RestorePlan& plan, MemoryAccess& memory, bool force) {
    // What is written: every change, and with force the refused values that have bytes.
    struct Write {
        const ConfigEntry* entry;
        const std::vector<std::uint8_t>* bytes;
        bool forced;
    };
    std::vector<Write> todo;
    todo.reserve(plan.changes.size() + plan.refused.size());
    for (const ValueChange& c : plan.changes) todo.push_back({c.entry, &c.bytes, false});
    for (const RefusedValue& r : plan.refused) {
        if (force && r.verdict.forcible()) todo.push_back({r.entry, &*r.verdict.bytes, true});
    }
    ConfigRestoreOutcome out;
    std::vector<ConfigEntry> written;
    std::vector<const Write*> kept;
    for (const Write& w : todo) {
        const ConfigEntry& e = *w.entry;
        AccessResult result = memory.write(static_cast<std::uint8_t>(e.space),
                                           static_cast<std::uint32_t>(e.address), *w.bytes);
        if (!result.ok) {
            out.errors.push_back(e.key + ": write failed (error " + base::hex(result.error) + ")");
            continue;
        }
        written.push_back(e);
        kept.push_back(&w);
    }
    // Read back: a node may refuse a value silently, or clamp it.
    const std::vector<ConfigValue> now = read_config_values(written, memory);
    for (std::size_t i = 0; i < written.size(); ++i) {
        std::string error;
        const auto want = format_backup_value(*written[i].element, *kept[i]->bytes, error);
        if (now[i].text && now[i].text == want) {
            ++out.written;
            out.forced += kept[i]->forced;
        } else {
            out.errors.push_back(written[i].key + ": wrote " + shown_value(want) +
                                 ", the node holds " + shown_value(now[i].text));
        }
    }
    return out;
}

ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text, bool force) {
    const std::vector<ConfigEntry> entries = config_entries(layout);
    const RestorePlan plan =
        plan_restore(entries, parse_backup_file(text), read_config_values(entries, memory));
    ConfigRestoreOutcome out = apply_restore(plan, memory, force);
    out.unknown_keys = plan.unknown_keys;
    std::vector<std::string> problems = plan.file_errors;
    for (const RefusedValue& r : plan.refused) {
        if (!force || !r.verdict.forcible()) problems.push_back(refused_text(r));
    }
    out.errors.insert(out.errors.begin(), problems.begin(), problems.end());
    return out;
}

std::string shown_value(const std::optional<std::string>& value) {
    return value ? "\"" + escape_backup_text(*value) + "\"" : "(unreadable)";
}

}  // namespace olcb::conform
