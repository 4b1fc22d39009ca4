// The HTML pages in a real browser: lcc-conform --html against simnode (the default scenario, and
// the int-byte-order fault opened with its FAIL filter) and lcc-cdi render --html (the sample CDI
// and the largest corpus CDI), each loaded in headless Chromium. Each test checks the DOM the
// page scripts built against the data in the page, that the browser console stayed silent (the
// scripts never log, so any console line is an error, a CSP refusal or an uncaught exception),
// and keeps a screenshot under <build>/artifacts/html/ for CI.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH) && defined(LCC_CDI_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";
// One browser run: the page's scripts get this much virtual time, the process this much real.
constexpr const char* kVirtualTimeMs = "3000";
constexpr const char* kBrowserSeconds = "40";

// Debian's chromium (ci/setup installs it), or the one OLCB_CHROMIUM names.
std::string find_chromium() {
    if (const char* env = std::getenv("OLCB_CHROMIUM"); env != nullptr && *env != '\0') return env;
    const char* path = std::getenv("PATH");
    std::istringstream dirs(path != nullptr ? path : "/usr/bin");
    for (std::string dir; std::getline(dirs, dir, ':');) {
        for (const char* name : {"chromium", "chromium-browser"}) {
            const fs::path candidate = fs::path(dir) / name;
            if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
        }
    }
    return {};
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

// The JSON the page's scripts render, from the page itself.
nlohmann::json page_data(const std::string& page) {
    const std::string open = "id=\"page-data\">";
    const auto begin = page.find(open);
    if (begin == std::string::npos) return nullptr;
    const auto end = page.find("</script>", begin);
    return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()),
                                 nullptr, false);
}

// What the browser made of a page.
struct PageView {
    int code = -1;
    bool ready = false;  ///< the page script ran to its end (<body data-ready="true">)
    /// The page's content after the scripts ran (--dump-dom), without the stylesheet and scripts
    /// (their text would match what the tests count).
    std::string dom;
    std::vector<std::string> console;  ///< every console line of the browser's log
    fs::path screenshot;
};

class HtmlPage : public ::testing::Test {
protected:
    void SetUp() override {
        chromium_ = find_chromium();
        if (chromium_.empty()) GTEST_SKIP() << "chromium not found (ci/setup installs it)";
    }

    // Opens file://page#fragment in headless Chromium (a window `height` pixels tall), bounded
    // in time; its console goes to a log file, its own chatter (D-Bus, GPU) to /dev/null.
    PageView view(const fs::path& page, const std::string& fragment, const std::string& name,
                  int height = 2000) {
        PageView out;
        const fs::path shots = fs::path(OLCB_BINARY_DIR) / "artifacts" / "html";
        fs::create_directories(shots);
        out.screenshot = shots / (name + ".png");
        fs::remove(out.screenshot);
        const fs::path log = work_.path() / (name + ".log");
        std::vector<std::string> args = {
            "-c",
            "exec \"$@\" 2>/dev/null",
            "sh",
            "timeout",
            "-k",
            "5",
            kBrowserSeconds,
            chromium_,
            "--headless",
            "--disable-gpu",
            "--no-first-run",
            "--disable-extensions",
            "--disable-background-networking",
            "--disable-sync",
            "--disable-component-update",
            "--disable-default-apps",
            "--user-data-dir=" + (work_.path() / ("profile-" + name)).string(),
            "--enable-logging",
            "--log-file=" + log.string(),
            "--v=0",
            std::string("--virtual-time-budget=") + kVirtualTimeMs,
            "--window-size=1280," + std::to_string(height),
            "--hide-scrollbars",
            "--screenshot=" + out.screenshot.string(),
            "--dump-dom",
            "file://" + fs::absolute(page).string() + (fragment.empty() ? "" : "#" + fragment)};
        // The sandbox needs user namespaces a root process in a container does not get.
        if (::geteuid() == 0) args.insert(args.begin() + 9, "--no-sandbox");
        auto [code, dom] = run_program("/bin/sh", args, milliseconds(50000));
        out.code = code;
        out.ready = dom.find("<body data-ready=\"true\">") != std::string::npos;
        const auto app = dom.find("<div id=\"app\">");
        out.dom = app == std::string::npos ? dom : dom.substr(app, dom.find("<script", app) - app);
        std::istringstream lines(read_text(log));
        for (std::string line; std::getline(lines, line);) {
            if (line.find(":CONSOLE") != std::string::npos) out.console.push_back(line);
        }
        std::cout << "screenshot: " << out.screenshot.string() << "\n";
        return out;
    }

