#include "conformance/report/check_result.hpp"

#include <algorithm>
#include <map>

namespace olcb::conform {

std::string_view status_name(Status status) {
    switch (status) {
        case Status::kPass:
            return "PASS";
        case Status::kFail:
            return "FAIL";
        case Status::kWarn:
            return "WARN";
        case Status::kSkip:
            return "SKIP";
    }
    return "?";
}

std::string_view category_name(Category category) {
    switch (category) {
        case Category::kFrame:
            return "frame";
        case Category::kMessage:
            return "message";
        case Category::kPip:
            return "pip";
        case Category::kSnip:
            return "snip";
        case Category::kDatagram:
            return "datagram";
        case Category::kMemory:
            return "memory";
        case Category::kCdi:
            return "cdi";
        case Category::kAcdi:
            return "acdi";
        case Category::kEncoding:
            return "encoding";
        case Category::kLink:
            return "link";
        case Category::kNode:
            return "node";
        case Category::kEvents:
            return "events";
        case Category::kStream:
            return "stream";
        case Category::kTrain:
            return "train";
        case Category::kSearch:
            return "search";
        case Category::kFdi:
            return "fdi";
        case Category::kClock:
            return "clock";
    }
    return "?";
}

void merge_duplicate_ids(std::vector<CheckResult>& results) {
    std::vector<CheckResult> out;
    std::map<std::string, std::size_t> index;
    std::map<std::string, std::size_t> merged;
    for (CheckResult& c : results) {
        auto [it, fresh] = index.emplace(c.id, out.size());
        if (fresh) {
            out.push_back(std::move(c));
            continue;
        }
        CheckResult& first = out[it->second];
        first.duration += c.duration;
        if (merged[c.id]++ == 0 && first.details.empty())
            first.details.push_back(std::string(status_name(first.status)) + " " + first.message);
        first.details.push_back(std::string(status_name(c.status)) + " " + c.message);
        for (std::string& d : c.details) first.details.push_back("  " + d);
        if (severity(c.status) > severity(first.status)) {
            first.status = c.status;
            first.message = c.message;
            first.expected = c.expected;
            first.seen = c.seen;
        }
    }
    for (auto& [id, extra] : merged) {
        CheckResult& c = out[index[id]];
        c.message += " (and " + std::to_string(extra) + " more: see the details)";
    }
    results = std::move(out);
}

std::size_t NodeReport::count(Status status) const {
    return static_cast<std::size_t>(
        std::count_if(checks.begin(), checks.end(),
                      [status](const CheckResult& c) { return c.status == status; }));
}

int severity(Status s) {
    switch (s) {
        case Status::kFail:
            return 3;
        case Status::kWarn:
            return 2;
        case Status::kPass:
            return 1;
        case Status::kSkip:
            return 0;
    }
    return 0;
}

}  // namespace olcb::conform
