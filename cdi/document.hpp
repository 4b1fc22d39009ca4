// The typed model of a CDI document (CDI standard, schema 1.4, section 5.1).
//
// The model mirrors the XML tree one to one and never expands replication: a group with
// replication="1000000" is one Element with replication_ = 1000000. Addresses are computed by
// Layout (layout.hpp), not stored here.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cdi/boxed.hpp"

namespace olcb::cdi {

/// Integer wide enough for every value of a signed or unsigned 8-byte <int>.
using WideInt = __int128;

/// Decimal text of a WideInt (std::to_string has no __int128 overload).
std::string to_string(WideInt value);

/// The kind of a data element; Unknown is a future element recognised by its size attribute.
enum class ElementKind : std::uint8_t {
    kGroup,
    kInt,
    kString,
    kEventId,
    kFloat,
    kAction,
    kBlob,
    kBit,      ///< schema 1.0 <bit>, read leniently as a 1-byte variable
    kUnknown,  ///< unknown element with a size attribute (standard section 6)
};

/// The element name of a kind ("group", "int", ...); kUnknown returns "unknown".
const char* kind_name(ElementKind kind);

/// An optional hyperlink (<link ref="...">text</link>).
struct Link {
    std::string ref;   ///< the ref attribute
    std::string text;  ///< the element text
};

/// One <relation> of a <map>: a stored property and its displayed value.
struct MapEntry {
    std::string property;  ///< the stored value, as text (decimal int, dotted event ID, string)
    std::string value;     ///< the text shown to the user
};

/// A <map> enumeration.
struct Map {
    std::string name;
    std::string description;
    std::vector<MapEntry> entries;
};

/// Slider hint of an <int> (schema 1.4).
struct SliderHint {
    std::int64_t tick_spacing = 0;
    bool immediate = false;
    bool show_value = false;
};

/// Display hints of a variable or group (schema 1.4 <hints>).
struct Hints {
    // Variable hints.
    std::optional<SliderHint> slider;
    bool radiobutton = false;
    bool checkbox = false;
    // Group hints.
    bool visibility = false;  ///< a <visibility> element is present
    bool hideable = false;
    bool hidden = false;
    bool read_only = false;
};

/// Where an element starts in the source text, for file:line messages.
struct SourcePos {
    std::uint32_t line = 0;  ///< 1-based; 0 when unknown
};

/// A data element: a <group> or a variable (int, string, eventid, float, action, blob, bit,
/// or an unknown element with a size). Large members that most elements lack are Boxed (kept
/// out of line), so a document of thousands of elements stays compact.
struct Element {
    /// Every member has its initializer; a constructor of our own (defined out of line) spares
    /// the zeroing of the whole object that value-initialising an aggregate would do first.
    Element();

    ElementKind kind = ElementKind::kUnknown;
    SourcePos pos;
    /// Index among all content nodes of the parent element in the text as parsed (whitespace
    /// runs, comments, CDATA, PIs and elements count; cdi/content_index.hpp): OpenLCB_Java names
    /// an unnamed element "child<N>" by it.
    std::uint32_t content_index = 0;
    std::string tag;  ///< the element name as written (matters for kUnknown)

    std::int64_t offset = 0;  ///< the offset attribute (0 when absent)
    std::uint64_t size = 0;   ///< bytes of one variable; 0 for groups (derived by Layout)

    std::string name;
    std::string description;
    Boxed<Link> link;
    Hints hints;

    // <int>, <action> (value), <bit>: integer constraints, parsed from decimal text.
    std::optional<WideInt> int_min;
    std::optional<WideInt> int_max;
    std::optional<WideInt> int_default;
    // <float>: floating constraints and the formatting attribute.
    Boxed<double> float_min;
    Boxed<double> float_max;
    Boxed<double> float_default;
    Boxed<std::string> formatting;  ///< absent when the attribute is missing or empty
    // <string>/<eventid>: the <default> text when present.
    Boxed<std::string> text_default;
    Boxed<Map> map;

    // <action>; the texts are absent when missing or empty.
    Boxed<std::string> button_text;
    Boxed<std::string> dialog_text;
    Boxed<WideInt> action_value;
    // <blob>
    Boxed<std::string> blob_mode;  ///< "read", "write" or "readwrite"; absent when missing/empty

    // <group>
    std::uint64_t replication = 1;
    std::vector<std::string> repnames;
    std::vector<Element> children;

    /// True for every kind except kGroup.
    bool is_variable() const { return kind != ElementKind::kGroup; }
    /// True when an <int> is stored signed (a <min> below zero, standard 5.1.4.2).
    bool is_signed() const { return int_min && *int_min < 0; }
};

/// A <segment>: one memory space's worth of data elements.
struct Segment {
    SourcePos pos;
    /// Index among all content nodes of <cdi> (as Element::content_index): OpenLCB_Java names an
    /// unnamed segment "seg<N>" by it.
    std::uint32_t content_index = 0;
    std::uint32_t space = 0;  ///< 0..255 once validated
    std::int64_t origin = 0;
    std::string name;
    std::string description;
    std::optional<Link> link;
    std::vector<Element> children;
};

/// The <identification> element.
struct Identification {
    SourcePos pos;
    std::string manufacturer;
    std::string model;
    std::string hardware_version;
    std::string software_version;
    std::optional<Link> link;
    std::optional<Map> map;
};

/// The <acdi> element and its version attributes (defaults 4 and 2, standard 5.1.2).
struct Acdi {
    SourcePos pos;
    std::uint32_t fixed = 4;
    std::uint32_t var = 2;
};

/// A whole CDI document.
struct Document {
    std::optional<Identification> identification;
    std::optional<Acdi> acdi;
    std::vector<Segment> segments;

    std::string schema_location;       ///< xsi:noNamespaceSchemaLocation, verbatim ("" if absent)
    bool has_xml_declaration = false;  ///< the text starts with <?xml ...?>
    std::string xml_declaration;       ///< the declaration as written, for conformance checks
};

/// Calls visit(element, depth) for every element under `top` in document order, a group before
/// its children (depth 0 = top level). An explicit stack instead of recursion: nesting costs
/// heap in proportion to the model, never the call stack.
template <typename Visit>
void walk_elements(const std::vector<Element>& top, Visit&& visit) {
    std::vector<std::pair<const Element*, const Element*>> open;
    open.emplace_back(top.data(), top.data() + top.size());
    while (!open.empty()) {
        auto& [next, end] = open.back();
        if (next == end) {
            open.pop_back();
            continue;
        }
        const Element& e = *next++;
        visit(e, open.size() - 1);
        if (!e.children.empty()) {
            open.emplace_back(e.children.data(), e.children.data() + e.children.size());
        }
    }
}

}  // namespace olcb::cdi
