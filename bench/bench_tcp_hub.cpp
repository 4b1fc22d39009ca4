// Frames per second through the GridConnect TCP hub (three loopback clients) and through the
// in-process bus (no timing model).
#include <benchmark/benchmark.h>

#include <chrono>
#include <memory>
#include <vector>

#include "openlcb/in_process_bus.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"

namespace {

using namespace olcb;

CanFrame bench_frame(std::uint16_t alias, std::uint32_t seq) {
    CanFrame f;
    f.id = 0x195B4000u | alias;
    f.len = 8;
    f.data = {5,
              1,
              1,
              1,
              static_cast<std::uint8_t>(seq >> 24),
              static_cast<std::uint8_t>(seq >> 16),
              static_cast<std::uint8_t>(seq >> 8),
              static_cast<std::uint8_t>(seq)};
    return f;
}

// Each of three clients sends N frames per iteration; the iteration ends when every client has
// received the 2N frames of the other two. Items = frames sent (each is delivered twice).
void BM_TcpHubThreeClients(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    boost::asio::io_context io;
    TcpHubServer hub(io);
    if (hub.listen("127.0.0.1", 0)) {
        state.SkipWithError("cannot listen on 127.0.0.1");
        return;
    }
    std::vector<std::unique_ptr<TcpClient>> clients;
    std::vector<std::uint64_t> received(3, 0);
    for (int i = 0; i < 3; ++i) {
        clients.push_back(std::make_unique<TcpClient>(io, "127.0.0.1", hub.port()));
        clients.back()->set_handler([&received, i](const CanFrame&) { ++received[i]; });
        clients.back()->start();
    }
    auto wait = [&](auto done) {
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
        while (!done() && std::chrono::steady_clock::now() < deadline) {
            if (io.stopped()) io.restart();
            io.run_one_for(std::chrono::milliseconds(10));
        }
        return done();
    };
    if (!wait([&] {
            return hub.client_count() == 3 && clients[0]->connected() && clients[1]->connected() &&
                   clients[2]->connected();
        })) {
        state.SkipWithError("clients did not connect");
        return;
    }
    std::uint64_t target = 0;
    for (auto _ : state) {
        for (std::uint32_t seq = 0; seq < n; ++seq) {
            for (std::uint16_t c = 0; c < 3; ++c) clients[c]->send(bench_frame(0x100 + c, seq));
        }
        target += 2 * n;
        if (!wait([&] {
                return received[0] >= target && received[1] >= target && received[2] >= target;
            })) {
            state.SkipWithError("frames lost");
            return;
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 3 * n);
    state.counters["deliveries_per_s"] = benchmark::Counter(
        static_cast<double>(state.iterations()) * 6 * n, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_TcpHubThreeClients)->Arg(1000)->UseRealTime()->Unit(benchmark::kMillisecond);

// Three ports; each sends N frames, then the bus delivers them all.
void BM_InProcessBusThreePorts(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    InProcessBus bus;
    std::uint64_t received = 0;
    std::vector<Transport*> ports;
    for (int i = 0; i < 3; ++i) {
        ports.push_back(&bus.add_endpoint([&received](const CanFrame&) { ++received; }));
    }
    for (auto _ : state) {
        for (std::uint32_t seq = 0; seq < n; ++seq) {
            for (std::uint16_t c = 0; c < 3; ++c) ports[c]->send(bench_frame(0x100 + c, seq));
        }
        bus.deliver();
    }
    benchmark::DoNotOptimize(received);
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 3 * n);
}
BENCHMARK(BM_InProcessBusThreePorts)->Arg(1000);

}  // namespace

BENCHMARK_MAIN();
