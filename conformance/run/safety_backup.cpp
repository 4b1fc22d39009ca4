#include "conformance/run/safety_backup.hpp"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string_view>

#include "base/error_codes.hpp"
#include "base/file.hpp"
#include "base/hex.hpp"
#include "base/number.hpp"

namespace olcb::conform {
namespace {

constexpr const char* kHeader = "# lcc-conform safety backup v1";
// A backup never holds more than a whole 32-bit space; refuse absurd files instead of allocating.
constexpr std::size_t kMaxRangeBytes = std::size_t{1} << 24;

std::string where(std::uint8_t space, std::uint32_t address) {
    return "space " + std::to_string(space) + " @" + base::hex(address, 8);
}

}  // namespace

std::vector<RangeRequest> merge_ranges(std::vector<RangeRequest> requests) {
    std::erase_if(requests, [](const RangeRequest& r) { return r.length == 0; });
    std::sort(requests.begin(), requests.end(), [](const RangeRequest& a, const RangeRequest& b) {
        return a.space != b.space ? a.space < b.space : a.address < b.address;
    });
    std::vector<RangeRequest> out;
    for (const RangeRequest& r : requests) {
        if (!out.empty() && out.back().space == r.space) {
            RangeRequest& last = out.back();
            std::uint64_t last_end = std::uint64_t{last.address} + last.length;
            if (r.address <= last_end) {
                std::uint64_t end = std::max(last_end, std::uint64_t{r.address} + r.length);
                last.length = static_cast<std::uint32_t>(end - last.address);
                continue;
            }
        }
        out.push_back(r);
    }
    return out;
}

std::vector<RangeRequest> SafetyBackup::uncovered(std::uint8_t space, std::uint32_t address,
                                                  std::uint32_t length) const {
    std::vector<RangeRequest> out{{space, address, length}};
    for (const BackupRange& saved : ranges_) {
        if (saved.space != space || saved.bytes.empty()) continue;
        const std::uint64_t s0 = saved.address;
        const std::uint64_t s1 = s0 + saved.bytes.size();
        std::vector<RangeRequest> rest;
        for (const RangeRequest& r : out) {
            const std::uint64_t r0 = r.address;
            const std::uint64_t r1 = r0 + r.length;
            if (s1 <= r0 || s0 >= r1) {
                rest.push_back(r);
                continue;
            }
            if (r0 < s0) rest.push_back({space, r.address, static_cast<std::uint32_t>(s0 - r0)});
            if (s1 < r1)
                rest.push_back(
                    {space, static_cast<std::uint32_t>(s1), static_cast<std::uint32_t>(r1 - s1)});
        }
        out = std::move(rest);
    }
    return out;
}

std::string SafetyBackup::save_bytes(MemoryAccess& memory, const RangeRequest& r) {
    // Bytes saved earlier keep their first value: a later read may see what a write changed.
    for (const RangeRequest& piece : uncovered(r.space, r.address, r.length)) {
        AccessResult got = memory.read(piece.space, piece.address, piece.length);
        if (got.ok && got.data.size() == piece.length) {
            ranges_.push_back({piece.space, piece.address, std::move(got.data)});
            continue;
        }
        if (got.ok) {
            return std::to_string(got.data.size()) + " of " + std::to_string(piece.length) +
                   " bytes came back";
        }
        return "read failed with " + base::hex(got.error, 4) +
               (got.error == base::to_u16(base::ErrorCode::kTimeout) ? " (timed out)" : "");
    }
    return {};
}

bool SafetyBackup::capture(MemoryAccess& memory, const std::vector<RangeRequest>& requests,
                           std::string& error) {
    for (const RangeRequest& r : merge_ranges(requests)) {
        if (std::string why = save_bytes(memory, r); !why.empty()) {
            error = "cannot read " + std::to_string(r.length) + " bytes at " +
                    where(r.space, r.address) + " for the backup (" + why + ")";
            return false;
        }
    }
    return save(error);
}

bool SafetyBackup::capture_available(MemoryAccess& memory,
                                     const std::vector<RangeRequest>& requests,
                                     std::vector<std::pair<RangeRequest, std::string>>& missing,
                                     std::string& error) {
    for (const RangeRequest& r : requests) {
        if (std::string why = save_bytes(memory, r); !why.empty()) missing.emplace_back(r, why);
    }
    return save(error);
}

std::string SafetyBackup::to_text() const {
    std::ostringstream out;
    out << kHeader << "\n";
    out << "# Bytes lcc-conform saved before writing; put them back with: lcc-conform restore "
           "FILE\n";
    out << "node " << node_id_ << "\n";
    for (const BackupRange& r : ranges_) {
        out << "range " << static_cast<unsigned>(r.space) << " " << base::hex(r.address, 8) << " "
            << r.bytes.size() << " " << base::hex_bytes(r.bytes, "") << "\n";
    }
    out << "end\n";
    return out.str();
}

bool SafetyBackup::save(std::string& error) const {
    // A fresh temporary name, created exclusively: with the fixed PATH.tmp opened O_TRUNC, a link
    // planted there had its target overwritten with this text and renamed into place.
    return base::write_file(path_, to_text(), error);
}

bool SafetyBackup::is_safety_backup(const std::string& text) {
    return text.rfind(kHeader, 0) == 0;
}

namespace {

// One field of a range line as a number of at most `max` (base::parse_unsigned: the whole
// field, decimal or 0x-hex); sscanf's %u wrapped 2^32 + 253 to space 253 instead of refusing it.
std::optional<std::uint64_t> range_field(std::string_view field, std::uint64_t max) {
    const auto value = base::parse_unsigned(field);
    return value && *value <= max ? value : std::nullopt;
}

// "range SPACE ADDRESS LENGTH HEX": one range of a safety backup; nullopt with `why` when not.
std::optional<BackupRange> parse_range_line(const std::string& line, std::string& why) {
    std::istringstream fields(line);
    std::string word, space_text, address_text, length_text, hex;
    fields >> word >> space_text >> address_text >> length_text;
    std::getline(fields >> std::ws, hex);
    const auto space = range_field(space_text, 255);
    // The address is written in hex with its 0x; a bare number is refused, not read as decimal.
    const bool hex_address = address_text.starts_with("0x") || address_text.starts_with("0X");
    const auto address = range_field(address_text, 0xFFFFFFFFu);
    const auto length = range_field(length_text, kMaxRangeBytes);
    if (word != "range" || !space || !hex_address || !address || !length) {
        why = "malformed range line";
        return std::nullopt;
    }
    if (hex.size() != *length * 2) {
        why = "range length does not match its bytes";
        return std::nullopt;
    }
    BackupRange r{static_cast<std::uint8_t>(*space), static_cast<std::uint32_t>(*address), {}};
    r.bytes.reserve(*length);
    for (std::size_t i = 0; i < *length; ++i) {
        const int hi = base::hex_value(hex[2 * i]);
        const int lo = base::hex_value(hex[2 * i + 1]);
        if (hi < 0 || lo < 0) {
            why = "bad hex digit";
            return std::nullopt;
        }
        r.bytes.push_back(static_cast<std::uint8_t>(hi << 4 | lo));
    }
    return r;
}

}  // namespace

std::optional<SafetyBackup> SafetyBackup::load(const std::string& path, std::string& error) {
    const auto text = base::read_file(path, error);
    if (!text) return std::nullopt;
    std::istringstream in(*text);
    std::string line;
    if (!std::getline(in, line) || line.rfind(kHeader, 0) != 0) {
        error = path + " is not an lcc-conform safety backup";
        return std::nullopt;
    }
    SafetyBackup backup(path, "");
    bool ended = false;
    std::size_t line_no = 1;
    while (std::getline(in, line)) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        auto bad = [&](const std::string& why) {
            error = path;
            error += ":" + std::to_string(line_no) + ": " + why;
            return std::nullopt;
        };
        if (line.rfind("node ", 0) == 0) {
            backup.node_id_ = line.substr(5);
        } else if (line == "end") {
            ended = true;
        } else if (line.rfind("range ", 0) == 0) {
            std::string why;
            auto range = parse_range_line(line, why);
            if (!range) return bad(why);
            backup.ranges_.push_back(std::move(*range));
        } else {
            return bad("unknown line");
        }
    }
    if (!ended) {
        error = path + " is incomplete (no 'end' line)";
        return std::nullopt;
    }
    if (backup.node_id_.empty()) {
        error = path + " names no node";
        return std::nullopt;
    }
    return backup;
}

