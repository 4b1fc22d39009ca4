// Findings about a CDI (cdi/diagnostic.cpp): merging passes' findings, telling errors from
// warnings, and the two ways a finding is written.
#include "cdi/diagnostic.hpp"

#include <gtest/gtest.h>

namespace olcb::cdi {
namespace {

TEST(Diagnostic, AppendMovesEveryFindingToTheEnd) {
    Diagnostics out = {{Severity::kWarning, 1, "first"}};
    Diagnostics more = {{Severity::kError, 7, "second"}, {Severity::kWarning, 0, "third"}};
    append(out, std::move(more));
    ASSERT_EQ(out.size(), 3u);
    EXPECT_EQ(out[0].message, "first");
    EXPECT_EQ(out[1].message, "second");
    EXPECT_EQ(out[1].line, 7u);
    EXPECT_EQ(out[2].message, "third");
    EXPECT_TRUE(more.empty());  // NOLINT(bugprone-use-after-move): append() empties it
    append(out, Diagnostics{});
    EXPECT_EQ(out.size(), 3u);
}

TEST(Diagnostic, HasErrorsIgnoresWarnings) {
    EXPECT_FALSE(has_errors({}));
    EXPECT_FALSE(has_errors({{Severity::kWarning, 1, "w"}, {Severity::kWarning, 2, "w"}}));
    EXPECT_TRUE(has_errors({{Severity::kWarning, 1, "w"}, {Severity::kError, 2, "e"}}));
    EXPECT_EQ(Diagnostic{}.severity, Severity::kError);  // a finding is an error unless told
}

TEST(Diagnostic, FormattedWithFileLineAndSeverity) {
    EXPECT_EQ(format_diagnostic("node.xml", {Severity::kError, 12, "bad size"}),
              "node.xml:12: error: bad size");
    EXPECT_EQ(format_diagnostic("node.xml", {Severity::kWarning, 3, "overlap"}),
              "node.xml:3: warning: overlap");
    EXPECT_EQ(format_diagnostic("node.xml", {Severity::kWarning, 0, "no schema"}),
              "node.xml: warning: no schema");
}

TEST(Diagnostic, LocatedQuotesTheLineOnly) {
    EXPECT_EQ(located({Severity::kError, 4, "bad size"}), "line 4: bad size");
    EXPECT_EQ(located({Severity::kWarning, 4, "overlap"}), "line 4: overlap");
    EXPECT_EQ(located({Severity::kError, 0, "whole document"}), "whole document");
}

}  // namespace
}  // namespace olcb::cdi
