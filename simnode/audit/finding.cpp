#include "simnode/audit/finding.hpp"

#include <chrono>
#include <utility>

#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {

double FindingLog::seconds(TimePoint now) const {
    return std::chrono::duration<double>(now - start_).count();
}

void FindingLog::add(Finding finding, std::string_view key, TimePoint now) {
    std::string dedup = std::string(rule(finding.rule).name) + '|' +
                        std::to_string(finding.client.connection) + '|' +
                        std::to_string(finding.client.alias) + '|' +
                        (finding.node ? std::to_string(finding.node->node_id.value()) : "-") + '|';
    dedup.append(key);
    ++revision_;
    const double t = seconds(now);
    if (const auto it = index_.find(dedup); it != index_.end()) {
        Finding& earlier = findings_[it->second];
        ++earlier.count;
        earlier.last_time = t;
        return;
    }
    if (findings_.size() >= kMaxFindings) {
        ++dropped_;
        return;
    }
    finding.time = t;
    finding.last_time = t;
    if (finding.frames.size() > kMaxFindingFrames) finding.frames.resize(kMaxFindingFrames);
    index_.emplace(std::move(dedup), findings_.size());
    findings_.push_back(std::move(finding));
}

}  // namespace olcb::simnode::audit