    // What every page must show: the scripts ran to the end, nothing on the console, a PNG.
    static void expect_clean(const PageView& v) {
        EXPECT_EQ(v.code, 0) << "chromium exit status";
        EXPECT_TRUE(v.ready) << "the page script did not finish:\n" << v.dom.substr(0, 2000);
        for (const std::string& line : v.console) ADD_FAILURE() << "console: " << line;
        const std::string png = read_text(v.screenshot);
        EXPECT_GT(png.size(), 10000u) << v.screenshot;
        EXPECT_EQ(png.substr(0, 4), "\x89PNG") << v.screenshot;
    }

    // Every listed variable of every space is one bar start of its class, and gaps, overlaps and
    // summaries are all drawn.
    static void expect_map_bars(const std::string& dom, const nlohmann::json& maps,
                                const std::function<std::string(const nlohmann::json&)>& cls) {
        std::map<std::string, std::size_t> want;
        std::size_t gaps = 0, overlaps = 0, summaries = 0;
        for (const auto& space : maps) {
            for (const auto& v : space["variables"]) ++want[cls(v)];
            gaps += space["gaps"].size();
            overlaps += space["overlaps"].size();
            for (const auto& s : space["summaries"]) summaries += s["size"] != 0 ? 1 : 0;
        }
        ASSERT_FALSE(want.empty());
        for (const auto& [c, n] : want) {
            EXPECT_EQ(count(dom, "class=\"mm-item mm-var " + c + " mm-start"), n)
                << c;  // maybe picked
        }
        EXPECT_EQ(count(dom, "class=\"mm-item mm-gap mm-start\""), gaps);
        EXPECT_EQ(count(dom, "class=\"mm-item mm-overlap mm-start\""), overlaps);
        EXPECT_EQ(count(dom, "class=\"mm-item mm-summary mm-start\""), summaries);
        EXPECT_EQ(count(dom, "<section class=\"mm\""), maps.size());
    }

    // lcc-conform --html against simnode running `scenario`; the page and the text report.
    std::pair<int, std::string> conform_html(const std::string& scenario, const fs::path& page) {
        Simnode sim(source_path(scenario));
        EXPECT_NE(sim.port, 0) << "simnode did not start";
        if (sim.port == 0) return {-1, ""};
        return conform({"--connect", sim.connect(), "--node", kNode, "--backup",
                        (work_.path() / "safety.txt").string(), "--html", page.string()});
    }

    std::string chromium_;
    TempDir work_{"html-page-e2e"};
};

std::string verdict_class(const nlohmann::json& v) {
    return "v-" + v["verdict"].get<std::string>();
}

TEST_F(HtmlPage, ConformDefaultScenario) {
    const fs::path page = work_.path() / "default.html";
    const auto [code, text] = conform_html("scenarios/default.ini", page);
    EXPECT_EQ(code, 0) << text;
    const std::string html = read_text(page);
    const nlohmann::json data = page_data(html);
    ASSERT_TRUE(data.is_object()) << "no page data in " << page;
    ASSERT_EQ(data["nodes"].size(), 1u);
    const nlohmann::json& node = data["nodes"][0];
    EXPECT_EQ(node["checks"].size(), check_lines(text).size());

    const PageView v = view(page, "", "conform-default", 5000);
    expect_clean(v);
    std::map<std::string, std::size_t> rows;
    for (const auto& c : node["checks"]) ++rows[c["status"].get<std::string>()];
    EXPECT_EQ(rows.count("FAIL"), 0u);
    for (const char* status : {"PASS", "FAIL", "WARN", "SKIP"}) {
        EXPECT_EQ(count(v.dom, std::string("data-status=\"") + status + "\">"), rows[status])
            << status;
    }
    EXPECT_EQ(count(v.dom, "hidden=\"\">"), 0u);  // no filter: every row shown
    expect_map_bars(v.dom, node["memory_map"], verdict_class);
    EXPECT_GT(count(v.dom, "mm-var v-verified mm-start"), 10u);
    EXPECT_EQ(count(v.dom, "mm-var v-protected mm-start"), 1u);  // the <action>
    EXPECT_EQ(count(v.dom, "mm-var v-failed"), 0u);
}

