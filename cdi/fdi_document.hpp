// The typed model of an FDI (Function Description Information, FunctionDescriptionInformationS):
// the functions a train node describes in memory space 0xFA, with the groups that organise them
// for a throttle. No recursion: groups are a flat list in document order with parent indices.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::cdi {

/// How a throttle's button for a function behaves (FunctionDescriptionInformationS §5.1.4,
/// the 'kind' attribute).
enum class FunctionKind : std::uint8_t {
    kBinary,     ///< on/off, toggled by a press (latching; the default)
    kMomentary,  ///< on/off, on while the button is held
    kAnalog,     ///< an unsigned value between <min> and <max>
};

/// "binary", "momentary" or "analog", as the 'kind' attribute spells it.
std::string_view function_kind_name(FunctionKind kind);

/// The largest function number (§5.1.4: 0..16777215, the 24-bit address of Train Control's Set
/// Function).
inline constexpr std::uint32_t kMaxFunctionNumber = 16777215;
/// An analog function's range when it gives no <min> or <max> (§5.1.4).
inline constexpr std::int64_t kDefaultAnalogMin = 0;
inline constexpr std::int64_t kDefaultAnalogMax = 255;

/// One <function>: the metadata of one function of the train.
struct FdiFunction {
    std::uint32_t number = 0;  ///< <number>: the function's address in Train Control
    FunctionKind kind = FunctionKind::kBinary;
    std::string name;                  ///< <name>, XML whitespace trimmed ("" when absent)
    std::optional<std::int32_t> icon;  ///< <icon>: a function of RailCommunity TN-218 §3
    std::optional<std::int32_t> min;   ///< <min> as written (meaningful for analog only)
    std::optional<std::int32_t> max;   ///< <max> as written (meaningful for analog only)
    std::optional<std::size_t> group;  ///< index in FdiDocument::groups; none: in the segment
    bool size_given = false;           ///< the reserved 'size' attribute is present
    std::uint32_t line = 0;            ///< 1-based source line of the <function> tag

    bool momentary() const { return kind == FunctionKind::kMomentary; }
    /// A binary function latches: a press turns it on until the next press.
    bool latching() const { return kind == FunctionKind::kBinary; }
    /// The smallest value an analog function accepts: <min>, else 0.
    std::int64_t value_min() const { return min ? *min : kDefaultAnalogMin; }
    /// The largest value an analog function accepts: <max>, else 255.
    std::int64_t value_max() const { return max ? *max : kDefaultAnalogMax; }
};

/// One <group>: a name and description shared by the functions and groups inside it.
struct FdiGroup {
    std::string name;                   ///< <name>, trimmed ("" when absent)
    std::string description;            ///< <description>, trimmed ("" when absent)
    std::optional<std::size_t> parent;  ///< index of the enclosing group; none: in the segment
    std::size_t depth = 1;              ///< 1: directly in the segment
    std::size_t first_function = 0;     ///< how many functions come before it in the document
    std::uint32_t line = 0;             ///< 1-based source line of the <group> tag
};

/// One step of FdiDocument::walk().
struct FdiStep {
    enum class Kind : std::uint8_t { kOpenGroup, kFunction, kCloseGroup };
    Kind kind = Kind::kFunction;
    std::size_t index = 0;  ///< into groups (kOpenGroup, kCloseGroup) or functions (kFunction)
    std::size_t depth = 0;  ///< groups around it: 0 directly in the segment
};

/// An FDI as a throttle uses it: the segment's texts, the groups and every function.
struct FdiDocument {
    std::string schema_location;  ///< the root's xsi:noNamespaceSchemaLocation ("" when none)
    std::string name;             ///< the segment's <name>
    std::string description;      ///< the segment's <description>
    bool space_given = false;     ///< the segment has the reserved 'space' attribute
    bool origin_given = false;    ///< the segment has the reserved 'origin' attribute
    std::uint32_t segment_line = 0;
    std::vector<FdiGroup> groups;        ///< document order: a group before those inside it
    std::vector<FdiFunction> functions;  ///< document order

    /// The first function (document order) with this number; nullptr when there is none.
    const FdiFunction* find(std::uint32_t number) const;

    /// Visits the groups and functions as nested in the document: in each container its
    /// functions in list order, a child group coming before the functions from its
    /// first_function on. A parent or group index that does not name an earlier group (a
    /// hand-built model's mistake) counts as the segment. Iterative: nesting costs heap.
    void walk(const std::function<void(const FdiStep&)>& visit) const;
};

}  // namespace olcb::cdi
