// The progress bar of long reads: bytes and ETA on a terminal, nothing when output is not one.
#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <string>

namespace olcb::conform {
namespace {

TEST(ProgressBar, ShowsBytesAndEta) {
    std::ostringstream out;
    ProgressBar bar(out, true);
    auto t0 = std::chrono::steady_clock::time_point{} + std::chrono::hours(1);
    bar.start("CDI", 1000, t0);
    std::string s = bar.render(500, t0 + std::chrono::seconds(2));
    EXPECT_NE(s.find("500/1000 B"), std::string::npos) << s;
    EXPECT_NE(s.find("ETA 0:02"), std::string::npos) << s;
    bar.update(500, t0 + std::chrono::seconds(2));
    EXPECT_FALSE(out.str().empty());
    std::ostringstream quiet;
    ProgressBar off(quiet, false);
    off.start("CDI", 10, t0);
    off.update(5, t0);
    off.finish();
    EXPECT_TRUE(quiet.str().empty());
}

}  // namespace
}  // namespace olcb::conform
