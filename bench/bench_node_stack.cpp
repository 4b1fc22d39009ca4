// NodeStack throughput: datagram round trips between two stacks over the in-process bus, the
// cost of a frame that is not for us, and the start-up of 1,000 stacks on one simulated bus.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <chrono>
#include <deque>
#include <vector>

#include "openlcb/can_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/sim_network.hpp"
#include "openlcb/stack_driver.hpp"

namespace {

using namespace olcb;
using namespace std::chrono_literals;

NodeStackConfig config(std::uint64_t id) {
    NodeStackConfig c;
    c.node_id = NodeId(id);
    c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration};
    return c;
}

// Two stacks, each on its own port of a manually driven InProcessBus; replies are pumped onto
// the bus from inside the delivery handler, as a driver would.
struct BusPair {
    InProcessBus bus;
    NodeStack a{config(0x050101012200)};
    NodeStack b{config(0x02010D000001)};
    Transport* port_a = nullptr;
    Transport* port_b = nullptr;
    TimePoint now = TimePoint{} + 1h;

    BusPair() {
        port_a = &bus.add_endpoint([this](const CanFrame& f) {
            a.on_frame(f, now);
            pump(a, *port_a);
        });
        port_b = &bus.add_endpoint([this](const CanFrame& f) {
            b.on_frame(f, now);
            pump(b, *port_b);
        });
        a.start(now);
        b.start(now);
        pump(a, *port_a);
        pump(b, *port_b);
        bus.deliver();
        now += 200ms;
        a.poll(now);
        b.poll(now);
        pump(a, *port_a);
        pump(b, *port_b);
        bus.deliver();
    }
    static void pump(NodeStack& s, Transport& port) {
        while (auto f = s.pop_frame()) port.send(*f);
    }
};

