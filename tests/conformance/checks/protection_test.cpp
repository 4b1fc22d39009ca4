#include "conformance/checks/protection.hpp"

#include <gtest/gtest.h>

namespace olcb::conform {
namespace {

TEST(SaysDoNotChange, KnowsTheUsualPhrasings) {
    for (const char* text :
         {"Do not change these settings.", "Set to 2 and do not change", "DON'T CHANGE",
          "don\xE2\x80\x99t change this", "must not be changed", "Do not modify"}) {
        EXPECT_TRUE(says_do_not_change(text)) << text;
    }
    for (const char* text :
         {"", "Change this to your liking", "Do not forget to save", "Internal data"}) {
        EXPECT_FALSE(says_do_not_change(text)) << text;
    }
}

TEST(KeyMatches, StarCrossesDotsAndQuestionMarkIsOneCharacter) {
    EXPECT_TRUE(key_matches("Internal data.*", "Internal data.Version"));
    EXPECT_TRUE(key_matches("*.Version", "seg0.Internal data.Version"));
    EXPECT_TRUE(key_matches("Port I/O.Line(?).Event On", "Port I/O.Line(3).Event On"));
    EXPECT_FALSE(key_matches("Port I/O.Line(?).Event On", "Port I/O.Line(13).Event On"));
    EXPECT_FALSE(key_matches("Internal data.*", "Settings.Trim"));
}

TEST(SelectionReason, ExcludeWinsOverOnly) {
    ProtectionRules rules;
    EXPECT_EQ(selection_reason(rules, "a.b"), "");
    rules.only = {"a.*"};
    EXPECT_EQ(selection_reason(rules, "a.b"), "");
    EXPECT_EQ(selection_reason(rules, "c.d"), "not matched by --only");
    rules.exclude = {"a.b"};
    EXPECT_EQ(selection_reason(rules, "a.b"), "--exclude 'a.b'");
}

}  // namespace
}  // namespace olcb::conform
