// GridConnect codec throughput: format and parse, frames per second on one core.
// Target (brief D): >= 10 M frames/s each way in a Release build.
#include <benchmark/benchmark.h>

#include <array>
#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"

namespace {

// A realistic mix: empty, node-ID, event and full datagram frames.
std::vector<olcb::CanFrame> sample_frames() {
    std::vector<olcb::CanFrame> frames;
    constexpr std::array<std::uint8_t, 8> kLengths{0, 6, 8, 8, 2, 7, 8, 3};
    for (const std::uint8_t len : kLengths) {
        olcb::CanFrame f;
        f.id = 0x19490343u + len * 0x1000u;
        f.len = len;
        for (std::uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(0x3C + i * 17);
        frames.push_back(f);
    }
    return frames;
}

void bm_format_to(benchmark::State& state) {
    const auto frames = sample_frames();
    std::string out;
    out.reserve(64);
    std::size_t i = 0;
    for (auto _ : state) {
        out.clear();
        olcb::gridconnect::format_to(frames[i++ & 7], out);
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(bm_format_to);

void bm_format_string(benchmark::State& state) {
    const auto frames = sample_frames();
    std::size_t i = 0;
    for (auto _ : state) {
        auto s = olcb::gridconnect::format(frames[i++ & 7]);
        benchmark::DoNotOptimize(s);
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(bm_format_string);

void bm_parse_frame(benchmark::State& state) {
    std::vector<std::string> texts;
    for (const auto& f : sample_frames()) texts.push_back(olcb::gridconnect::format(f));
    std::size_t i = 0;
    for (auto _ : state) {
        auto f = olcb::gridconnect::parse_frame(texts[i++ & 7]);
        benchmark::DoNotOptimize(f);
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(bm_parse_frame);

// Streaming parser over a newline-separated log, fed in 4 KiB chunks like a socket read.
void bm_parser_feed(benchmark::State& state) {
    std::string stream;
    const auto frames = sample_frames();
    constexpr int kFrames = 4096;
    for (int i = 0; i < kFrames; ++i) {
        olcb::gridconnect::format_to(frames[i & 7], stream);
        stream.push_back('\n');
    }
    std::uint64_t sum = 0;
    for (auto _ : state) {
        olcb::gridconnect::Parser parser;
        for (std::size_t pos = 0; pos < stream.size(); pos += 4096) {
            parser.feed(std::string_view(stream).substr(pos, 4096),
                        [&](const olcb::CanFrame& f) { sum += f.id; });
        }
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(state.iterations() * kFrames);
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(stream.size()));
}
BENCHMARK(bm_parser_feed);

}  // namespace

BENCHMARK_MAIN();
