#!/usr/bin/env python3
"""Turns bench/run_each.py's result into markdown tables, or regenerates them in a document.

    bench/benchmarks_doc.py RESULT.json                 every table, markdown, on stdout
    bench/benchmarks_doc.py RESULT.json DOC.md [--check] [--force]

With DOC.md, only what lies between a pair of marker lines is replaced, everything else (the
hand-written history) stays byte for byte:

    <!-- bench-results:BLOCK:begin -->
    ...generated...
    <!-- bench-results:BLOCK:end -->

BLOCK is `machine` (what was measured on, how, when) or a program (`bench_cdi`: its table). A
block whose program is not in RESULT is left as it was, with a note on stderr. The output
depends only on RESULT, so a second run changes nothing. --check: change nothing, exit 1 if
DOC.md would change. A --quick or filtered result is refused unless --force.

Descriptions and targets of known benchmarks are in DESCRIPTIONS and TARGETS below; a benchmark
not listed there gets a row under its name.
"""
import argparse
import json
import os
import re
import sys
import textwrap

# Benchmark name (as listed by --benchmark_list_tests) -> what it measures.
DESCRIPTIONS = {
    "BM_ParseLayoutLargestCorpusFile": "parse + layout, largest corpus CDI",
    "BM_ValidateLargestCorpusFile": "`validate()` (schema, model, rules, layout), largest corpus CDI",
    "BM_ParseLayoutGenerated1MB": "parse + layout, generated 1 MB CDI (6,242 variables)",
    "BM_ParseLayoutMillionReplicas": "parse + layout, 10^6-replication CDI (3 x 10^6 variables)",
    "BM_EnumerateMillionReplicas": "lazy enumeration of those 3 x 10^6 variables",
    "BM_FindMillionReplicas": "`Layout::find(space, address)` in that layout",
    "bm_backup_can_125k/largest/iterations:3/manual_time":
        "`lcc-conform backup`, largest corpus CDI, 125 kbit/s CAN (simulated time)",
    "bm_backup_can_125k/most_variables/iterations:3/manual_time":
        "same, the CDI with the most variables (simulated time)",
    "bm_backup_in_process/largest": "backup of the largest corpus CDI, in-process, no bit timing",
    "bm_backup_in_process/most_variables": "same, the CDI with the most variables",
    "bm_format_to": "GridConnect format (`format_to`)",
    "bm_format_string": "GridConnect format into a new `std::string`",
    "bm_parse_frame": "GridConnect parse (`parse_frame`)",
    "bm_parser_feed": "GridConnect streaming parser, 4 KiB chunks",
    "bm_datagram_round_trip_64": "64-byte datagram round trip, two NodeStacks, in-process bus",
    "bm_datagram_round_trip_64_sim_network": "same through SimNetwork (simulated clock)",
    "bm_on_frame_not_for_us": "`NodeStack::on_frame`, a frame not addressed to the node",
    "bm_next_deadline_idle": "next deadline of an idle stack (StackDriver's timer)",
    "bm_thousand_stack_startup/0/iterations:3":
        "1,000 NodeStacks start up on one SimNetwork, distinct first aliases",
    "bm_thousand_stack_startup/1/iterations:3": "same, every first alias colliding",
    "bm_driver_thousand_stacks_verify_global":
        "1,000 stacks on one StackDriver answer a global Verify Node ID",
    "bm_read_round_trip_tcp/real_time": "memory-config read round trip over TCP loopback",
    "bm_cdi_download_tcp/real_time": "CDI download over TCP (24,701-byte corpus CDI)",
    "bm_cdi_download_can_125k/iterations:3/manual_time":
        "same CDI, in-process bus at 125 kbit/s (simulated time)",
    "bm_startup_1000/iterations:1/manual_time": "1,000 default nodes in-process, fresh images",
    "cdi_by_stream_125k/iterations:5/manual_time":
        "largest corpus CDI by stream, 125 kbit/s (simulated time)",
    "cdi_by_datagram_125k/iterations:5/manual_time": "same by 64-byte datagram reads",
    "bm_tcp_hub_three_clients/1000/real_time": "TCP hub, 3 loopback clients x 1000 frames",
    "bm_in_process_bus_three_ports/1000": "in-process bus, 3 ports, no timing model",
    "bm_tcp_hub_one_to_another/10000/real_time": "TcpHubServer, one client to another",
    "bm_simnode_cdi_download_125k/iterations:3/manual_time":
        "CDI download through `simnode --bitrate 125000`",
    "bm_simnode_two_cdi_downloads_125k/iterations:3/manual_time":
        "two tools downloading that CDI at once",
    "bm_simnode_hub_one_to_another/10000/iterations:5/real_time":
        "simnode's hub, one client to another, no bitrate (per-client limit)",
    "bm_simnode_verify_round_trip/flood:0/bitrate:0/iterations:200/manual_time":
        "Verify Node ID round trip through simnode, no flood, no bitrate",
    "bm_simnode_verify_round_trip/flood:1/bitrate:0/iterations:200/manual_time":
        "same while another client floods",
    "bm_simnode_verify_round_trip/flood:0/bitrate:125000/iterations:200/manual_time":
        "round trip at `--bitrate 125000`, no flood",
    "bm_simnode_verify_round_trip/flood:1/bitrate:125000/iterations:200/manual_time":
        "round trip at `--bitrate 125000`, flood",
}

