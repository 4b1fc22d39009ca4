#include "conformance/run/memory_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "conformance/backup/backup_keys.hpp"
#include "conformance/run/encoding_checks.hpp"

namespace olcb::conform {
namespace {

using cdi::ElementKind;

// The smallest replica >= from that replica_sampled() tests (count when none does): the same
// evenly spread picks, so every tested replica is listed in the map (a test holds the two
// together).
std::uint64_t next_sampled(std::uint64_t from, std::uint64_t count, std::size_t sample) {
    if (sample == 0 || count <= sample) return from;
    if (sample == 1) return from == 0 ? 0 : count;
    for (std::size_t i = 0; i < sample; ++i) {
        const auto pick = static_cast<std::uint64_t>(
            std::round((static_cast<long double>(count - 1) * i) / (sample - 1)));
        if (pick >= from) return pick;
    }
    return count;
}

VariableVerdict skipped(std::string reason) {
    return {MapVerdict::kSkipped, std::move(reason), "", "", {}};
}

// The verdict on each listed variable: the encoding checks' own for those they reached, else
// the rule that kept the variable from being written, in the order plan_encoding() and the run
// apply them.
class Judge {
public:
    Judge(const cdi::Layout& layout, const MapEvidence& evidence)
        : layout_(layout), evidence_(evidence), planned_(evidence.planned) {
        for (const TestedVariable& t : evidence.tested) tested_.emplace(t.ordinal, &t.verdict);
        std::sort(planned_.begin(), planned_.end());
    }

    VariableVerdict verdict(const cdi::MapVariable& v) const {
        if (auto it = tested_.find(v.ordinal); it != tested_.end()) return judged(*it->second);
        const cdi::Cursor c = layout_.at(v.ordinal);
        return c.valid() ? untested(c) : skipped("not in the layout");
    }

private:
    VariableVerdict judged(const VariableVerdict& tested) const {
        VariableVerdict out = tested;
        const bool decided =
            out.verdict == MapVerdict::kVerified || out.verdict == MapVerdict::kFailed;
        if (decided && !evidence_.not_judged.empty()) {
            out.verdict = MapVerdict::kSkipped;
            out.reason = evidence_.not_judged;
        }
        return out;
    }

    bool sampled(const cdi::Cursor& c) const {
        for (std::size_t level = 0; level < c.group_depth(); ++level) {
            if (!replica_sampled(c.replica(level), c.group(level).replication, evidence_.sample))
                return false;
        }
        return true;
    }

    VariableVerdict untested(const cdi::Cursor& c) const {
        const cdi::Element& e = c.element();
        const std::string protection = protection_reason(layout_, c);
        if (e.kind == ElementKind::kAction) {
            return {MapVerdict::kProtected, protection + "; never written", "", "", {}};
        }
        if (!protection.empty() && !evidence_.protection.write_protected) {
            return {
                MapVerdict::kProtected, protection + " (--write-protected probes it)", "", "", {}};
        }
        if (!evidence_.not_written.empty()) return skipped(evidence_.not_written);
        const std::uint32_t space = c.space();
        if (space == 0xFF || space == 0xFC || (space == 0xFB && c.address() == 0)) {
            return skipped("read-only: space " + std::to_string(space) +
                           (space == 0xFB ? " @0 (the ACDI version byte)" : "") +
                           " is never written (MemoryConfigurationS 4.2)");
        }
        if (!sampled(c)) {
            return skipped("not sampled: --sample " + std::to_string(evidence_.sample) +
                           " tests that many replicas of each group (0 = all)");
        }
        if (boundary_values(e, evidence_.blob).empty()) {
            if (e.kind != ElementKind::kBlob) return skipped("no test value for this variable");
            return skipped(evidence_.blob ? "only a readwrite <blob> of up to 4096 bytes is written"
                                          : "a <blob> is written only with --blob");
        }
        const std::string selection =
            selection_reason(evidence_.protection, jmri_backup_key(layout_, c));
        if (!selection.empty()) return skipped("not selected: " + selection);
        if (std::binary_search(planned_.begin(), planned_.end(), c.ordinal())) {
            return skipped("not reached: the encoding checks stopped before it");
        }
        return skipped("beyond the " + std::to_string(evidence_.max_variables) +
                       " variables tested per run");
    }

    const cdi::Layout& layout_;
    const MapEvidence& evidence_;
    std::vector<std::uint64_t> planned_;
    std::unordered_map<std::uint64_t, const VariableVerdict*> tested_;
};

}  // namespace

std::vector<MemoryMapSpace> node_memory_map(const cdi::Layout& layout,
                                            const MapEvidence& evidence) {
    cdi::MemoryMapOptions options;
    const std::size_t sample = evidence.sample;
    options.also_list = [sample](std::uint64_t from, std::uint64_t count) {
        return next_sampled(from, count, sample);
    };
    const Judge judge(layout, evidence);
    std::vector<MemoryMapSpace> out;
    for (cdi::SpaceMap& map : cdi::build_memory_map(layout, options)) {
        MemoryMapSpace space{std::move(map), {}};
        space.verdicts.reserve(space.map.variables.size());
        for (const cdi::MapVariable& v : space.map.variables) {
            space.verdicts.push_back(judge.verdict(v));
        }
        out.push_back(std::move(space));
    }
    return out;
}

}  // namespace olcb::conform
