#!/usr/bin/env python3
"""docs/ci.md's jobs, as CI maintainers copy them: each YAML block parses (PyYAML, an independent
parser), every job that checks a node runs ci/conform-node with options ci/conform-node has,
after `ci/setup --runtime` and without building, and the JUnit report and the HTML page are
published. Usage: ci_doc_test.py SOURCE_DIR"""
import re
import subprocess
import sys
from pathlib import Path

import yaml

root = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
doc = (root / "docs" / "ci.md").read_text()
blocks = re.findall(r"^```yaml\n(.*?)^```$", doc, re.S | re.M)
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


help_text = subprocess.run([str(root / "ci" / "conform-node"), "--help"], capture_output=True,
                           text=True, check=True).stdout
known = set(re.findall(r"(--[a-z-]+)", help_text))


def conform_commands(commands, where):
    """The ci/conform-node lines of a job, each option checked against its --help."""
    runs = [c for c in commands if "ci/conform-node" in c]
    for c in runs:
        words = c.split()
        start = next(i for i, w in enumerate(words) if w.endswith("ci/conform-node"))
        options = [w for w in words[start + 1:] if w.startswith("--")]
        for o in options:
            if o == "--":
                break
            check(o in known, f"{where}: ci/conform-node has no option {o}")
    return runs


def before_conform(commands, where):
    """Nothing is built where the node is checked; the runtime packages come first."""
    runs = [i for i, c in enumerate(commands) if "ci/conform-node" in c]
    setup = [i for i, c in enumerate(commands) if "ci/setup --runtime" in c]
    check(setup and runs and setup[0] < runs[0], f"{where}: ci/setup --runtime before the run")
    check(not any("cmake" in c or "ci/setup --build" in c or c.strip() == "ci/setup"
                  for c in commands), f"{where}: a job that checks a node builds nothing")


check(len(blocks) == 2, f"docs/ci.md has {len(blocks)} YAML blocks, want GitHub's and GitLab's")
github = gitlab = None
for text in blocks:
    data = yaml.safe_load(text)
    if text.startswith("# .github/workflows/"):
        github = data
    elif text.startswith("# .gitlab-ci.yml"):
        gitlab = data

check(github is not None, "no GitHub Actions workflow")
if github:
    jobs = github["jobs"]
    routes = set()
    for name, job in jobs.items():
        steps = job["steps"]
        commands = [s.get("run", "") for s in steps]
        if not any("ci/conform-node" in c for c in commands):
            continue
        where = f"GitHub job {name}"
        routes.update(r for c in conform_commands(commands, where) for r in ("--tcp", "--vcan")
                      if r in c)
        before_conform(commands, where)
        check(name != "build" and "build" in job.get("needs", []), f"{where}: needs the build")
        uses = [s.get("uses", "") for s in steps]
        junit = [s for s in steps if s.get("uses", "").startswith("mikepenz/action-junit-report")]
        check(junit and junit[0]["with"]["report_paths"].endswith("report.xml"),
              f"{where}: JUnit to a check run")
        check(all(s.get("if") == "always()" for s in junit), f"{where}: JUnit even on failure")
        uploads = [s for s in steps if s.get("uses", "").startswith("actions/upload-artifact")]
        check(uploads and uploads[0].get("if") == "always()" and
              "lcc-conform-reports" in uploads[0]["with"]["path"],
              f"{where}: the reports (HTML page) as an artifact, even on failure")
        check(any(u.startswith("actions/checkout") for u in uses), f"{where}: checks out")
    check(routes == {"--tcp", "--vcan"}, f"GitHub: TCP and vcan jobs, got {sorted(routes)}")
    check(github.get("permissions", {}).get("checks") == "write", "GitHub: checks: write")

check(gitlab is not None, "no GitLab CI file")
if gitlab:
    template = gitlab[".conform"]
    reports = template["artifacts"]["reports"]
    check(reports["junit"].endswith("report.xml"), "GitLab: JUnit to the test view")
    check(template["artifacts"]["when"] == "always", "GitLab: artifacts even on failure")
    check("lcc-conform-reports/" in template["artifacts"]["paths"], "GitLab: the HTML page")
    routes = set()
    for name, job in gitlab.items():
        if name.startswith(".") or not isinstance(job, dict) or "script" not in job:
            continue
        commands = template["before_script"] + job["script"] if job.get("extends") else job["script"]
        if not any("ci/conform-node" in c for c in commands):
            continue
        where = f"GitLab job {name}"
        check(job.get("extends") == ".conform", f"{where}: extends .conform")
        routes.update(r for c in conform_commands(commands, where) for r in ("--tcp", "--vcan")
                      if r in c)
        before_conform(commands, where)
    check(routes == {"--tcp", "--vcan"}, f"GitLab: TCP and vcan jobs, got {sorted(routes)}")
    check(gitlab["build"]["artifacts"]["paths"] == ["build/simnode/simnode",
                                                    "build/conformance/lcc-conform"],
          "GitLab: the build ships the two programs")

# This project's CI runs the same script.
check("ci/conform-node" in (root / "ci" / "test").read_text(), "ci/test runs ci/conform-node")

for f in failures:
    print("FAIL:", f)
print(f"ci_doc_test: {len(blocks)} YAML blocks, {len(failures)} failures")
sys.exit(1 if failures else 0)
