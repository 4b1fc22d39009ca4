#!/usr/bin/env python3
"""clang-tidy over every translation unit of a build, for ci/lint.

Usage: ci/lint_tidy.py ROOT BUILD JOBS CLANG_TIDY [FILE...]

Runs the processes itself: it starts the slowest TUs first (so the run does not end waiting on
one big file), reports what a header says once however many TUs include it, and keeps a cache.

The cache (OLCB_LINT_CACHE, default ~/.cache/olcb-lint; "off" disables it) maps a TU's exact
input to clang-tidy's output for it: the key hashes the clang-tidy version, every .clang-tidy of
the tree, the TU's flags and its preprocessed text with comments (so a NOLINT counts), paths
made relative to the checkout. Any change to the file, a header it includes (ours or the
system's), a flag or the configuration is a miss and runs clang-tidy; a hit replays the
findings, so a failing TU fails again. A full run on 2 cores takes minutes; the cache lets a
clean clone on the same machine pass in about one.
"""
import concurrent.futures
import hashlib
import json
import os
import re
import resource
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

ROOT_MARK = "@OLCB_ROOT@"


def without_pch(args):
    """The command without CMake's precompiled header: GCC's .gch is no input for clang, and
    each test TU includes what the header holds itself."""
    out, skip = [], False
    for i, a in enumerate(args):
        if skip:
            skip = False
        elif a == "-include" and i + 1 < len(args) and args[i + 1].endswith("cmake_pch.hxx"):
            skip = True
        elif a != "-Winvalid-pch":
            out.append(a)
    return out


def load_entries(root, build, tracked):
    """The build's TUs of the tree, plus tracked .cpp files the build does not compile."""
    entries = {}
    for e in json.load(open(os.path.join(build, "compile_commands.json"))):
        f = os.path.normpath(os.path.join(e["directory"], e["file"]))
        if f.startswith(root + "/") and not f.startswith(build + "/"):
            args = shlex.split(e["command"]) if "command" in e else list(e["arguments"])
            # The compiler enforces -Werror on the strict targets (cmake/warnings.cmake); under
            # it clang-tidy's newer clang would fail a TU on libstdc++ 12's own deprecated
            # internals (get_temporary_buffer inside std::stable_sort), no finding of ours.
            args = without_pch([a for a in args if a != "-Werror"])
            entries.setdefault(f, {"directory": e["directory"], "file": f, "arguments": args})
    # A TU missing from the build (the fuzz targets) is parsed with a test TU's flags.
    template = next((e for f, e in sorted(entries.items()) if "/tests/" in f), None)
    borrowed = []
    for rel in tracked:
        f = os.path.join(root, rel)
        if rel.endswith(".cpp") and f not in entries and template:
            args = [f if a == template["file"] else a for a in template["arguments"]]
            entries[f] = {"directory": template["directory"], "file": f, "arguments": args}
            borrowed.append(rel)
    return entries, borrowed


def preprocess_args(entry, clang):
    """The TU's compile command turned into a preprocessing-only run of `clang`."""
    args = list(entry["arguments"])
    while args and os.path.basename(args[0]) in ("ccache", "sccache"):
        args.pop(0)
    out, skip = [clang], False
    for a in args[1:]:
        if skip:
            skip = False
        elif a == "-o":
            skip = True
        elif a != "-c":
            out.append(a)
    return out + ["-E", "-C", "-o", "-"]


class Cache:
    def __init__(self, root, build, tidy_bin, filter_key):
        location = os.environ.get("OLCB_LINT_CACHE",
                                  os.path.join(os.path.expanduser("~"), ".cache", "olcb-lint"))
        self.dir = None if location == "off" else location
        self.root, self.build = root, build
        version = subprocess.run([tidy_bin, "--version"], capture_output=True, text=True).stdout
        configs = subprocess.run(["git", "ls-files", "*.clang-tidy", ".clang-tidy"], cwd=root,
                                 capture_output=True, text=True).stdout.split()
        base = hashlib.sha256(version.encode())
        for rel in sorted(configs):
            base.update(rel.encode() + b"\0" + open(os.path.join(root, rel), "rb").read())
        base.update(filter_key.encode())
        self.base = base
        # The clang of the same release as clang-tidy preprocesses (clang-tidy-19: clang++-19).
        suffix = re.sub(r"^clang-tidy", "", os.path.basename(tidy_bin))
        self.clang = shutil.which("clang++" + suffix) or shutil.which("clang++")
        self.hits = 0
        if self.dir and self.clang:
            os.makedirs(self.dir, exist_ok=True)
        else:
            self.dir = None

    def relative(self, text):
        return text.replace(self.build, ROOT_MARK + "/<build>").replace(self.root, ROOT_MARK)

    def key(self, entry):
        if not self.dir:
            return None
        p = subprocess.run(preprocess_args(entry, self.clang), cwd=entry["directory"],
                           capture_output=True)
        if p.returncode != 0:
            return None  # clang-tidy will say why
        h = self.base.copy()
        h.update(self.relative(" ".join(entry["arguments"][1:])).encode() + b"\0")
        h.update(p.stdout.replace(self.root.encode(), ROOT_MARK.encode()))
        return h.hexdigest()

    def get(self, key):
        if not key:
            return None
        try:
            with open(os.path.join(self.dir, key + ".json")) as f:
                found = json.load(f)
        except (OSError, ValueError):
            return None
        self.hits += 1
        return found["rc"], found["text"].replace(ROOT_MARK, self.root)

    def put(self, key, rc, text):
        if not key:
            return
        path = os.path.join(self.dir, key + ".json")
        with open(path + ".tmp", "w") as f:
            json.dump({"rc": rc, "text": text.replace(self.root, ROOT_MARK)}, f)
        os.replace(path + ".tmp", path)


