#include "conformance/backup/backup_csv.hpp"

#include <charconv>
#include <optional>

#include "base/hex.hpp"
#include "base/utf8.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

// How a CSV record ended.
enum class RecordEnd : std::uint8_t {
    kLineEnd,    ///< at its line end
    kTextEnd,    ///< at the end of the text, without a line end (cut short?)
    kOpenQuote,  ///< at the end of the text inside a quoted field
};

// The fields of one CSV record starting at text[pos], advancing pos past its line end. Quoted
// fields may hold line ends; line counts them.
RecordEnd read_record(std::string_view text, std::size_t& pos, std::size_t& line,
                      std::vector<std::string>& fields) {
    fields.assign(1, {});
    bool quoted = false;
    while (pos < text.size()) {
        const char c = text[pos++];
        if (quoted) {
            if (c != '"') {
                if (c == '\n') ++line;
                fields.back() += c;
            } else if (pos < text.size() && text[pos] == '"') {
                fields.back() += '"';
                ++pos;
            } else {
                quoted = false;
            }
        } else if (c == '"' && fields.back().empty()) {
            quoted = true;
        } else if (c == ',') {
            fields.emplace_back();
        } else if (c == '\n') {
            ++line;
            return RecordEnd::kLineEnd;
        } else if (c != '\r' || (pos < text.size() && text[pos] != '\n')) {
            fields.back() += c;
        }
    }
    return quoted ? RecordEnd::kOpenQuote : RecordEnd::kTextEnd;
}

// A field no text file holds outside a value: a control byte or bytes that are not UTF-8.
std::string not_text(std::string_view field) {
    for (std::size_t i = 0; i < field.size(); ++i) {
        const auto b = static_cast<unsigned char>(field[i]);
        if ((b < 0x20 && b != '\t') || b == 0x7F) return "control byte " + base::hex(b, 2);
    }
    if (const auto bad = base::find_invalid_utf8(field)) {
        return "byte " + std::to_string(*bad + 1) + " is not UTF-8";
    }
    return {};
}

template <class T>
std::optional<T> number(const std::string& text) {
    T v{};
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return v;
}

// Column positions by header name; npos when absent.
struct Columns {
    std::size_t key = std::string::npos, value = std::string::npos, type = std::string::npos,
                space = std::string::npos, address = std::string::npos, size = std::string::npos;
};

Columns columns_of(const std::vector<std::string>& header) {
    Columns c;
    const std::pair<std::string_view, std::size_t*> slots[] = {
        {"key", &c.key},     {"value", &c.value},     {"type", &c.type},
        {"space", &c.space}, {"address", &c.address}, {"size", &c.size},
    };
    for (std::size_t i = 0; i < header.size(); ++i) {
        for (const auto& [name, slot] : slots) {
            if (header[i] == name) *slot = i;
        }
    }
    return c;
}

std::optional<BackupPlace> place_of(const Columns& c, const std::vector<std::string>& f) {
    if (c.type >= f.size() || c.space >= f.size() || c.address >= f.size() || c.size >= f.size())
        return std::nullopt;
    const auto space = number<std::uint32_t>(f[c.space]);
    const auto address = number<std::uint64_t>(f[c.address]);
    const auto size = number<std::uint64_t>(f[c.size]);
    if (!space || !address || !size) return std::nullopt;
    return BackupPlace{f[c.type], *space, *address, *size};
}

}  // namespace

bool is_backup_csv(std::string_view text) {
    // A hand-made file may have only these two columns, or others after them.
    return text.starts_with("key,value");
}

std::string csv_field(std::string_view text) {
    const bool quote = text.find_first_of(",\"\r\n") != std::string_view::npos ||
                       (!text.empty() && (text.front() == ' ' || text.back() == ' '));
    if (!quote) return std::string(text);
    std::string out = "\"";
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    out += '"';
    return out;
}

std::string backup_csv(const std::vector<ConfigEntry>& entries,
                       const std::vector<ConfigValue>& values) {
    std::string out(kBackupCsvHeader);
    out += "\r\n";
    for (std::size_t i = 0; i < entries.size() && i < values.size(); ++i) {
        if (!values[i].text) continue;
        const ConfigEntry& e = entries[i];
        out += csv_field(e.key) + "," + csv_field(*values[i].text) + "," +
               backup_type_name(*e.element) + "," + std::to_string(e.space) + "," +
               std::to_string(e.address) + "," + std::to_string(e.size) + "\r\n";
    }
    return out;
}

namespace {

// Every field but the value (which holds a string's bytes raw, controls too) must be text.
void check_fields(const std::vector<std::string>& fields, std::size_t value_column,
                  std::size_t line, UnusableBackup& bad) {
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i == value_column) continue;
        if (const std::string why = not_text(fields[i]); !why.empty()) {
            bad.add("line " + std::to_string(line) + ", field " + std::to_string(i + 1) + ": " +
                    why);
        }
    }
}

// The file's problem when its text ended inside a record: the last row or a quoted field cut
// short.
UnusableBackup cut_short(RecordEnd end, std::size_t first, const std::vector<std::string>& f) {
    UnusableBackup u;
    if (end == RecordEnd::kOpenQuote) {
        u.cause =
            "is cut short: a quoted field begun on line " + std::to_string(first) + " never ends";
    } else {
        u.cause = "is cut short: its last row (line " + std::to_string(first) +
                  ") has no line end, so its value may be incomplete (if the file is whole, end "
                  "that row with a line end)";
    }
    u.add("line " + std::to_string(first) + ": " + std::string(base::truncate_utf8(f[0], 60)));
    return u;
}

}  // namespace

BackupFile parse_backup_csv(std::string_view text) {
    BackupFile file;
    file.csv = true;
    if (text.find('\0') != std::string_view::npos) {
        file.unusable = UnusableBackup{"is not a text file: it holds NUL bytes", {}, 0};
        return file;
    }
    std::size_t pos = 0;
    std::size_t line = 1;
    std::vector<std::string> fields;
    UnusableBackup bad;
    read_record(text, pos, line, fields);  // the header: its end is the rows' business
    const Columns c = columns_of(fields);
    check_fields(fields, std::string::npos, 1, bad);
    if (c.key == std::string::npos || c.value == std::string::npos) {
        file.errors.emplace_back("line 1: the CSV header has no key or value column");
        return file;
    }
    while (pos < text.size()) {
        const std::size_t first = line;
        const RecordEnd end = read_record(text, pos, line, fields);
        if (end != RecordEnd::kLineEnd && !(fields.size() == 1 && fields[0].empty())) {
            file.unusable = cut_short(end, first, fields);
        }
        if (end == RecordEnd::kOpenQuote) {
            file.errors.push_back("line " + std::to_string(first) + ": unterminated quote");
            break;
        }
        check_fields(fields, c.value, first, bad);
        if (fields.size() == 1 && fields[0].empty()) continue;  // a blank line
        if (c.key >= fields.size() || c.value >= fields.size() || fields[c.key].empty()) {
            file.errors.push_back("line " + std::to_string(first) + ": no key and value");
            continue;
        }
        file.records.push_back(
            {normal_backup_key(fields[c.key]), fields[c.value], first, place_of(c, fields)});
    }
    if (bad.count != 0) {  // a file that is not text says so before it says it was cut short
        bad.cause = "is not text: " + std::to_string(bad.count) +
                    " field(s) outside the value column hold control bytes or bytes that are "
                    "not UTF-8";
        file.unusable = std::move(bad);
    }
    return file;
}

}  // namespace olcb::conform
