#include "cdi/semantic_rules.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

namespace olcb::cdi {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::ContainsRegex;
using ::testing::ElementsAre;
using ::testing::Field;
using ::testing::IsEmpty;

constexpr std::uint32_t kLine = 7;

Element variable(ElementKind kind, std::uint64_t size, const std::string& name = "Speed") {
    Element e;
    e.kind = kind;
    e.size = size;
    e.name = name;
    e.pos.line = kLine;
    return e;
}

Element int_var(std::uint64_t size) {
    return variable(ElementKind::kInt, size);
}

Map map_of(std::initializer_list<const char*> properties) {
    Map map;
    for (const char* p : properties) map.entries.push_back({p, std::string("v") + p});
    return map;
}

Document with(Element e) {
    Document doc;
    Segment segment;
    segment.space = 253;
    segment.pos.line = 3;
    segment.children.push_back(std::move(e));
    doc.segments.push_back(std::move(segment));
    return doc;
}

Diagnostics check(Element e) {
    return check_semantics(with(std::move(e)));
}

auto error_like(const std::string& regex, std::uint32_t line = kLine) {
    return AllOf(Field(&Diagnostic::severity, Severity::kError), Field(&Diagnostic::line, line),
                 Field(&Diagnostic::message, ContainsRegex(regex)));
}

auto warning_like(const std::string& regex, std::uint32_t line = kLine) {
    return AllOf(Field(&Diagnostic::severity, Severity::kWarning), Field(&Diagnostic::line, line),
                 Field(&Diagnostic::message, ContainsRegex(regex)));
}

// --- hints -------------------------------------------------------------------------------

TEST(CheckboxHint, AcceptsExactlyTwoEntries) {
    Element e = int_var(1);
    e.hints.checkbox = true;
    e.map = map_of({"0", "1"});
    EXPECT_THAT(check(e), IsEmpty());
}

TEST(CheckboxHint, RefusesOtherEntryCountsAndMissingMap) {
    Element e = int_var(1);
    e.hints.checkbox = true;
    e.map = map_of({"0", "1", "2"});
    EXPECT_THAT(check(e), ElementsAre(error_like("<int> \"Speed\": a checkbox .*exactly two.*3")));
    e.map.reset();
    EXPECT_THAT(check(e), ElementsAre(error_like("checkbox.*no map")));
}

TEST(RadiobuttonHint, NeedsAMap) {
    Element e = int_var(1);
    e.hints.radiobutton = true;
    EXPECT_THAT(check(e), ElementsAre(error_like("radiobutton hint needs a <map>")));
    e.map = map_of({"0", "1", "2"});
    EXPECT_THAT(check(e), IsEmpty());
}

// --- int ranges --------------------------------------------------------------------------

TEST(IntDefault, WithinMinAndMaxPasses) {
    Element e = int_var(1);
    e.int_min = 1;
    e.int_max = 10;
    e.int_default = 10;
    EXPECT_THAT(check(e), IsEmpty());
}

TEST(IntDefault, OutsideMinOrMaxFails) {
    Element e = int_var(1);
    e.int_min = 1;
    e.int_max = 10;
    e.int_default = 0;
    EXPECT_THAT(check(e), ElementsAre(error_like("default 0 is below min 1")));
    e.int_default = 11;
    EXPECT_THAT(check(e), ElementsAre(error_like("default 11 is above max 10")));
}

TEST(IntDefault, MustBeAMapProperty) {
    Element e = int_var(1);
    e.map = map_of({"0", "2"});
    e.int_default = 2;
    EXPECT_THAT(check(e), IsEmpty());
    e.int_default = 1;
    EXPECT_THAT(check(e),
                ElementsAre(warning_like("default 1 is not one of the map's properties")));
}

TEST(IntMinMax, MinAboveMaxFails) {
    Element e = int_var(2);
    e.int_min = 5;
    e.int_max = 5;
    EXPECT_THAT(check(e), IsEmpty());
    e.int_min = 6;
    EXPECT_THAT(check(e), ElementsAre(error_like("min 6 is greater than max 5")));
}

TEST(IntRepresentable, UnsignedLimitsFollowTheSize) {
    Element e = int_var(1);
    e.int_max = 255;
    EXPECT_THAT(check(e), IsEmpty());
    e.int_max = 256;
    EXPECT_THAT(check(e), ElementsAre(error_like("max 256 does not fit in a 1-byte unsigned")));

    Element wide = int_var(8);
    wide.int_max = (WideInt{1} << 64) - 1;
    EXPECT_THAT(check(wide), IsEmpty());
    wide.int_max = WideInt{1} << 64;
    EXPECT_THAT(check(wide), ElementsAre(error_like("max 18446744073709551616 does not fit")));
}

TEST(IntRepresentable, NegativeMinMakesItTwosComplement) {
    Element e = int_var(1);
    e.int_min = -128;
    e.int_max = 127;
    EXPECT_THAT(check(e), IsEmpty());
    e.int_max = 128;
    EXPECT_THAT(check(e), ElementsAre(error_like("max 128 does not fit in a 1-byte signed "
                                                 "\\(-128\\.\\.127\\)")));
    e.int_max = 127;
    e.int_min = -129;
    EXPECT_THAT(check(e), ElementsAre(error_like("min -129 does not fit")));
}

TEST(IntRepresentable, NegativeDefaultWithoutNegativeMinIsUnsigned) {
    Element e = int_var(2);
    e.int_default = -1;
    EXPECT_THAT(check(e), ElementsAre(error_like("default -1 does not fit in a 2-byte unsigned")));
}

// --- map properties ----------------------------------------------------------------------

TEST(IntMap, PropertiesMustBeDecimalsInRange) {
    Element e = int_var(1);
    e.map = map_of({"0", " 255 ", "+7"});
    EXPECT_THAT(check(e), IsEmpty());
    e.map = map_of({"0x10", "256", "-1"});
    EXPECT_THAT(check(e), ElementsAre(error_like("property \"0x10\" is not a decimal integer"),
                                      error_like("property \"256\" does not fit"),
                                      error_like("property \"-1\" does not fit")));
}

TEST(IntMap, PropertiesOutsideMinMaxFail) {
    Element e = int_var(1);
    e.int_min = 1;
    e.int_max = 3;
    e.map = map_of({"1", "3"});
    EXPECT_THAT(check(e), IsEmpty());
    e.map = map_of({"0", "3"});
    EXPECT_THAT(check(e), ElementsAre(error_like("property \"0\" is outside min/max")));
}

TEST(IntMap, DuplicatePropertiesWarn) {
    Element e = int_var(1);
    e.map = map_of({"1", "2", "01"});  // equal numbers, however spelled
    EXPECT_THAT(check(e), ElementsAre(warning_like("property \"01\" appears more than once")));
}

TEST(EventIdMap, PropertiesMustBeEventIds) {
    Element e = variable(ElementKind::kEventId, 8);
    e.map = map_of({"05.01.01.01.22.00.00.FF", "0501010122000001", "0", "1234"});
    EXPECT_THAT(check(e), IsEmpty());
    e.map = map_of({"05.01.01", "05.01.01.01.22.00.00.FG", "-1"});
    EXPECT_THAT(check(e), ElementsAre(error_like("\"05.01.01\" is not an event ID"),
                                      error_like("\"05.01.01.01.22.00.00.FG\" is not an event ID"),
                                      error_like("\"-1\" is not an event ID")));
}

TEST(EventIdMap, DuplicatesAndDefaultCompareAsIds) {
    Element e = variable(ElementKind::kEventId, 8);
    e.map = map_of({"00.00.00.00.00.00.00.01", "1"});
    EXPECT_THAT(check(e), ElementsAre(warning_like("\"1\" appears more than once")));
    e.map = map_of({"05.01.01.01.22.00.00.ff"});
    e.text_default = "05.01.01.01.22.00.00.FF";
    EXPECT_THAT(check(e), IsEmpty());
    e.text_default = "05.01.01.01.22.00.00.FE";
    EXPECT_THAT(check(e), ElementsAre(warning_like("not one of the map's properties")));
    e.text_default = "nonsense";
    EXPECT_THAT(check(e), ElementsAre(error_like("default \"nonsense\" is not an event ID")));
}

TEST(FloatMap, PropertiesMustBeDecimalNumbers) {
    Element e = variable(ElementKind::kFloat, 4);
    e.map = map_of({"0.0", "-2.5", "1e3"});
    e.float_default = 0;
    EXPECT_THAT(check(e), IsEmpty());
    e.map = map_of({"0.0", "fast", "nan"});
    EXPECT_THAT(check(e), ElementsAre(error_like("\"fast\" is not a decimal number"),
                                      error_like("\"nan\" is not a decimal number")));
}

TEST(FloatMap, DefaultMustBeAPropertyNumerically) {
    Element e = variable(ElementKind::kFloat, 4);
    e.map = map_of({"0.50", "1"});
    e.float_default = 0.5;
    EXPECT_THAT(check(e), IsEmpty());
    e.float_default = 0.25;
    EXPECT_THAT(check(e), ElementsAre(warning_like("default 0.25 is not one of")));
}

TEST(StringMap, PropertiesMustLeaveRoomForTheNul) {
    Element e = variable(ElementKind::kString, 4, "Label");
    e.map = map_of({"abc", ""});
    EXPECT_THAT(check(e), IsEmpty());
    e.map = map_of({"abcd"});
    EXPECT_THAT(check(e), ElementsAre(error_like("<string> \"Label\": map property \"abcd\" is 4 "
                                                 "bytes; at most 3 fit")));
}

TEST(StringMap, DuplicatesWarnAndDefaultMustFitAndBeListed) {
    Element e = variable(ElementKind::kString, 4);
    e.map = map_of({"a", "a"});
    EXPECT_THAT(check(e), ElementsAre(warning_like("\"a\" appears more than once")));
    e.map = map_of({"a", "b"});
    e.text_default = "b";
    EXPECT_THAT(check(e), IsEmpty());
    e.text_default = "c";
    EXPECT_THAT(check(e), ElementsAre(warning_like("default \"c\" is not one of")));
    e.map.reset();
    e.text_default = "toolong";
    EXPECT_THAT(check(e), ElementsAre(error_like("default is 7 bytes; at most 3")));
}

// --- float ranges ------------------------------------------------------------------------

TEST(FloatRange, DefaultWithinMinMax) {
    Element e = variable(ElementKind::kFloat, 8);
    e.float_min = -1.5;
    e.float_max = 1.5;
    e.float_default = 1.5;
    EXPECT_THAT(check(e), IsEmpty());
    e.float_default = 2;
    EXPECT_THAT(check(e), ElementsAre(error_like("default 2 is above max 1.5")));
    e.float_default = -2;
    EXPECT_THAT(check(e), ElementsAre(error_like("default -2 is below min -1.5")));
    e.float_default.reset();
    e.float_min = 2;
    EXPECT_THAT(check(e), ElementsAre(error_like("min 2 is greater than max 1.5")));
}

// --- sizes -------------------------------------------------------------------------------

TEST(Sizes, IntAcceptsOneTwoFourEight) {
    for (std::uint64_t size : {1, 2, 4, 8}) EXPECT_THAT(check(int_var(size)), IsEmpty()) << size;
}

TEST(Sizes, IntRefusesOthers) {
    for (std::uint64_t size : {0, 3, 5, 16}) {
        const Diagnostics d = check(int_var(size));
        ASSERT_EQ(d.size(), 1u) << size;
        EXPECT_THAT(d[0], error_like("int.*size"));
        EXPECT_THAT(d[0].message, ContainsRegex("1, 2, 4, or 8"));
    }
}

TEST(Sizes, FloatAcceptsTwoFourEightWithoutWarning) {
    for (std::uint64_t size : {2, 4, 8}) {
        EXPECT_THAT(check(variable(ElementKind::kFloat, size)), IsEmpty()) << size;
    }
    EXPECT_THAT(check(variable(ElementKind::kFloat, 3)),
                ElementsAre(error_like("float size must be 2, 4, or 8")));
}

TEST(Sizes, EventIdIsEightBytes) {
    EXPECT_THAT(check(variable(ElementKind::kEventId, 8)), IsEmpty());
    EXPECT_THAT(check(variable(ElementKind::kEventId, 4)),
                ElementsAre(error_like("size 4 is not valid; an eventid is 8 bytes")));
}

TEST(Sizes, ActionAcceptsOneTwoFourEight) {
    EXPECT_THAT(check(variable(ElementKind::kAction, 8)), IsEmpty());
    EXPECT_THAT(check(variable(ElementKind::kAction, 3)),
                ElementsAre(error_like("action size must be 1, 2, 4, or 8")));
}

TEST(Sizes, StringNeedsAtLeastOneByte) {
    EXPECT_THAT(check(variable(ElementKind::kString, 1)), IsEmpty());
    EXPECT_THAT(check(variable(ElementKind::kString, 0)),
                ElementsAre(error_like("string size must be at least 1")));
}

TEST(ActionValue, MustFitItsSize) {
    Element e = variable(ElementKind::kAction, 1);
    e.action_value = 255;
    EXPECT_THAT(check(e), IsEmpty());
    e.action_value = -128;
    EXPECT_THAT(check(e), IsEmpty());
    e.action_value = 256;
    EXPECT_THAT(check(e), ElementsAre(error_like("value 256 does not fit")));
}

// --- groups, segments, identification, acdi ------------------------------------------------

// §5.1.3 sets no lower bound: a group repeated no time is odd, so a warning, not an error.
TEST(Replication, ZeroWarns) {
    Element group = variable(ElementKind::kGroup, 0, "Port");
    group.replication = 1;
    EXPECT_THAT(check(group), IsEmpty());
    group.replication = 0;
    EXPECT_THAT(check(group), ElementsAre(warning_like("<group> \"Port\": replication 0")));
}

TEST(Groups, NestedVariablesAreChecked) {
    Element inner = int_var(3);
    inner.pos.line = 12;
    Element group = variable(ElementKind::kGroup, 0, "Port");
    Element middle = variable(ElementKind::kGroup, 0, "");
    middle.children.push_back(inner);
    group.children.push_back(middle);
    EXPECT_THAT(check(group), ElementsAre(error_like("<int> \"Speed\": size 3", 12)));
}

TEST(Groups, DeepNestingIsCheckedAllTheWayDown) {
    // The walk keeps its own stack: the leaf under 2,000 groups is still judged.
    Element leaf = int_var(3);
    for (int i = 0; i < 2000; ++i) {
        Element group = variable(ElementKind::kGroup, 0, "");
        group.children.push_back(std::move(leaf));
        leaf = std::move(group);
    }
    EXPECT_THAT(check(leaf), ElementsAre(error_like("<int>.*size 3")));
}

TEST(Segments, SpaceMustBeAByte) {
    Document doc = with(int_var(1));
    doc.segments[0].space = 255;
    EXPECT_THAT(check_semantics(doc), IsEmpty());
    doc.segments[0].space = 256;
    doc.segments[0].name = "Main";
    EXPECT_THAT(check_semantics(doc),
                ElementsAre(error_like("<segment> \"Main\": space 256 is not a valid", 3)));
}

TEST(UnknownElements, AreFlaggedAsFutureVariables) {
    Element e = variable(ElementKind::kUnknown, 4, "Future");
    e.tag = "bogus";
    EXPECT_THAT(check(e), ElementsAre(warning_like("<bogus> \"Future\": unknown element read as a "
                                                   "4-byte variable")));
}

TEST(Acdi, VersionsOtherThanFourAndTwoWarn) {
    Document doc;
    doc.acdi = Acdi{};
    doc.acdi->pos.line = 5;
    EXPECT_THAT(check_semantics(doc), IsEmpty());
    doc.acdi->fixed = 3;
    doc.acdi->var = 1;
    EXPECT_THAT(check_semantics(doc), ElementsAre(warning_like("fixed=\"3\" is not 4", 5),
                                                  warning_like("var=\"1\" is not 2", 5)));
}

TEST(Identification, StringsMustFitSnipSlots) {
    Document doc;
    doc.identification = Identification{};
    doc.identification->pos.line = 2;
    doc.identification->manufacturer = std::string(40, 'm');
    doc.identification->model = std::string(40, 'o');
    doc.identification->hardware_version = std::string(20, 'h');
    doc.identification->software_version = std::string(20, 's');
    EXPECT_THAT(check_semantics(doc), IsEmpty());
    doc.identification->manufacturer += "m";
    doc.identification->model += "o";
    doc.identification->hardware_version += "h";
    doc.identification->software_version += "s";
    EXPECT_THAT(check_semantics(doc),
                ElementsAre(warning_like("manufacturer is 41 bytes; .*at most 40", 2),
                            warning_like("model is 41 bytes", 2),
                            warning_like("hardwareVersion is 21 bytes; .*at most 20", 2),
                            warning_like("softwareVersion is 21 bytes", 2)));
}

TEST(Identification, LengthIsCountedInUtf8Bytes) {
    Document doc;
    doc.identification = Identification{};
    doc.identification->hardware_version =
        "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9"
        "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9"
        "x";  // 11 characters, 21 bytes
    EXPECT_THAT(check_semantics(doc), Contains(warning_like("hardwareVersion is 21 bytes", 0)));
}

TEST(Identification, DuplicateMapPropertiesWarn) {
    Document doc;
    doc.identification = Identification{};
    doc.identification->map = map_of({"board", "board"});
    EXPECT_THAT(check_semantics(doc),
                ElementsAre(warning_like("\"board\" appears more than once", 0)));
}

TEST(CheckSemantics, ReportsInDocumentOrder) {
    Document doc = with(int_var(3));
    Element second = variable(ElementKind::kFloat, 5, "F");
    second.pos.line = 9;
    doc.segments[0].children.push_back(second);
    doc.acdi = Acdi{};
    doc.acdi->fixed = 1;
    doc.acdi->pos.line = 1;
    EXPECT_THAT(check_semantics(doc),
                ElementsAre(warning_like("fixed", 1), error_like("int size", kLine),
                            error_like("<float> \"F\": size 5", 9)));
}

}  // namespace
}  // namespace olcb::cdi
