// Check results: status and category names the reports print, counts per status, and results of
// one ID merged into one line that keeps the worst status.
#include "conformance/report/check_result.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "conformance/report_test_util.hpp"

namespace olcb::conform {
namespace {

TEST(CheckResultTest, NamesAreThoseOfTheReportsAndTheRegistry) {
    EXPECT_EQ(status_name(Status::kPass), "PASS");
    EXPECT_EQ(status_name(Status::kFail), "FAIL");
    EXPECT_EQ(status_name(Status::kWarn), "WARN");
    EXPECT_EQ(status_name(Status::kSkip), "SKIP");
    EXPECT_EQ(category_name(Category::kMemory), "memory");
    EXPECT_EQ(category_name(Category::kEvents), "events");
    EXPECT_EQ(category_name(Category::kStream), "stream");
}

TEST(CheckResultTest, ANodeReportCountsEachStatus) {
    const NodeReport r = testing::sample();
    EXPECT_EQ(r.count(Status::kPass), 1u);
    EXPECT_EQ(r.count(Status::kFail), 1u);
    EXPECT_EQ(r.count(Status::kWarn), 1u);
    EXPECT_EQ(r.count(Status::kSkip), 1u);
}

TEST(CheckResultTest, DuplicateIdsMergeIntoTheFirstKeepingTheWorstStatusAndEveryMessage) {
    using std::chrono::milliseconds;
    std::vector<CheckResult> results = {
        {"memory.lock", Category::kMemory, Status::kPass, "space fd ok", "", "", ""},
        {"cdi.valid", Category::kCdi, Status::kPass, "valid", "", "", ""},
        {"memory.lock", Category::kMemory, Status::kFail, "space fb refused", "MCS 4", "ok",
         "0x1041"},
        {"memory.lock", Category::kMemory, Status::kWarn, "space fe slow", "", "", ""},
    };
    results[0].duration = milliseconds(10);
    results[2].duration = milliseconds(5);
    merge_duplicate_ids(results);
    ASSERT_EQ(results.size(), 2u);
    EXPECT_EQ(results[0].id, "memory.lock");  // where the first one was
    EXPECT_EQ(results[1].id, "cdi.valid");
    const CheckResult& m = results[0];
    EXPECT_EQ(m.status, Status::kFail);  // a later WARN never hides the FAIL
    EXPECT_EQ(m.message, "space fb refused (and 2 more: see the details)");
    EXPECT_EQ(m.seen, "0x1041");
    EXPECT_EQ(m.duration, milliseconds(15));
    const std::vector<std::string> details = {"PASS space fd ok", "FAIL space fb refused",
                                              "WARN space fe slow"};
    EXPECT_EQ(m.details, details);
}

}  // namespace
}  // namespace olcb::conform
