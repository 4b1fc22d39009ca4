#include "cdi/render_html.hpp"

#include <algorithm>
#include <unordered_map>

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

class PageBuilder {
public:
    explicit PageBuilder(const Layout& layout) : layout_(layout) {}

    nlohmann::json document(std::string_view source, const MemoryMapOptions& options) {
        const Document& doc = layout_.document();
        nlohmann::json out = {{"source", std::string(source)}};
        out["identification"] = nullptr;
        if (doc.identification) {
            const Identification& id = *doc.identification;
            nlohmann::json j = {{"manufacturer", id.manufacturer},
                                {"model", id.model},
                                {"hardware_version", id.hardware_version},
                                {"software_version", id.software_version}};
            if (id.link) j["link"] = link_json(*id.link);
            if (id.map) j["map"] = map_json(*id.map);
            out["identification"] = std::move(j);
        }
        out["acdi"] = nullptr;
        if (doc.acdi) out["acdi"] = {{"fixed", doc.acdi->fixed}, {"var", doc.acdi->var}};
        nlohmann::json segments = nlohmann::json::array();
        for (const Segment& s : doc.segments) segments.push_back(segment(s));
        out["segments"] = std::move(segments);
        out["memory_map"] = memory_map(options);
        return out;
    }

private:
    nlohmann::json segment(const Segment& s) {
        nlohmann::json out = {{"name", s.name},
                              {"description", s.description},
                              {"space", s.space},
                              {"origin", s.origin}};
        if (s.link) out["link"] = link_json(*s.link);
        out["children"] = children(s.children);
        return out;
    }

    nlohmann::json children(const std::vector<Element>& elements) {
        nlohmann::json out = nlohmann::json::array();
        for (const Element& e : elements) out.push_back(element(e));
        return out;
    }

    nlohmann::json element(const Element& e) {
        const std::uint64_t id = ids_.size();
        ids_[&e] = id;
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
            return out;
        }
        out["replication"] = e.replication;
        out["stride"] = placement ? placement->stride : 0;
        nlohmann::json names = nlohmann::json::array();
        for (std::uint64_t r = 0; r < std::min(e.replication, kNamedReplicas); ++r) {
            names.push_back(replica_name(e, r));
        }
        out["replica_names"] = std::move(names);
        out["children"] = children(e.children);
        return out;
    }

    // The shared memory map, each variable with the element and replicas that show it.
    nlohmann::json memory_map(const MemoryMapOptions& options) {
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
                if (auto it = ids_.find(&c.element()); it != ids_.end()) v["element"] = it->second;
                v["replicas"] = std::move(replicas);
            }
        }
        return out;
    }

    const Layout& layout_;
    std::unordered_map<const Element*, std::uint64_t> ids_;
};

}  // namespace

nlohmann::json cdi_page_json(const Layout& layout, std::string_view source,
                             const MemoryMapOptions& options) {
    return PageBuilder(layout).document(source, options);
}

std::string render_html(const Layout& layout, std::string_view source,
                        const MemoryMapOptions& options) {
    return html_page(PageKind::kCdi, cdi_page_json(layout, source, options));
}

}  // namespace olcb::cdi