TEST_F(HtmlPage, ConformFaultScenarioWithTheFailFilter) {
    const fs::path page = work_.path() / "fault.html";
    const auto [code, text] = conform_html("scenarios/faults/int-byte-order.ini", page);
    EXPECT_EQ(code, 1) << text;
    const nlohmann::json data = page_data(read_text(page));
    ASSERT_TRUE(data.is_object());
    const nlohmann::json& node = data["nodes"][0];
    std::size_t fails = 0;
    for (const auto& c : node["checks"]) fails += c["status"] == "FAIL" ? 1 : 0;
    ASSERT_GT(fails, 0u);

    // Trim (variable 1 of space 253) opened as by a click: its values written and read back.
    const PageView v = view(page, "status=FAIL&pick=253:1", "conform-int-byte-order", 2300);
    expect_clean(v);
    // Only the FAIL rows are shown, and only the FAIL toggle is on.
    EXPECT_EQ(count(v.dom, "data-status=\"FAIL\">"), fails);
    EXPECT_EQ(count(v.dom, "data-status=\"FAIL\" hidden=\"\">"), 0u);
    EXPECT_EQ(count(v.dom, "<tr class=\"check"), node["checks"].size());
    EXPECT_EQ(count(v.dom, "hidden=\"\">"), node["checks"].size() - fails);
    EXPECT_EQ(count(v.dom, "aria-pressed=\"true\""), 1u);
    EXPECT_NE(v.dom.find("class=\"filter s-fail\" type=\"button\" data-status=\"FAIL\" "
                         "aria-pressed=\"true\""),
              std::string::npos);
    EXPECT_NE(v.dom.find(std::to_string(fails) + " of "), std::string::npos);
    expect_map_bars(v.dom, node["memory_map"], verdict_class);
    EXPECT_GE(count(v.dom, "mm-var v-failed mm-start"), 1u);  // Trim, where writing stopped
    const auto panel = v.dom.find("<div class=\"mm-detail\"><strong>Settings.Trim</strong>");
    ASSERT_NE(panel, std::string::npos);
    const std::string detail = v.dom.substr(panel, v.dom.find("</table>", panel) - panel);
    EXPECT_NE(detail.find("verdict: failed"), std::string::npos) << detail;
    EXPECT_NE(detail.find("<td>-1000</td><td>FC 18</td><td>6396</td><td>18 FC</td>"),
              std::string::npos)
        << detail;
}

// Issue 34: a failing run's page opens on what failed. Without a fragment it shows the FAIL and
// WARN rows only, FAILs first, and the first row is on the first screen (1280x900): a probe
// script after the page's own notes where the first shown row is, at the top of the page (the
// dump of a page is bounded).
TEST_F(HtmlPage, AFailingRunOpensOnItsFailures) {
    const fs::path page = work_.path() / "failing.html";
    const auto [code, text] = conform_html("scenarios/faults/int-byte-order.ini", page);
    EXPECT_EQ(code, 1) << text;
    std::string html = read_text(page);
    const nlohmann::json data = page_data(html);
    ASSERT_TRUE(data.is_object());
    const nlohmann::json& node = data["nodes"][0];
    std::size_t findings = 0;
    for (const auto& c : node["checks"]) findings += c["status"] == "FAIL" || c["status"] == "WARN";
    ASSERT_GT(findings, 0u);
    html.insert(html.rfind("</body>"),
                "<script>{const row = [...document.querySelectorAll('tr.check')]"
                ".find((r) => !r.hidden); const box = row.getBoundingClientRect();"
                "const note = document.createElement('div'); note.dataset.firstRow = "
                "row.dataset.status + ' ' + (box.top >= 0 && box.bottom <= window.innerHeight ? "
                "'on-screen' : 'below'); document.getElementById('app').prepend(note);}"
                "</script>\n");
    std::ofstream(page, std::ios::binary | std::ios::trunc) << html;
    const PageView v = view(page, "", "conform-opens-on-failures", 900);
    expect_clean(v);
    EXPECT_EQ(count(v.dom, "data-first-row=\"FAIL on-screen\""), 1u) << v.dom.substr(0, 3000);
    EXPECT_EQ(count(v.dom, "hidden=\"\">"), node["checks"].size() - findings);
    EXPECT_EQ(count(v.dom, "aria-pressed=\"true\""), 2u);  // FAIL and WARN
    // The rows in order: every FAIL before the first row of another status.
    const auto first_other = std::min({v.dom.find("<tr class=\"check s-warn\""),
                                       v.dom.find("<tr class=\"check s-pass\""),
                                       v.dom.find("<tr class=\"check s-skip\"")});
    ASSERT_NE(first_other, std::string::npos);
    EXPECT_LT(v.dom.find("<tr class=\"check s-fail\""), first_other);
    EXPECT_EQ(v.dom.find("<tr class=\"check s-fail\"", first_other), std::string::npos);
}

// The console check itself: a page whose script throws is caught.
TEST_F(HtmlPage, ConsoleErrorsAreSeen) {
    const fs::path cdi_page = work_.path() / "broken.html";
    const auto [code, html] =
        run_program(LCC_CDI_PATH, {"render", "--html", source_path("scenarios/one-line.xml")});
    ASSERT_EQ(code, 0);
    std::string broken = html;
    broken.insert(broken.rfind("</body>"), "<script>missingFunction();</script>\n");
    std::ofstream(cdi_page, std::ios::binary) << broken;
    const PageView v = view(cdi_page, "", "console-error-self-test", 600);
    EXPECT_TRUE(v.ready);
    ASSERT_EQ(v.console.size(), 1u);
    EXPECT_NE(v.console[0].find("missingFunction is not defined"), std::string::npos)
        << v.console[0];
}

