// Reading and writing a JMRI-format backup file: comments, blank lines, CRLF, BOM, bad lines.
#include "conformance/backup/backup_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "conformance/backup/backup_csv.hpp"

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

// The cause line a bad file gets, as restore prints it.
std::string cause_of(std::string_view text) {
    const BackupFile f = parse_backup_file(text);
    if (!f.unusable) return "usable";
    std::ostringstream out;
    print_unusable("F", *f.unusable, "", out);
    return out.str().substr(0, out.str().find('\n'));
}

TEST(ConfigBackupFile, AnEmptyFileOrOneWithoutKeyValueLinesIsUnusable) {
    EXPECT_EQ(cause_of(""), "lcc-conform: F is empty (0 bytes)");
    EXPECT_EQ(cause_of("# just a comment\n\n"),
              "lcc-conform: F holds no key=value line (only comments and blank lines)");
    EXPECT_EQ(cause_of("hello\nworld\n"),
              "lcc-conform: F holds no key=value line: 2 line(s) are not key=value");
    EXPECT_EQ(cause_of("key,value,type\r\n"), "lcc-conform: F holds no row after its CSV header");
    EXPECT_EQ(cause_of("A.b=1\n"), "usable");
    EXPECT_EQ(cause_of("A.b=1\n# a last comment without line end"), "usable");
}

TEST(ConfigBackupFile, ABinaryFileIsNotTextAndItsBytesAreNeverShownRaw) {
    static constexpr char kElf[] =
        "\x7F"
        "ELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0>\0=\x1B[2J\n";
    const std::string elf(kElf, sizeof kElf - 1);
    const BackupFile f = parse_backup_file(elf);
    ASSERT_TRUE(f.unusable);
    EXPECT_TRUE(f.records.empty());
    EXPECT_EQ(f.unusable->count, 17u);
    EXPECT_EQ(f.unusable->examples.size(), kMaxBackupExamples);
    EXPECT_EQ(f.unusable->examples[0], "line 1, column 1: byte 0x7F");
    std::ostringstream out;
    print_unusable("/bin/\x1Btrue", *f.unusable, "; nothing written", out);
    const std::string text = out.str();
    EXPECT_EQ(text.substr(0, text.find('\n')),
              "lcc-conform: /bin/?true is not a text file: it holds 17 control or NUL byte(s), "
              "which no backup has; nothing written");
    EXPECT_NE(text.find("\n  ... and 7 more (17 in all)\n"), std::string::npos) << text;
    for (char c : text) {
        EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20) << text;
    }
    // A CSV file with a NUL is no text either; a lone CR is a control byte.
    EXPECT_TRUE(parse_backup_file(std::string("key,value\nA,\0\n", 14)).unusable);
    EXPECT_TRUE(parse_backup_file("A.b=1\rA.c=2\n").unusable);
    EXPECT_FALSE(parse_backup_file("A.b=1\r\nA.c=\t2\r\n").unusable);
}

TEST(ConfigBackupFile, InvalidUtf8OutsideAValueIsNotTextInsideItIsTheValuesProblem) {
    BackupFile f = parse_backup_file("A.b=1\nA.\xC3x=2\n# caf\xE9\n");
    ASSERT_TRUE(f.unusable);
    EXPECT_EQ(f.unusable->cause,
              "is not UTF-8 text: 2 line(s) have bytes that are not UTF-8 outside a value");
    EXPECT_EQ(f.unusable->examples, (std::vector<std::string>{"line 2, byte 3 of the key",
                                                              "line 3, byte 6 of a comment"}));
    f = parse_backup_file("A.b=caf\xE9\n");  // Latin-1 in a value: that value is refused
    EXPECT_FALSE(f.unusable);
    ASSERT_EQ(f.records.size(), 1u);
    EXPECT_EQ(f.records[0].value, "caf\xE9");
    f = parse_backup_file("key,value,type\nA\xC3,1,int\n");
    ASSERT_TRUE(f.unusable);
    EXPECT_EQ(f.unusable->examples,
              (std::vector<std::string>{"line 2, field 1: byte 2 is not UTF-8"}));
    f = parse_backup_file("key,value,type\nA,\x1B\xC3,int\n");  // CSV values are raw
    EXPECT_FALSE(f.unusable);
}

TEST(ConfigBackupFile, AFileCutShortIsUnusable) {
    const BackupFile f = parse_backup_file("# node 05.01.01.01.22.00\nA.b=1\nA.c=655");
    ASSERT_TRUE(f.unusable);
    EXPECT_EQ(f.unusable->cause,
              "is cut short: its last line (3) has no line end, so its value may be incomplete "
              "(if the file is whole, end that line with a line end)");
    EXPECT_EQ(f.unusable->examples, std::vector<std::string>{"line 3: A.c=655"});
    EXPECT_TRUE(parse_backup_file("A.b=1\nA.c").unusable);
    const BackupFile csv = parse_backup_file("key,value\r\nA,1\r\nB,2");
    ASSERT_TRUE(csv.unusable);
    EXPECT_NE(csv.unusable->cause.find("its last row (line 3) has no line end"), std::string::npos);
    const BackupFile quote = parse_backup_file("key,value\r\nA,\"open\r\nB,2\r\n");
    ASSERT_TRUE(quote.unusable);
    EXPECT_EQ(quote.unusable->cause, "is cut short: a quoted field begun on line 2 never ends");
}

TEST(ConfigBackupFile, ReadsAtMostTheLimitOfAFileOrStream) {
    std::string error;
    EXPECT_FALSE(read_backup_text("/dev/zero", error, 1000));
    EXPECT_NE(error.find("over the backup file limit of 1000 bytes"), std::string::npos) << error;
    BackupFile f;
    EXPECT_FALSE(load_backup_file("/no/such/file", f, error));
    EXPECT_NE(error.find("cannot read /no/such/file"), std::string::npos) << error;
}

}  // namespace
}  // namespace olcb::conform