void SafetyBackup::remove_file() const {
    std::remove(path_.c_str());
}

std::string RestoreOutcome::summary() const {
    if (identical) {
        return "node memory byte-identical to before (" + std::to_string(bytes) +
               " saved bytes read back, " + std::to_string(rewritten) + " of them written back)";
    }
    std::string s = "node memory NOT identical to before:";
    for (const std::string& d : differences) s += " " + d + ";";
    if (!s.empty() && s.back() == ';') s.pop_back();
    return s;
}

namespace {

// "N bytes differ from space S @A: expected .., seen .." for a range that read back wrong.
std::string difference(const BackupRange& r, const AccessResult& got) {
    std::size_t first = 0, count = 0;
    bool found = false;
    for (std::size_t i = 0; i < r.bytes.size(); ++i) {
        if (i >= got.data.size() || got.data[i] != r.bytes[i]) {
            if (!found) first = i;
            found = true;
            ++count;
        }
    }
    const auto at = static_cast<std::uint32_t>(r.address + first);
    std::span<const std::uint8_t> want(r.bytes);
    std::span<const std::uint8_t> seen(got.data);
    return std::to_string(count) + " bytes differ from " + where(r.space, at) + ": expected " +
           hex_bytes(want.subspan(first), 8) + ", seen " +
           hex_bytes(first < seen.size() ? seen.subspan(first) : seen.subspan(0, 0), 8);
}

std::string access_failed(const char* what, const BackupRange& r, const AccessResult& a) {
    return std::string(what) + " of " + std::to_string(r.bytes.size()) + " bytes at " +
           where(r.space, r.address) + " failed" +
           (a.not_sent.empty() ? " (error " + base::hex(a.error, 4) + ")"
                               : " (" + a.not_sent + ")");
}

}  // namespace

