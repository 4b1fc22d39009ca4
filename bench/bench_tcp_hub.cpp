// Frames per second through the GridConnect TCP hub (three loopback clients; one client to
// another) and through the in-process bus (no timing model). Against the simnode program
// (issue 15): a CDI download with --bitrate 125000 compared with the frame-time bound, two
// downloads sharing the bus, one client to another through simnode's hub, and the Verify Node
// ID round trip of a well-behaved tool while another client floods.
#include <benchmark/benchmark.h>

#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "bench/cdi_reader.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"
#ifdef SIMNODE_PATH
#include "bench/simnode_process.hpp"
#endif

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

// Runs io until done() or the limit; returns done().
bool run_io_within(boost::asio::io_context& io, std::chrono::milliseconds limit,
                   const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done() && std::chrono::steady_clock::now() < deadline) {
        if (io.stopped()) io.restart();
        io.run_one_for(std::chrono::milliseconds(1));
    }
    return done();
}

// Runs io until done(), at most 30 s; returns done().
bool run_io(boost::asio::io_context& io, const std::function<bool()>& done) {
    return run_io_within(io, std::chrono::seconds(30), done);
}

// Runs io for d.
void run_io_for(boost::asio::io_context& io, std::chrono::milliseconds d) {
    run_io_within(io, d, [] { return false; });
}

// Listens on a free loopback port; false, the benchmark skipped, when the hub cannot.
bool listen_or_skip(TcpHubServer& hub, benchmark::State& state) {
    if (!hub.listen("127.0.0.1", 0)) return true;
    state.SkipWithError("cannot listen on 127.0.0.1");
    return false;
}

