// The review before a restore: two backup files compared without a CDI (an int written signed
// by one tool and unsigned by the other is the same value), and a plan printed.
#include "conformance/backup/backup_diff.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace olcb::conform {
namespace {

TEST(BackupDiff, SameValueAcrossSignedAndUnsignedForms) {
    EXPECT_TRUE(same_backup_value("65413", "-123"));                 // 2-byte
    EXPECT_TRUE(same_backup_value("-616", "18446744073709551000"));  // 8-byte
    EXPECT_TRUE(same_backup_value("255", "-1"));                     // 1-byte
    EXPECT_TRUE(same_backup_value("1.50", "1.5"));
    EXPECT_FALSE(same_backup_value("1", "2"));
    EXPECT_FALSE(same_backup_value("127", "-129"));  // 127 is no 1-byte reading of -129
    EXPECT_FALSE(same_backup_value("65413", "-65413"));
    EXPECT_FALSE(same_backup_value("abc", "abd"));
}

TEST(BackupDiff, ChangedOnlyInAAndOnlyInBInOrder) {
    const BackupFile a = parse_backup_file("X.a=1\nX.b=2\nX.r=1\nX.r=2\nX.only=5\n");
    const BackupFile b = parse_backup_file("X.a=1\nX.b=3\nX.r=1\nX.new=7\nX.r=2\nX.r=9\n");
    const std::vector<BackupDifference> d = diff_backups(a, b);
    ASSERT_EQ(d.size(), 4u);
    EXPECT_EQ(d[0].key, "X.b");
    EXPECT_EQ(d[0].a, "2");
    EXPECT_EQ(d[0].b, "3");
    EXPECT_EQ(d[1].key, "X.only");
    EXPECT_FALSE(d[1].b);
    EXPECT_EQ(d[2].key, "X.new");
    EXPECT_FALSE(d[2].a);
    EXPECT_EQ(d[3].key, "X.r");  // the third X.r
    EXPECT_EQ(d[3].b, "9");
    std::ostringstream out;
    print_differences(d, 7, out);
    EXPECT_EQ(out.str(),
              "  changed    X.b: \"2\" -> \"3\"\n"
              "  only in A  X.only = \"5\"\n"
              "  only in B  X.new = \"7\"\n"
              "  only in B  X.r = \"9\"\n"
              "diff: 4 difference(s) in 7 key(s)\n");
    EXPECT_TRUE(diff_backups(a, a).empty());
}

TEST(BackupDiff, ValuesAreShownEscaped) {
    const BackupFile a = parse_backup_file("X.s=a\\x003db\n");
    const BackupFile b = parse_backup_file("X.s=\n");
    std::ostringstream out;
    print_differences(diff_backups(a, b), 1, out);
    EXPECT_NE(out.str().find("X.s: \"a\\x003db\" -> \"\""), std::string::npos) << out.str();
}

}  // namespace
}  // namespace olcb::conform
