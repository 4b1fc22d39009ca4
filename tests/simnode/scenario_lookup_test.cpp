// Scenario names: which directories a binary searches (build tree or installed), a path before a
// name, NAME and NAME.ini, the first directory winning, the list --list-scenarios prints, and an
// installed copy of a scenario whose CDI is found beside its .ini from any working directory.
#include "simnode/scenario_lookup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "simnode/scenario.hpp"
#include "support/temp_files.hpp"

namespace olcb::simnode {
namespace {

namespace fs = std::filesystem;
using test_support::TempDir;

void write(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
}

// Runs a test body with dir as the working directory, restoring the old one after.
class WorkingDir {
public:
    explicit WorkingDir(const fs::path& dir) : old_(fs::current_path()) { fs::current_path(dir); }
    ~WorkingDir() { fs::current_path(old_); }
    WorkingDir(const WorkingDir&) = delete;
    WorkingDir& operator=(const WorkingDir&) = delete;

private:
    fs::path old_;
};

TEST(ScenarioLookupTest, ABinaryInItsBuildTreeReadsTheSourceTree) {
    const TempDir tree("lookup-tree");
    const ScenarioPlaces places{tree.path() / "src/scenarios", tree.path() / "build",
                                "/usr/local/share/olcb-tools/scenarios"};
    fs::create_directories(tree.path() / "build/simnode");
    const auto dirs = scenario_dirs(tree.path() / "build/simnode/simnode", places);
    EXPECT_EQ(dirs, (std::vector<fs::path>{places.source_dir, "scenarios"}));
}

TEST(ScenarioLookupTest, AnInstalledBinaryReadsTheDataBesideItThenTheConfiguredPrefix) {
    const TempDir tree("lookup-tree");
    const ScenarioPlaces places{tree.path() / "src/scenarios", tree.path() / "build",
                                "/usr/local/share/olcb-tools/scenarios"};
    // Unpacked anywhere (dpkg -x into a fake root): the data beside the binary comes first.
    const auto dirs = scenario_dirs(tree.path() / "root/usr/bin/simnode", places);
    EXPECT_EQ(dirs, (std::vector<fs::path>{tree.path() / "root/usr/share/olcb-tools/scenarios",
                                           places.installed_dir, "scenarios"}));
}

TEST(ScenarioLookupTest, ThisBuildSearchesTheSourceTree) {
    const auto places = built_scenario_places();
    EXPECT_EQ(places.source_dir, fs::path(OLCB_SOURCE_DIR) / "scenarios");
    EXPECT_EQ(places.installed_dir.filename(), "scenarios");
    EXPECT_EQ(scenario_dirs(places.build_dir / "simnode/simnode", places).front(),
              places.source_dir);
}

TEST(ScenarioLookupTest, APathComesBeforeANameAndNamesTakeOptionalIni) {
    const TempDir tree("lookup-names");
    write(tree.path() / "a/default.ini", "a");
    write(tree.path() / "a/faults/int-byte-order.ini", "a");
    write(tree.path() / "b/default.ini", "b");
    write(tree.path() / "b/io-board.ini", "b");
    write(tree.path() / "cwd/default", "a path");
    const std::vector<fs::path> dirs{tree.path() / "a", tree.path() / "b"};
    const WorkingDir cwd(tree.path() / "cwd");

    EXPECT_EQ(find_scenario("default", dirs), fs::path("default"));  // the file in cwd
    EXPECT_EQ(find_scenario("default.ini", dirs), tree.path() / "a/default.ini");
    EXPECT_EQ(find_scenario("io-board", dirs), tree.path() / "b/io-board.ini");
    EXPECT_EQ(find_scenario("faults/int-byte-order", dirs),
              tree.path() / "a/faults/int-byte-order.ini");
    EXPECT_EQ(find_scenario("faults/int-byte-order.ini", dirs),
              tree.path() / "a/faults/int-byte-order.ini");
    EXPECT_EQ(find_scenario("/nowhere/x.ini", dirs), fs::path("/nowhere/x.ini"));
    EXPECT_FALSE(find_scenario("no-such", dirs));
    EXPECT_FALSE(find_scenario("faults", dirs));  // a directory is not a scenario
}

TEST(ScenarioLookupTest, TheListIsSortedAndAnEarlierDirectoryHidesALaterOne) {
    const TempDir tree("lookup-list");
    write(tree.path() / "a/default.ini", "a");
    write(tree.path() / "a/default.xml", "<cdi/>");
    write(tree.path() / "a/faults/int-byte-order.ini", "a");
    write(tree.path() / "b/default.ini", "b");
    write(tree.path() / "b/io-board.ini", "b");
    const std::vector<fs::path> dirs{tree.path() / "a", tree.path() / "b", tree.path() / "none"};
    const auto names = scenario_names(dirs);
    ASSERT_EQ(names.size(), 3u);
    EXPECT_EQ(names[0].name, "default");
    EXPECT_EQ(names[0].file, tree.path() / "a/default.ini");
    EXPECT_EQ(names[1].name, "faults/int-byte-order");
    EXPECT_EQ(names[2].name, "io-board");
    EXPECT_EQ(names[2].file, tree.path() / "b/io-board.ini");
}

TEST(ScenarioLookupTest, EveryShippedScenarioHasAName) {
    const std::vector<fs::path> dirs{fs::path(OLCB_SOURCE_DIR) / "scenarios"};
    std::vector<std::string> names;
    for (const auto& entry : scenario_names(dirs)) names.push_back(entry.name);
    for (const char* name : {"default", "io-board", "faults/int-byte-order"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    }
}

// What an installed copy needs: the scenario found by name from an unrelated working directory,
// its CDI (cdi = ../default.xml) read relative to the .ini file.
TEST(ScenarioLookupTest, AnInstalledCopyRunsByNameFromAnyDirectory) {
    const TempDir tree("lookup-installed");
    const fs::path data = tree.path() / "usr/share/olcb-tools/scenarios";
    fs::create_directories(data / "faults");
    const fs::path source = fs::path(OLCB_SOURCE_DIR) / "scenarios";
    fs::copy_file(source / "default.xml", data / "default.xml");
    fs::copy_file(source / "faults/int-byte-order.ini", data / "faults/int-byte-order.ini");
    fs::create_directories(tree.path() / "elsewhere");
    const WorkingDir cwd(tree.path() / "elsewhere");

    const auto dirs = scenario_dirs(tree.path() / "usr/bin/simnode", built_scenario_places());
    std::string error;
    const std::vector<std::string> args{"--scenario", "faults/int-byte-order", "--image-dir",
                                        (tree.path() / "images").string()};
    const auto parsed = parse_arguments(args, dirs, error);
    ASSERT_TRUE(parsed) << error;
    EXPECT_EQ(parsed->scenario.scenario_file, data / "faults/int-byte-order.ini");
    ASSERT_FALSE(parsed->scenario.nodes.empty());
    EXPECT_EQ(parsed->scenario.nodes.front().cdi_file.lexically_normal(), data / "default.xml");
}

TEST(ScenarioLookupTest, AnUnknownNameSaysSo) {
    const TempDir tree("lookup-unknown");
    const std::vector<fs::path> dirs{tree.path()};
    std::string error;
    EXPECT_FALSE(parse_arguments(std::vector<std::string>{"--scenario", "no-such"}, dirs, error));
    EXPECT_EQ(error, "no scenario 'no-such': no such file, nor a name of --list-scenarios");
    EXPECT_FALSE(parse_arguments(std::vector<std::string>{}, dirs, error));
    EXPECT_EQ(error, "no scenario: give a scenario file, or --node-id and --cdi (see --help)");
}

TEST(ScenarioLookupTest, ListScenariosIsAskedForOnItsOwn) {
    std::string error;
    const auto parsed = parse_arguments(std::vector<std::string>{"--list-scenarios"}, {}, error);
    ASSERT_TRUE(parsed) << error;
    EXPECT_TRUE(parsed->list_scenarios);
}

}  // namespace
}  // namespace olcb::simnode
