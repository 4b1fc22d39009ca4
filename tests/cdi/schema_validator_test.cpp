#include "cdi/schema_validator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace olcb::cdi {
namespace {

using ::testing::AllOf;
using ::testing::Contains;
using ::testing::Each;
using ::testing::Field;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

std::string location_of(int minor) {
    return "http://openlcb.org/schema/cdi/1/" + std::to_string(minor) + "/cdi.xsd";
}

/// A small CDI; `body` goes inside the one segment, `location` empty = no attribute.
std::string cdi(const std::string& location, const std::string& body) {
    std::string text = "<?xml version=\"1.0\"?>\n";  // line 1
    text += "<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\"";
    if (!location.empty()) text += " xsi:noNamespaceSchemaLocation=\"" + location + "\"";
    text += ">\n";                        // line 2
    text += "<segment space=\"253\">\n";  // line 3
    text += body;                         // line 4...
    text += "</segment>\n</cdi>\n";
    return text;
}

constexpr const char* kPlainBody = "<int size=\"1\"><name>A</name></int>\n";
constexpr const char* kFloatBody = "<float size=\"4\"><name>F</name></float>\n";
constexpr const char* kBitBody = "<bit><name>B</name></bit>\n";

auto error_at(std::uint32_t line, const std::string& text) {
    return AllOf(Field(&Diagnostic::severity, Severity::kError), Field(&Diagnostic::line, line),
                 Field(&Diagnostic::message, HasSubstr(text)));
}

TEST(SchemaVersionFromLocation, ReadsTheMinorVersionOfTheOfficialPath) {
    EXPECT_EQ(schema_version_from_location(location_of(0)), SchemaVersion::kV1_0);
    EXPECT_EQ(schema_version_from_location("https://openlcb.org/schema/cdi/1/4/cdi.xsd"),
              SchemaVersion::kV1_4);
    EXPECT_EQ(schema_version_from_location("  http://openlcb.org/schema/cdi/1/3/cdi.xsd\n"),
              SchemaVersion::kV1_3);
}

TEST(SchemaVersionFromLocation, RefusesUnknownAndUnversionedLocations) {
    EXPECT_EQ(schema_version_from_location(""), std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/trunk/specs/schema/cdi.xsd"),
              std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/schema/cdi/1/43/cdi.xsd"),
              std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/schema/cdi/1/5/cdi.xsd"),
              std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/schema/cdi/1//cdi.xsd"),
              std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/schema/cdi/1/x/cdi.xsd"),
              std::nullopt);
}

TEST(EmbeddedSchema, HoldsEachOfficialXsd) {
    for (int minor = 0; minor <= 4; ++minor) {
        const auto version = static_cast<SchemaVersion>(minor);
        const std::string_view xsd = embedded_schema(version);
        EXPECT_TRUE(xsd.starts_with("<?xml")) << minor;
        EXPECT_NE(xsd.find("version=\"CDI 1." + std::to_string(minor) + "\""), std::string::npos)
            << minor;
        EXPECT_EQ(schema_version_name(version), "1." + std::to_string(minor));
    }
}

TEST(EmbeddedSchema, IsByteForByteTheXsdFile) {
    for (int minor = 0; minor <= 4; ++minor) {
        const std::string path =
            std::string(OLCB_SOURCE_DIR) + "/cdi/schema/cdi-1." + std::to_string(minor) + ".xsd";
        std::ifstream in(path, std::ios::binary);
        ASSERT_TRUE(in) << path;
        std::ostringstream file;
        file << in.rdbuf();
        EXPECT_EQ(embedded_schema(static_cast<SchemaVersion>(minor)), file.str()) << path;
    }
    EXPECT_EQ(embedded_schema(static_cast<SchemaVersion>(5)), "");
}

TEST(ValidateSchema, UsesTheDeclaredVersionForEachOfTheFive) {
    for (int minor = 0; minor <= 4; ++minor) {
        SchemaChoice choice;
        const Diagnostics d = validate_schema(cdi(location_of(minor), kPlainBody), &choice);
        EXPECT_THAT(d, IsEmpty()) << "1." << minor;
        EXPECT_EQ(choice.version, static_cast<SchemaVersion>(minor));
        EXPECT_TRUE(choice.declared);
        EXPECT_TRUE(choice.well_formed);
    }
}

TEST(ValidateSchema, TheDeclaredVersionDecidesWhatIsValid) {
    // <float> arrived in 1.2, <bit> left after 1.0: only the right schema gives these results.
    EXPECT_THAT(validate_schema(cdi(location_of(1), kFloatBody)),
                ::testing::ElementsAre(error_at(4, "'float': This element is not expected")));
    EXPECT_THAT(validate_schema(cdi(location_of(2), kFloatBody)), IsEmpty());
    EXPECT_THAT(validate_schema(cdi(location_of(0), kBitBody)), IsEmpty());
    EXPECT_THAT(validate_schema(cdi(location_of(1), kBitBody)),
                ::testing::ElementsAre(error_at(4, "'bit'")));
}

TEST(ValidateSchema, MissingLocationFallsBackToNewestWithWarning) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(cdi("", kFloatBody), &choice);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].severity, Severity::kWarning);
    EXPECT_EQ(d[0].line, 2u);
    EXPECT_EQ(d[0].message, "no schema version declared; validated against CDI 1.4");
    EXPECT_EQ(choice.version, SchemaVersion::kV1_4);
    EXPECT_FALSE(choice.declared);
}

