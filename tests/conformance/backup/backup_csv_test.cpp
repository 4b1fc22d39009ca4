// The CSV form of a backup: RFC 4180 quoting both ways, columns by header name, and a restore
// that refuses rows whose place is not the node's (a key of another CDI).
#include "conformance/backup/backup_csv.hpp"
#include "conformance/conform_test_util.hpp"

#include <gtest/gtest.h>

#include "cdi/parser.hpp"
#include "conformance/fake_memory.hpp"
#include "conformance/run/config_backup.hpp"

namespace olcb::conform {
namespace {

constexpr const char* kCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253" origin="16"><name>S</name>
<int size="2"><name>N</name><min>-5</min></int>
<string size="16"><name>Text, "quoted"</name></string>
<eventid><name>E</name></eventid>
</segment></cdi>)";

class BackupCsvTest : public ::testing::Test {
protected:
    void SetUp() override {
        load_cdi(kCdi, doc_, layout_);
        entries_ = config_entries(*layout_);
        memory_.spaces[253] = std::vector<std::uint8_t>(64, 0);
    }
    cdi::Document doc_;
    std::optional<cdi::Layout> layout_;
    std::vector<ConfigEntry> entries_;
    testing::FakeMemory memory_;
};

TEST(BackupCsv, QuotesOnlyWhatMustBeQuoted) {
    EXPECT_EQ(csv_field("plain"), "plain");
    EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
    EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
    EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
    EXPECT_EQ(csv_field(" edge"), "\" edge\"");
    EXPECT_EQ(csv_field(""), "");
}

TEST_F(BackupCsvTest, WritesKeyValueTypeSpaceAddressSize) {
    memory_.spaces[253][16] = 0xFF;  // N = -2: written as OpenLCB_Java does, unsigned
    memory_.spaces[253][17] = 0xFE;
    const std::string s = "a,\"b\"\n";
    std::copy(s.begin(), s.end(), memory_.spaces[253].begin() + 18);
    const std::string csv = backup_csv(entries_, read_config_values(entries_, memory_));
    EXPECT_EQ(csv,
              "key,value,type,space,address,size\r\n"
              "S.N,65534,int,253,16,2\r\n"
              "\"S.Text, \"\"quoted\"\"\",\"a,\"\"b\"\"\n\",string,253,18,16\r\n"
              "S.E,00.00.00.00.00.00.00.00,eventid,253,34,8\r\n");
}

TEST_F(BackupCsvTest, ReadsBackWhatItWroteAndRestoresIt) {
    const std::string s = "a\r\nb, \"x\"";
    std::copy(s.begin(), s.end(), memory_.spaces[253].begin() + 18);
    memory_.spaces[253][41] = 9;
    memory_.spaces[253][17] = 4;
    const auto before = memory_.spaces[253];
    const std::string csv = backup_csv(entries_, read_config_values(entries_, memory_));
    const BackupFile f = parse_backup_file(csv);
    EXPECT_TRUE(f.csv);
    EXPECT_TRUE(f.errors.empty()) << ::testing::PrintToString(f.errors);
    ASSERT_EQ(f.records.size(), 3u);
    EXPECT_EQ(f.records[1].value, s);
    EXPECT_EQ(f.records[2].line, 5u);  // the quoted line end counts
    ASSERT_TRUE(f.records[2].place);
    EXPECT_EQ(*f.records[2].place, (BackupPlace{"eventid", 253, 34, 8}));
    memory_.spaces[253].assign(64, 0);
    const auto out = restore_config(*layout_, memory_, csv);
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(out.written, 3u);
    EXPECT_EQ(memory_.spaces[253], before);
}

TEST_F(BackupCsvTest, ColumnsAreFoundByNameAndExtraOnesIgnored) {
    const BackupFile f = parse_backup_file("key,value\nS.N,3\n");  // hand-made, no places
    ASSERT_EQ(f.records.size(), 1u);
    EXPECT_FALSE(f.records[0].place);
    const auto out = restore_config(*layout_, memory_,
                                    "key,value,type,space,address,size,note\n"
                                    "S.N,3,int,253,16,2,mine\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.spaces[253][17], 3);
}

TEST_F(BackupCsvTest, ARowWhosePlaceDiffersIsAKeyOfAnotherCdi) {
    const auto out = restore_config(*layout_, memory_,
                                    "key,value,type,space,address,size\r\n"
                                    "S.N,3,int,253,20,2\r\nS.E,01.02.03.04.05.06.07.08,eventid,"
                                    "253,34,8\r\n");
    ASSERT_EQ(out.unknown_keys.size(), 1u);
    EXPECT_NE(out.unknown_keys[0].find("line 2: S.N (a key of another CDI: the file's variable "
                                       "is int of 2 byte(s) at space 253 address 20, the node's "
                                       "int of 2 byte(s) at space 253 address 16)"),
              std::string::npos)
        << out.unknown_keys[0];
    EXPECT_EQ(out.written, 1u);
    EXPECT_EQ(memory_.spaces[253][16 + 2 + 16], 1);
}

TEST(BackupCsv, MalformedRowsAreErrorsNotCrashes) {
    BackupFile f = parse_backup_file("key,value,type,space,address,size\n,1\nA,\"open\n");
    EXPECT_EQ(f.errors,
              (std::vector<std::string>{"line 2: no key and value", "line 3: unterminated quote"}));
    f = parse_backup_file("key,value,type,space,address,size\nA\n");
    EXPECT_EQ(f.errors.size(), 1u);
    EXPECT_TRUE(f.records.empty());
}

}  // namespace
}  // namespace olcb::conform
