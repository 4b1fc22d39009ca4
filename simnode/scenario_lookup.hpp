// Where simnode finds a scenario given by name (`default`, `faults/int-byte-order`) rather than
// by path: the source tree's scenarios/ for a binary in its build tree, the installed
// share/olcb-tools/scenarios for any other, so one command works from a build and from a package.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace olcb::simnode {

/// What a binary knows, from its build, about where scenarios are.
struct ScenarioPlaces {
    std::filesystem::path source_dir;     ///< the source tree's scenarios/
    std::filesystem::path build_dir;      ///< the build tree the binary was built in
    std::filesystem::path installed_dir;  ///< <prefix>/share/olcb-tools/scenarios as configured
};

/// The places compiled into this library (CMake's source, binary and install data directories).
ScenarioPlaces built_scenario_places();

/// The data directory relative to the installed programs: <prefix>/bin/simnode finds its
/// scenarios in <prefix>/share/olcb-tools/scenarios wherever <prefix> was unpacked.
inline constexpr const char* kInstalledScenarios = "../share/olcb-tools/scenarios";

/// The directories scenario names are looked up in, in order, for the binary at exe: the source
/// tree's when exe is inside the build tree (tests and developers run the scenarios they edit);
/// otherwise the installed ones, next to exe and then where the build was to install them. Last,
/// ./scenarios.
std::vector<std::filesystem::path> scenario_dirs(const std::filesystem::path& exe,
                                                 const ScenarioPlaces& places);

/// given as a path when it is absolute or exists from the working directory; otherwise the
/// first dirs/given or dirs/given.ini that is a file. nullopt when none is.
std::optional<std::filesystem::path> find_scenario(const std::string& given,
                                                   std::span<const std::filesystem::path> dirs);

/// One scenario a name gives: its name (path under its directory without .ini) and its file.
struct ScenarioEntry {
    std::string name;
    std::filesystem::path file;
};

/// Every scenario of dirs, sorted by name; a name in an earlier directory hides a later one, as
/// find_scenario() would pick it.
std::vector<ScenarioEntry> scenario_names(std::span<const std::filesystem::path> dirs);

}  // namespace olcb::simnode