HEAD = re.compile(r"^(/[^:]+):(\d+):(\d+): (error|warning): ")
NOISE = re.compile(r"^\d+ (warning|error)s? (generated|treated as errors)|^Error while processing|"
                   r"^Suppressed \d+ warnings|^Use -header-filter|^Use -system-headers")


def has_diagnostic(text):
    return any(HEAD.match(line) for line in text.splitlines())


def collect(text, findings):
    """Adds each diagnostic of clang-tidy's output (its first line with what follows) once."""
    block = None
    for line in text.splitlines():
        if HEAD.match(line):
            block = findings.setdefault(line, []) if line not in findings else None
            if block is not None:
                block.append(line)
        elif block is not None and not NOISE.match(line):
            block.append(line)
    return has_diagnostic(text)


def main():
    root, build, jobs, tidy_bin = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
    only = sys.argv[5:]
    tracked = subprocess.run(["git", "ls-files", "*.cpp", "*.hpp"], cwd=root, check=True,
                             capture_output=True, text=True).stdout.split()
    dirs = sorted({rel.split("/")[0] for rel in tracked if "/" in rel})
    tail = "/(" + "|".join(map(re.escape, dirs)) + ")/"
    header_filter = "^" + re.escape(root) + tail
    # The key's form of the filter names no checkout: re.escape writes "ci-clone" as "ci\-clone",
    # so replacing the root in the escaped text would miss.
    filter_key = "^" + ROOT_MARK + tail
    entries, borrowed = load_entries(root, build, tracked)
    if only:
        wanted = {os.path.abspath(f) for f in only}
        entries = {f: e for f, e in entries.items() if f in wanted}
        borrowed = [rel for rel in borrowed if os.path.join(root, rel) in wanted]
    db = tempfile.mkdtemp(prefix="olcb-lint-")
    with open(os.path.join(db, "compile_commands.json"), "w") as out:
        json.dump(list(entries.values()), out)
    files = sorted(entries, key=lambda f: -os.path.getsize(f))
    cache = Cache(root, build, tidy_bin, filter_key)
    print(f"{len(files)} translation units", end="")
    print(f" ({len(borrowed)} not in the build, checked with a test's flags: "
          f"{', '.join(borrowed)})" if borrowed else "", end="")
    print(f"; cache {cache.dir}" if cache.dir else "; no cache", flush=True)

    def tidy(f):
        key = cache.key(entries[f])
        cached = cache.get(key)
        if cached:
            return f, cached[0], cached[1], 0.0
        started = time.monotonic()
        p = subprocess.run([tidy_bin, "-p", db, "--quiet", "--header-filter", header_filter, f],
                           capture_output=True, text=True)
        text = p.stdout + p.stderr
        # A crash (signal) or a TU clang-tidy could not process is not a result to keep.
        if p.returncode == 0 or (p.returncode > 0 and has_diagnostic(text)):
            cache.put(key, p.returncode, text)
        return f, p.returncode, text, time.monotonic() - started

    findings, failed, times, done = {}, [], [], 0
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        for future in concurrent.futures.as_completed([pool.submit(tidy, f) for f in files]):
            f, rc, text, seconds = future.result()
            done += 1
            times.append((seconds, f))
            if done * 10 // len(files) != (done - 1) * 10 // len(files):
                print(f"  checked {done}/{len(files)}", flush=True)
            # A TU clang-tidy could not process, with no diagnostic to show, is a finding too.
            if not collect(text, findings) and rc != 0:
                failed.append((f, text.strip().splitlines()[-5:]))
    shutil.rmtree(db)
    report(root, findings, failed, times, cache)
    sys.exit(1 if findings or failed else 0)


def report(root, findings, failed, times, cache):
    def where(first):
        m = HEAD.match(first)
        return m.group(1), int(m.group(2)), int(m.group(3))

    for first in sorted(findings, key=where):
        print("\n".join(findings[first]).replace(root + "/", ""))
    for f, tail in failed:
        print(f"clang-tidy failed on {f.replace(root + '/', '')}:", *tail, sep="\n  ")
    files = {where(first)[0] for first in findings}
    slowest = ", ".join(f"{os.path.relpath(f, root)} {s:.0f} s"
                        for s, f in sorted(times, reverse=True)[:3] if s > 0)
    # CPU time as well as wall time: on a shared machine the wall time says little about CI's.
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    print(f"clang-tidy: {len(findings)} finding(s) in {len(files)} file(s)"
          + (f", {len(failed)} TU(s) failed" if failed else "")
          + f"; {cache.hits}/{len(times)} TUs from the cache"
          + f"; {usage.ru_utime + usage.ru_stime:.0f} s CPU"
          + (f"; slowest: {slowest}" if slowest else ""))


if __name__ == "__main__":
    main()
