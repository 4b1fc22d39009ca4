// libFuzzer target: arbitrary text as a configuration backup file (key=value or CSV), the form a
// user hands to `lcc-conform restore` and `diff`. Parsing never crashes, every record's line
// number lies in the text, and escaping round-trips text: unescape(escape(x)) == x for UTF-8.
// (Bytes that are not UTF-8 have no form in OpenLCB_Java's format: they are written as their
// code point and come back as that character, so a restore refuses them as too long.)
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <string_view>

#include "base/utf8.hpp"
#include "conformance/backup/backup_csv.hpp"
#include "conformance/backup/backup_file.hpp"
#include "conformance/backup/backup_values.hpp"

namespace {

void check(bool ok) {
    if (!ok) std::abort();
}

std::size_t lines_in(std::string_view text) {
    std::size_t n = 1;
    for (char c : text) n += c == '\n' ? 1 : 0;
    return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const std::size_t lines = lines_in(text);
    for (const auto& file :
         {olcb::conform::parse_backup_file(text), olcb::conform::parse_backup_csv(text)}) {
        for (const auto& r : file.records) check(r.line >= 1 && r.line <= lines);
    }
    const std::string escaped = olcb::conform::escape_backup_text(text);
    check(escaped.find('\n') == std::string::npos && escaped.find('=') == std::string::npos);
    if (olcb::base::is_valid_utf8(std::span<const std::uint8_t>(data, size))) {
        check(olcb::conform::unescape_backup_text(escaped) == text);
    }
    return 0;
}
