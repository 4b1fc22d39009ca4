// The folders of conformance/ are layers (conformance/CMakeLists.txt): a file includes its own
// folder's headers and those of the layers before it, never one after it, so the runner, the
// JMRI backups and the reports stay apart and a change below never needs one above.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

constexpr std::array<std::string_view, 6> kLayers = {"link",   "backup", "report",
                                                     "checks", "run",    "app"};

int layer_of(std::string_view folder) {
    const auto it = std::find(kLayers.begin(), kLayers.end(), folder);
    return it == kLayers.end() ? -1 : static_cast<int>(it - kLayers.begin());
}

TEST(ConformanceLayering, EveryIncludePointsToTheSameOrALowerLayer) {
    const fs::path root = fs::path(OLCB_SOURCE_DIR) / "conformance";
    const std::regex include(R"re(#include "conformance/([a-z_]+)/)re");
    std::size_t files = 0;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
        const std::string folder = fs::relative(e.path(), root).begin()->string();
        const int mine = layer_of(folder);
        ASSERT_GE(mine, 0) << e.path() << ": a file outside the layers of conformance/";
        ++files;
        std::ifstream in(e.path());
        for (std::string line; std::getline(in, line);) {
            std::smatch m;
            if (!std::regex_search(line, m, include)) continue;
            const int theirs = layer_of(m[1].str());
            EXPECT_GE(theirs, 0) << e.path() << ": " << line;
            EXPECT_LE(theirs, mine)
                << e.path() << " (" << folder << ") includes a layer above it: " << line;
        }
    }
    EXPECT_GT(files, 60u);
}

}  // namespace
}  // namespace olcb::conform
