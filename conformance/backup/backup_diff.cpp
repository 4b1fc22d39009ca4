#include "conformance/backup/backup_diff.hpp"

#include <map>
#include <ostream>

#include "base/utf8.hpp"
#include "cdi/decimal.hpp"

namespace olcb::conform {

namespace {

// The same stored bytes for a negative and a non-negative integer in the smallest int size the
// non-negative one fits unsigned.
bool same_int(cdi::WideInt x, cdi::WideInt y) {
    if (x == y) return true;
    if ((x < 0) == (y < 0)) return false;
    const cdi::WideInt neg = x < 0 ? x : y;
    const cdi::WideInt pos = x < 0 ? y : x;
    for (int bytes : {1, 2, 4, 8}) {
        const cdi::WideInt span = cdi::WideInt{1} << (8 * bytes);
        if (pos >= span) continue;
        return pos >= span / 2 && neg >= -(span / 2) && neg + span == pos;
    }
    return false;
}

// Per key, the values of its lines in file order.
std::map<std::string, std::vector<const BackupRecord*>, std::less<>> by_key(const BackupFile& f) {
    std::map<std::string, std::vector<const BackupRecord*>, std::less<>> out;
    for (const BackupRecord& r : f.records) out[r.key].push_back(&r);
    return out;
}

}  // namespace

bool same_backup_value(std::string_view a, std::string_view b) {
    if (a == b) return true;
    const auto x = cdi::parse_decimal_int(a);
    const auto y = cdi::parse_decimal_int(b);
    if (x && y) return same_int(*x, *y);
    const auto fx = cdi::parse_decimal_float(a);
    const auto fy = cdi::parse_decimal_float(b);
    return fx && fy && *fx == *fy;
}

std::vector<BackupDifference> diff_backups(const BackupFile& a, const BackupFile& b) {
    std::vector<BackupDifference> out;
    const auto in_b = by_key(b);
    std::map<std::string, std::size_t, std::less<>> seen;
    for (const BackupRecord& r : a.records) {
        const std::size_t nth = seen[r.key]++;
        const auto it = in_b.find(r.key);
        if (it == in_b.end() || nth >= it->second.size()) {
            out.push_back({r.key, r.value, std::nullopt});
        } else if (!same_backup_value(r.value, it->second[nth]->value)) {
            out.push_back({r.key, r.value, it->second[nth]->value});
        }
    }
    for (const auto& [key, records] : in_b) {
        const auto it = seen.find(key);
        const std::size_t in_a = it == seen.end() ? 0 : it->second;
        for (std::size_t n = in_a; n < records.size(); ++n) {
            out.push_back({key, std::nullopt, records[n]->value});
        }
    }
    return out;
}

void print_differences(const std::vector<BackupDifference>& diffs, std::size_t keys,
                       std::ostream& out) {
    for (const BackupDifference& d : diffs) {
        if (d.a && d.b) {
            out << "  changed    " << base::printable(d.key) << ": "
                << base::printable(shown_value(d.a)) << " -> " << base::printable(shown_value(d.b))
                << "\n";
        } else if (d.a) {
            out << "  only in A  " << base::printable(d.key) << " = "
                << base::printable(shown_value(d.a)) << "\n";
        } else {
            out << "  only in B  " << base::printable(d.key) << " = "
                << base::printable(shown_value(d.b)) << "\n";
        }
    }
    out << "diff: " << diffs.size() << " difference(s) in " << keys << " key(s)\n";
}

void print_problems(const RestorePlan& plan, std::ostream& out, bool force) {
    for (const std::string& k : plan.unknown_keys) {
        out << "  unknown    " << base::printable(k) << "\n";
    }
    for (const RefusedValue& r : plan.refused) {
        const bool forced = force && r.verdict.forcible();
        out << (forced ? "  forced     " : "  refused    ") << refused_text(r)
            << (forced ? " [--force: written anyway]" : "") << "\n";
    }
    for (const std::string& e : plan.file_errors) {
        out << "  malformed  " << base::printable(e) << "\n";
    }
}

void print_plan(const RestorePlan& plan, bool show_missing, std::ostream& out, bool force) {
    for (const ValueChange& c : plan.changes) {
        out << "  change     " << base::printable(c.entry->key) << ": node "
            << base::printable(shown_value(c.node_value)) << " -> file "
            << base::printable(shown_value(c.file_value)) << "\n";
    }
    print_problems(plan, out, force);
    if (show_missing) {
        for (const ConfigEntry* e : plan.missing) {
            out << "  not in file " << base::printable(e->key) << "\n";
        }
    }
}

}  // namespace olcb::conform
