#include "simnode/scenario_lookup.hpp"

#include <algorithm>
#include <map>
#include <system_error>

namespace olcb::simnode {

namespace fs = std::filesystem;

namespace {

// Whether path lies inside dir, compared on their canonical forms so a symlinked build directory
// or a relative exe path still counts.
bool is_inside(const fs::path& path, const fs::path& dir) {
    if (dir.empty()) return false;
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    if (ec) return false;
    const fs::path d = fs::weakly_canonical(dir, ec);
    if (ec) return false;
    const auto [end, _] = std::mismatch(d.begin(), d.end(), p.begin(), p.end());
    return end == d.end();
}

}  // namespace

ScenarioPlaces built_scenario_places() {
    return {OLCB_SOURCE_SCENARIOS, OLCB_BUILD_DIR, OLCB_INSTALLED_SCENARIOS};
}

std::vector<fs::path> scenario_dirs(const fs::path& exe, const ScenarioPlaces& places) {
    std::vector<fs::path> out;
    if (is_inside(exe, places.build_dir)) {
        out.push_back(places.source_dir);
    } else {
        if (!exe.empty())
            out.push_back((exe.parent_path() / kInstalledScenarios).lexically_normal());
        if (!places.installed_dir.empty()) out.push_back(places.installed_dir);
    }
    out.emplace_back("scenarios");
    return out;
}

std::optional<fs::path> find_scenario(const std::string& given, std::span<const fs::path> dirs) {
    fs::path path(given);
    std::error_code ec;
    if (path.is_absolute() || fs::exists(path, ec)) return path;
    for (const auto& dir : dirs) {
        for (const fs::path& candidate : {dir / path, dir / fs::path(given + ".ini")}) {
            if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal();
        }
    }
    return std::nullopt;
}

std::vector<ScenarioEntry> scenario_names(std::span<const fs::path> dirs) {
    std::map<std::string, fs::path> found;
    for (const auto& dir : dirs) {
        std::error_code ec;
        for (fs::recursive_directory_iterator it(dir, ec), end; !ec && it != end;
             it.increment(ec)) {
            if (it->path().extension() != ".ini" || !it->is_regular_file(ec)) continue;
            fs::path name = it->path().lexically_relative(dir);
            name.replace_extension();
            found.try_emplace(name.generic_string(), it->path().lexically_normal());
        }
    }
    std::vector<ScenarioEntry> out;
    out.reserve(found.size());
    for (auto& [name, file] : found) out.push_back({name, std::move(file)});
    return out;
}

}  // namespace olcb::simnode