// Each of three clients sends N frames per iteration; the iteration ends when every client has
// received the 2N frames of the other two. Items = frames sent (each is delivered twice).
void bm_tcp_hub_three_clients(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    boost::asio::io_context io;
    TcpHubServer hub(io);
    if (!listen_or_skip(hub, state)) return;
    std::vector<std::unique_ptr<TcpClient>> clients;
    std::vector<std::uint64_t> received(3, 0);
    for (std::size_t i = 0; i < received.size(); ++i) {
        clients.push_back(std::make_unique<TcpClient>(io, "127.0.0.1", hub.port()));
        clients.back()->set_handler([&received, i](const CanFrame&) { ++received[i]; });
        clients.back()->start();
    }
    if (!run_io(io, [&] {
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
        target += std::uint64_t{2} * n;
        if (!run_io(io, [&] {
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
BENCHMARK(bm_tcp_hub_three_clients)->Arg(1000)->UseRealTime()->Unit(benchmark::kMillisecond);

// Three ports; each sends N frames, then the bus delivers them all.
void bm_in_process_bus_three_ports(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    InProcessBus bus;
    std::uint64_t received = 0;
    std::vector<Transport*> ports;
    ports.reserve(3);
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
BENCHMARK(bm_in_process_bus_three_ports)->Arg(1000);

// A sender whose whole burst fits in its output queue (the default 256 KiB is ~9,000 frames).
TcpClientOptions big_queue() {
    TcpClientOptions o;
    o.max_queue_bytes = 16u << 20;
    return o;
}

// One client sends N frames per iteration to one other client through a hub with default
// options (no rate limit, no bitrate); items = frames delivered.
void bm_tcp_hub_one_to_another(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    boost::asio::io_context io;
    TcpHubServer hub(io);
    if (!listen_or_skip(hub, state)) return;
    TcpClient sender(io, "127.0.0.1", hub.port(), big_queue());
    TcpClient receiver(io, "127.0.0.1", hub.port());
    std::uint64_t received = 0;
    receiver.set_handler([&](const CanFrame&) { ++received; });
    sender.start();
    receiver.start();
    if (!run_io(io, [&] { return hub.client_count() == 2 && sender.connected(); })) {
        state.SkipWithError("clients did not connect");
        return;
    }
    std::uint64_t target = 0;
    for (auto _ : state) {
        for (std::uint32_t seq = 0; seq < n; ++seq) sender.send(bench_frame(0x100, seq));
        target += n;
        if (!run_io(io, [&] { return received >= target; })) {
            state.SkipWithError("frames lost");
            return;
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * n);
}
BENCHMARK(bm_tcp_hub_one_to_another)->Arg(10000)->UseRealTime()->Unit(benchmark::kMillisecond);

#ifdef SIMNODE_PATH
constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
constexpr std::uint32_t kBitrate = 125000;

NodeStackConfig tool_config(NodeId id) {
    NodeStackConfig c;
    c.node_id = id;
    c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration};
    return c;
}

// A tool node on its own TCP client to simnode's hub, its traffic tallied at kBitrate.
struct Tool {
    Tool(boost::asio::io_context& io, std::uint16_t port, NodeId id)
        : client(io, "127.0.0.1", port),
          tally(client, kBitrate),
          driver(io, tally),
          stack(tool_config(id)),
          reader(stack, [] { return Clock::now(); }) {
        driver.attach(stack);
        client.set_connection_handler([this](bool up) {
            if (up && !started) {
                started = true;
                driver.start_all();
            }
        });
        client.start();
    }
    // The default node's alias, asked with Verify Node ID (global) once the tool is up.
    std::optional<std::uint16_t> find_node(boost::asio::io_context& io) {
        if (!run_io(io, [&] { return stack.initialized(); })) return std::nullopt;
        std::optional<std::uint16_t> alias;
        stack.set_message_handler([&](const Message& m) {
            if (m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) {
                if (m.payload.size() == 6 && NodeId::from_bytes(m.payload) == kDefaultNode)
                    alias = m.source.alias;
            }
            return true;
        });
        const auto bytes = kDefaultNode.to_bytes();
        Message m;
        m.mti = Mti::kVerifyNodeIdGlobal;
        m.payload.assign(bytes.begin(), bytes.end());
        stack.send_message(m);
        run_io_within(io, std::chrono::seconds(5), [&] { return alias.has_value(); });
        stack.set_message_handler([](const Message&) { return true; });  // `alias` goes away
        return alias;
    }
    // Runs io until the tool received nothing for `quiet` (the node's start-up traffic and the
    // previous download are off the bus).
    bool wait_quiet(boost::asio::io_context& io, std::chrono::milliseconds quiet) {
        return run_io_within(io, std::chrono::seconds(10),
                             [&] { return Clock::now() - tally.last_rx() >= quiet; });
    }

    TcpClient client;
    bench::BusTally tally;
    StackDriver driver;
    NodeStack stack;
    bench::Reader reader;
    bool started = false;
};

double seconds(std::chrono::nanoseconds d) {
    return std::chrono::duration<double>(d).count();
}

// The CDI of scenarios/default.xml (2,561 bytes + NUL: 41 reads of 64 bytes) downloaded through
// `simnode --bitrate 125000`. Time = first request sent to last reply received (real time).
// bound = sum of can_frame_time() of every frame that crossed the bus meanwhile, both
// directions (as the tool saw them: its own and every frame the hub delivered to it).
void bm_simnode_cdi_download_125k(benchmark::State& state) {
    bench::SimnodeProcess sim({"--bitrate", std::to_string(kBitrate)});
    boost::asio::io_context io;
    Tool tool(io, sim.port(), NodeId(0x02'01'0D'00'00'21ull));
    const auto node = tool.find_node(io);
    if (!node) {
        state.SkipWithError("the default node did not answer");
        return;
    }
    double took = 0, bound = 0;
    std::uint64_t frames = 0, reads = 0, bytes = 0;
    for (auto _ : state) {
        tool.wait_quiet(io, std::chrono::milliseconds(100));
        tool.tally.reset();
        const auto t0 = Clock::now();
        tool.reader.start(*node, 0, true);
        if (!run_io_within(io, std::chrono::seconds(60), [&] { return tool.reader.done(); })) {
            state.SkipWithError("download timed out");
            return;
        }
        const double t = seconds(tool.reader.done_at() - t0);
        took += t;
        bound += seconds(tool.tally.committed());
        frames = tool.tally.committed_frames();
        reads = tool.reader.reads();
        bytes = tool.reader.data().size();
        state.SetIterationTime(t);
    }
    // Means over the iterations.
    const auto n = static_cast<double>(state.iterations());
    state.counters["download_s"] = took / n;
    state.counters["bound_s"] = bound / n;
    state.counters["ratio"] = took / bound;
    state.counters["frames"] = static_cast<double>(frames);
    state.counters["reads"] = static_cast<double>(reads);
    state.counters["cdi_bytes"] = static_cast<double>(bytes);
}
BENCHMARK(bm_simnode_cdi_download_125k)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// Two tools download the same CDI at once through `simnode --bitrate 125000`: each takes about
// twice as long as one alone. bound = the bus time of every frame until the later one finished.
void bm_simnode_two_cdi_downloads_125k(benchmark::State& state) {
    bench::SimnodeProcess sim({"--bitrate", std::to_string(kBitrate)});
    boost::asio::io_context io;
    Tool a(io, sim.port(), NodeId(0x02'01'0D'00'00'22ull));
    Tool b(io, sim.port(), NodeId(0x02'01'0D'00'00'23ull));
    const auto node_a = a.find_node(io), node_b = b.find_node(io);
    if (!node_a || !node_b) {
        state.SkipWithError("the default node did not answer");
        return;
    }
    double took_a = 0, took_b = 0, took_both = 0, bound = 0;
    for (auto _ : state) {
        a.wait_quiet(io, std::chrono::milliseconds(100));
        a.tally.reset();
        b.tally.reset();
        const auto t0 = Clock::now();
        a.reader.start(*node_a, 0, true);
        b.reader.start(*node_b, 0, true);
        if (!run_io_within(io, std::chrono::seconds(60),
                           [&] { return a.reader.done() && b.reader.done(); })) {
            state.SkipWithError("downloads timed out");
            return;
        }
        const double ta = seconds(a.reader.done_at() - t0);
        const double tb = seconds(b.reader.done_at() - t0);
        took_a += ta;
        took_b += tb;
        // Each tool sees every frame on the bus; the later finisher's tally covers both.
        bound += seconds(ta > tb ? a.tally.committed() : b.tally.committed());
        took_both += std::max(ta, tb);
        state.SetIterationTime(std::max(ta, tb));
    }
    // Means over the iterations.
    const auto n = static_cast<double>(state.iterations());
    state.counters["a_s"] = took_a / n;
    state.counters["b_s"] = took_b / n;
    state.counters["bound_s"] = bound / n;
    state.counters["ratio"] = took_both / bound;
}
BENCHMARK(bm_simnode_two_cdi_downloads_125k)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// One client sends N frames per iteration to another through simnode's hub (no bitrate); the
// hub's policy lets a client send 20,000 frames/s after a one-second burst (spent before the
// timed iterations).
void bm_simnode_hub_one_to_another(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    bench::SimnodeProcess sim({});
    boost::asio::io_context io;
    TcpClient sender(io, "127.0.0.1", sim.port(), big_queue());
    TcpClient receiver(io, "127.0.0.1", sim.port());
    std::uint64_t received = 0;
    receiver.set_handler([&](const CanFrame& f) { received += (f.id & 0xFFF) == 0x100 ? 1 : 0; });
    sender.start();
    receiver.start();
    if (!run_io(io, [&] { return sender.connected() && receiver.connected(); })) {
        state.SkipWithError("clients did not connect");
        return;
    }
    run_io_for(io, std::chrono::milliseconds(100));  // both joined the hub
    // Spend the one-second burst first, so the iterations measure the sustained rate.
    std::uint64_t target = 20000;
    for (std::uint32_t seq = 0; seq < target; ++seq) sender.send(bench_frame(0x100, seq));
    if (!run_io(io, [&] { return received >= target; })) {
        state.SkipWithError("frames lost");
        return;
    }
    for (auto _ : state) {
        for (std::uint32_t seq = 0; seq < n; ++seq) sender.send(bench_frame(0x100, seq));
        target += n;
        if (!run_io(io, [&] { return received >= target; })) {
            state.SkipWithError("frames lost");
            return;
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * n);
}
BENCHMARK(bm_simnode_hub_one_to_another)
    ->Arg(10000)
    ->Iterations(5)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// Sends valid frames as fast as the hub (or the kernel's socket buffers) takes them until
// stopped.
class Flooder {
public:
    explicit Flooder(std::uint16_t port) {
        thread_ = std::thread([this, port] { run(port); });
    }
    ~Flooder() {
        stop_ = true;
        thread_.join();
    }

private:
    void run(std::uint16_t port) {
        const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(port);
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
            if (fd >= 0) ::close(fd);
            return;
        }
        timeval limit{0, 200'000};  // a paused hub must not keep this thread past the run
        ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
        std::string chunk;
        for (int i = 0; i < 2000; ++i) chunk += ":X195B4123N0501010100000000;\n";
        while (!stop_) {
            const ssize_t n = ::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL);
            if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) break;
        }
        ::close(fd);
    }

    std::atomic<bool> stop_{false};
    std::thread thread_;
};

// Verify Node ID (addressed) round trips of a tool to the default node, one every 10 ms, with
// or without another client flooding the hub; args: flood (0/1), bitrate (0 = off).
// Counters: median and worst round trip of the run, and the flood frames per second the hub
// relayed to the tool meanwhile.
void bm_simnode_verify_round_trip(benchmark::State& state) {
    const bool flood = state.range(0) != 0;
    const auto bitrate = static_cast<std::uint32_t>(state.range(1));
    std::vector<std::string> extra;
    if (bitrate > 0) extra = {"--bitrate", std::to_string(bitrate)};
    bench::SimnodeProcess sim(extra);
    boost::asio::io_context io;
    Tool tool(io, sim.port(), NodeId(0x02'01'0D'00'00'24ull));
    const auto node = tool.find_node(io);
    if (!node) {
        state.SkipWithError("the default node did not answer");
        return;
    }
    bool answered = false;
    std::uint64_t flood_frames = 0;  // the flood as the hub relayed it to the tool
    tool.stack.set_message_handler([&](const Message& m) {
        if (m.mti == Mti::kVerifiedNodeId && m.source.alias == *node) answered = true;
        if (m.source.alias == 0x123) ++flood_frames;
        return true;
    });
    std::optional<Flooder> flooder;
    if (flood) flooder.emplace(sim.port());
    run_io_for(io, std::chrono::milliseconds(500));  // the flood is on
    flood_frames = 0;
    const auto start = Clock::now();
    std::vector<double> rtt;
    for (auto _ : state) {
        answered = false;
        const auto t0 = Clock::now();
        Message m;
        m.mti = Mti::kVerifyNodeIdAddressed;
        m.destination = NodeHandle{NodeId(), *node};
        tool.stack.send_message(m);
        if (!run_io_within(io, std::chrono::seconds(5), [&] { return answered; })) {
            state.SkipWithError("no answer within 5 s");
            return;
        }
        const double took = seconds(Clock::now() - t0);
        rtt.push_back(took);
        state.SetIterationTime(took);
        run_io_for(io, std::chrono::milliseconds(10));
    }
    const double span = seconds(Clock::now() - start);
    flooder.reset();
    std::sort(rtt.begin(), rtt.end());
    state.counters["median_ms"] = rtt[rtt.size() / 2] * 1e3;
    state.counters["worst_ms"] = rtt.back() * 1e3;
    state.counters["flood_frames_per_s"] = static_cast<double>(flood_frames) / span;
}
BENCHMARK(bm_simnode_verify_round_trip)
    ->ArgNames({"flood", "bitrate"})
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 125000})
    ->Args({1, 125000})
    ->Iterations(200)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
#endif

}  // namespace

BENCHMARK_MAIN();
