// NodeRegistry: nodes added, removed and rebuilt with other faults while the others run, on an
// in-process bus through a StackDriver (real time, bounded loops).
#include "simnode/node_registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/stack_driver.hpp"
#include "simnode/sim_node_test_util.hpp"
#include "support/temp_files.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;

constexpr NodeId kOther{0x05'01'01'01'22'01ull};

class NodeRegistryTest : public ::testing::Test {
protected:
    NodeRegistryTest()
        : bus_(io_),
          outside_(bus_.add_endpoint(
              [this](const CanFrame& f) { frames_.push_back(gridconnect::format(f)); })),
          driver_(io_, bus_.add_endpoint()),
          registry_(nodes_, driver_) {}

    static NodeConfig config(NodeId id) {
        NodeConfig c;
        c.node_id = id;
        c.cdi = test::default_cdi();
        return c;
    }

    bool run_until(const std::function<bool()>& done, std::chrono::milliseconds limit = 3s) {
        const auto end = std::chrono::steady_clock::now() + limit;
        while (!done() && std::chrono::steady_clock::now() < end) {
            io_.run_one_for(5ms);
            if (io_.stopped()) io_.restart();
        }
        return done();
    }

    bool initialized(NodeId id) const {
        const SimNode* node = registry_.find(id);
        return node != nullptr && node->stack().initialized();
    }

    // Frames seen outside whose text starts with prefix.
    std::size_t count(const std::string& prefix) const {
        return static_cast<std::size_t>(
            std::count_if(frames_.begin(), frames_.end(),
                          [&](const std::string& f) { return f.starts_with(prefix); }));
    }

    boost::asio::io_context io_;
    InProcessBus bus_;
    Transport& outside_;
    std::vector<std::string> frames_;
    StackDriver driver_;
    std::vector<std::unique_ptr<SimNode>> nodes_;
    NodeRegistry registry_;
};

TEST_F(NodeRegistryTest, NodesAddedBeforeAndAfterTheStartRun) {
    std::string error;
    ASSERT_TRUE(registry_.add(config(test::kNodeId), error)) << error;
    EXPECT_FALSE(registry_.started());
    registry_.start_all();
    EXPECT_TRUE(run_until([&] { return initialized(test::kNodeId); }));
    ASSERT_TRUE(registry_.add(config(kOther), error)) << error;  // starts at once
    EXPECT_TRUE(run_until([&] { return initialized(kOther); }));
    EXPECT_EQ(registry_.nodes().size(), 2u);
    EXPECT_EQ(nodes_.size(), 2u) << "the registry adds to the caller's vector";
}

// The client audit learns each added node here, before the node says anything.
TEST_F(NodeRegistryTest, TheAddedHandlerHearsOfEachAddedNodeBeforeItStarts) {
    std::vector<NodeId> heard;
    std::size_t frames_then = 0;
    registry_.set_added_handler([&](const SimNode& node) {
        heard.push_back(node.node_id());
        EXPECT_FALSE(node.stack().initialized());
        frames_then = frames_.size();
    });
    std::string error;
    registry_.start_all();
    const std::size_t frames_before = frames_.size();
    ASSERT_TRUE(registry_.add(config(test::kNodeId), error)) << error;
    EXPECT_EQ(frames_then, frames_before);
    EXPECT_EQ(registry_.add(config(test::kNodeId), error), nullptr);  // refused: not heard
    ASSERT_TRUE(run_until([&] { return initialized(test::kNodeId); }));
    EXPECT_EQ(heard, std::vector<NodeId>{test::kNodeId});
}

TEST_F(NodeRegistryTest, ARunningNodeIdOrABadCdiIsRefused) {
    std::string error;
    ASSERT_TRUE(registry_.add(config(test::kNodeId), error)) << error;
    EXPECT_EQ(registry_.add(config(test::kNodeId), error), nullptr);
    EXPECT_FALSE(error.empty());
    NodeConfig broken = config(kOther);
    broken.cdi = "<cdi><segment";
    error.clear();
    EXPECT_EQ(registry_.add(broken, error), nullptr);
    EXPECT_FALSE(error.empty());
    EXPECT_EQ(registry_.nodes().size(), 1u);
}

TEST_F(NodeRegistryTest, RemoveReleasesTheAliasWithAnAmr) {
    std::string error;
    ASSERT_TRUE(registry_.add(config(test::kNodeId), error)) << error;
    registry_.start_all();
    ASSERT_TRUE(run_until([&] { return initialized(test::kNodeId); }));
    EXPECT_TRUE(registry_.remove(test::kNodeId));
    EXPECT_TRUE(run_until([&] { return count(":X10703") > 0; })) << "AMR";
    EXPECT_EQ(registry_.find(test::kNodeId), nullptr);
    EXPECT_FALSE(registry_.remove(test::kNodeId));
}

TEST_F(NodeRegistryTest, SetFaultsRebuildsTheNodeWhichStartsAgain) {
    std::string error;
    ASSERT_TRUE(registry_.add(config(test::kNodeId), error)) << error;
    registry_.start_all();
    ASSERT_TRUE(run_until([&] { return initialized(test::kNodeId); }));
    const std::size_t starts = count(":X19100");
    SimNode* rebuilt =
        registry_.set_faults(test::kNodeId, test::faults_of({"acdi-version"}), error);
    ASSERT_NE(rebuilt, nullptr) << error;
    EXPECT_EQ(registry_.find(test::kNodeId), rebuilt);
    EXPECT_EQ(rebuilt->config().faults.value("acdi-version"), FaultValue{1});
    EXPECT_TRUE(run_until([&] { return count(":X19100") > starts; })) << "Initialization Complete";
    EXPECT_FALSE(registry_.set_faults(kOther, {}, error));
}

// A node with images holds a descriptor: add() refuses the one that would pass the limit, before
// it opens anything, and a removed node gives its descriptor back.
TEST_F(NodeRegistryTest, AddPastTheDescriptorLimitIsRefusedWithTheNumbers) {
    const test_support::TempDir images("olcb-registry");
    const auto with_images = [&](NodeId id) {
        NodeConfig c = config(id);
        c.image_dir = images.path() / id.to_string();
        return c;
    };
    registry_.set_fd_budget({100, 101});
    std::string error;
    ASSERT_TRUE(registry_.add(with_images(test::kNodeId), error)) << error;
    EXPECT_EQ(registry_.fds_needed(), 101u);
    EXPECT_EQ(registry_.add(with_images(kOther), error), nullptr);
    EXPECT_NE(error.find("needs about 102 file descriptors, the limit is 101"), std::string::npos)
        << error;
    EXPECT_FALSE(std::filesystem::exists(images.path() / kOther.to_string()));
    error.clear();
    EXPECT_TRUE(registry_.add(config(kOther), error)) << error << " (a node in RAM holds none)";
    EXPECT_TRUE(registry_.remove(kOther));
    EXPECT_TRUE(registry_.remove(test::kNodeId));
    EXPECT_EQ(registry_.fds_needed(), 100u);
    EXPECT_TRUE(registry_.add(with_images(kOther), error)) << error;
}

}  // namespace
}  // namespace olcb::simnode
