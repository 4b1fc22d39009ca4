// simnode benchmarks: memory-config read round trips over TCP loopback; download of the largest
// valid corpus CDI over TCP and over a simulated 125 kbit/s CAN bus (against the lower bound its
// frame count allows); start-up time and memory of 1,000 nodes on one segment.
#include <benchmark/benchmark.h>

#include "bench/bench_util.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/cdi_reader.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/asio.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/sim_network.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "simnode/resident_memory.hpp"
#include "simnode/sim_node.hpp"

namespace {

namespace fs = std::filesystem;
using namespace olcb;
using bench::kReadSize;
using bench::Reader;
using simnode::NodeConfig;
using simnode::SimNode;

constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
constexpr NodeId kToolId{0x02'01'0D'00'00'01ull};
// The largest corpus CDI that validates (the bigger train-node CDI does not, so no node serves
// it).
constexpr std::string_view kLargeCdi = "corpus/cdi/bowties__rrcirkits_signal_lcc_rev_c7c.xml";
constexpr std::size_t kNetworkSize = 1000;

using olcb::bench::read_text;

// scenarios/default.xml of the source tree (not from __FILE__: ccache may make it relative).
std::string default_cdi() {
    return read_text(fs::path(OLCB_SOURCE_DIR) / "scenarios/default.xml");
}

std::unique_ptr<SimNode> make_node(NodeId id, const std::string& cdi, const fs::path& dir) {
    NodeConfig c;
    c.node_id = id;
    c.cdi = cdi;
    c.image_dir = dir / id.to_string();
    fs::create_directories(c.image_dir);
    std::string error;
    auto node = SimNode::create(std::move(c), error);
    if (!node) throw std::runtime_error("SimNode::create: " + error);
    return node;
}

NodeStackConfig tool_config() {
    NodeStackConfig c;
    c.node_id = kToolId;
    c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration};
    return c;
}

// A SimNode behind a TCP hub and a tool joined over loopback, all on one io_context.
class TcpRig {
public:
    explicit TcpRig(const std::string& cdi)
        : node_(make_node(kNodeId, cdi, dir_.path())),
          hub_(io_),
          tool_(tool_config()),
          reader_(tool_, [] { return Clock::now(); }) {
        if (hub_.listen("127.0.0.1", 0)) throw std::runtime_error("cannot listen");
        node_driver_ = std::make_unique<StackDriver>(io_, hub_.add_local_endpoint());
        node_driver_->attach(node_->stack());
        node_driver_->start_all();
        client_ = std::make_unique<TcpClient>(io_, "127.0.0.1", hub_.port());
        tool_driver_ = std::make_unique<StackDriver>(io_, *client_);
        tool_driver_->attach(tool_);
        client_->set_connection_handler([this](bool up) {
            if (up) tool_driver_->start_all();
        });
        client_->start();
        if (!run([&] { return tool_.initialized() && node_->stack().initialized(); })) {
            throw std::runtime_error("TCP rig did not start");
        }
    }

