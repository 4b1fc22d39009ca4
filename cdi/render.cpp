#include "cdi/render.hpp"

#include <charconv>
#include <cinttypes>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace olcb::cdi {

namespace {

std::string hex_address(std::uint64_t address) {
    char buf[24];
    std::snprintf(buf, sizeof buf, "0x%08" PRIX64, address);
    return buf;
}

std::string hints_text(const Hints& h) {
    std::string out;
    auto add = [&out](const std::string& s) { out += (out.empty() ? "" : ", ") + s; };
    if (h.slider) {
        add("slider(tickSpacing " + std::to_string(h.slider->tick_spacing) +
            (h.slider->immediate ? ", immediate" : "") +
            (h.slider->show_value ? ", showValue" : "") + ")");
    }
    if (h.radiobutton) add("radiobutton");
    if (h.checkbox) add("checkbox");
    if (h.visibility) {
        add(std::string("visibility(") + (h.hideable ? "hideable" : "not hideable") +
            (h.hidden ? ", hidden" : "") + ")");
    }
    if (h.read_only) add("readOnly");
    return out;
}

class Renderer {
public:
    Renderer(const Layout& layout, std::ostream& out) : layout_(layout), out_(out) {}

    void document() {
        const Document& doc = layout_.document();
        if (doc.identification) {
            const Identification& id = *doc.identification;
            out_ << "Identification\n";
            line(1, "manufacturer: " + id.manufacturer);
            line(1, "model: " + id.model);
            line(1, "hardware version: " + id.hardware_version);
            line(1, "software version: " + id.software_version);
            if (id.link) line(1, "link: " + id.link->text + " <" + id.link->ref + ">");
            if (id.map) map(1, *id.map);
        }
        if (doc.acdi) {
            out_ << "ACDI (fixed " << doc.acdi->fixed << ", var " << doc.acdi->var
                 << "): space 252 manufacturer data, space 251 user name and description\n";
        }
        for (const Segment& s : doc.segments) {
            out_ << "Segment " << (s.name.empty() ? "(unnamed)" : "\"" + s.name + "\"")
                 << ", space " << s.space << ", origin " << s.origin << "\n";
            text(1, s.description);
            if (s.link) line(1, "link: " + s.link->text + " <" + s.link->ref + ">");
            elements(1, s.children);
        }
    }

private:
    void line(int depth, const std::string& s) {
        out_ << std::string(static_cast<std::size_t>(depth) * 2, ' ') << s << "\n";
    }
    void text(int depth, const std::string& s) {
        if (!s.empty()) line(depth, "| " + s);
    }
    void map(int depth, const Map& m) {
        line(depth, "map" + (m.name.empty() ? std::string() : " \"" + m.name + "\"") + ":");
        for (const MapEntry& entry : m.entries)
            line(depth + 1, entry.property + " = " + entry.value);
    }

    // One element and what belongs to it, its children excepted.
    void element(int depth, const Element& e) {
        auto placement = layout_.placement(e);
        std::string where = placement ? "@" + hex_address(placement->address) + " " : "";
        std::string label = e.name.empty() ? "(unnamed)" : "\"" + e.name + "\"";
        if (e.kind == ElementKind::kGroup) {
            line(depth, where + group_head(e, label, placement));
        } else {
            line(depth, where + variable_head(e, label));
        }
        text(depth + 1, e.description);
        if (e.link) line(depth + 1, "link: " + e.link->text + " <" + e.link->ref + ">");
        std::string hints = hints_text(e.hints);
        if (!hints.empty()) line(depth + 1, "hints: " + hints);
        if (e.dialog_text) line(depth + 1, "dialog: " + *e.dialog_text);
        if (e.map) map(depth + 1, *e.map);
    }

    // "group LABEL" with its replication, stride and repnames.
    static std::string group_head(const Element& e, const std::string& label,
                                  const std::optional<Placement>& placement) {
        std::string head = "group " + label;
        if (e.replication > 1) {
            head += " x" + std::to_string(e.replication);
            if (placement) head += ", stride " + std::to_string(placement->stride) + " bytes";
        }
        if (!e.repnames.empty()) {
            head += ", repname";
            for (const auto& r : e.repnames) head += " \"" + r + "\"";
        }
        return head;
    }

    // "TYPE(SIZE) LABEL" with every attribute the variable has.
    static std::string variable_head(const Element& e, const std::string& label) {
        std::string type = e.kind == ElementKind::kUnknown ? e.tag : kind_name(e.kind);
        std::string head = type + "(" + std::to_string(e.size) + ") " + label;
        if (e.kind == ElementKind::kInt && e.is_signed()) head += " signed";
        if (e.int_min) head += " min " + to_string(*e.int_min);
        if (e.int_max) head += " max " + to_string(*e.int_max);
        if (e.int_default) head += " default " + to_string(*e.int_default);
        if (e.float_min) head += " min " + format_double(*e.float_min);
        if (e.float_max) head += " max " + format_double(*e.float_max);
        if (e.float_default) head += " default " + format_double(*e.float_default);
        if (e.text_default) head += " default \"" + *e.text_default + "\"";
        if (e.action_value) head += " value " + to_string(*e.action_value);
        if (e.button_text) head += " button \"" + *e.button_text + "\"";
        if (e.blob_mode) head += " mode " + *e.blob_mode;
        return head;
    }

    // The elements under a segment in document order, each group's children below it
    // (cdi::walk_elements: no recursion).
    void elements(int depth, const std::vector<Element>& top) {
        walk_elements(top, [this, depth](const Element& e, std::size_t below) {
            element(depth + static_cast<int>(below), e);
        });
    }

    static std::string format_double(double v) {
        char buf[32];
        auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
        return ec == std::errc() ? std::string(buf, end) : std::string("?");
    }

    const Layout& layout_;
    std::ostream& out_;
};

}  // namespace

void render(const Layout& layout, std::ostream& out) {
    Renderer(layout, out).document();
}

}  // namespace olcb::cdi