RestoreOutcome restore(const SafetyBackup& backup, MemoryAccess& memory,
                       const RestoreScope& scope) {
    // Only what differs is written: a node is touched as little as the restore allows, and a
    // range of a read-only space that a refused probe left unchanged needs no write at all. A
    // range no write of the run reached is not written either: what changed there is another
    // tool's doing (a second run, a user's configuration tool), and writing it back would undo it.
    RestoreOutcome outcome;
    std::vector<const BackupRange*> written;
    std::vector<const BackupRange*> others;
    for (const BackupRange& r : backup.ranges()) {
        outcome.bytes += r.bytes.size();
        const AccessResult now = memory.read(r.space, r.address, r.bytes.size());
        if (now.ok && now.data == r.bytes) continue;
        if (scope && !scope(r)) {
            others.push_back(&r);
            continue;
        }
        const AccessResult w = memory.write(r.space, r.address, r.bytes);
        if (!w.ok) outcome.differences.push_back(access_failed("write", r, w));
        outcome.rewritten += r.bytes.size();
        written.push_back(&r);
    }
    // Read back only after every write: a node may mirror one space into another (251 and 253),
    // so a range outside the scope may read as saved again once its mirror is restored.
    for (const BackupRange* r : written) {
        const AccessResult got = memory.read(r->space, r->address, r->bytes.size());
        if (!got.ok) {
            outcome.differences.push_back(access_failed("read back", *r, got));
        } else if (got.data != r->bytes) {
            outcome.differences.push_back(difference(*r, got));
        }
    }
    for (const BackupRange* r : others) {
        const AccessResult got = memory.read(r->space, r->address, r->bytes.size());
        if (got.ok && got.data == r->bytes) continue;
        outcome.left_as_found.push_back(
            {{r->space, r->address, static_cast<std::uint32_t>(r->bytes.size())},
             got.ok ? difference(*r, got) : access_failed("read back", *r, got)});
    }
    outcome.identical = outcome.differences.empty();
    return outcome;
}

RestoreGuard::~RestoreGuard() {
    if (!armed_) return;
    // A destructor must not throw, but a node left unrestored must not go unnoticed: say so, and
    // where the values are (the backup file stays on disk for `lcc-conform restore FILE`).
    try {
        restore(backup_, memory_, scope_);
    } catch (const std::exception& e) {
        std::cerr << "lcc-conform: restoring the node's values failed (" << e.what()
                  << "); restore them from the backup file with `lcc-conform restore FILE`\n";
    } catch (...) {
        std::cerr << "lcc-conform: restoring the node's values failed; restore them from the "
                     "backup file with `lcc-conform restore FILE`\n";
    }
}

RestoreOutcome RestoreGuard::finish() {
    armed_ = false;
    return restore(backup_, memory_, scope_);
}

std::string default_backup_path(const std::string& node_id) {
    std::string compact;
    for (char c : node_id) {
        if (c != '.') compact.push_back(c);
    }
    return "./lcc-conform-backup-" + compact + ".txt";
}

}  // namespace olcb::conform
