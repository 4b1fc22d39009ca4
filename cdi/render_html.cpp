#include "cdi/render_html.hpp"

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cdi/html_page.hpp"

namespace olcb::cdi {
namespace {

// Replica names listed per group; the page numbers later replicas itself ("#300").
constexpr std::uint64_t kNamedReplicas = 256;

nlohmann::json link_json(const Link& link) {
    return {{"ref", link.ref}, {"text", link.text}};
}

nlohmann::json map_json(const Map& map) {
    nlohmann::json entries = nlohmann::json::array();
    for (const MapEntry& e : map.entries)
        entries.push_back({{"property", e.property}, {"value", e.value}});
    return entries;
}

nlohmann::json hints_json(const Hints& h) {
    nlohmann::json out = nlohmann::json::object();
    if (h.slider) {
        out["slider"] = {{"tick_spacing", h.slider->tick_spacing},
                         {"immediate", h.slider->immediate},
                         {"show_value", h.slider->show_value}};
    }
    if (h.radiobutton) out["radiobutton"] = true;
    if (h.checkbox) out["checkbox"] = true;
    if (h.visibility) {
        out["hideable"] = h.hideable;
        out["hidden"] = h.hidden;
    }
    if (h.read_only) out["read_only"] = true;
    return out;
}

// The type's constraints and defaults; integers as decimal text (an 8-byte <int> does not fit a
// JavaScript number).
void add_constraints(const Element& e, nlohmann::json& out) {
    if (e.int_min) out["min"] = to_string(*e.int_min);
    if (e.int_max) out["max"] = to_string(*e.int_max);
    if (e.int_default) out["default"] = to_string(*e.int_default);
    if (e.kind == ElementKind::kInt || e.kind == ElementKind::kBit) out["signed"] = e.is_signed();
    if (e.float_min) out["min"] = *e.float_min;
    if (e.float_max) out["max"] = *e.float_max;
    if (e.float_default) out["default"] = *e.float_default;
    if (e.formatting) out["formatting"] = *e.formatting;
    if (e.text_default) out["default"] = *e.text_default;
    if (e.map) out["map"] = map_json(*e.map);
    if (e.button_text) out["button"] = *e.button_text;
    if (e.dialog_text) out["dialog"] = *e.dialog_text;
    if (e.action_value) out["value"] = to_string(*e.action_value);
    if (e.blob_mode) out["mode"] = *e.blob_mode;
}

// Writes the page's data into the page text as it walks the layout: only one element's JSON
// exists at a time (the whole tree cost 9x the page's text on a 16 MiB CDI, issue 31).
class PageWriter {
public:
    PageWriter(const Layout& layout, std::string& out) : layout_(layout), out_(out) {}

    void document(std::string_view source, const MemoryMapOptions& options) {
        const Document& doc = layout_.document();
        out_ += "{\"source\":";
        append_script_json(out_, std::string(source));
        out_ += ",\"identification\":";
        append_script_json(out_, identification(doc));
        out_ += ",\"acdi\":";
        append_script_json(
            out_, doc.acdi ? nlohmann::json{{"fixed", doc.acdi->fixed}, {"var", doc.acdi->var}}
                           : nlohmann::json(nullptr));
        out_ += ",\"segments\":[";
        for (std::size_t i = 0; i < doc.segments.size(); ++i) {
            if (i != 0) out_ += ',';
            segment(doc.segments[i]);
        }
        out_ += "],\"memory_map\":";
        std::sort(ids_.begin(), ids_.end());
        append_script_json(out_, memory_map(options));
        out_ += '}';
    }

private:
    static nlohmann::json identification(const Document& doc) {
        if (!doc.identification) return nullptr;
        const Identification& id = *doc.identification;
        nlohmann::json j = {{"manufacturer", id.manufacturer},
                            {"model", id.model},
                            {"hardware_version", id.hardware_version},
                            {"software_version", id.software_version}};
        if (id.link) j["link"] = link_json(*id.link);
        if (id.map) j["map"] = map_json(*id.map);
        return j;
    }

