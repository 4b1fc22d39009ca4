// Images in image_dir: one file per writable space, created with the defaults, written before the
// acknowledgement, found again by a node re-created on the same directory.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "memory/snip.hpp"
#include "sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

class PersistenceTest : public SimNodeTest {
protected:
    // Starts the default node on images in dir; the lines it logs are kept in the result.
    std::shared_ptr<std::vector<std::string>> start_logging(const TempDir& dir) {
        NodeConfig c = default_config();
        c.image_dir = dir.path();
        start(c);
        auto logged = std::make_shared<std::vector<std::string>>();
        node_->set_log_handler([logged](const std::string& line) { logged->push_back(line); });
        return logged;
    }
};

TEST_F(PersistenceTest, ImagesSurviveRecreation) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    start(c);
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "space-253.img"));
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "space-251.img"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "space-255.img"));
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "space-252.img"));
    EXPECT_EQ(std::filesystem::file_size(dir.path() / "space-253.img"), 179u);
    EXPECT_EQ(std::filesystem::file_size(dir.path() / "space-251.img"), 128u);
    write_ok(0xFD, 15, {3});
    write_ok(0xFB, 1, {'K', 'e', 'p', 't', 0});
    const auto ids = exchange({0x20, 0x8C, 1}).reply;
    node_.reset();  // closes the images (releases their locks)

    // Same directory, different initial strings: the image wins over the config.
    SimNetwork net2;
    c.user_name = "Ignored";
    std::string error;
    auto again = SimNode::create(c, error);
    ASSERT_TRUE(again) << error;
    EXPECT_EQ(again->memory().read(0xFD, 15, 1), (std::vector<std::uint8_t>{3}));
    EXPECT_EQ(again->snip().user_name, "Kept");
    // The Get Unique ID counter is persisted too: no ID is handed out twice.
    EXPECT_EQ(again->memory().unique_id_counter(), 9u);
    ASSERT_TRUE(ids);
    EXPECT_EQ(ids->back(), 8);
}

TEST_F(PersistenceTest, SecondNodeOnTheSameImagesIsRefused) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    std::string error;
    auto first = SimNode::create(c, error);
    ASSERT_TRUE(first) << error;
    auto second = SimNode::create(c, error);
    EXPECT_EQ(second, nullptr);
    EXPECT_FALSE(error.empty());
}

TEST_F(PersistenceTest, ImageOfAnotherSizeIsRefused) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    std::string error;
    ASSERT_TRUE(SimNode::create(c, error)) << error;
    std::filesystem::resize_file(dir.path() / "space-253.img", 10);
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_NE(error.find("253"), std::string::npos) << error;
}

TEST_F(PersistenceTest, FactoryResetRewritesTheImage) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    start(c);
    write_ok(0xFD, 15, {3});
    EXPECT_TRUE(exchange({0x20, 0xAA, 5, 1, 1, 1, 0x22, 0x00}).ok);
    net_.run_for(1s);
    node_.reset();
    std::string error;
    auto again = SimNode::create(c, error);
    ASSERT_TRUE(again) << error;
    EXPECT_EQ(again->memory().read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
}

// Files may not grow past `bytes` while it lives: a write that needs more fails as on a full disk.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &saved_);
        old_handler_ = std::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead
        rlimit tight = saved_;
        tight.rlim_cur = bytes;
        setrlimit(RLIMIT_FSIZE, &tight);
    }
    ~FileSizeLimit() {
        setrlimit(RLIMIT_FSIZE, &saved_);
        std::signal(SIGXFSZ, old_handler_);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit saved_{};
    void (*old_handler_)(int) = nullptr;
};

// Factory Reset rewrites whole spaces through the journal (a 203-byte record for space 253); a
// disk that cannot take it must not see the command acknowledged (issue 31).
TEST_F(PersistenceTest, FactoryResetThatCannotBeStoredIsRefusedAndLogged) {
    TempDir dir;
    const auto logged = start_logging(dir);
    write_ok(0xFD, 15, {3});
    Answer a;
    {
        const FileSizeLimit full(100);  // room for a small write's record, not a whole space's
        a = exchange({0x20, 0xAA, 5, 1, 1, 1, 0x22, 0x00});
    }
    EXPECT_FALSE(a.ok) << "acknowledged a reset the disk did not take";
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1000);
    EXPECT_EQ(node_->counters().factory_resets, 0u);
    EXPECT_EQ(node_->counters().storage_errors, 1u);
    ASSERT_EQ(logged->size(), 1u);
    EXPECT_NE(logged->at(0).find("factory reset not stored"), std::string::npos) << logged->at(0);
    net_.run_for(1s);
    EXPECT_EQ(node_->memory().read(0xFD, 15, 1), (std::vector<std::uint8_t>{3}))
        << "the settings stay as they were";
}

TEST_F(PersistenceTest, AWriteThatCannotBeStoredFails1000AndIsLogged) {
    TempDir dir;
    const auto logged = start_logging(dir);
    Answer a;
    {
        const FileSizeLimit full(30);  // the journal record of 15 bytes needs 39
        a = exchange(write_cmd(0xFD, 0, std::vector<std::uint8_t>(15, 7)));
    }
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(a.reply->at(1), 0x19) << "Write Reply Fail for space 253";
    EXPECT_EQ(node_->counters().storage_errors, 1u);
    ASSERT_EQ(logged->size(), 1u);
    EXPECT_NE(logged->at(0).find("write of 15 bytes to space 253 at 0 not stored"),
              std::string::npos)
        << logged->at(0);
}

TEST_F(PersistenceTest, MissingImageDirectoryIsAnError) {
    NodeConfig c = default_config();
    c.image_dir = "/nonexistent/simnode/images";
    std::string error;
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace olcb::simnode::test