TEST(ValidateSchema, UnversionedAndUnknownLocationsFallBackWithWarning) {
    SchemaChoice choice;
    Diagnostics d =
        validate_schema(cdi("http://openlcb.org/trunk/specs/schema/cdi.xsd", kPlainBody), &choice);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_EQ(d[0].message, "no schema version declared; validated against CDI 1.4");
    EXPECT_EQ(choice.version, SchemaVersion::kV1_4);

    d = validate_schema(cdi("http://openlcb.org/schema/cdi/1/43/cdi.xsd", kBitBody), &choice);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_EQ(d[0].severity, Severity::kWarning);
    EXPECT_THAT(d[0].message, HasSubstr("unknown schema version declared"));
    EXPECT_THAT(d[0].message, HasSubstr("validated against CDI 1.4"));
    EXPECT_THAT(d[1], error_at(4, "'bit'"));  // 1.4 has no <bit>: proof 1.4 was used
    EXPECT_EQ(choice.version, SchemaVersion::kV1_4);
    EXPECT_FALSE(choice.declared);
}

TEST(ValidateSchema, ReportsEveryValidityErrorWithItsLine) {
    const std::string body =
        "<int size=\"3\"><name>A</name></int>\n"   // line 4
        "<string size=\"8\"/>\n"                   // line 5
        "<int size=\"5\"><name>B</name></int>\n";  // line 6
    const Diagnostics d = validate_schema(cdi(location_of(4), body));
    EXPECT_THAT(d, ::testing::ElementsAre(error_at(4, "attribute 'size'"),
                                          error_at(6, "The value '5' is not an element")));
    EXPECT_THAT(d[0].message, HasSubstr("CDI 1.4 schema: "));
}

TEST(ValidateSchema, LineNumbersBeyond65535AreNotClamped) {
    const std::string body = std::string(70000, '\n') + "<int size=\"3\"/>\n";
    const Diagnostics d = validate_schema(cdi(location_of(4), body));
    ASSERT_EQ(d.size(), 1u);
    // Past 65535 libxml2 2.9 takes an empty element's line from the text after it (+1, as
    // xmllint prints); without XML_PARSE_BIG_LINES it would say 65535.
    EXPECT_GE(d[0].line, 4u + 70000u);
    EXPECT_LE(d[0].line, 4u + 70001u);
}

TEST(ValidateSchema, IgnoresTrailingNulBytes) {
    std::string text = cdi(location_of(1), kPlainBody);
    text.push_back('\0');
    EXPECT_THAT(validate_schema(text), IsEmpty());
    text += std::string(3, '\0');
    EXPECT_THAT(validate_schema(text), IsEmpty());
}

TEST(ValidateSchema, NulInsideTheTextIsAnError) {
    std::string text = cdi(location_of(1), kPlainBody);
    text.insert(text.find("<segment"), 1, '\0');
    SchemaChoice choice;
    EXPECT_TRUE(has_errors(validate_schema(text, &choice)));
    EXPECT_FALSE(choice.well_formed);
}

