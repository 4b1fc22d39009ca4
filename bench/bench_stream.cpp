// CDI download by memory-config stream vs by datagrams, on one simulated 125 kbit/s CAN bus
// (SimNetwork::enable_timing, the frame-time model of openlcb/can_timing.hpp), from a SimNode
// serving the largest corpus CDI. The stream time is compared with the sum of the frame times of
// every frame the stream read put on the bus (the bound when the bus is never idle).
#include <benchmark/benchmark.h>

#include "bench/bench_util.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/cdi_reader.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/can_timing.hpp"
#include "openlcb/sim_network.hpp"
#include "openlcb/stream_defs.hpp"
#include "simnode/sim_node.hpp"

namespace {

namespace fs = std::filesystem;
using namespace olcb;

constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
constexpr NodeId kToolId{0x02'01'0D'00'00'01ull};
constexpr std::uint32_t kBitrate = 125000;
// The largest file of the corpus (a train node's CDI, 51,662 bytes).
constexpr std::string_view kLargestCdi = "corpus/cdi/openlcb_java__nmranet_database_train_node.xml";
// What lcc-conform grants (conform::kToolStreamBuffer): the largest buffer.
constexpr std::uint16_t kToolBuffer = 0xFFFF;
constexpr std::uint8_t kDid = 0x40;

using olcb::bench::read_text;

NodeStackConfig tool_config() {
    NodeStackConfig c;
    c.node_id = kToolId;
    c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration, Protocol::kStream};
    c.streams = true;
    return c;
}

// A SimNode with the largest CDI and the tool on one paced bus; every frame is tallied.
struct Rig {
    olcb::bench::TempDir dir{"bench-stream"};
    std::string cdi = read_text(fs::path(OLCB_SHARED_DIR) / kLargestCdi);
    std::unique_ptr<simnode::SimNode> node;
    SimNetwork net;
    NodeStack tool{tool_config()};
    std::uint64_t frames = 0;
    std::chrono::nanoseconds busy{0};

    Rig() {
        simnode::NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = cdi;
        std::string error;
        node = simnode::SimNode::create(std::move(c), error);
        if (!node) throw std::runtime_error("SimNode::create: " + error);
        net.enable_timing(kBitrate);
        net.set_logging(false);
        net.add_stack(node->stack());
        net.add_stack(tool);
        net.add_endpoint([this](const CanFrame& f, TimePoint) {
            ++frames;
            busy += can_frame_time(f.len, kBitrate);
        });
        net.start_all();
        net.run_until([&] { return tool.initialized() && node->stack().initialized(); },
                      std::chrono::seconds(5));
    }
    void reset_tally() {
        frames = 0;
        busy = {};
    }
    std::size_t space_size() { return node->memory().space(0xFF)->size(); }
};

void cdi_by_stream_125k(benchmark::State& state) {
    double simulated = 0;
    double bound = 0;
    std::uint64_t frames = 0;
    std::size_t bytes = 0;
    for (auto _ : state) {
        Rig rig;
        std::vector<std::uint8_t> data;
        bool complete = false;
        TimePoint done_at{};
        std::chrono::nanoseconds busy_at_done{0};
        std::uint64_t frames_at_done = 0;
        rig.tool.set_datagram_handler(
            [&](const ReceivedDatagram& d) { rig.tool.accept_datagram(d.source_alias); });
        rig.tool.set_stream_handler([&](const StreamEvent& e) {
            if (e.kind == StreamEvent::Kind::kData)
                data.insert(data.end(), e.data.begin(), e.data.end());
            if (e.kind == StreamEvent::Kind::kCompleted) {
                complete = true;
                done_at = rig.net.now();
                busy_at_done = rig.busy;
                frames_at_done = rig.frames;
            }
        });
        rig.net.run_for(std::chrono::milliseconds(100));
        rig.reset_tally();
        const auto t0 = rig.net.now();
        const std::uint16_t node = rig.node->stack().alias();
        rig.tool.expect_stream(node, kDid, kToolBuffer);
        const auto cmd =
            memory::encode(memory::ReadStream{memory::Space::kCdi, 0, 0xFF, kDid, 0xFFFF'FFFF, {}});
        rig.tool.send_datagram(node, cmd, t0);
        rig.net.run_until([&] { return complete; }, std::chrono::seconds(600));
        if (!complete || data.size() != rig.space_size()) {
            state.SkipWithError("stream download failed");
            return;
        }
        simulated = std::chrono::duration<double>(done_at - t0).count();
        bound = std::chrono::duration<double>(busy_at_done).count();
        frames = frames_at_done;
        bytes = data.size();
        state.SetIterationTime(simulated);
    }
    state.counters["simulated_s"] = simulated;
    state.counters["frame_time_bound_s"] = bound;
    state.counters["ratio"] = simulated / bound;
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["data_frames_min"] =
        static_cast<double>(stream::data_frames(bytes, kToolBuffer));
    state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(cdi_by_stream_125k)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

void cdi_by_datagram_125k(benchmark::State& state) {
    double simulated = 0;
    std::uint64_t frames = 0;
    std::size_t bytes = 0;
    for (auto _ : state) {
        Rig rig;
        bench::Reader reader(rig.tool, [&rig] { return rig.net.now(); });
        rig.net.run_for(std::chrono::milliseconds(100));
        rig.reset_tally();
        const auto t0 = rig.net.now();
        reader.start(rig.node->stack().alias(), 0, true);
        rig.net.run_until([&] { return reader.done(); }, std::chrono::seconds(600));
        if (reader.data().size() != rig.cdi.size() + 1) {
            state.SkipWithError("datagram download failed");
            return;
        }
        simulated = std::chrono::duration<double>(rig.net.now() - t0).count();
        frames = rig.frames;
        bytes = reader.data().size();
        state.SetIterationTime(simulated);
    }
    state.counters["simulated_s"] = simulated;
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["bytes"] = static_cast<double>(bytes);
}
BENCHMARK(cdi_by_datagram_125k)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