void bm_datagram_round_trip_64(benchmark::State& state) {
    BusPair p;
    if (!p.a.initialized() || !p.b.initialized()) {
        state.SkipWithError("stacks did not initialize");
        return;
    }
    p.b.set_datagram_handler(
        [&](const ReceivedDatagram& d) { p.b.accept_datagram(d.source_alias); });
    std::uint64_t outcomes = 0;
    p.a.set_outcome_handler([&](const DatagramOutcome& o) {
        if (o.status == DatagramOutcome::Status::kAccepted) ++outcomes;
    });
    std::vector<std::uint8_t> payload(64);
    for (std::size_t i = 0; i < payload.size(); ++i) payload[i] = static_cast<std::uint8_t>(i);
    payload[0] = 0x20;
    const std::uint16_t dest = p.b.alias();
    for (auto _ : state) {
        p.a.send_datagram(dest, payload, p.now);
        BusPair::pump(p.a, *p.port_a);
        p.bus.deliver();
    }
    if (outcomes != static_cast<std::uint64_t>(state.iterations())) {
        state.SkipWithError("a datagram was not accepted");
    }
    state.SetItemsProcessed(state.iterations());
    state.counters["round_trips_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(bm_datagram_round_trip_64);

// The same round trip through SimNetwork (what tests and lcc-conform's in-process mode use).
void bm_datagram_round_trip_64_sim_network(benchmark::State& state) {
    SimNetwork net;
    net.set_logging(false);
    NodeStack a(config(0x050101012200));
    NodeStack b(config(0x02010D000001));
    net.add_stack(a);
    net.add_stack(b);
    net.start_all();
    net.run_for(300ms);
    b.set_datagram_handler([&](const ReceivedDatagram& d) { b.accept_datagram(d.source_alias); });
    std::uint64_t outcomes = 0;
    a.set_outcome_handler([&](const DatagramOutcome&) { ++outcomes; });
    std::vector<std::uint8_t> payload(64, 0x20);
    for (auto _ : state) {
        const std::uint64_t before = outcomes;
        a.send_datagram(b.alias(), payload, net.now());
        net.run_until([&] { return outcomes != before; }, 10s);
    }
    state.counters["round_trips_per_s"] =
        benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(bm_datagram_round_trip_64_sim_network);

// What each of 1,000 stacks pays for traffic between two other nodes.
void bm_on_frame_not_for_us(benchmark::State& state) {
    BusPair p;
    const CanFrame frames[] = {
        *gridconnect::parse_frame(":X1A99912CN2043000000004041;"),  // datagram for another alias
        *gridconnect::parse_frame(":X19A2812CN099900;"),            // addressed, another alias
        *gridconnect::parse_frame(":X195B4123N0102030405060708;"),  // global PCER, no handler
    };
    std::size_t i = 0;
    for (auto _ : state) {
        p.a.on_frame(frames[i], p.now);
        i = i == 2 ? 0 : i + 1;
    }
    benchmark::DoNotOptimize(p.a.has_output());
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(bm_on_frame_not_for_us);

// StackDriver re-arms its timer with the minimum over all stacks once per burst: 1,000 times this.
void bm_next_deadline_idle(benchmark::State& state) {
    BusPair p;
    for (auto _ : state) benchmark::DoNotOptimize(p.a.next_deadline());
}
BENCHMARK(bm_next_deadline_idle);

// 1,000 stacks with distinct first aliases (or all colliding on one) started together on a
// simulated bus until every one is Initialized and the bus is quiet; wall time per start-up,
// heap per stack (each stack's alias cache learns all 999 others).
void bm_thousand_stack_startup(benchmark::State& state) {
    const bool colliding = state.range(0) != 0;
    constexpr int kCount = 1000;
    double sim_ms = 0;
    double heap_per_stack = 0;
    std::uint64_t frames = 0;
    for (auto _ : state) {
        const auto heap_before = mallinfo2().uordblks;
        SimNetwork net;
        net.set_logging(false);
        std::deque<NodeStack> stacks;
        for (std::uint64_t i = 1; i <= kCount; ++i) {
            const std::uint64_t id =
                colliding ? (0x050101000000ull | i << 12 | i) : 0x050101010000ull + i;
            stacks.emplace_back(config(id));
            net.add_stack(stacks.back());
        }
        const TimePoint t0 = net.now();
        net.start_all();
        std::size_t done = 0;
        for (auto& s : stacks) s.set_initialized_handler([&done] { ++done; });
        const bool ok = net.run_until([&] { return done == kCount; }, 60s);
        if (!ok) state.SkipWithError("not all stacks initialized");
        net.run_for(0ms);  // deliver the last AMDs and Initialization Completes to everyone
        sim_ms = std::chrono::duration<double, std::milli>(net.now() - t0).count();
        heap_per_stack =
            static_cast<double>(mallinfo2().uordblks - heap_before) / static_cast<double>(kCount);
        frames = net.bus().frames_delivered();
    }
    state.counters["sim_ms"] = sim_ms;
    state.counters["heap_bytes_per_stack"] = heap_per_stack;
    state.counters["frames"] = static_cast<double>(frames);
}
BENCHMARK(bm_thousand_stack_startup)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// 1,000 stacks on one StackDriver (real io_context, InProcessBus): one global Verify Node ID
// from outside, answered by all 1,000 (each answer also reaches the 999 other stacks).
void bm_driver_thousand_stacks_verify_global(benchmark::State& state) {
    constexpr std::size_t kCount = 1000;
    boost::asio::io_context io;
    InProcessBus bus(io);
    std::size_t verified = 0;
    Transport& outside = bus.add_endpoint([&](const CanFrame& f) {
        if (can::is_message(f.id) && can::can_mti(f.id) == 0x170) ++verified;
    });
    std::deque<NodeStack> stacks;
    StackDriver driver(io, bus.add_endpoint());
    for (std::uint64_t i = 1; i <= kCount; ++i) {
        stacks.emplace_back(config(0x050101010000ull + i));
        driver.attach(stacks.back());
    }
    const auto start = std::chrono::steady_clock::now();
    driver.start_all();
    auto all_initialized = [&] {
        for (const auto& s : stacks) {
            if (!s.initialized()) return false;
        }
        return true;
    };
    while (!all_initialized() && std::chrono::steady_clock::now() - start < 10s) {
        if (io.stopped()) io.restart();
        io.run_one_for(10ms);
    }
    const double startup_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (!all_initialized()) {
        state.SkipWithError("stacks did not initialize");
        return;
    }
    const CanFrame verify = *gridconnect::parse_frame(":X19490999N;");
    for (auto _ : state) {
        verified = 0;
        outside.send(verify);
        const auto t0 = std::chrono::steady_clock::now();
        while (verified < kCount && std::chrono::steady_clock::now() - t0 < 10s) {
            if (io.stopped()) io.restart();  // the io_context stops whenever it runs out of work
            io.run_one_for(10ms);
        }
        if (verified < kCount) state.SkipWithError("not every stack answered");
    }
    state.counters["startup_wall_ms"] = startup_ms;
    state.counters["timer_arms"] = static_cast<double>(driver.stats().timer_arms);
    // Per round: the one Verify Node ID Global and its kCount answers.
    const auto frames = state.iterations() * static_cast<benchmark::IterationCount>(kCount + 1);
    state.counters["frames_per_s"] =
        benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}
BENCHMARK(bm_driver_thousand_stacks_verify_global)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
