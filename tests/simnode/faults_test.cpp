// Fault names: parsing, parameters, errors and the catalogue (simnode/faults.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "simnode/faults.hpp"
#include "simnode/faults/fault_catalog.hpp"

namespace olcb::simnode {
namespace {

TEST(ParseFaults, CommaListsAndParametersCompose) {
    std::string error;
    auto f = parse_faults(
        {"int-byte-order, reject-temporary=5", "slow-reply", "pip-missing-bit=snip"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("int-byte-order"), FaultValue{1});
    EXPECT_EQ(f->value("reject-temporary"), FaultValue{5});
    // to_names() lists them in catalogue order, whatever the order given.
    EXPECT_EQ(to_names(*f), (std::vector<std::string>{"pip-missing-bit=snip", "int-byte-order",
                                                      "slow-reply=1200", "reject-temporary=5"}));
    EXPECT_EQ(f->value("write-dropped"), FaultValue{});
    EXPECT_FALSE(f->none());
}

TEST(ParseFaults, DefaultsOfParameters) {
    std::string error;
    auto f = parse_faults({"reject-temporary", "unsolicited-traffic", "pip-missing-bit"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reject-temporary"), FaultValue{3});
    EXPECT_EQ(f->value("unsolicited-traffic"), FaultValue{1000});
    EXPECT_EQ(to_names(*f), (std::vector<std::string>{"pip-missing-bit=acdi", "reject-temporary=3",
                                                      "unsolicited-traffic=1000"}));
}

TEST(ParseFaults, RestartAndMemoryFaults) {
    std::string error;
    auto f = parse_faults({"abort-on-value, reboot-on-write", "reset-rejected,lock-rejected",
                           "factory-reset-on-version-change", "new-alias-on-reboot",
                           "field-reads-only", "unknown-space-0x1041", "readonly-0x1041"},
                          error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("abort-on-value"), FaultValue{3000});
    EXPECT_EQ(f->value("reboot-on-write"), FaultValue{1});
    for (const char* name :
         {"factory-reset-on-version-change", "reset-rejected", "lock-rejected",
          "new-alias-on-reboot", "field-reads-only", "unknown-space-0x1041", "readonly-0x1041"}) {
        EXPECT_EQ(fault_value(*f, *find_fault(name)), FaultValue{1}) << name;
    }
    f = parse_faults({"abort-on-value=600000", "reboot-on-write=5"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("abort-on-value"), FaultValue{600000});
    EXPECT_EQ(f->value("reboot-on-write"), FaultValue{5});
    EXPECT_EQ(to_names(*f),
              (std::vector<std::string>{"abort-on-value=600000", "reboot-on-write=5"}));
    EXPECT_FALSE(parse_faults({"abort-on-value=0"}, error));
    EXPECT_NE(error.find("1..600000"), std::string::npos) << error;
    EXPECT_FALSE(parse_faults({"abort-on-value=600001"}, error));
    EXPECT_FALSE(parse_faults({"reboot-on-write=0"}, error));
    EXPECT_FALSE(parse_faults({"field-reads-only=1"}, error));
}

// reply-pending=N[:MS]: the delay stays below the 2^N s the OK promises.
TEST(ParseFaults, ReplyPendingTakesAnExponentAndADelayWithinIt) {
    std::string error;
    auto f = parse_faults({"reply-pending"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reply-pending"), (FaultValue{1, 1000}));  // half of 2^1 s
    EXPECT_EQ(to_names(*f), std::vector<std::string>{"reply-pending=1:1000"});
    f = parse_faults({"reply-pending=3"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reply-pending"), (FaultValue{3, 4000}));
    f = parse_faults({"reply-pending=15"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reply-pending"), (FaultValue{15, 600000}));  // at most 10 minutes
    f = parse_faults({"reply-pending=1:1999", "reply-pending-timeout=2"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reply-pending"), (FaultValue{1, 1999}));
    EXPECT_EQ(to_names(*f),
              (std::vector<std::string>{"reply-pending-timeout=2", "reply-pending=1:1999"}));
    f = parse_faults({"reply-pending=2:0"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("reply-pending"), (FaultValue{2, 0}));
    EXPECT_EQ(parse_faults(to_names(*f), error), f);
    EXPECT_FALSE(parse_faults({"reply-pending=1:2000"}, error));  // the promise would break
    EXPECT_NE(error.find("0..1999"), std::string::npos) << error;
    EXPECT_FALSE(parse_faults({"reply-pending=0"}, error));
    EXPECT_NE(error.find("1..15"), std::string::npos) << error;
    EXPECT_FALSE(parse_faults({"reply-pending=16"}, error));
    EXPECT_FALSE(parse_faults({"reply-pending=1:"}, error));
    EXPECT_FALSE(parse_faults({"reply-pending=1:x"}, error));
    EXPECT_FALSE(parse_faults({"reply-pending=:5"}, error));
}

TEST(ParseFaults, EmptyIsAGoodNode) {
    std::string error;
    auto f = parse_faults({"", " , "}, error);
    ASSERT_TRUE(f);
    EXPECT_TRUE(f->none());
}

TEST(ParseFaults, Errors) {
    std::string error;
    EXPECT_FALSE(parse_faults({"no-such-fault"}, error));
    EXPECT_NE(error.find("no-such-fault"), std::string::npos);
    EXPECT_NE(error.find("slow-reply"), std::string::npos) << "lists the known names";
    EXPECT_FALSE(parse_faults({"reject-temporary=x"}, error));
    EXPECT_FALSE(parse_faults({"reject-temporary=0"}, error));
    EXPECT_FALSE(parse_faults({"slow-reply=99999999999"}, error));
    EXPECT_FALSE(parse_faults({"write-dropped=1"}, error));
    EXPECT_NE(error.find("takes no value"), std::string::npos);
    EXPECT_FALSE(parse_faults({"pip-missing-bit=foo"}, error));
}

TEST(ParseFaults, NamesRoundTrip) {
    std::string error;
    const auto all = parse_faults(fault_names(), error);
    ASSERT_TRUE(all) << error;
    const auto again = parse_faults(to_names(*all), error);
    ASSERT_TRUE(again) << error;
    EXPECT_EQ(*again, *all);
    EXPECT_EQ(to_names(*all).size(), fault_names().size());
}

TEST(ParseFaults, CatalogHasEveryFaultOnce) {
    const auto names = fault_names();
    // Every fault has its scenario, which the end-to-end matrix runs.
    for (const auto& name : names) {
        EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(OLCB_SOURCE_DIR) /
                                            "scenarios/faults" / (name + ".ini")))
            << name;
    }
    EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
    for (const auto& info : fault_catalog()) EXPECT_FALSE(info.summary.empty()) << info.name;
}

}  // namespace
}  // namespace olcb::simnode
