#include "base/file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace olcb::base {
namespace {

namespace fs = std::filesystem;

class FileTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ =
            fs::temp_directory_path() /
            ("olcb_base_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
             "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& bytes) {
        fs::path p = dir_ / name;
        std::ofstream(p, std::ios::binary) << bytes;
        return p;
    }

    fs::path dir_;
};

TEST_F(FileTest, ReadsEveryByteAsItIs) {
    std::string bytes("a\0b\r\n\xFF", 6);
    bytes += std::string(200000, 'x');  // several read() calls
    std::string error;
    const auto got = read_file(write("bin", bytes), error);
    ASSERT_TRUE(got.has_value()) << error;
    EXPECT_EQ(*got, bytes);
    EXPECT_TRUE(error.empty());
}

TEST_F(FileTest, ReadsAnEmptyFile) {
    std::string error;
    const auto got = read_file(write("empty", ""), error);
    ASSERT_TRUE(got.has_value()) << error;
    EXPECT_TRUE(got->empty());
}

TEST_F(FileTest, AMissingFileSaysPathAndReason) {
    const fs::path missing = dir_ / "missing.xml";
    std::string error;
    EXPECT_FALSE(read_file(missing, error).has_value());
    EXPECT_EQ(error, "cannot read " + missing.string() + ": No such file or directory");
}

TEST_F(FileTest, ADirectoryIsRefusedNotReadAsEmpty) {
    std::string error;
    EXPECT_FALSE(read_file(dir_, error).has_value());
    EXPECT_EQ(error, "cannot read " + dir_.string() + ": Is a directory");
}

}  // namespace
}  // namespace olcb::base