# Benchmark -> (figure, comparison, bound, what the target says). The figure is a counter's
# name or "time" (the row's time in seconds); judged on the median.
TARGETS = {
    "BM_ParseLayoutLargestCorpusFile": ("bytes_per_second", ">=", 100e6, ">= 100 MB/s"),
    "BM_ParseLayoutGenerated1MB": ("bytes_per_second", ">=", 100e6, ">= 100 MB/s"),
    "BM_ParseLayoutMillionReplicas": ("peak_heap_bytes", "<", 10e6, "peak heap < 10 MB"),
    "BM_EnumerateMillionReplicas": ("variables/s", ">=", 20e6, ">= 20 M variables/s"),
    "bm_format_to": ("items_per_second", ">=", 10e6, ">= 10 M frames/s"),
    "bm_parse_frame": ("items_per_second", ">=", 10e6, ">= 10 M frames/s"),
    "bm_datagram_round_trip_64": ("round_trips_per_s", ">=", 500e3, ">= 500 k/s"),
    "bm_simnode_cdi_download_125k/iterations:3/manual_time":
        ("ratio", "<=", 1.02, "within 2 % of the frame-time bound"),
    "cdi_by_stream_125k/iterations:5/manual_time":
        ("ratio", "<=", 1.03, "within 3 % of the frame-time bound"),
}

UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
BEGIN = re.compile(r"^<!-- bench-results:([A-Za-z0-9_.,-]+):begin -->$")
END = "<!-- bench-results:{}:end -->"


def num(x):
    """Three significant digits, no exponent."""
    a = abs(x)
    if x == int(x) and a < 1e15:
        return f"{int(x):,}"
    if a >= 1000:
        return f"{x:,.0f}"
    if a >= 100:
        return f"{x:.0f}"
    if a >= 10:
        return f"{x:.1f}"
    if a >= 1:
        return f"{x:.2f}"
    return f"{x:.3g}"


def si(x):
    for bound, suffix in ((1e9, " G"), (1e6, " M"), (1e3, " k")):
        if abs(x) >= bound:
            return num(x / bound) + suffix
    return num(x)


def time_unit_for(seconds):
    for unit, bound in (("ns", 1e-6), ("us", 1e-3), ("ms", 1.0)):
        if seconds < bound:
            return unit
    return "s"


def primary(entry):
    """Which time a row is about: its own clock (manual), real time, or CPU time."""
    if "/manual_time" in entry["name"]:
        return "real_time", "manual"
    if "/real_time" in entry["name"]:
        return "real_time", "real"
    return "cpu_time", "CPU"


def figures(entry):
    parts = []
    for name, c in entry.get("counters", {}).items():
        v = c["median"]
        if name == "bytes_per_second":
            parts.append(f"{num(v / 1e6)} MB/s")
        elif name == "items_per_second":
            parts.append(f"{si(v)} items/s")
        elif name == "bytes":
            continue  # the input's size: in the description
        else:
            parts.append(f"{name} {si(v)}")
    return ", ".join(parts)


def target(entry):
    t = TARGETS.get(entry["name"])
    if not t or "cpu_time" not in entry:
        return ""
    figure, op, bound, text = t
    if figure == "time":
        key, _ = primary(entry)
        value = entry[key]["median"] * UNIT_SECONDS[entry["time_unit"]]
    elif figure in entry.get("counters", {}):
        value = entry["counters"][figure]["median"]
    else:
        return text
    met = {">=": value >= bound, "<=": value <= bound, "<": value < bound, ">": value > bound}[op]
    return f"{text}: {'met' if met else '**not met**'}"


def table(entries):
    rows = ["| benchmark | time (median) | range over processes | figures (median) | target |",
            "|---|---|---|---|---|"]
    for e in entries:
        name = e["name"]
        label = f"{DESCRIPTIONS[name]} (`{name}`)" if name in DESCRIPTIONS else f"`{name}`"
        if "cpu_time" not in e:
            rows.append(f"| {label} | failed: {'; '.join(e.get('errors', []))} | | | |")
            continue
        key, kind = primary(e)
        scale = UNIT_SECONDS[e["time_unit"]]
        t = e[key]
        unit = time_unit_for(t["median"] * scale)
        conv = scale / UNIT_SECONDS[unit]
        time_cell = f"{num(t['median'] * conv)} {unit} {kind}"
        spread = f"{num(t['min'] * conv)}-{num(t['max'] * conv)} {unit}"
        if e["processes"] < 2:
            spread = "one process"
        if e.get("errors"):
            spread += f" ({len(e['errors'])} failed)"
        rows.append(f"| {label} | {time_cell} | {spread} | {figures(e)} | {target(e)} |")
    return rows


