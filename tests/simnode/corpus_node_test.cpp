// Every corpus CDI that parses and lays out becomes a node whose spaces match its layout: 0xFF is
// the CDI plus one NUL, each segment space is sized to its layout's end, and it starts up.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

namespace fs = std::filesystem;

TEST(CorpusNode, EveryUsableCorpusCdiServesItsLayout) {
    const fs::path dir = fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
    if (!fs::is_directory(dir)) {
        GTEST_SKIP() << "corpus not found at " << dir << "; corpus node test skipped";
    }
    int started = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".xml") continue;
        SCOPED_TRACE(entry.path().filename().string());
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = text.str();
        std::string error;
        auto node = SimNode::create(c, error);
        if (!node) {
            EXPECT_FALSE(error.empty());  // refused with a reason, never a crash
            continue;
        }
        const CdiModel& model = node->memory().model();
        const std::string xml = c.cdi.substr(0, c.cdi.find('\0'));
        ASSERT_NE(node->memory().space(0xFF), nullptr);
        EXPECT_EQ(node->memory().space(0xFF)->size(), xml.size() + 1);
        for (const auto& ext : model.layout->extents()) {
            if (ext.space == 0xFF || ext.space == 0xFC || ext.end == 0) continue;
            const auto* s = node->memory().space(static_cast<std::uint8_t>(ext.space));
            ASSERT_NE(s, nullptr) << "space " << ext.space;
            const std::uint64_t want =
                ext.space == 0xFB ? std::max<std::uint64_t>(ext.end, 128) : ext.end;
            EXPECT_EQ(s->size(), want) << "space " << ext.space;
            EXPECT_FALSE(s->read_only());
        }
        EXPECT_EQ(node->memory().space(0xFC) != nullptr, model.document->acdi.has_value());
        EXPECT_EQ(node->served_protocols().has(Protocol::kAcdi), model.document->acdi.has_value());

        SimNetwork net;
        net.add_stack(node->stack());
        node->stack().start(net.now());
        EXPECT_TRUE(net.run_until([&] { return node->stack().initialized(); }, 1s));
        ++started;
    }
    EXPECT_GE(started, 30) << "most corpus CDIs should make a node";
    std::cout << "[          ] " << started << " corpus CDIs made a well-behaved node\n";
}

}  // namespace
}  // namespace olcb::simnode::test
