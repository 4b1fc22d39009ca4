#!/usr/bin/env python3
"""Times two commands side by side: A B A B ..., and reports the median of the per-pair ratios.

    bench/paired.py [-n PAIRS] [--warmup W] [--names A,B] [--gbench] [--figure NAME=REGEX]...
                    [--timeout S] [--json FILE] -- COMMAND_A [ARG...] --vs COMMAND_B [ARG...]

Each pair runs A, then B, so a drift in the machine's speed (another build starting, a VM's
neighbour) hits both alike; the ratio A/B is taken pair by pair and its median reported with
its range. A ratio of the two sides' medians would mix minutes of different load.

Figures of every run: wall seconds (a monotonic clock around the child), CPU seconds (user +
system of the child and what it waited for, from wait4), peak RSS. With --gbench the commands
are Google Benchmark programs asked for --benchmark_format=json: each benchmark's CPU and real
time (its median row when it ran repetitions) become figures too; a command may print several
reports (sh -c 'for ...': one process per benchmark). --figure NAME=REGEX takes a
number from what the command prints (the first group of REGEX, searched in stdout).

A command's output is thrown away unless it is parsed; its exit status is reported, not acted
on. PAIRS defaults to 10, WARMUP (pairs not counted) to 1. Exit status 2: unusable arguments.

Also a module: run_pairs(run_a, run_b, pairs, warmup) for callers that time something else
(bench/validate_compare.sh --e2e times loops of processes).
"""
import argparse
import json
import os
import re
import resource
import signal
import statistics
import subprocess
import sys
import threading
import time