// The page is written on every exit, a connection error (exit 2) included, naming the cause.
TEST(HtmlReport, WrittenOnAnErrorExit) {
    TempDir out("html-page-error");
    const fs::path page = out.path() / "r.html";
    const auto [code, text] = conform({"--connect", "127.0.0.1:1", "--html", page.string()});
    EXPECT_EQ(code, 2) << text;
    const nlohmann::json data = page_data(read_text(page));
    ASSERT_TRUE(data.is_object()) << "no page at " << page;
    EXPECT_TRUE(data["nodes"].empty());
    EXPECT_FALSE(data["run"]["error"].get<std::string>().empty());
}

std::string type_class(const nlohmann::json& v) {
    static const std::set<std::string> known = {"int",    "string", "eventid", "float",
                                                "action", "blob",   "bit"};
    const std::string type = v["type"];
    return "t-" + (known.count(type) ? type : std::string("other"));
}

// Renders `cdi` with lcc-cdi render --html; the page path.
fs::path render_html(const fs::path& cdi, const fs::path& page) {
    const auto [code, html] = run_program(LCC_CDI_PATH, {"render", "--html", cdi.string()});
    EXPECT_EQ(code, 0) << cdi;
    std::ofstream(page, std::ios::binary) << html;
    return page;
}

// The maps a CDI page shows: its space's map in every segment's tab.
nlohmann::json maps_shown(const nlohmann::json& data) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& segment : data["segments"]) {
        for (const auto& space : data["memory_map"]) {
            if (space["space"] == segment["space"]) out.push_back(space);
        }
    }
    return out;
}

TEST_F(HtmlPage, CdiSampleWithHints) {
    const fs::path page =
        render_html(source_path("scenarios/default.xml"), work_.path() / "default-cdi.html");
    const nlohmann::json data = page_data(read_text(page));
    ASSERT_TRUE(data.is_object());
    const PageView v = view(page, "segment=2", "cdi-default");
    expect_clean(v);
    EXPECT_EQ(count(v.dom, "role=\"tab\""), data["segments"].size());
    EXPECT_EQ(count(v.dom, "aria-selected=\"true\">Settings</button>"), 1u);
    // The 1.4 hints as a configuration tool shows them.
    EXPECT_EQ(count(v.dom, "type=\"checkbox\""), 1u);
    EXPECT_EQ(count(v.dom, "type=\"range\""), 1u);
    EXPECT_EQ(count(v.dom, "<output"), 1u);         // slider showValue
    EXPECT_EQ(count(v.dom, "type=\"radio\""), 3u);  // Mode's three map entries
    // The replicated group: one tab per replica, numbered by its repname.
    for (int i = 1; i <= 4; ++i) {
        EXPECT_EQ(count(v.dom, ">Port " + std::to_string(i) + "</button>"), 1u) << i;
    }
    EXPECT_NE(v.dom.find("<legend>Port \xE2\x80\x94 Port 1</legend>"), std::string::npos);
    EXPECT_NE(v.dom.find(">Identify</button>"), std::string::npos);  // the action's buttonText
    expect_map_bars(v.dom, maps_shown(data), type_class);
}

TEST_F(HtmlPage, CdiLargestCorpusFile) {
    const fs::path dir = fs::path(OLCB_SHARED_DIR) / "corpus" / "cdi";
    if (!fs::is_directory(dir)) GTEST_SKIP() << "no corpus at " << dir << " (../shared absent)";
    fs::path largest;
    for (const auto& e : fs::directory_iterator(dir)) {
        if (e.path().extension() != ".xml") continue;
        if (largest.empty() || e.file_size() > fs::file_size(largest)) largest = e.path();
    }
    ASSERT_FALSE(largest.empty());
    std::cout << "largest corpus CDI: " << largest.filename().string() << "\n";
    const fs::path page = render_html(largest, work_.path() / "largest-cdi.html");
    const nlohmann::json data = page_data(read_text(page));
    ASSERT_TRUE(data.is_object());
    const PageView v = view(page, "", "cdi-largest-corpus");
    expect_clean(v);
    EXPECT_EQ(count(v.dom, "role=\"tab\""), data["segments"].size());
    EXPECT_EQ(count(v.dom, "role=\"tabpanel\""), data["segments"].size());
    EXPECT_EQ(count(v.dom, "class=\"var\""),
              count(read_text(page), "\"kind\":\"") - count(read_text(page), "\"kind\":\"group\""));
    expect_map_bars(v.dom, maps_shown(data), type_class);
}

}  // namespace
}  // namespace olcb::e2e

#endif
