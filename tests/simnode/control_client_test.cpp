// `simnode ctl`: its arguments become the requests of docs/control.md, its output is readable.
#include "simnode/control_client.hpp"

#include <gtest/gtest.h>

namespace olcb::simnode {
namespace {

using Json = ControlJson;
using Strings = std::vector<std::string>;

std::optional<CtlInvocation> parse(const Strings& args, std::string& error) {
    return parse_ctl_arguments(args, "/home/me", error);
}

Json request_of(const Strings& args) {
    std::string error;
    const auto parsed = parse(args, error);
    EXPECT_TRUE(parsed) << error;
    return parsed ? parsed->request : Json();
}

std::string error_of(const Strings& args) {
    std::string error;
    EXPECT_FALSE(parse(args, error));
    return error;
}

TEST(ControlClient, EachCommandBecomesItsRequest) {
    std::string error;
    const auto list = parse({"12022", "list"}, error);
    ASSERT_TRUE(list) << error;
    EXPECT_EQ(list->where, (HostPort{"127.0.0.1", 12022}));
    EXPECT_EQ(list->request, (Json{{"cmd", "list"}}));
    EXPECT_FALSE(list->json);
    EXPECT_EQ(
        request_of({"h:1", "read", "N", "0xFD", "16", "0x40"}),
        (Json{{"cmd", "read"}, {"node", "N"}, {"space", 253}, {"address", 16}, {"count", 64}}));
    EXPECT_EQ(
        request_of({"h:1", "write", "N", "253", "0", "01ff"}),
        (Json{{"cmd", "write"}, {"node", "N"}, {"space", 253}, {"address", 0}, {"data", "01ff"}}));
    EXPECT_EQ(request_of({"h:1", "set-faults", "N", "a", "b=2"}),
              (Json{{"cmd", "set-faults"}, {"node", "N"}, {"faults", {"a", "b=2"}}}));
    EXPECT_EQ(request_of({"h:1", "clear-faults", "N"}),
              (Json{{"cmd", "clear-faults"}, {"node", "N"}}));
    EXPECT_EQ(request_of({"h:1", "reboot", "N"}), (Json{{"cmd", "reboot"}, {"node", "N"}}));
    EXPECT_EQ(request_of({"h:1", "remove", "N"}), (Json{{"cmd", "remove"}, {"node", "N"}}));
    EXPECT_EQ(request_of({"h:1", "request", "{\"cmd\":\"x\"}"}), (Json{{"cmd", "x"}}));
}

TEST(ControlClient, AddTakesScenarioKeysWithPathsMadeAbsolute) {
    EXPECT_EQ(request_of({"h:1", "add", "node-id=05.01.01.01.22.10", "cdi=my.xml", "image-dir=/abs",
                          "fault=latency=20", "fault=int-byte-order"}),
              (Json{{"cmd", "add"},
                    {"node-id", "05.01.01.01.22.10"},
                    {"cdi", "/home/me/my.xml"},
                    {"image-dir", "/abs"},
                    {"fault", {"latency=20", "int-byte-order"}}}));
    EXPECT_EQ(error_of({"h:1", "add", "cdi"}),
              "add: 'cdi' is not KEY=VALUE (keys as in docs/scenarios.md)");
    EXPECT_EQ(error_of({"h:1", "add", "cdi=a", "cdi=b"}), "add: 'cdi' is given twice");
}

TEST(ControlClient, OptionsAndUsageErrors) {
    std::string error;
    const auto parsed = parse({"--json", "127.0.0.1:5", "list", "--timeout", "0.5"}, error);
    ASSERT_TRUE(parsed) << error;
    EXPECT_TRUE(parsed->json);
    EXPECT_EQ(parsed->timeout, std::chrono::milliseconds(500));
    EXPECT_EQ(error_of({"list"}), "give HOST:PORT and a command");
    EXPECT_EQ(error_of({"h:1", "dance"}), "unknown command 'dance'");
    EXPECT_EQ(error_of({"h:1", "read", "N", "253", "zero", "4"}),
              "address 'zero' is not a number (decimal or 0x hex)");
    EXPECT_EQ(error_of({"h:1", "reboot"}), "usage: simnode ctl HOST:PORT reboot NODE");
    EXPECT_EQ(error_of({"h:0", "list"}),
              "'h:0' is not HOST:PORT: port 0 only asks for a free port when listening; give "
              "1..65535");
    EXPECT_EQ(error_of({"--timeout", "-1", "h:1", "list"}),
              "--timeout '-1' must be seconds, 0 < S <= 3600");
    EXPECT_EQ(error_of({"--verbose", "h:1", "list"}), "unknown option '--verbose'");
    EXPECT_TRUE(error_of({"h:1", "request", "{"}).starts_with("request: not JSON: "));
}

TEST(ControlClient, ResponsesPrintReadably) {
    EXPECT_EQ(
        format_ctl_response(
            Json{{"cmd", "read"}},
            Json{{"ok", true}, {"address", 16}, {"data", "000102030405060708090a0b0c0d0e0f10"}}),
        "0x00000010: 00 01 02 03 04 05 06 07 08 09 0a 0b 0c 0d 0e 0f\n"
        "0x00000020: 10\n");
    const Json node{{"node_id", "05.01.01.01.22.00"},
                    {"alias", "0x343"},
                    {"initialized", true},
                    {"cdi", "d.xml"},
                    {"faults", {"a", "b=1"}},
                    {"images", nullptr}};
    EXPECT_EQ(format_ctl_response(Json{{"cmd", "list"}}, Json{{"ok", true}, {"nodes", {node}}}),
              "node 05.01.01.01.22.00 alias 0x343 cdi d.xml faults a,b=1 images none\n");
    EXPECT_EQ(format_ctl_response(Json{{"cmd", "remove"}},
                                  Json{{"ok", true}, {"node", "N"}, {"alias", "0x343"}}),
              "node N removed (AMR for alias 0x343)\n");
}

TEST(ControlClient, NoServerIsAConnectionError) {
    std::string error;
    // Port 1 on loopback: nothing listens there on a test machine.
    EXPECT_FALSE(
        ctl_exchange(HostPort{"127.0.0.1", 1}, "{}", std::chrono::milliseconds(2000), error));
    EXPECT_TRUE(error.starts_with("cannot connect to 127.0.0.1:1: ")) << error;
    std::ostringstream out, err;
    const Strings args{"127.0.0.1:1", "list"};
    EXPECT_EQ(run_ctl(args, out, err), kCtlUsage);
    EXPECT_EQ(run_ctl(Strings{"--help"}, out, err), kCtlOk);
    EXPECT_NE(out.str().find("usage: simnode ctl"), std::string::npos);
}

}  // namespace
}  // namespace olcb::simnode
