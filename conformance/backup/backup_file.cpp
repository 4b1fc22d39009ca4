#include "conformance/backup/backup_file.hpp"

#include <ostream>

#include "base/bounded_read.hpp"
#include "base/hex.hpp"
#include "base/utf8.hpp"
#include "conformance/backup/backup_csv.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

constexpr std::string_view kNodePrefix = "# node ";
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";
constexpr std::size_t kShownLine = 60;  // bytes of a line an example shows

std::string_view trim_line(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

std::string line_text(std::size_t line) {
    return "line " + std::to_string(line);
}

// A byte no text file holds: NUL and the C0 controls other than tab and line ends (a CR only
// before its LF), and DEL.
bool binary_byte(std::string_view text, std::size_t i) {
    const auto b = static_cast<unsigned char>(text[i]);
    if (b == '\t' || b == '\n') return false;
    if (b == '\r') return i + 1 >= text.size() || text[i + 1] != '\n';
    return b < 0x20 || b == 0x7F;
}

// Every control or NUL byte of a key=value text (its values escape them all); nullopt when
// there is none.
std::optional<UnusableBackup> binary_bytes(std::string_view text) {
    UnusableBackup found;
    std::size_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        } else if (binary_byte(text, i)) {
            if (found.count < kMaxBackupExamples) {
                found.add(line_text(line) + ", column " + std::to_string(i - line_start + 1) +
                          ": byte " + base::hex(static_cast<unsigned char>(text[i]), 2));
            } else {
                ++found.count;
            }
        }
    }
    if (found.count == 0) return std::nullopt;
    found.cause = "is not a text file: it holds " + std::to_string(found.count) +
                  " control or NUL byte(s), which no backup has";
    return found;
}

// The line cut short when the text does not end with a line end and its last line holds more
// than a comment: the rest of a value (or of the file) may be missing.
std::optional<UnusableBackup> cut_short(std::string_view text, std::size_t lines) {
    if (text.empty() || text.back() == '\n') return std::nullopt;
    const std::string_view last = trim_line(text.substr(text.rfind('\n') + 1));
    if (last.empty() || last.front() == '#') return std::nullopt;
    UnusableBackup u;
    u.cause = "is cut short: its last line (" + std::to_string(lines) +
              ") has no line end, so its value may be incomplete (if the file is whole, end "
              "that line with a line end)";
    u.add(line_text(lines) + ": " + std::string(base::truncate_utf8(last, kShownLine)) +
          (last.size() > kShownLine ? "..." : ""));
    return u;
}

// Invalid UTF-8 in a comment line or a key: the text is not UTF-8, so no backup (a value's
// invalid UTF-8 is that value's problem: a restore refuses it).
void check_utf8_outside_value(std::string_view line, std::size_t line_no,
                              UnusableBackup& not_utf8) {
    const std::string_view outside = line.front() == '#' ? line : line.substr(0, line.find('='));
    if (const auto bad = base::find_invalid_utf8(outside)) {
        not_utf8.add(line_text(line_no) + ", byte " + std::to_string(*bad + 1) +
                     (line.front() == '#' ? " of a comment" : " of the key"));
    }
}

BackupFile parse_key_value(std::string_view text) {
    BackupFile file;
    UnusableBackup not_utf8;
    std::size_t line_no = 0;
    const std::string_view whole = text;
    while (!text.empty()) {
        const auto nl = text.find('\n');
        const std::string_view line = trim_line(text.substr(0, nl));
        text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
        ++line_no;
        if (line.starts_with(kNodePrefix) && !file.node) {
            file.node = std::string(line.substr(kNodePrefix.size()));
        }
        if (line.empty()) continue;
        check_utf8_outside_value(line, line_no, not_utf8);
        if (line.front() == '#') continue;
        const auto eq = line.find('=');
        if (eq == std::string_view::npos || eq == 0) {
            file.errors.push_back(line_text(line_no) + ": not key=value");
            continue;
        }
        file.records.push_back({normal_backup_key(line.substr(0, eq)),
                                unescape_backup_text(line.substr(eq + 1)), line_no, std::nullopt});
    }
    if (not_utf8.count != 0) {
        not_utf8.cause = "is not UTF-8 text: " + std::to_string(not_utf8.count) +
                         " line(s) have bytes that are not UTF-8 outside a value";
        file.unusable = std::move(not_utf8);
    } else {
        file.unusable = cut_short(whole, line_no);
    }
    return file;
}