def machine_block(result):
    m, s, load = result["machine"], result["settings"], result["load_avg_1min"]
    commit = m["git_commit"][:10]
    if m["git_uncommitted_changes"]:
        commit += (f" (the source tree had uncommitted changes in "
                   f"{len(m['git_uncommitted_changes'])} files when measured)")
    runs = (f"{plural(s['processes'], 'process', 'processes')} of "
            f"{plural(s['repetitions'], 'repetition', 'repetitions')}")
    how = (f"each benchmark in its own process, {runs}; one with fixed iterations in "
           f"{plural(s['processes'] * s['repetitions'], 'process', 'processes')} of one")
    if s["mode"] == "shared":
        how = f"all benchmarks of a program in one process, {runs}"
    lines = [
        f"Machine: {m['cpu']}, {m['cores']} cores, {m['memory_gib']} GiB, {m['os']}, Linux "
        f"{m['kernel']}; {m['compiler']}, {m['build_type']} (`{m['build_flags']}`); commit "
        f"{commit}; measured {m['date_utc']}, load average (1 min) {load['min']:.1f}-"
        f"{load['max']:.1f} during the run, which took {result['duration_s']:.0f} s.",
        "",
        f"How: `bench/run_all.sh` ({how}; TMPDIR={s['tmpdir'] or 'unset'}). A time is the "
        "median of the processes' medians, CPU time unless the row says real time or manual (the "
        "benchmark's own clock: simulated time where it says so); the range is the lowest and "
        "highest process median, so it shows how much a fresh process varies. Figures are the "
        "median of the processes' counters. Tables generated by `bench/benchmarks_doc.py`.",
    ]
    if s.get("quick"):
        lines.append("")
        lines.append("**A --quick run (one process, one repetition): a smoke test, not a result.**")
    if s.get("filter"):
        lines.append("")
        lines.append(f"Only benchmarks matching `{s['filter']}`.")
    return lines


def plural(n, one, many):
    return f"{n} {one if n == 1 else many}"


def wrap(lines):
    """Paragraphs wrapped as the hand-written text is (100 columns)."""
    return [textwrap.fill(x, width=100, break_long_words=False, break_on_hyphens=False)
            if x else x for x in lines]


def blocks(result):
    out = {"machine": "\n".join(wrap(machine_block(result))).split("\n")}
    for program, entries in result["programs"].items():
        if entries:
            out[program] = table(entries)
    return out


def regenerate(text, generated, path):
    """The document with every known block replaced; the names of the blocks left alone."""
    lines = text.split("\n")
    out, kept, found = [], [], 0
    i = 0
    while i < len(lines):
        m = BEGIN.match(lines[i])
        if not m:
            if lines[i].startswith("<!-- bench-results:"):
                raise SystemExit(f"{path}:{i + 1}: a marker without its begin: {lines[i]}")
            out.append(lines[i])
            i += 1
            continue
        name, end = m.group(1), END.format(m.group(1))
        try:
            j = lines.index(end, i + 1)
        except ValueError:
            raise SystemExit(f"{path}:{i + 1}: no `{end}` after this begin marker") from None
        inner = lines[i + 1:j]
        if any(x.startswith("<!-- bench-results:") for x in inner):
            raise SystemExit(f"{path}:{i + 1}: block {name} contains another marker")
        found += 1
        out.append(lines[i])
        if name in generated:
            out.extend(generated[name])
        else:
            kept.append(name)
            out.extend(inner)
        out.append(end)
        i = j + 1
    if not found:
        raise SystemExit(f"{path}: no <!-- bench-results:BLOCK:begin --> markers")
    return "\n".join(out), kept


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("result")
    p.add_argument("doc", nargs="?")
    p.add_argument("--check", action="store_true", help="exit 1 if DOC would change")
    p.add_argument("--force", action="store_true", help="accept a --quick or filtered result")
    opts = p.parse_args()
    with open(opts.result) as f:
        result = json.load(f)
    generated = blocks(result)
    if opts.doc is None:
        for name, lines in generated.items():
            if name != "machine":
                print(f"\n### {name}\n")
            print("\n".join(lines))
        return 0
    settings = result["settings"]
    if (settings.get("quick") or settings.get("filter")) and not opts.force:
        print(f"{opts.result} is a --quick or filtered run; --force to use it anyway",
              file=sys.stderr)
        return 2
    with open(opts.doc) as f:
        text = f.read()
    new, kept = regenerate(text, generated, opts.doc)
    for name in kept:
        print(f"{opts.doc}: block {name} is not in {opts.result}: left as it was", file=sys.stderr)
    if opts.check:
        if new != text:
            print(f"{opts.doc}: the generated tables differ from {opts.result}", file=sys.stderr)
            return 1
        return 0
    if new != text:
        tmp = f"{opts.doc}.tmp{os.getpid()}"
        with open(tmp, "w") as f:
            f.write(new)
        os.replace(tmp, opts.doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