    bool run(const std::function<bool()>& done) {
        const auto deadline = Clock::now() + std::chrono::seconds(20);
        while (!done() && Clock::now() < deadline) io_.run_one_for(std::chrono::milliseconds(5));
        return done();
    }
    Reader& reader() { return reader_; }
    std::uint16_t node_alias() const { return node_->stack().alias(); }

private:
    olcb::bench::TempDir dir_{"bench-simnode"};
    std::unique_ptr<SimNode> node_;
    boost::asio::io_context io_;
    TcpHubServer hub_;
    NodeStack tool_;
    Reader reader_;
    std::unique_ptr<StackDriver> node_driver_;
    std::unique_ptr<TcpClient> client_;
    std::unique_ptr<StackDriver> tool_driver_;
};

void bm_read_round_trip_tcp(benchmark::State& state) {
    TcpRig rig(default_cdi());
    for (auto _ : state) {
        rig.reader().start(rig.node_alias(), 0, false);
        if (!rig.run([&] { return rig.reader().done(); })) {
            state.SkipWithError("read timed out");
            return;
        }
        benchmark::DoNotOptimize(rig.reader().data().data());
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["round_trips_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(bm_read_round_trip_tcp)->Unit(benchmark::kMicrosecond)->UseRealTime();

void bm_cdi_download_tcp(benchmark::State& state) {
    const std::string cdi = read_text(fs::path(OLCB_SHARED_DIR) / kLargeCdi);
    TcpRig rig(cdi);
    for (auto _ : state) {
        rig.reader().start(rig.node_alias(), 0, true);
        if (!rig.run([&] { return rig.reader().done(); }) ||
            rig.reader().data().size() != cdi.size() + 1) {
            state.SkipWithError("download failed");
            return;
        }
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(cdi.size() + 1));
    state.counters["cdi_bytes"] = static_cast<double>(cdi.size() + 1);
}
BENCHMARK(bm_cdi_download_tcp)->Unit(benchmark::kMillisecond)->UseRealTime();

// Worst-case bits on the wire one whole-space download needs, by the protocol's frame count:
// per read a 1-frame request datagram (7 bytes), Datagram Received OK (3 bytes), the reply
// datagram (6 header bytes + data, 8 per frame) and its Datagram Received OK.
std::uint64_t download_lower_bound_bits(std::size_t bytes) {
    std::uint64_t bits = 0;
    for (std::size_t done = 0;;) {
        const std::size_t n = std::min<std::size_t>(kReadSize, bytes - done);
        bits += can_frame_bits(7) + can_frame_bits(3) * 2;
        std::size_t reply = 6 + n;
        while (reply > 0) {
            const std::size_t f = std::min<std::size_t>(8, reply);
            bits += can_frame_bits(static_cast<std::uint8_t>(f));
            reply -= f;
        }
        done += n;
        if (n < kReadSize) break;
    }
    return bits;
}

void bm_cdi_download_can_125k(benchmark::State& state) {
    const std::string cdi = read_text(fs::path(OLCB_SHARED_DIR) / kLargeCdi);
    constexpr std::uint32_t kBitrate = 125000;
    double simulated = 0;
    std::size_t reads = 0;
    for (auto _ : state) {
        olcb::bench::TempDir dir{"bench-simnode"};
        auto node = make_node(kNodeId, cdi, dir.path());
        SimNetwork net;
        net.enable_timing(kBitrate);
        net.set_logging(false);
        NodeStack tool(tool_config());
        Reader reader(tool, [&net] { return net.now(); });
        net.add_stack(node->stack());
        net.add_stack(tool);
        net.start_all();
        net.run_until([&] { return tool.initialized() && node->stack().initialized(); },
                      std::chrono::seconds(5));
        const auto t0 = net.now();
        reader.start(node->stack().alias(), 0, true);
        net.run_until([&] { return reader.done(); }, std::chrono::seconds(600));
        if (reader.data().size() != cdi.size() + 1) {
            state.SkipWithError("download failed");
            return;
        }
        simulated = std::chrono::duration<double>(net.now() - t0).count();
        reads = reader.reads();
        state.SetIterationTime(simulated);
    }
    const double bound = static_cast<double>(download_lower_bound_bits(cdi.size() + 1)) / kBitrate;
    state.counters["simulated_s"] = simulated;
    state.counters["lower_bound_s"] = bound;
    state.counters["ratio"] = simulated / bound;
    state.counters["reads"] = static_cast<double>(reads);
    state.counters["cdi_bytes"] = static_cast<double>(cdi.size() + 1);
}
BENCHMARK(bm_cdi_download_can_125k)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(3);

// 1,000 nodes of the default CDI, fresh images, one simulated segment (no bit timing): wall time
// to create them and to bring every one to Initialized, and the memory they take.
void bm_startup_1000(benchmark::State& state) {
    const std::string cdi = default_cdi();
    for (auto _ : state) {
        olcb::bench::TempDir dir{"bench-simnode"};
        const long rss0 = simnode::resident_kib();
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<std::unique_ptr<SimNode>> nodes;
        nodes.reserve(kNetworkSize);
        for (std::size_t i = 0; i < kNetworkSize; ++i) {
            nodes.push_back(make_node(NodeId(0x05'01'01'01'30'00ull + i), cdi, dir.path()));
        }
        const auto t1 = std::chrono::steady_clock::now();
        SimNetwork net;
        net.set_logging(false);
        for (auto& n : nodes) net.add_stack(n->stack());
        net.start_all();
        const bool all = net.run_until(
            [&] {
                return std::all_of(nodes.begin(), nodes.end(),
                                   [](auto& n) { return n->stack().initialized(); });
            },
            std::chrono::seconds(60));
        const auto t2 = std::chrono::steady_clock::now();
        if (!all) {
            state.SkipWithError("not every node initialized");
            return;
        }
        state.SetIterationTime(std::chrono::duration<double>(t2 - t0).count());
        state.counters["create_s"] = std::chrono::duration<double>(t1 - t0).count();
        state.counters["init_wall_s"] = std::chrono::duration<double>(t2 - t1).count();
        state.counters["init_sim_s"] = std::chrono::duration<double>(net.bus().now()).count();
        state.counters["rss_MiB"] = static_cast<double>(simnode::resident_kib() - rss0) / 1024.0;
    }
}
BENCHMARK(bm_startup_1000)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