TEST(ValidateSchema, NotWellFormedGivesParseErrorWithLine) {
    const std::string text =
        "<?xml version=\"1.0\"?>\n<cdi>\n<identification>\n<model>x\n</identification>\n</cdi>\n";
    SchemaChoice choice;
    const Diagnostics d = validate_schema(text, &choice);
    ASSERT_FALSE(d.empty());
    EXPECT_THAT(d[0], error_at(5, "XML parse error: "));
    EXPECT_THAT(d[0].message, HasSubstr("mismatch"));
    EXPECT_FALSE(choice.well_formed);
}

TEST(ValidateSchema, EmptyInputIsAnError) {
    EXPECT_TRUE(has_errors(validate_schema("")));
    EXPECT_TRUE(has_errors(validate_schema(std::string(4, '\0'))));
}

TEST(ValidateSchema, WrongRootElementIsAnError) {
    const Diagnostics d = validate_schema(
        "<?xml version=\"1.0\"?>\n<configuration><segment space=\"1\"/></configuration>");
    EXPECT_THAT(d, ::testing::Contains(error_at(2, "No matching global declaration")));
}

TEST(ValidateSchema, RefusesADoctypeWithoutExpandingEntities) {
    // Billion laughs: fully expanded this is 10^9 "lol"s; refused at the DOCTYPE it costs nothing.
    std::string text = "<?xml version=\"1.0\"?>\n<!DOCTYPE cdi [\n<!ENTITY lol \"lol\">\n";
    for (int i = 1; i <= 9; ++i) {
        text += "<!ENTITY lol" + std::to_string(i) + " \"";
        for (int j = 0; j < 10; ++j)
            text += "&lol" + (i == 1 ? std::string() : std::to_string(i - 1)) + ";";
        text += "\">\n";
    }
    text +=
        "]>\n<cdi><segment space=\"1\"><string size=\"8\"><name>&lol9;</name></string>"
        "</segment></cdi>\n";
    SchemaChoice choice;
    const Diagnostics d = validate_schema(text, &choice);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_THAT(d[0], error_at(2, "DOCTYPE is not allowed"));
    EXPECT_FALSE(choice.well_formed);
}

TEST(ValidateSchema, RefusesExternalEntitiesWithoutFetching) {
    const std::string text =
        "<?xml version=\"1.0\"?>\n<!DOCTYPE cdi SYSTEM \"http://example.invalid/x.dtd\">\n"
        "<cdi/>\n";
    EXPECT_THAT(validate_schema(text), ::testing::ElementsAre(error_at(2, "DOCTYPE")));
    // Without a DOCTYPE an entity reference is simply undefined.
    const Diagnostics d = validate_schema("<cdi>&xxe;</cdi>");
    EXPECT_TRUE(has_errors(d));
}

TEST(ValidateSchema, NeverWritesToStderr) {
    ::testing::internal::CaptureStderr();
    (void)validate_schema("<cdi><oops></cdi>");
    (void)validate_schema(cdi(location_of(4), "<int size=\"3\"/>"));
    (void)validate_schema("<!DOCTYPE cdi [<!ENTITY a \"b\">]><cdi/>");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

TEST(ValidateSchema, RefusesOversizedInput) {
    const std::string huge(kMaxCdiBytes + 1, ' ');
    const Diagnostics d = validate_schema(huge);
    ASSERT_EQ(d.size(), 1u);
    EXPECT_THAT(d[0].message, HasSubstr("refusing"));
}

TEST(ValidateSchemaAs, IgnoresTheDeclaredVersion) {
    const std::string text = cdi(location_of(1), kFloatBody);
    EXPECT_THAT(validate_schema_as(text, SchemaVersion::kV1_4), IsEmpty());
    EXPECT_TRUE(has_errors(validate_schema_as(text, SchemaVersion::kV1_0)));
}

TEST(ValidateSchema, GivesTheSameAnswerFromManyThreads) {
    const std::string good = cdi(location_of(3), kPlainBody);
    const std::string bad = cdi(location_of(4), "<int size=\"3\"/>\n");
    std::vector<std::thread> threads;
    threads.reserve(4);
    std::vector<int> failures(4, 0);
    for (int t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] {
            for (int i = 0; i < 25; ++i) {
                if (!validate_schema(good).empty()) ++failures[t];
                const Diagnostics d = validate_schema(bad);
                if (d.size() != 1 || d[0].line != 4) ++failures[t];
            }
        });
    }
    for (auto& thread : threads) thread.join();
    EXPECT_EQ(failures, std::vector<int>(4, 0));
}

