// CDI parse + layout throughput, enumeration speed and memory of huge replication.
// Targets: >= 100 MB/s parse+layout, >= 20 M variables/s enumeration, < 10 MB peak for the
// 10^6-replication document.
#include <benchmark/benchmark.h>

#include <malloc.h>
#include "bench/bench_util.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <string>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "cdi/validator.hpp"

namespace {

// Counting global allocator, switched on only around the measured parse+layout so the other
// benchmarks pay nothing; the benchmarks run on one thread.
bool g_counting = false;
std::int64_t g_live = 0;
std::int64_t g_peak = 0;

void* counted_alloc(std::size_t size) {
    void* p = std::malloc(size == 0 ? 1 : size);
    if (p == nullptr) throw std::bad_alloc();
    if (g_counting) {
        g_live += static_cast<std::int64_t>(malloc_usable_size(p));
        g_peak = std::max(g_peak, g_live);
    }
    return p;
}

void counted_free(void* p) {
    if (p != nullptr && g_counting) g_live -= static_cast<std::int64_t>(malloc_usable_size(p));
    std::free(p);
}

}  // namespace

void* operator new(std::size_t size) {
    return counted_alloc(size);
}
void* operator new[](std::size_t size) {
    return counted_alloc(size);
}
void operator delete(void* p) noexcept {
    counted_free(p);
}
void operator delete[](void* p) noexcept {
    counted_free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    counted_free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    counted_free(p);
}

namespace {

using namespace olcb::cdi;
namespace fs = std::filesystem;

using olcb::bench::read_text;

std::string largest_corpus_file() {
    const fs::path dir = fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
    if (!fs::is_directory(dir)) return {};
    fs::path best;
    std::uintmax_t best_size = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.file_size() > best_size) {
            best_size = entry.file_size();
            best = entry.path();
        }
    }
    return read_text(best);
}

// A realistic ~1 MB CDI without replication (every element written out), so the parser does
// all the work: I/O-board style groups with names, descriptions, maps and defaults.
std::string generated_cdi(std::size_t target_bytes) {
    std::string out = R"(<?xml version="1.0" encoding="utf-8"?>
<cdi xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="https://openlcb.org/schema/cdi/1/4/cdi.xsd">
<identification><manufacturer>Bench Works</manufacturer><model>Big IO</model><hardwareVersion>1.0</hardwareVersion><softwareVersion>2.3.4</softwareVersion></identification>
<acdi/>
<segment space="251" origin="1"><name>User Info</name><string size="63"><name>User Name</name></string><string size="64"><name>User Description</name></string></segment>
<segment space="253" origin="128"><name>Settings</name>
)";
    for (int line = 0; out.size() < target_bytes; ++line) {
        const std::string n = std::to_string(line + 1);
        out += "<group offset=\"2\"><name>Line ";
        out += n;
        out += "</name><description>Input/output line ";
        out += n;
        out +=
            " of the board; configure its function and the events it produces.</description>\n"
            "  <string size=\"32\"><name>Description</name><description>User name of this "
            "line</description></string>\n"
            "  <int size=\"1\"><name>Function</name><default>0</default><map>"
            "<relation><property>0</property><value>Disabled</value></relation>"
            "<relation><property>1</property><value>Input</value></relation>"
            "<relation><property>2</property><value>Output</value></relation></map></int>\n"
            "  <int size=\"2\"><name>Debounce</name><min>1</min><max>1000</max>"
            "<default>20</default><hints><slider tickSpacing=\"100\" showValue=\"yes\"/>"
            "</hints></int>\n"
            "  <eventid><name>Event On</name><description>Sent or consumed when the line "
            "goes active.</description></eventid>\n"
            "  <eventid><name>Event Off</name></eventid>\n"
            "</group>\n";
    }
    out += "</segment>\n</cdi>\n";
    return out;
}

const char* const kMillion = R"(<?xml version="1.0"?>
<cdi><identification><manufacturer>M</manufacturer><model>Huge</model></identification><acdi/>
<segment space="253" origin="128"><name>Ports</name>
<group replication="1000000"><name>Port</name><repname>Port</repname>
<int size="1"><name>Mode</name><map><relation><property>0</property><value>Off</value></relation></map></int>
<eventid><name>On</name></eventid><eventid><name>Off</name></eventid>
</group></segment></cdi>)";