// No record at all: only comments and blank lines, or only lines that are not key=value.
UnusableBackup no_records(const BackupFile& file) {
    UnusableBackup u;
    if (file.errors.empty()) {
        u.cause = file.csv ? "holds no row after its CSV header"
                           : "holds no key=value line (only comments and blank lines)";
        return u;
    }
    u.cause = "holds no key=value line: " + std::to_string(file.errors.size()) +
              " line(s) are not key=value";
    for (const std::string& e : file.errors) u.add(e);
    return u;
}

}  // namespace

void UnusableBackup::add(std::string_view example) {
    if (count++ < kMaxBackupExamples) examples.push_back(base::printable(example));
}

void print_unusable(std::string_view path, const UnusableBackup& u, std::string_view consequence,
                    std::ostream& out) {
    out << "lcc-conform: " << base::printable(path) << " " << base::printable(u.cause)
        << consequence << "\n";
    for (const std::string& e : u.examples) out << "  " << e << "\n";
    if (u.count > u.examples.size()) {
        out << "  ... and " << u.count - u.examples.size() << " more (" << u.count << " in all)\n";
    }
}

std::string normal_backup_key(std::string_view key) {
    if (key.find('\\') == std::string_view::npos) return std::string(key);
    return escape_backup_text(unescape_backup_text(key));
}

BackupFile parse_backup_file(std::string_view text) {
    BackupFile file;
    if (text.empty()) {
        file.unusable = UnusableBackup{"is empty (0 bytes)", {}, 0};
        return file;
    }
    if (text.starts_with(kUtf8Bom)) text.remove_prefix(kUtf8Bom.size());
    if (is_backup_csv(text)) {
        file = parse_backup_csv(text);
    } else if (auto binary = binary_bytes(text)) {
        file.unusable = std::move(binary);
        return file;
    } else {
        file = parse_key_value(text);
    }
    if (!file.unusable && file.records.empty()) file.unusable = no_records(file);
    return file;
}

std::optional<std::string> read_backup_text(const std::string& path, std::string& error,
                                            std::size_t limit) {
    return base::read_bounded_file(path, limit, base::Streams::kReadBounded, error,
                                   "backup file limit");
}

bool load_backup_file(const std::string& path, BackupFile& file, std::string& error) {
    const auto text = read_backup_text(path, error);
    if (!text) return false;
    file = parse_backup_file(*text);
    return true;
}

std::string backup_text(const std::vector<ConfigEntry>& entries,
                        const std::vector<ConfigValue>& values, const std::string& node_id) {
    std::string text = "# OpenLCB configuration backup of node " + node_id + " (lcc-conform)\n";
    text += std::string(kNodePrefix) + node_id + "\n";
    for (std::size_t i = 0; i < entries.size() && i < values.size(); ++i) {
        if (!values[i].text) continue;
        text += entries[i].key;
        text += '=';
        text += escape_backup_text(*values[i].text);
        text += '\n';
    }
    return text;
}

std::optional<std::string> config_backup_node(std::string_view text) {
    while (!text.empty() && text.front() == '#') {
        const auto nl = text.find('\n');
        const std::string_view line = trim_line(text.substr(0, nl));
        if (line.starts_with(kNodePrefix)) return std::string(line.substr(kNodePrefix.size()));
        if (nl == std::string_view::npos) break;
        text.remove_prefix(nl + 1);
    }
    return std::nullopt;
}

}  // namespace olcb::conform
