// lcc-conform's configuration backup (`lcc-conform backup`, docs/backup.md): every variable of
// the largest corpus CDIs read from a simnode and written as OpenLCB_Java's key=value text.
// Over a simulated 125 kbit/s CAN segment the figure is simulated time (what a user waits);
// in-process without bit timing it is the tool's own CPU time. The CDI download is not part of
// it (bench_simnode measures that).
#include <benchmark/benchmark.h>

#include "bench/bench_util.hpp"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/run/config_backup.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace {

namespace fs = std::filesystem;
using namespace olcb;
using namespace olcb::conform;

constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
constexpr NodeId kToolId{0x05'01'01'01'22'FFull};
// The largest corpus CDI (51.7 KB, 274 variables) and the one with the most variables (2,239).
constexpr const char* kLargest = "openlcb_java__nmranet_database_train_node.xml";
constexpr const char* kMostVariables = "bowties__rrcirkits_signal_lcc_rev_c7c.xml";

using olcb::bench::read_text;

// A simnode serving the CDI (RAM images) and a started session that has laid its CDI out.
struct Bench {
    SimNetwork net;
    std::unique_ptr<simnode::SimNode> dut;
    std::unique_ptr<Link> link;
    std::unique_ptr<Session> session;
    NodeInfo node;
    NodeConfig config;

    Bench(const char* cdi_file, bool can_timing) {
        simnode::NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = read_text(fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi" / cdi_file);
        std::string error;
        dut = simnode::SimNode::create(c, error);
        if (!dut) throw std::runtime_error("SimNode::create: " + error);
        if (can_timing) net.enable_timing(125000);
        net.set_logging(false);
        net.add_stack(dut->stack());
        dut->stack().start(net.now());
        link = make_sim_link(net, kToolId);
        session = std::make_unique<Session>(*link);
        if (!session->start()) throw std::runtime_error("no alias");
        auto found = session->find_node(kNodeId);
        if (!found) throw std::runtime_error("node not found");
        node = *found;
        if (!load_node_config(*session, node, config, error)) throw std::runtime_error(error);
    }

    std::uint64_t reads() const {
        std::uint64_t n = 0;
        for (int space = 0; space < 256; ++space) {
            n += session->reads(kNodeId, static_cast<std::uint8_t>(space));
        }
        return n;
    }

    // One backup; false when a variable could not be read.
    bool backup(std::size_t& lines) {
        SessionMemory memory(*session, node);
        std::vector<std::string> errors;
        const std::string text =
            make_config_backup(*config.layout, memory, kNodeId.to_string(), errors);
        lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
        return errors.empty();
    }
};

void bm_backup_can_125k(benchmark::State& state, const char* cdi_file) {
    Bench b(cdi_file, true);
    std::size_t lines = 0;
    std::uint64_t reads = 0;
    double simulated = 0;
    for (auto _ : state) {
        const std::uint64_t reads_before = b.reads();
        const auto t0 = b.net.now();
        if (!b.backup(lines)) {
            state.SkipWithError("a variable could not be read");
            return;
        }
        simulated = std::chrono::duration<double>(b.net.now() - t0).count();
        reads = b.reads() - reads_before;
        state.SetIterationTime(simulated);
    }
    state.counters["simulated_s"] = simulated;
    state.counters["reads"] = static_cast<double>(reads);
    state.counters["variables"] = static_cast<double>(lines - 2);
}
BENCHMARK_CAPTURE(bm_backup_can_125k, largest, kLargest)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(bm_backup_can_125k, most_variables, kMostVariables)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

void bm_backup_in_process(benchmark::State& state, const char* cdi_file) {
    Bench b(cdi_file, false);
    std::size_t lines = 0;
    for (auto _ : state) {
        if (!b.backup(lines)) {
            state.SkipWithError("a variable could not be read");
            return;
        }
    }
    state.counters["variables"] = static_cast<double>(lines - 2);
}
BENCHMARK_CAPTURE(bm_backup_in_process, largest, kLargest)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bm_backup_in_process, most_variables, kMostVariables)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
