// The FDI schemas: the versions an FDI names, the embedded texts (the published files, 1.1 with
// the <icon> of the standard's Appendix A) and validation against them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_function;
using test::fdi_text;
using test::listing;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

TEST(FdiSchema, VersionFromLocation) {
    EXPECT_EQ(fdi_schema_version_from_location("https://openlcb.org/schema/fdi/1/0/fdi.xsd"),
              FdiSchemaVersion::kV1_0);
    EXPECT_EQ(fdi_schema_version_from_location("http://openlcb.org/schema/fdi/1/1/fdi.xsd \n"),
              FdiSchemaVersion::kV1_1);
    EXPECT_EQ(fdi_schema_version_from_location("http://openlcb.org/schema/fdi/1/2/fdi.xsd"),
              std::nullopt);
    EXPECT_EQ(fdi_schema_version_from_location("http://openlcb.org/schema/cdi/1/1/cdi.xsd"),
              std::nullopt);
    EXPECT_EQ(
        fdi_schema_version_from_location("http://openlcb.org/trunk/prototypes/xml/schema/fdi.xsd"),
        std::nullopt);
    EXPECT_EQ(schema_version_from_location("http://openlcb.org/schema/fdi/1/1/fdi.xsd"),
              std::nullopt);
    EXPECT_EQ(fdi_schema_version_name(FdiSchemaVersion::kV1_0), "1.0");
    EXPECT_EQ(fdi_schema_version_name(FdiSchemaVersion::kV1_1), "1.1");
}

TEST(FdiSchema, EmbeddedTextsAreThePublishedFilesWithTheStandardsIcon) {
    const std::string_view v10 = embedded_fdi_schema(FdiSchemaVersion::kV1_0);
    const std::string_view v11 = embedded_fdi_schema(FdiSchemaVersion::kV1_1);
    EXPECT_THAT(std::string(v10), HasSubstr("path schema/fdi/1/0/fdi.xsd"));
    EXPECT_THAT(std::string(v11), HasSubstr("path schema/fdi/1/1/fdi.xsd"));
    EXPECT_EQ(v10.find("name=\"icon\""), std::string_view::npos);
    const std::size_t icon = v11.find("<xs:element name=\"icon\" type=\"xs:int\"");
    const std::size_t number = v11.find("<xs:element name=\"number\"");
    ASSERT_NE(icon, std::string_view::npos);
    EXPECT_LT(icon, number);
    EXPECT_EQ(v11.find("name=\"icon\"", number), std::string_view::npos);  // inserted once
    EXPECT_TRUE(embedded_fdi_schema(static_cast<FdiSchemaVersion>(7)).empty());
}

TEST(FdiSchema, ValidatesAgainstTheDeclaredOrTheGivenVersion) {
    FdiSchemaChoice choice;
    const std::string text = fdi_text(fdi_function(0), 0);
    EXPECT_THAT(validate_fdi_schema(text, &choice), IsEmpty());
    EXPECT_EQ(choice.version, FdiSchemaVersion::kV1_0);
    EXPECT_TRUE(choice.declared);
    EXPECT_TRUE(choice.well_formed);

    const std::string icon = fdi_text("<function><icon>3</icon><number>0</number></function>\n", 0);
    const Diagnostics as10 = validate_fdi_schema_as(icon, FdiSchemaVersion::kV1_0);
    EXPECT_THAT(listing(as10), HasSubstr("cdi:4: error: FDI 1.0 schema: Element 'icon'"));
    EXPECT_THAT(validate_fdi_schema_as(icon, FdiSchemaVersion::kV1_1), IsEmpty());

    const Diagnostics unknown = validate_fdi_schema(fdi_text(fdi_function(0), 7), &choice);
    EXPECT_FALSE(choice.declared);
    EXPECT_EQ(choice.version, kNewestFdiSchema);
    EXPECT_THAT(
        listing(unknown),
        HasSubstr("cdi:2: warning: unknown schema version declared "
                  "(https://openlcb.org/schema/fdi/1/7/fdi.xsd); validated against FDI 1.1"));
}

TEST(FdiSchema, ACdiIsNoFdiAndAnFdiIsNoCdi) {
    EXPECT_THAT(listing(validate_fdi_schema("<cdi/>")),
                HasSubstr("FDI 1.1 schema: Element 'cdi': No matching global declaration"));
    EXPECT_THAT(listing(validate_schema(fdi_text(fdi_function(0)))),
                HasSubstr("CDI 1.4 schema: Element 'fdi': No matching global declaration"));
}

}  // namespace
}  // namespace olcb::cdi
