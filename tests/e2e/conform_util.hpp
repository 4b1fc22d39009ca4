// Helpers of the suites that run lcc-conform against simnode programs: image snapshots (to
// prove a restore), the check lines of the text report, and the lcc-conform invocation.
#pragma once

#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "e2e/e2e_util.hpp"
#include "support/report_schema.hpp"
#include "support/temp_files.hpp"

#if defined(LCC_CONFORM_PATH)

namespace olcb::e2e {

namespace fs = std::filesystem;

using test_support::read_text;

/// The JSON report at p, parsed (discarded when it is not JSON); a test failure when it breaks
/// docs/report.schema.json, so every report a suite reads is validated.
inline nlohmann::json read_report(const fs::path& p) {
    const std::string text = read_text(p);
    const std::string errors = test::json_report_errors(text);
    EXPECT_EQ(errors, "") << p << " breaks docs/report.schema.json";
    return nlohmann::json::parse(text, nullptr, false);
}

/// Every check of every node of a parsed JSON report, in order.
inline std::vector<nlohmann::json> report_checks(const nlohmann::json& report) {
    std::vector<nlohmann::json> out;
    if (!report.is_object() || !report.contains("nodes")) return out;
    for (const auto& node : report["nodes"])
        for (const auto& c : node["checks"]) out.push_back(c);
    return out;
}

/// A test failure when the JUnit report at p breaks tests/support/junit.xsd.
inline void expect_valid_junit(const fs::path& p) {
    EXPECT_EQ(test::junit_report_errors(read_text(p)), "") << p << " breaks junit.xsd";
}

/// Every image file (except journals) under dir with its contents.
inline std::map<std::string, std::string> snapshot_images(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file() || e.path().extension() == ".journal") continue;
        out[fs::relative(e.path(), dir).string()] = read_text(e.path());
    }
    return out;
}

/// The image files once they equal `expected`, or as they are after a bounded wait: simnode
/// applies journaled writes to its images in the background, so the last restore may lag a bit.
inline std::map<std::string, std::string> settled_images(
    const fs::path& dir, const std::map<std::string, std::string>& expected) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    auto now = snapshot_images(dir);
    while (now != expected && std::chrono::steady_clock::now() < deadline) {
        std::this_thread::sleep_for(milliseconds(20));
        now = snapshot_images(dir);
    }
    return now;
}

#if defined(SIMNODE_PATH)
/// A simnode program serving a scenario on an ephemeral loopback port, its images in a fresh
/// directory; killed when destroyed (and stopping by itself after 5 minutes in any case).
struct Simnode {
    TempDir images{"lcc-conform-e2e-img"};
    std::unique_ptr<Child> child;
    std::uint16_t port = 0;

    /// Starts `--scenario scenario` plus `extra` options (e.g. {"--fault", "reboot-on-write=5"});
    /// a big scenario's fresh images may take `startup` to create.
    explicit Simnode(const fs::path& scenario, std::vector<std::string> extra = {},
                     milliseconds startup = milliseconds(10000)) {
        std::vector<std::string> args = {
            "--scenario",  scenario.string(), "--listen",  "127.0.0.1:0",
            "--image-dir", images.str(),      "--run-for", "300"};
        args.insert(args.end(), extra.begin(), extra.end());
        child = Child::spawn(SIMNODE_PATH, args);
        if (!child) return;
        if (auto p = child->wait_listening(startup)) port = *p;
    }
    /// Waits for the "N node(s) initialized" line: every node has its alias and answers.
    bool wait_initialized(milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (child) {
            const auto left = std::chrono::duration_cast<milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) return false;
            auto line = child->wait_line("simnode: ", left);
            if (!line) return false;
            if (line->find(" initialized") != std::string::npos) return true;
        }
        return false;
    }
    /// HOST:PORT for --connect.
    std::string connect() const { return "127.0.0.1:" + std::to_string(port); }
};
#endif

/// Runs lcc-conform with args; exit code and stdout (bounded).
inline std::pair<int, std::string> conform(const std::vector<std::string>& args,
                                           milliseconds timeout = milliseconds(60000)) {
    return run_program(LCC_CONFORM_PATH, args, timeout);
}

/// The status of every check of the text report: each line "STATUS  id  message" (a SKIP under
/// the FAIL it depends on is indented), and each ID of the passes' block "PASS  N checks: id id"
/// with its indented continuation lines.
inline std::vector<std::pair<std::string, std::string>> check_lines(const std::string& out) {
    std::vector<std::pair<std::string, std::string>> lines;
    std::istringstream in(out);
    bool in_passes = false;
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string status, id, word;
        words >> status >> id;
        if (status == "PASS" && !id.empty() && std::isdigit(static_cast<unsigned char>(id[0]))) {
            words >> word;  // "checks:"
            while (words >> word) lines.emplace_back("PASS", word);
            in_passes = true;
        } else if (status == "PASS" || status == "FAIL" || status == "WARN" || status == "SKIP") {
            lines.emplace_back(status, id);
            in_passes = false;
        } else if (in_passes && line.starts_with(" ")) {
            std::istringstream ids(line);
            while (ids >> word) lines.emplace_back("PASS", word);
        } else {
            in_passes = false;
        }
    }
    return lines;
}

}  // namespace olcb::e2e

#endif  // LCC_CONFORM_PATH
