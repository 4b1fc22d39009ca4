// Reading and writing a JMRI-format backup file: comments, blank lines, CRLF, BOM, bad lines.
#include "conformance/backup/backup_file.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::conform {
namespace {

TEST(ConfigBackupFile, ReadsCommentsBlankLinesCrLfBomAndMalformedLines) {
    const BackupFile f = parse_backup_file(
        "\xEF\xBB\xBF# node 05.01.01.01.22.00\r\n\r\nA.b=1\r\nno equals\nC.d=\n"
        "E.x\\x003Dy=v\\x003d\n");
    EXPECT_EQ(f.node, "05.01.01.01.22.00");
    ASSERT_EQ(f.records.size(), 3u);
    EXPECT_EQ(f.records[0].key, "A.b");
    EXPECT_EQ(f.records[0].line, 3u);
    EXPECT_EQ(f.records[1].value, "");
    EXPECT_EQ(f.records[2].key, "E.x\\x003dy");  // upper-case escapes read as OpenLCB_Java's
    EXPECT_EQ(f.records[2].value, "v=");
    EXPECT_EQ(f.errors, std::vector<std::string>{"line 4: not key=value"});
}

TEST(ConfigBackupFile, WritesTheNodeAndEveryReadValueEscapedAndReadsThemBack) {
    const std::vector<ConfigEntry> entries = {
        {"A.x", nullptr, 253, 0, 1}, {"A.y", nullptr, 253, 1, 1}, {"A.z", nullptr, 253, 2, 8}};
    std::vector<ConfigValue> values(3);
    values[0].text = "7";
    values[1].error = "read failed";  // unreadable: left out, never written as empty
    values[2].text = "a=b\\n";        // a backslash: escaped too
    const std::string text = backup_text(entries, values, "05.01.01.01.22.00");
    EXPECT_EQ(config_backup_node(text), "05.01.01.01.22.00");
    EXPECT_EQ(text.find("A.y"), std::string::npos) << text;
    EXPECT_NE(text.find("\nA.z=a\\x003db\\x005cn\n"), std::string::npos) << text;
    const BackupFile f = parse_backup_file(text);
    EXPECT_EQ(f.node, "05.01.01.01.22.00");
    EXPECT_TRUE(f.errors.empty()) << ::testing::PrintToString(f.errors);
    ASSERT_EQ(f.records.size(), 2u);
    EXPECT_EQ(f.records[0].key, "A.x");
    EXPECT_EQ(f.records[0].value, "7");
    EXPECT_EQ(f.records[1].value, "a=b\\n");
    EXPECT_FALSE(config_backup_node("A.x=7\n# node 05.01.01.01.22.00\n"));  // not in the head
}

}  // namespace
}  // namespace olcb::conform
