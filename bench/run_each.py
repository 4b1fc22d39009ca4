#!/usr/bin/env python3
"""Runs every Google Benchmark of every bench_* program in its own process; writes one result.

    bench/run_each.py --build-dir DIR --out RESULT.json [--processes P] [--repetitions R]
                      [--min-time S] [--filter REGEX] [--quick] [--shared] [--timeout S]
                      [--tmpdir DIR] [PROGRAM...]

Why a process each: in one process a benchmark runs on the heap the ones before it left. glibc
raises its mmap threshold when a large block is freed, and a later benchmark may then grow and
trim the heap on every iteration: validate()'s benchmark took 265 us alone and 650-1,100 us
after parse+layout in the same process (60,000 page faults more). A fresh process per benchmark
measures each from the same start, whatever ran before.

Every benchmark runs in P processes (default 3), each --benchmark_repetitions=R (default 3,
aggregates only); one with fixed iterations (/iterations:N in its name: start-up, memory growth,
a fresh simnode each) in P x R processes of one repetition, since a second repetition in the
same process would find the first one's heap (bm_startup_1000's rss_MiB read 0 there). The
processes go in rounds (every benchmark once, then again), so a slow minute of the machine is
spread over all benchmarks, not concentrated on one. Per benchmark the result keeps each
process's median and reports the median of those, with their range (the honest noise figure:
it includes the start of a process, which repetitions do not).

--quick: P=1, R=1 and --benchmark_min_time=0.05 (benchmarks with fixed iterations ignore it):
a smoke run, not for docs/benchmarks.md (bench/benchmarks_doc.py refuses it unless forced).
--shared: the old way for comparison: one process per program running all its benchmarks.
PROGRAM: names (bench_cdi) or paths; default every DIR/bench/bench_* executable. --filter keeps
the benchmarks whose "program/name" matches REGEX (Python re.search). --tmpdir (default
/dev/shm) is the benchmarks' TMPDIR, where those that start nodes keep their fresh images: on
the disk each image costs an fsync, and bm_startup_1000 then measures the disk (36 s instead
of 0.5 s for its 1,000 nodes while another build wrote to it); '' keeps the environment's.
--timeout bounds each process (default 600 s).

The result records the machine (CPU model, cores, memory, kernel), the compiler, the build type
and flags, the git commit (and whether the tree had uncommitted changes), the date and the load
average during the run. bench/benchmarks_doc.py turns it into markdown tables.
"""
import argparse
import datetime
import json
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from paired import run_process  # noqa: E402  (the one killable child runner)

STANDARD_KEYS = {
    "name", "family_index", "per_family_instance_index", "run_name", "run_type", "repetitions",
    "repetition_index", "threads", "iterations", "real_time", "cpu_time", "time_unit",
    "aggregate_name", "aggregate_unit", "error_occurred", "error_message", "label",
}


def gbench_regex_escape(name):
    """A benchmark name as a POSIX extended regex matching only itself (Google Benchmark's)."""
    return re.sub(r"([\\^$.|?*+()\[\]{}])", r"\\\1", name)


def run(argv, timeout, env=None):
    """Runs argv; returns (exit code or None on timeout, stdout, stderr, wall s, rusage)."""
    return run_process(argv, timeout, env)


def sh(argv, cwd=None):
    try:
        return subprocess.run(argv, cwd=cwd, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return ""


def machine(build_dir):
    """What the figures were measured on and with."""
    cpu = ""
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    mem_kib = 0
    with open("/proc/meminfo") as f:
        for line in f:
            if line.startswith("MemTotal:"):
                mem_kib = int(line.split()[1])
    cache = {}
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt")) as f:
            for line in f:
                m = re.match(r"([A-Za-z_0-9]+):[A-Z]+=(.*)", line.rstrip("\n"))
                if m:
                    cache[m.group(1)] = m.group(2)
    except OSError:
        pass
    build_type = cache.get("CMAKE_BUILD_TYPE", "")
    compiler = cache.get("CMAKE_CXX_COMPILER", "")
    source = cache.get("CMAKE_HOME_DIRECTORY", os.path.dirname(os.path.dirname(
        os.path.abspath(__file__))))
    changed = sh(["git", "diff", "--name-only", "HEAD"], cwd=source).splitlines()
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "memory_gib": round(mem_kib / 1024 / 1024, 1),
        "kernel": platform.release(),
        "os": sh(["sh", "-c", ". /etc/os-release && echo \"$PRETTY_NAME\""]),
        "compiler": sh([compiler, "--version"]).splitlines()[0] if compiler else "",
        "build_type": build_type,
        "build_flags": " ".join(filter(None, [
            cache.get("CMAKE_CXX_FLAGS", ""),
            cache.get(f"CMAKE_CXX_FLAGS_{build_type.upper()}", "")])).strip(),
        "build_dir": os.path.abspath(build_dir),
        "git_commit": sh(["git", "rev-parse", "HEAD"], cwd=source),
        "git_uncommitted_changes": changed[:30],
        "date_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
    }