void parse_and_layout(benchmark::State& state, const std::string& text) {
    std::size_t variables = 0;
    for (auto _ : state) {
        ParseResult parsed = parse(text);
        if (!parsed.document) {
            state.SkipWithError("parse failed");
            return;
        }
        LayoutResult laid = build_layout(*parsed.document);
        if (!laid.layout) {
            state.SkipWithError("layout failed");
            return;
        }
        variables = laid.layout->variable_count();
        benchmark::DoNotOptimize(variables);
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
    state.counters["bytes"] = static_cast<double>(text.size());
    state.counters["variables"] = static_cast<double>(variables);
}

void BM_ParseLayoutLargestCorpusFile(benchmark::State& state) {
    static const std::string text = largest_corpus_file();
    if (text.empty()) {
        state.SkipWithError("corpus not found");
        return;
    }
    parse_and_layout(state, text);
}
BENCHMARK(BM_ParseLayoutLargestCorpusFile);

// What every program runs on a CDI: schema validation, the model, the semantic rules, the
// layout.
void BM_ValidateLargestCorpusFile(benchmark::State& state) {
    static const std::string text = largest_corpus_file();
    if (text.empty()) {
        state.SkipWithError("corpus not found");
        return;
    }
    for (auto _ : state) {
        ValidationReport report = validate(text);
        if (!report.parsed) {
            state.SkipWithError("validate produced no model");
            return;
        }
        benchmark::DoNotOptimize(report.diagnostics.data());
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(text.size()));
    state.counters["bytes"] = static_cast<double>(text.size());
}
BENCHMARK(BM_ValidateLargestCorpusFile)->Unit(benchmark::kMicrosecond);

void BM_ParseLayoutGenerated1MB(benchmark::State& state) {
    static const std::string text = generated_cdi(1 << 20);
    parse_and_layout(state, text);
}
BENCHMARK(BM_ParseLayoutGenerated1MB)->Unit(benchmark::kMillisecond);

void BM_ParseLayoutMillionReplicas(benchmark::State& state) {
    const std::string text = kMillion;
    std::int64_t peak = 0;
    for (auto _ : state) {
        g_live = 0;
        g_peak = 0;
        g_counting = true;
        {
            ParseResult parsed = parse(text);
            LayoutResult laid = build_layout(*parsed.document);
            benchmark::DoNotOptimize(laid.layout->variable_count());
        }
        g_counting = false;
        peak = std::max(peak, g_peak);
    }
    state.counters["peak_heap_bytes"] = static_cast<double>(peak);
    state.counters["variables"] = 3e6;
}
BENCHMARK(BM_ParseLayoutMillionReplicas)->Unit(benchmark::kMicrosecond);

void BM_EnumerateMillionReplicas(benchmark::State& state) {
    static ParseResult parsed = parse(kMillion);
    static LayoutResult laid = build_layout(*parsed.document);
    const Layout& layout = *laid.layout;
    std::uint64_t visited = 0;
    for (auto _ : state) {
        std::uint64_t sum = 0;
        for (Cursor c = layout.begin(); c.valid(); c.next()) sum += c.address();
        benchmark::DoNotOptimize(sum);
        visited += layout.variable_count();
    }
    state.counters["variables/s"] =
        benchmark::Counter(static_cast<double>(visited), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EnumerateMillionReplicas)->Unit(benchmark::kMillisecond);

void BM_FindMillionReplicas(benchmark::State& state) {
    static ParseResult parsed = parse(kMillion);
    static LayoutResult laid = build_layout(*parsed.document);
    const Layout& layout = *laid.layout;
    std::uint64_t address = 128;
    for (auto _ : state) {
        Cursor c = layout.find(253, address);
        benchmark::DoNotOptimize(c.ordinal());
        address = 128 + (address * 2654435761u) % 17000000u;
    }
}
BENCHMARK(BM_FindMillionReplicas);

}  // namespace

BENCHMARK_MAIN();
