#include "conformance/backup/backup_file.hpp"

#include "base/file.hpp"
#include "conformance/backup/backup_csv.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

constexpr std::string_view kNodePrefix = "# node ";
constexpr std::string_view kUtf8Bom = "\xEF\xBB\xBF";

std::string_view trim_line(std::string_view line) {
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    return line;
}

}  // namespace

std::string normal_backup_key(std::string_view key) {
    if (key.find('\\') == std::string_view::npos) return std::string(key);
    return escape_backup_text(unescape_backup_text(key));
}

BackupFile parse_backup_file(std::string_view text) {
    if (text.starts_with(kUtf8Bom)) text.remove_prefix(kUtf8Bom.size());
    if (is_backup_csv(text)) return parse_backup_csv(text);
    BackupFile file;
    std::size_t line_no = 0;
    while (!text.empty()) {
        const auto nl = text.find('\n');
        const std::string_view line = trim_line(text.substr(0, nl));
        text.remove_prefix(nl == std::string_view::npos ? text.size() : nl + 1);
        ++line_no;
        if (line.starts_with(kNodePrefix) && !file.node) {
            file.node = std::string(line.substr(kNodePrefix.size()));
        }
        if (line.empty() || line.front() == '#') continue;
        const auto eq = line.find('=');
        if (eq == std::string_view::npos || eq == 0) {
            file.errors.push_back("line " + std::to_string(line_no) + ": not key=value");
            continue;
        }
        file.records.push_back({normal_backup_key(line.substr(0, eq)),
                                unescape_backup_text(line.substr(eq + 1)), line_no, std::nullopt});
    }
    return file;
}

bool load_backup_file(const std::string& path, BackupFile& file, std::string& error) {
    const auto text = base::read_file(path, error);
    if (!text) return false;
    file = parse_backup_file(*text);
    if (file.records.empty() && file.errors.empty()) {
        error = path + " holds no key=value line";
        return false;
    }
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