def rows_of(report):
    """Per benchmark (run_name) of one process's JSON report: the row to use and any error."""
    result = {}
    for b in report.get("benchmarks", []):
        name = b.get("run_name", b["name"])
        entry = result.setdefault(name, {"iterations": [], "median": None, "cv": None,
                                         "error": None})
        if b.get("error_occurred"):
            entry["error"] = b.get("error_message", "error")
        elif b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                entry["median"] = b
            elif b.get("aggregate_name") == "cv":
                entry["cv"] = b
        else:
            entry["iterations"].append(b)
    out = {}
    for name, e in result.items():
        if e["error"]:
            out[name] = {"error": e["error"]}
            continue
        row = e["median"]
        if row is None:
            if not e["iterations"]:
                continue
            its = e["iterations"]  # one repetition, or aggregates not reported
            row = dict(its[len(its) // 2])
            for key in ("cpu_time", "real_time"):
                row[key] = statistics.median(b[key] for b in its)
        figures = {
            "cpu_time": row["cpu_time"], "real_time": row["real_time"],
            "time_unit": row["time_unit"], "iterations": row["iterations"],
            "counters": {k: v for k, v in row.items()
                         if k not in STANDARD_KEYS and isinstance(v, (int, float))},
        }
        if e["cv"] is not None:
            figures["cv_cpu"] = e["cv"]["cpu_time"]
        out[name] = figures
    return out


def list_tests(program):
    code, out, err, _, _ = run([program, "--benchmark_list_tests"], 60)
    if code != 0:
        raise SystemExit(f"{program} --benchmark_list_tests failed: {err.strip()}")
    return [line.strip() for line in out.splitlines() if line.strip()]


def summarize(samples):
    """Across processes: median and range of each process's figures."""
    med = statistics.median
    ok = [s for s in samples if "error" not in s["figures"]]
    entry = {"processes": len(samples)}
    errors = sorted({s["figures"]["error"] for s in samples if "error" in s["figures"]})
    if errors:
        entry["errors"] = errors
    if not ok:
        return entry
    first = ok[0]["figures"]
    entry["time_unit"] = first["time_unit"]
    entry["iterations"] = med(s["figures"]["iterations"] for s in ok)
    for key in ("cpu_time", "real_time"):
        values = [s["figures"][key] for s in ok]
        entry[key] = {"median": med(values), "min": min(values), "max": max(values),
                      "per_process": values}
    counters = {}
    for name in first["counters"]:
        values = [s["figures"]["counters"][name] for s in ok if name in s["figures"]["counters"]]
        counters[name] = {"median": med(values), "min": min(values), "max": max(values)}
    entry["counters"] = counters
    cvs = [s["figures"]["cv_cpu"] for s in ok if "cv_cpu" in s["figures"]]
    if cvs:
        entry["cv_cpu_within_process"] = med(cvs)
    entry["process"] = {
        "wall_s": med(s["wall_s"] for s in samples),
        "minor_faults": med(s["minor_faults"] for s in samples),
        "peak_rss_mib": med(s["peak_rss_mib"] for s in samples),
    }
    return entry


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--build-dir", required=True)
    p.add_argument("--out", required=True, help="the result, JSON")
    p.add_argument("--processes", type=int)
    p.add_argument("--repetitions", type=int)
    p.add_argument("--min-time", type=float, help="--benchmark_min_time, seconds")
    p.add_argument("--filter", default="", help="regex on PROGRAM/BENCHMARK")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--shared", action="store_true",
                   help="one process per program, all its benchmarks in it (the old way)")
    p.add_argument("--timeout", type=float, default=600, help="seconds per process")
    p.add_argument("--tmpdir", default="/dev/shm" if os.path.isdir("/dev/shm") else "",
                   help="TMPDIR of the benchmarks (default /dev/shm; '' keeps the environment's)")
    p.add_argument("programs", nargs="*")
    opts = p.parse_args()
    processes = opts.processes or (1 if opts.quick else 3)
    repetitions = opts.repetitions or (1 if opts.quick else 3)
    min_time = opts.min_time if opts.min_time is not None else (0.05 if opts.quick else None)

    bench_dir = os.path.join(opts.build_dir, "bench")
    if opts.programs:
        programs = [x if os.sep in x else os.path.join(bench_dir, x) for x in opts.programs]
    else:
        programs = sorted(os.path.join(bench_dir, f) for f in os.listdir(bench_dir)
                          if f.startswith("bench_")
                          and os.access(os.path.join(bench_dir, f), os.X_OK)
                          and os.path.isfile(os.path.join(bench_dir, f)))
    pattern = re.compile(opts.filter)
    plan = []  # (program, [benchmark names], repetitions) per process of a round
    names = {}
    for program in programs:
        prog = os.path.basename(program)
        tests = [t for t in list_tests(program) if pattern.search(f"{prog}/{t}")]
        names[prog] = tests
        if not tests:
            continue
        if opts.shared:
            plan.append((program, tests, repetitions))
            continue
        for t in tests:
            if "/iterations:" in t:
                # Fixed iterations: what it measures happens once per process (start-up, memory
                # growth, a fresh simnode); a second repetition would find the first one's heap.
                plan.extend((program, [t], 1) for _ in range(repetitions))
            else:
                plan.append((program, [t], repetitions))

    def options(reps):
        common = [f"--benchmark_repetitions={reps}", "--benchmark_format=json"]
        if reps > 1:
            common.append("--benchmark_report_aggregates_only=true")
        if min_time is not None:
            common.append(f"--benchmark_min_time={min_time}")
        return common

    info = machine(opts.build_dir)
    env = dict(os.environ)
    if opts.tmpdir:
        env["TMPDIR"] = opts.tmpdir
    samples = {}  # (program, benchmark) -> [{figures, wall_s, ...}]
    loads = [os.getloadavg()[0]]
    gbench_context = {}
    started = time.perf_counter()
    total = processes * len(plan)
    done = 0
    for round_ in range(processes):
        for program, tests, reps in plan:
            prog = os.path.basename(program)
            if opts.shared:
                filt = "^(" + "|".join(gbench_regex_escape(t) for t in tests) + ")$"
            else:
                filt = "^" + gbench_regex_escape(tests[0]) + "$"
            argv = [program, f"--benchmark_filter={filt}", *options(reps)]
            code, out, err, wall, usage = run(argv, opts.timeout, env)
            loads.append(os.getloadavg()[0])
            done += 1
            what = prog if opts.shared else f"{prog} {tests[0]}"
            print(f"[{done}/{total}] round {round_ + 1}: {what}: {wall:.1f} s", file=sys.stderr,
                  flush=True)
            try:
                report = json.loads(out)
            except json.JSONDecodeError:
                report = {}
            gbench_context = report.get("context", gbench_context)
            rows = rows_of(report)
            for test in tests:
                figures = rows.get(test)
                if figures is None:
                    why = "timeout" if code is None else f"exit {code}: {err.strip()[-300:]}"
                    figures = {"error": f"no result ({why})"}
                samples.setdefault((prog, test), []).append({
                    "figures": figures, "wall_s": wall, "minor_faults": usage.ru_minflt,
                    "peak_rss_mib": usage.ru_maxrss / 1024,
                })

    result = {
        "generated_by": "bench/run_each.py",
        "machine": info,
        "settings": {
            "mode": "shared" if opts.shared else "per-benchmark process",
            "processes": processes, "repetitions": repetitions, "min_time_s": min_time,
            "quick": opts.quick, "filter": opts.filter,
            "tmpdir": env.get("TMPDIR", ""),
            # A child's peak RSS starts at this process's own (fork copies it; exec keeps the
            # maximum): figures at this floor mean "at most".
            "peak_rss_floor_mib": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
                                        / 1024, 1),
            "benchmark_library_build_type": gbench_context.get("library_build_type", ""),
        },
        "load_avg_1min": {"min": min(loads), "max": max(loads),
                          "median": statistics.median(loads)},
        "duration_s": round(time.perf_counter() - started, 1),
        "programs": {},
    }
    for program in programs:
        prog = os.path.basename(program)
        result["programs"][prog] = [
            {"name": t, **summarize(samples[(prog, t)])} for t in names[prog]
            if (prog, t) in samples
        ]
    with open(opts.out, "w") as f:
        json.dump(result, f, indent=1)
        f.write("\n")
    print(f"wrote {opts.out}: {sum(len(v) for v in result['programs'].values())} benchmarks, "
          f"{result['duration_s']} s, load {min(loads):.2f}-{max(loads):.2f}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
