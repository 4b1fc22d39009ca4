// What simnode says when it starts: one line per node (ID, CDI file, faults, images), the
// listener line, --list-faults with a meaning per fault, and the Run: line of every shipped
// scenario working as written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

#ifdef SIMNODE_PATH
// The line simnode prints at startup for the node id, its image in images_dir/id.
std::string node_line(const std::string& id, const std::string& cdi, const std::string& faults,
                      const std::string& images_dir) {
    return "simnode: node " + id + " cdi " + cdi + " faults " + faults + " images " + images_dir +
           "/" + id + "\n";
}

TEST(SimnodeStartup, OneLinePerNodeThenTheListener) {
    TempDir images("simnode-startup");
    const auto board = source_path("scenarios/io-board.xml").string();
    const auto [rc, out] =
        run_program(SIMNODE_PATH, {"--listen", "127.0.0.1:0", "--image-dir", images.str(),
                                   "--node.a.node-id=05.01.01.01.50.00", "--node.a.count=2",
                                   "--node.a.cdi=" + board, "--node.b.node-id=05.01.01.01.51.00",
                                   "--node.b.cdi=" + board, "--node.b.fault=reply-form,latency=10",
                                   "--run-for", "0.3"});
    EXPECT_EQ(rc, 0) << out;
    const std::string images_dir = images.str();
    for (const std::string& line :
         {node_line("05.01.01.01.50.00", board, "none", images_dir),
          node_line("05.01.01.01.50.01", board, "none", images_dir),
          node_line("05.01.01.01.51.00", board, "reply-form,latency=10", images_dir)}) {
        EXPECT_NE(out.find(line), std::string::npos) << line << "in\n" << out;
    }
    EXPECT_LT(out.find("simnode: node "), out.find("simnode: listening on 127.0.0.1:")) << out;
}

TEST(SimnodeStartup, ListFaultsGivesEachAMeaning) {
    const auto [rc, out] = run_program(SIMNODE_PATH, {"--list-faults"});
    ASSERT_EQ(rc, 0);
    std::istringstream in(out);
    std::string line;
    int count = 0;
    while (std::getline(in, line)) {
        ++count;
        const auto space = line.find(' ');
        ASSERT_NE(space, std::string::npos) << line;
        EXPECT_GT(line.find_first_not_of(' ', space), 20u) << line;
    }
    // One line per fault: as many as docs/faults.md has rows.
    std::ifstream doc(std::filesystem::path(OLCB_SOURCE_DIR) / "docs/faults.md");
    int rows = 0;
    for (std::string row; std::getline(doc, row);) rows += row.starts_with("| `") ? 1 : 0;
    EXPECT_EQ(count, rows);
    EXPECT_GT(rows, 30);
    EXPECT_NE(out.find("latency "), std::string::npos);
}

// The scenario a "Run: simnode FILE" comment names, or "" when the file has none.
std::string run_line_target(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream s;
    s << in.rdbuf();
    const std::string text = s.str();
    const auto at = text.find("Run: simnode");
    if (at == std::string::npos) return {};
    auto start = text.find_first_not_of(" \t\n#", at + 12);
    const auto end = text.find_first_of(" \t\n", start);
    return text.substr(start, end - start);
}

TEST(SimnodeStartup, EveryRunLineWorksAsWritten) {
    TempDir images("simnode-run-lines");
    int checked = 0;
    for (const auto& dir : {source_path("scenarios"), source_path("scenarios/faults")}) {
        for (const auto& entry : std::filesystem::directory_iterator(dir)) {
            if (entry.path().extension() != ".ini") continue;
            const std::string target = run_line_target(entry.path());
            if (target.empty()) continue;
            ++checked;
            // As written (relative to nothing in particular: the test runs in the build tree);
            // only the port and the images are moved out of the way.
            const auto [rc, out] = run_program(
                SIMNODE_PATH, {target, "--listen", "127.0.0.1:0", "--image-dir",
                               (images.path() / entry.path().stem()).string(), "--run-for", "0"});
            EXPECT_EQ(rc, 0) << entry.path() << ": Run: simnode " << target << "\n" << out;
        }
    }
    EXPECT_GE(checked, 31);
}
#endif

}  // namespace
}  // namespace olcb::e2e