    void segment(const Segment& s) {
        nlohmann::json out = {{"name", s.name},
                              {"description", s.description},
                              {"space", s.space},
                              {"origin", s.origin}};
        if (s.link) out["link"] = link_json(*s.link);
        append_open_object(out_, out);
        children(s.children);
        out_ += '}';
    }

    // `,"children":[...]` of an open object.
    void children(const std::vector<Element>& elements) {
        out_ += ",\"children\":[";
        for (std::size_t i = 0; i < elements.size(); ++i) {
            if (i != 0) out_ += ',';
            element(elements[i]);
        }
        out_ += ']';
    }

    void element(const Element& e) {
        const std::uint64_t id = ids_.size();
        ids_.emplace_back(&e, id);
        nlohmann::json out = {{"id", id},
                              {"kind", kind_name(e.kind)},
                              {"tag", e.tag},
                              {"name", e.name},
                              {"description", e.description},
                              {"size", e.size},
                              {"hints", hints_json(e.hints)}};
        if (e.link) out["link"] = link_json(*e.link);
        const auto placement = layout_.placement(e);
        out["address"] = nullptr;
        if (placement) out["address"] = placement->address;
        if (e.kind != ElementKind::kGroup) {
            add_constraints(e, out);
            append_script_json(out_, out);
            return;
        }
        out["replication"] = e.replication;
        out["stride"] = placement ? placement->stride : 0;
        nlohmann::json names = nlohmann::json::array();
        for (std::uint64_t r = 0; r < std::min(e.replication, kNamedReplicas); ++r) {
            names.push_back(replica_name(e, r));
        }
        out["replica_names"] = std::move(names);
        append_open_object(out_, out);
        children(e.children);
        out_ += '}';
    }

    // The shared memory map (bounded by MemoryMapOptions), each variable with the element and
    // replicas that show it.
    nlohmann::json memory_map(const MemoryMapOptions& options) const {
        const std::vector<SpaceMap> maps = build_memory_map(layout_, options);
        nlohmann::json out = memory_map_json(maps);
        for (std::size_t s = 0; s < maps.size(); ++s) {
            for (std::size_t i = 0; i < maps[s].variables.size(); ++i) {
                const Cursor c = layout_.at(maps[s].variables[i].ordinal);
                if (!c.valid()) continue;
                nlohmann::json replicas = nlohmann::json::array();
                for (std::size_t level = 0; level < c.group_depth(); ++level) {
                    if (c.group(level).replication > 1) replicas.push_back(c.replica(level));
                }
                nlohmann::json& v = out[s]["variables"][i];
                if (const auto id = id_of(c.element())) v["element"] = *id;
                v["replicas"] = std::move(replicas);
            }
        }
        return out;
    }

    std::optional<std::uint64_t> id_of(const Element& e) const {
        const auto it = std::lower_bound(ids_.begin(), ids_.end(),
                                         std::pair<const Element*, std::uint64_t>(&e, 0));
        if (it == ids_.end() || it->first != &e) return std::nullopt;
        return it->second;
    }

    const Layout& layout_;
    std::string& out_;
    // (element, id) in walk order, sorted by element once the walk is done: 16 bytes an element
    // where a hash map cost about 50.
    std::vector<std::pair<const Element*, std::uint64_t>> ids_;
};

}  // namespace

void append_cdi_page_data(std::string& out, const Layout& layout, std::string_view source,
                          const MemoryMapOptions& options) {
    PageWriter(layout, out).document(source, options);
}

std::string render_html(const Layout& layout, std::string_view source,
                        const MemoryMapOptions& options) {
    return html_page_from(PageKind::kCdi, [&](std::string& out) {
        append_cdi_page_data(out, layout, source, options);
    });
}

}  // namespace olcb::cdi
