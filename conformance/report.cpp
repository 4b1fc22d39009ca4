#include "conformance/report.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <pugixml.hpp>
#include <sstream>

namespace olcb::conform {
namespace {

const char* colour_of(Status status) {
    switch (status) {
        case Status::kPass:
            return "\033[32m";
        case Status::kFail:
            return "\033[31m";
        case Status::kWarn:
            return "\033[33m";
        case Status::kSkip:
            return "\033[36m";
    }
    return "";
}

// Node text comes from the device under test: keep XML and terminals safe from control bytes.
std::string printable(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (unsigned char c : text) {
        out.push_back(c < 0x20 || c == 0x7F ? '?' : static_cast<char>(c));
    }
    return out;
}

nlohmann::json node_json(const NodeReport& report) {
    nlohmann::json checks = nlohmann::json::array();
    for (const CheckResult& c : report.checks) {
        nlohmann::json j = {{"id", c.id},
                            {"category", std::string(category_name(c.category))},
                            {"status", std::string(status_name(c.status))},
                            {"message", c.message},
                            {"section", c.section}};
        if (!c.expected.empty()) j["expected"] = c.expected;
        if (!c.seen.empty()) j["seen"] = c.seen;
        if (!c.details.empty()) j["details"] = c.details;
        checks.push_back(std::move(j));
    }
    Summary s = summarize({report});
    const RunTiming& t = report.timing;
    auto ms = [](Duration d) {
        return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
    };
    nlohmann::json timing = {{"silence_ms", ms(t.silence)},
                             {"answer_ms", ms(t.answer)},
                             {"reply_ms", ms(t.reply)},
                             {"quiet_ms", ms(t.quiet)},
                             {"scale", t.scale}};
    if (t.latency) {
        timing["latency_ms"] = ms(*t.latency);
        timing["worst_ms"] = ms(t.worst);
    }
    return {{"node", {{"id", report.node_id}, {"name", report.name}}},
            {"timing", std::move(timing)},
            {"checks", std::move(checks)},
            {"summary",
             {{"pass", s.pass},
              {"fail", s.fail},
              {"warn", s.warn},
              {"skip", s.skip},
              {"total", s.total()},
              {"restore", report.restore_summary}}}};
}

// Node names and messages carry the node's own bytes, which may not be UTF-8: they are written
// with U+FFFD in place of invalid bytes instead of aborting the report (and the run) on them.
std::string dump_json(const nlohmann::json& root) {
    return root.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

std::string format_duration(double seconds) {
    if (seconds < 0) seconds = 0;
    const long long total = std::llround(seconds);
    char buf[32];
    std::snprintf(buf, sizeof buf, "%lld:%02lld", total / 60, total % 60);
    return buf;
}

}  // namespace

Summary summarize(const std::vector<NodeReport>& reports) {
    Summary s;
    for (const NodeReport& r : reports) {
        s.pass += r.count(Status::kPass);
        s.fail += r.count(Status::kFail);
        s.warn += r.count(Status::kWarn);
        s.skip += r.count(Status::kSkip);
    }
    return s;
}

std::string format_check(const CheckResult& check, bool colour) {
    std::string line;
    if (colour) line += colour_of(check.status);
    line += status_name(check.status);
    if (colour) line += "\033[0m";
    line += "  " + check.id;
    if (!check.message.empty()) line += "  " + printable(check.message);
    if (check.status == Status::kFail || check.status == Status::kWarn) {
        if (!check.expected.empty()) line += "\n      expected: " + printable(check.expected);
        if (!check.seen.empty()) line += "\n      seen:     " + printable(check.seen);
        if (!check.section.empty()) line += "\n      section:  " + check.section;
    }
    // Details (every CDI error, every merged result) under the line, the first few only.
    constexpr std::size_t kShown = 10;
    for (std::size_t i = 0; i < check.details.size() && i < kShown; ++i)
        line += "\n      - " + printable(check.details[i]);
    if (check.details.size() > kShown)
        line +=
            "\n      ... " + std::to_string(check.details.size() - kShown) + " more (see --json)";
    return line;
}

void write_text(std::ostream& out, const NodeReport& report, bool colour) {
    out << "node " << report.node_id;
    if (!report.name.empty()) out << "  " << printable(report.name);
    out << '\n';
    out << "timing: " << report.timing.describe() << '\n';
    for (const CheckResult& c : report.checks) out << format_check(c, colour) << '\n';
    if (!report.restore_summary.empty()) out << "restore: " << report.restore_summary << '\n';
    Summary s = summarize({report});
    out << s.total() << " checks: " << s.pass << " passed, " << s.fail << " failed, " << s.warn
        << " warnings, " << s.skip << " skipped\n";
}

std::string to_json(const std::vector<NodeReport>& reports, const RunInfo& run) {
    auto extras = [&](nlohmann::json& root) {
        if (!run.error.empty()) root["error"] = printable(run.error);
        if (!run.late_nodes.empty()) root["late_nodes"] = run.late_nodes;
    };
    if (reports.size() == 1) {
        nlohmann::json root = node_json(reports.front());
        extras(root);
        return dump_json(root);
    }
    nlohmann::json nodes = nlohmann::json::array();
    for (const NodeReport& r : reports) nodes.push_back(node_json(r));
    Summary s = summarize(reports);
    nlohmann::json root = {{"nodes", std::move(nodes)},
                           {"summary",
                            {{"pass", s.pass},
                             {"fail", s.fail},
                             {"warn", s.warn},
                             {"skip", s.skip},
                             {"total", s.total()}}}};
    extras(root);
    return dump_json(root);
}

std::string to_junit(const std::vector<NodeReport>& reports, const RunInfo& run) {
    pugi::xml_document doc;
    auto decl = doc.append_child(pugi::node_declaration);
    decl.append_attribute("version") = "1.0";
    decl.append_attribute("encoding") = "UTF-8";
    auto suites = doc.append_child("testsuites");
    suites.append_attribute("name") = "lcc-conform";
    Summary all = summarize(reports);
    suites.append_attribute("tests") = static_cast<unsigned long long>(all.total());
    suites.append_attribute("failures") = static_cast<unsigned long long>(all.fail);
    suites.append_attribute("skipped") = static_cast<unsigned long long>(all.skip);
    for (const NodeReport& r : reports) {
        Summary s = summarize({r});
        auto suite = suites.append_child("testsuite");
        suite.append_attribute("name") = ("node " + r.node_id).c_str();
        suite.append_attribute("tests") = static_cast<unsigned long long>(s.total());
        suite.append_attribute("failures") = static_cast<unsigned long long>(s.fail);
        suite.append_attribute("errors") = 0;
        suite.append_attribute("skipped") = static_cast<unsigned long long>(s.skip);
        for (const CheckResult& c : r.checks) {
            auto tc = suite.append_child("testcase");
            tc.append_attribute("classname") = std::string(category_name(c.category)).c_str();
            tc.append_attribute("name") = c.id.c_str();
            std::string detail = printable(c.message);
            if (!c.expected.empty()) detail += "\nexpected: " + printable(c.expected);
            if (!c.seen.empty()) detail += "\nseen: " + printable(c.seen);
            if (!c.section.empty()) detail += "\nsection: " + printable(c.section);
            for (const std::string& d : c.details) detail += "\n- " + printable(d);
            if (c.status == Status::kFail) {
                auto f = tc.append_child("failure");
                f.append_attribute("message") = printable(c.message).c_str();
                f.append_attribute("type") = std::string(category_name(c.category)).c_str();
                f.text().set(detail.c_str());
            } else if (c.status == Status::kSkip) {
                tc.append_child("skipped").append_attribute("message") =
                    printable(c.message).c_str();
            } else if (c.status == Status::kWarn) {
                tc.append_child("system-out").text().set(("WARN: " + detail).c_str());
            }
        }
        if (!r.restore_summary.empty()) {
            suite.append_child("system-out")
                .text()
                .set(("restore: " + printable(r.restore_summary)).c_str());
        }
    }
    if (!run.error.empty()) {
        // CI must see a red result, not "no tests", when the run could not check anything.
        auto suite = suites.append_child("testsuite");
        suite.append_attribute("name") = "lcc-conform";
        suite.append_attribute("tests") = 1;
        suite.append_attribute("failures") = 0;
        suite.append_attribute("errors") = 1;
        suite.append_attribute("skipped") = 0;
        auto tc = suite.append_child("testcase");
        tc.append_attribute("classname") = "run";
        tc.append_attribute("name") = "run";
        auto e = tc.append_child("error");
        e.append_attribute("message") = printable(run.error).c_str();
        e.append_attribute("type") = "run";
        suites.append_attribute("errors") = 1;
    }
    std::ostringstream out;
    doc.save(out, "  ", pugi::format_default, pugi::encoding_utf8);
    return out.str();
}

bool write_file(const std::string& path, const std::string& text, std::string& error) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) {
        error = "cannot open " + path + " for writing";
        return false;
    }
    f << text;
    f.flush();
    if (!f) {
        error = "cannot write " + path;
        return false;
    }
    return true;
}