def run_process(argv, timeout, env=None):
    """Runs argv in its own session, killed after timeout seconds (None or 0: never); returns
    (exit code or None on timeout, stdout, stderr, wall s, rusage of the child alone)."""
    start = time.perf_counter()
    proc = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, start_new_session=True, env=env)
    expired = threading.Event()

    def kill():
        expired.set()
        try:
            os.killpg(proc.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass

    timer = threading.Timer(timeout, kill) if timeout else None
    if timer:
        timer.start()
    err_chunks = []
    reader = threading.Thread(target=lambda: err_chunks.append(proc.stderr.read()))
    reader.start()
    try:
        out = proc.stdout.read()
        reader.join()
        # wait4, not Popen.wait: the child's own CPU time, page faults and peak memory.
        _, status, usage = os.wait4(proc.pid, 0)
    except KeyboardInterrupt:  # the child is in its own session: Ctrl-C does not reach it
        kill()
        raise
    wall = time.perf_counter() - start
    if timer:
        timer.cancel()
    proc.returncode = os.waitstatus_to_exitcode(status)
    proc.stdout.close()
    proc.stderr.close()
    code = None if expired.is_set() else proc.returncode
    return code, out.decode(errors="replace"), b"".join(err_chunks).decode(errors="replace"), \
        wall, usage


class Runner:
    """One side's command: runs it and turns its run into figures."""

    def __init__(self, argv, timeout, gbench, figures):
        self.argv, self.timeout, self.gbench, self.figures = argv, timeout, gbench, figures
        self.failures = []

    def __call__(self):
        code, text, _, wall, usage = run_process(self.argv, self.timeout)
        if code is None:
            self.failures.append("timeout")
            return None
        figures = {
            "wall s": wall,
            "cpu s": usage.ru_utime + usage.ru_stime,
            "peak rss MiB": usage.ru_maxrss / 1024,
        }
        if code != 0:
            self.failures.append(f"exit {code}")
        if self.gbench:
            figures.update(gbench_figures(text))
        for name, pattern in self.figures:
            m = re.search(pattern, text)
            if m:
                figures[name] = float(m.group(1))
        return figures


def gbench_figures(text):
    """CPU and real time of each benchmark in Google Benchmark JSON reports, in its own unit.

    The text may hold several reports one after the other (a loop of one process per
    benchmark)."""
    reports, decoder, pos = [], json.JSONDecoder(), 0
    while True:
        while pos < len(text) and text[pos].isspace():
            pos += 1
        if pos >= len(text):
            break
        try:
            report, pos = decoder.raw_decode(text, pos)
        except json.JSONDecodeError:
            break
        reports.append(report)
    rows = {}
    for b in (b for r in reports for b in r.get("benchmarks", [])):
        if b.get("error_occurred"):
            continue
        name = b.get("run_name", b["name"])
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                rows.setdefault(name, {})["median"] = b
        else:
            rows.setdefault(name, {}).setdefault("iterations", []).append(b)
    figures = {}
    for name, row in rows.items():
        for what in ("cpu_time", "real_time"):
            if "median" in row:
                value, unit = row["median"][what], row["median"]["time_unit"]
            else:
                its = row["iterations"]
                value, unit = statistics.median(b[what] for b in its), its[0]["time_unit"]
            figures[f"{name} {what.split('_')[0]} {unit}"] = value
    return figures


def run_pairs(run_a, run_b, pairs, warmup, progress=None):
    """Calls run_a then run_b, warmup + pairs times; returns the counted pairs as (a, b) dicts.

    A run that returns None (failed) drops its pair."""
    done = []
    for i in range(warmup + pairs):
        a = run_a()
        b = run_b()
        if i >= warmup and a is not None and b is not None:
            done.append((a, b))
        if progress:
            progress(i + 1 - warmup, pairs)
    return done


def summarize(done):
    """Per figure both sides: median, min, max; the per-pair ratio A/B: median, min, max."""
    names = [n for n in done[0][0] if all(n in a and n in b for a, b in done)] if done else []
    med = statistics.median
    result = {}
    for name in names:
        a = [p[0][name] for p in done]
        b = [p[1][name] for p in done]
        ratios = [x / y for x, y in zip(a, b) if y]
        result[name] = {
            "a": {"median": med(a), "min": min(a), "max": max(a), "runs": a},
            "b": {"median": med(b), "min": min(b), "max": max(b), "runs": b},
            "ratio": {"median": med(ratios), "min": min(ratios), "max": max(ratios),
                      "pairs": ratios} if ratios else None,
        }
    return result


def fmt(v):
    return f"{v:.4g}" if abs(v) < 1e6 else f"{v:.4e}"


def print_summary(summary, names, pairs, out=sys.stdout):
    a_name, b_name = names
    width = max([len(n) for n in summary] + [6])
    ratio_name = f"{a_name}/{b_name}"
    print(f"{'figure':{width}}  {a_name:>12}  {b_name:>12}  "
          f"{ratio_name + ', median of pairs':>24}  {'range':>13}", file=out)
    for name, s in summary.items():
        r = s["ratio"]
        ratio = f"{r['median']:.3f}" if r else "-"
        spread = f"{r['min']:.3f}-{r['max']:.3f}" if r else "-"
        print(f"{name:{width}}  {fmt(s['a']['median']):>12}  {fmt(s['b']['median']):>12}  "
              f"{ratio:>24}  {spread:>13}", file=out)
    print(f"({pairs} pairs, {a_name} then {b_name} in each; the two sides' columns are medians. "
          "On a shared machine trust CPU figures over wall/real ones.)", file=out)


def main():
    argv = sys.argv[1:]
    if "--" not in argv or "--vs" not in argv[argv.index("--"):]:
        print(__doc__, file=sys.stderr)
        return 2
    sep = argv.index("--")
    vs = sep + argv[sep:].index("--vs")
    cmd_a, cmd_b = argv[sep + 1:vs], argv[vs + 1:]
    p = argparse.ArgumentParser(usage=__doc__.splitlines()[2].strip())
    p.add_argument("-n", "--pairs", type=int, default=10)
    p.add_argument("--warmup", type=int, default=1)
    p.add_argument("--names", default="A,B", help="names of the two sides, A,B")
    p.add_argument("--gbench", action="store_true")
    p.add_argument("--figure", action="append", default=[], metavar="NAME=REGEX")
    p.add_argument("--timeout", type=float, default=None, help="seconds per run")
    p.add_argument("--json", metavar="FILE")
    opts = p.parse_args(argv[:sep])
    if not cmd_a or not cmd_b or opts.pairs < 1 or opts.names.count(",") != 1:
        print(__doc__, file=sys.stderr)
        return 2
    figures = []
    for f in opts.figure:
        name, _, pattern = f.partition("=")
        if not pattern:
            print(f"--figure needs NAME=REGEX: {f}", file=sys.stderr)
            return 2
        figures.append((name, pattern))
    names = opts.names.split(",")
    run_a = Runner(cmd_a, opts.timeout, opts.gbench, figures)
    run_b = Runner(cmd_b, opts.timeout, opts.gbench, figures)

    def progress(i, n):
        if i > 0 and sys.stderr.isatty():
            print(f"pair {i}/{n}", file=sys.stderr, end="\r" if i < n else "\n", flush=True)

    load_before = os.getloadavg()[0]
    done = run_pairs(run_a, run_b, opts.pairs, opts.warmup, progress)
    load_after = os.getloadavg()[0]
    if not done:
        print("no pair completed", file=sys.stderr)
        return 1
    summary = summarize(done)
    # A child's peak RSS starts at this script's own (fork copies it, exec keeps the maximum).
    floor = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    rss = summary.get("peak rss MiB")
    if rss and max(rss["a"]["max"], rss["b"]["max"]) <= floor * 1.01:
        del summary["peak rss MiB"]
    print_summary(summary, names, len(done))
    for side, runner in zip(names, (run_a, run_b)):
        if runner.failures:
            print(f"note: {side}: {len(runner.failures)} runs did not exit 0 "
                  f"({', '.join(sorted(set(runner.failures)))})")
    print(f"load average (1 min): {load_before:.2f} before, {load_after:.2f} after; peak RSS "
          f"cannot read below this script's own, {floor:.1f} MiB (not shown when at it)")
    if opts.json:
        with open(opts.json, "w") as f:
            json.dump({"a": {"name": names[0], "command": cmd_a},
                       "b": {"name": names[1], "command": cmd_b},
                       "pairs": len(done), "warmup": opts.warmup,
                       "load_avg_1min": [load_before, load_after],
                       "failures": {names[0]: run_a.failures, names[1]: run_b.failures},
                       "figures": summary}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
