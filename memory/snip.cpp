#include "memory/snip.hpp"

#include <algorithm>
#include <array>

#include "base/utf8.hpp"

namespace olcb::memory {
namespace {

// Sections older than the current layout still carried at least the current strings, so every
// version below it (legacy 1 included) is read as the current one.
std::size_t strings_in_section(std::uint8_t version, std::uint8_t current) {
    return std::max<std::size_t>(version, current);
}

// Walks a payload section by section; each step yields one string or reports the end.
class SnipReader {
public:
    explicit SnipReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

    bool at_end() const { return pos_ >= bytes_.size(); }

    std::optional<std::uint8_t> version() {
        if (at_end()) return std::nullopt;
        return bytes_[pos_++];
    }

    // Returns the string and whether its NUL was seen.
    std::pair<std::string, bool> string() {
        const auto start = bytes_.begin() + static_cast<std::ptrdiff_t>(pos_);
        const auto nul = std::find(start, bytes_.end(), std::uint8_t{0});
        std::string text(start, nul);
        const bool terminated = nul != bytes_.end();
        pos_ = static_cast<std::size_t>(nul - bytes_.begin()) + (terminated ? 1 : 0);
        return {std::move(text), terminated};
    }

    std::size_t position() const { return pos_; }

private:
    std::span<const std::uint8_t> bytes_;
    std::size_t pos_ = 0;
};

void append_string(std::vector<std::uint8_t>& out, std::string_view text, std::size_t max) {
    const std::string_view clamped = clamp_utf8(text, max - 1);
    out.insert(out.end(), clamped.begin(), clamped.end());
    out.push_back(0);
}

}  // namespace

std::string_view clamp_utf8(std::string_view text, std::size_t max_bytes) {
    return base::truncate_utf8(text.substr(0, text.find('\0')), max_bytes);
}

std::vector<std::uint8_t> encode_snip(const Snip& snip) {
    std::vector<std::uint8_t> out;
    out.reserve(kSnipMaxPayload);
    out.push_back(kSnipManufacturerVersion);
    append_string(out, snip.manufacturer, kSnipManufacturerMax);
    append_string(out, snip.model, kSnipModelMax);
    append_string(out, snip.hardware_version, kSnipHardwareVersionMax);
    append_string(out, snip.software_version, kSnipSoftwareVersionMax);
    out.push_back(kSnipUserVersion);
    append_string(out, snip.user_name, kSnipUserNameMax);
    append_string(out, snip.user_description, kSnipUserDescriptionMax);
    return out;
}

Snip decode_snip(std::span<const std::uint8_t> payload) {
    Snip snip;
    SnipReader reader(payload);
    const std::array<std::string*, 4> manufacturer_fields{
        &snip.manufacturer, &snip.model, &snip.hardware_version, &snip.software_version};
    const std::array<std::string*, 2> user_fields{&snip.user_name, &snip.user_description};

    const auto read_section = [&reader](std::uint8_t version, std::uint8_t current,
                                        std::span<std::string* const> fields) {
        const std::size_t count = strings_in_section(version, current);
        for (std::size_t i = 0; i < count && !reader.at_end(); ++i) {
            auto [text, terminated] = reader.string();
            if (i < fields.size()) *fields[i] = std::move(text);
            if (!terminated) break;
        }
    };

    const auto manufacturer_version = reader.version();
    if (!manufacturer_version) return snip;
    snip.manufacturer_version = *manufacturer_version;
    read_section(*manufacturer_version, kSnipManufacturerVersion, manufacturer_fields);
    const auto user_version = reader.version();
    if (!user_version) return snip;
    snip.user_version = *user_version;
    read_section(*user_version, kSnipUserVersion, user_fields);
    return snip;
}

std::optional<std::size_t> complete_snip_size(std::span<const std::uint8_t> bytes) {
    SnipReader reader(bytes);
    for (const std::uint8_t current : {kSnipManufacturerVersion, kSnipUserVersion}) {
        const auto version = reader.version();
        if (!version) return std::nullopt;
        const std::size_t count = strings_in_section(*version, current);
        for (std::size_t i = 0; i < count; ++i) {
            if (reader.at_end() || !reader.string().second) return std::nullopt;
        }
    }
    return reader.position();
}

bool is_complete_snip(std::span<const std::uint8_t> bytes) {
    return complete_snip_size(bytes).has_value();
}

}  // namespace olcb::memory