// The schema check is fed events (from pugixml's tree, or while libxml2 parses), never a DOM:
// what that changes at the edges — how the schema is chosen before the root is validated, which
// line a finding gets, and what is kept when the text turns out not to be XML.
constexpr const char* kXsi = "http://www.w3.org/2001/XMLSchema-instance";

std::string root_with(const std::string& attributes) {
    return "<cdi " + attributes +
           ">\n<segment space=\"253\">\n<int size=\"1\"/>\n</segment>\n</cdi>\n";
}

TEST(SchemaStream, AnyPrefixBoundToTheInstanceNamespaceDeclaresTheVersion) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(
        root_with(std::string("xmlns:q=\"") + kXsi +
                  "\" q:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/1/cdi.xsd\""),
        &choice);
    EXPECT_THAT(d, IsEmpty());
    EXPECT_TRUE(choice.declared);
    EXPECT_EQ(choice.version, SchemaVersion::kV1_1);
}

TEST(SchemaStream, TheLocalNameInAnotherNamespaceDeclaresNothing) {
    SchemaChoice choice;
    const Diagnostics d = validate_schema(
        root_with("xmlns:q=\"urn:other\" "
                  "q:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/1/cdi.xsd\""),
        &choice);
    EXPECT_FALSE(choice.declared);
    EXPECT_EQ(choice.version, kNewestSchema);
    EXPECT_THAT(d, Contains(Field(&Diagnostic::message, HasSubstr("no schema version declared"))));
}

TEST(SchemaStream, CommentsAndInstructionsBeforeTheRootDoNotHideTheDeclaration) {
    SchemaChoice choice;
    const std::string text =
        "<?xml version=\"1.0\"?>\n<!-- generated -->\n<?xml-stylesheet href=\"x.xsl\"?>\n" +
        root_with(std::string("xmlns:xsi=\"") + kXsi +
                  "\" xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/0/cdi.xsd\"");
    EXPECT_THAT(validate_schema(text, &choice), IsEmpty());
    EXPECT_TRUE(choice.declared);
    EXPECT_EQ(choice.version, SchemaVersion::kV1_0);
}

TEST(SchemaStream, FindingsMadeBeforeTheTextStopsBeingXmlAreDropped) {
    // <bogus> breaks the schema on line 3; the text then ends inside <segment>.
    const std::string text = "<cdi>\n<segment space=\"253\">\n<bogus/>\n";
    SchemaChoice choice;
    const Diagnostics d = validate_schema(text, &choice);
    EXPECT_FALSE(choice.well_formed);
    EXPECT_THAT(d, Contains(Field(&Diagnostic::message, HasSubstr("XML parse error"))));
    EXPECT_THAT(d, Each(Field(&Diagnostic::message, Not(HasSubstr("schema")))));
}

TEST(SchemaStream, AStartTagFindingIsOnItsLineAndMissingContentOnTheEndTag) {
    const std::string text =
        "<cdi>\n"                             // 1
        "<segment space=\"253\">\n"           // 2
        "<int size=\"1\" colour=\"red\">\n"   // 3: an attribute the schema does not allow
        "<map>\n"                             // 4
        "<relation><property>1</property>\n"  // 5: a relation needs a <value>
        "</relation>\n"                       // 6
        "</map>\n</int>\n</segment>\n</cdi>\n";
    const Diagnostics d = validate_schema_as(text, SchemaVersion::kV1_4);
    EXPECT_THAT(d, Contains(AllOf(Field(&Diagnostic::line, 3u),
                                  Field(&Diagnostic::message, HasSubstr("colour")))));
    EXPECT_THAT(d, Contains(AllOf(Field(&Diagnostic::line, 6u),
                                  Field(&Diagnostic::message, HasSubstr("relation")))));
}

}  // namespace
}  // namespace olcb::cdi