bool is_terminal(int fd) {
    return ::isatty(fd) == 1;
}

void ProgressBar::start(std::string label, std::size_t total,
                        std::chrono::steady_clock::time_point now) {
    label_ = std::move(label);
    total_ = total;
    started_ = now;
}

std::string ProgressBar::render(std::size_t done, std::chrono::steady_clock::time_point now) const {
    constexpr int kWidth = 30;
    double elapsed = std::chrono::duration<double>(now - started_).count();
    std::string line = label_ + " ";
    if (total_ > 0) {
        std::size_t shown = done > total_ ? total_ : done;
        int filled =
            static_cast<int>(static_cast<double>(shown) * kWidth / static_cast<double>(total_));
        line += "[" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] ";
        line += std::to_string(shown) + "/" + std::to_string(total_) + " B";
        if (shown > 0 && elapsed > 0) {
            double rate = static_cast<double>(shown) / elapsed;
            line += " ETA " + format_duration(static_cast<double>(total_ - shown) / rate);
        } else {
            line += " ETA --:--";
        }
    } else {
        line += std::to_string(done) + " B";
    }
    if (elapsed > 0 && done > 0) {
        line += " (" + std::to_string(std::llround(static_cast<double>(done) / elapsed)) + " B/s)";
    }
    return line;
}

void ProgressBar::update(std::size_t done, std::chrono::steady_clock::time_point now) {
    if (!enabled_) return;
    out_ << '\r' << render(done, now) << "\033[K" << std::flush;
    drawn_ = true;
}

void ProgressBar::finish() {
    if (!enabled_ || !drawn_) return;
    out_ << "\r\033[K" << std::flush;
    drawn_ = false;
}

}  // namespace olcb::conform
