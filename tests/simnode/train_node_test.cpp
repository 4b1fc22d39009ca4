// A simulated train node driven by a throttle on a simulated segment: speed with its direction,
// the emergency stops, functions and space 0xF9, controller, listeners and their forwarding,
// reserve, heartbeat, Train Search, and a command station creating a train; simulated clock.
#include "simnode/train_node.hpp"

#include <gtest/gtest.h>

#include "cdi/fdi_validator.hpp"
#include "openlcb/sim_network.hpp"
#include "openlcb/train_search.hpp"
#include "simnode/sim_node.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;
namespace tr = olcb::train;
namespace ts = olcb::train_search;

constexpr NodeId kTrainId{0x05'01'01'01'22'60ull};
constexpr NodeId kThrottleId{0x02'01'0D'00'00'01ull};
constexpr NodeId kOtherId{0x02'01'0D'00'00'02ull};

NodeConfig train_config(std::uint8_t heartbeat = 0, const std::vector<std::string>& faults = {}) {
    NodeConfig c;
    c.node_id = kTrainId;
    c.cdi = test::read_source_file("scenarios/train.xml");
    c.user_name = "Big Boy 4014";
    TrainConfig t;
    t.identity.address = 1732;
    t.identity.long_address = true;
    t.heartbeat = heartbeat;
    t.fdi = test::read_source_file("scenarios/fdi/train.xml");
    c.train = t;
    c.faults = test::faults_of(faults);
    return c;
}

// A throttle (a real node stack) that records what it receives.
struct Throttle {
    NodeStack stack;
    std::vector<Message> got;

    Throttle(SimNetwork& net, NodeId id)
        : stack([id] {
              NodeStackConfig c;
              c.node_id = id;
              return c;
          }()) {
        stack.set_message_handler([this](const Message& m) {
            got.push_back(m);
            return true;
        });
        net.add_stack(stack);
    }
};

class TrainNodeTest : public ::testing::Test {
protected:
    void start(NodeConfig config) {
        std::string error;
        node_ = SimNode::create(std::move(config), error);
        ASSERT_TRUE(node_) << error;
        net_.add_stack(node_->stack());
        net_.start_all();
        ASSERT_TRUE(net_.run_until(
            [&] {
                return node_->stack().initialized() && throttle_.stack.initialized() &&
                       other_.stack.initialized();
            },
            2s));
        net_.run_for(50ms);
    }

    void send(Throttle& from, const tr::Command& c) {
        Message m;
        m.mti = Mti::kTractionControlCommand;
        m.destination = NodeHandle{kTrainId, 0};
        m.payload = tr::encode(c);
        ASSERT_EQ(from.stack.send_message(std::move(m)), SendStatus::kSent);
        net_.run_for(20ms);
    }

    // The last reply of type R the throttle got after sending c.
    template <typename R>
    std::optional<R> ask(const tr::Command& c, Throttle* from = nullptr) {
        Throttle& t = from ? *from : throttle_;
        t.got.clear();
        send(t, c);
        for (const Message& m : t.got) {
            if (m.mti != Mti::kTractionControlReply) continue;
            const auto d = tr::decode_reply(m.payload);
            if (d.ok() && std::holds_alternative<R>(*d.value)) return std::get<R>(*d.value);
        }
        return std::nullopt;
    }

    tr::Speed set_speed() {
        const auto r = ask<tr::SpeedsReply>({tr::QuerySpeeds{}});
        EXPECT_TRUE(r);
        return r ? r->set : tr::Speed::unknown();
    }

    // Commands forwarded to t (P bit set).
    static std::vector<tr::Command> forwarded(const Throttle& t) {
        std::vector<tr::Command> out;
        for (const Message& m : t.got) {
            if (m.mti != Mti::kTractionControlCommand) continue;
            if (auto d = tr::decode_command(m.payload); d.ok()) out.push_back(*d.value);
        }
        return out;
    }

    SimNetwork net_;
    Throttle throttle_{net_, kThrottleId};
    Throttle other_{net_, kOtherId};
    std::unique_ptr<SimNode> node_;
};

TEST_F(TrainNodeTest, ItsPipClaimsTractionAndFdiAndItServesBothSpaces) {
    start(train_config());
    const ProtocolSet p = node_->served_protocols();
    EXPECT_TRUE(p.has(Protocol::kTractionControl));
    EXPECT_TRUE(p.has(Protocol::kFdi));
    EXPECT_TRUE(p.has(Protocol::kEventExchange));
    ASSERT_NE(node_->memory().space(tr::kFdiSpace), nullptr);
    EXPECT_EQ(node_->memory().read(tr::kFdiSpace, 0, 5),
              (std::vector<std::uint8_t>{'<', '?', 'x', 'm', 'l'}));
    ASSERT_NE(node_->memory().space(tr::kFunctionSpace), nullptr);
    bool is_train = false;
    for (const auto& [id, role] : node_->events()) is_train = is_train || id == tr::kIsTrain;
    EXPECT_TRUE(is_train);
}

TEST_F(TrainNodeTest, SetSpeedReadsBackWithItsDirectionAndEmergencyStopKeepsIt) {
    start(train_config());
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.75, true)}});
    EXPECT_EQ(set_speed().bits(), 0xBA00);
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0, true)}});
    EXPECT_EQ(set_speed().bits(), 0x8000);  // zero, still reverse
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, true)}});
    send(throttle_, {tr::EmergencyStop{}});
    auto r = ask<tr::SpeedsReply>({tr::QuerySpeeds{}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->set.bits(), 0x8000);
    EXPECT_EQ(r->status, tr::kStatusEmergencyStop);
    EXPECT_TRUE(r->actual.is_nan());
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, false)}});
    r = ask<tr::SpeedsReply>({tr::QuerySpeeds{}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 0);
    EXPECT_EQ(r->set, tr::Speed::of(0.5, false));
}

TEST_F(TrainNodeTest, GlobalStopsKeepTheSetSpeedButZeroTheCommandedOne) {
    start(train_config());
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, true)}});
    const auto raw = tr::kEmergencyOffAll.to_bytes();
    Message pcer;
    pcer.mti = Mti::kEventReport;
    pcer.payload.assign(raw.begin(), raw.end());
    throttle_.stack.send_message(pcer);
    net_.run_for(20ms);
    EXPECT_TRUE(node_->train()->global_off());
    auto r = ask<tr::SpeedsReply>({tr::QuerySpeeds{}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->set, tr::Speed::of(0.5, true));
    EXPECT_TRUE(r->commanded.is_zero());
    EXPECT_EQ(r->status, 0);  // only the Emergency Stop state shows
}

TEST_F(TrainNodeTest, FunctionsAreTheFunctionSpace) {
    start(train_config());
    send(throttle_, {tr::SetFunction{0, 1}});
    EXPECT_EQ(node_->memory().read(tr::kFunctionSpace, 0, 1), std::vector<std::uint8_t>{1});
    const std::vector<std::uint8_t> on{1};
    ASSERT_EQ(node_->write_memory(tr::kFunctionSpace, 2, on), memory::WriteStatus::kOk);
    const auto f2 = ask<tr::FunctionReply>({tr::QueryFunction{2}});
    ASSERT_TRUE(f2);
    EXPECT_EQ(f2->value, 1);
    send(throttle_, {tr::SetFunction{1000, 300}});  // beyond the space: kept aside
    const auto f1000 = ask<tr::FunctionReply>({tr::QueryFunction{1000}});
    ASSERT_TRUE(f1000);
    EXPECT_EQ(f1000->value, 300);
}

TEST_F(TrainNodeTest, ControllerAssignQueryReleaseAndTheNotifyToTheOldOne) {
    start(train_config());
    const auto a = ask<tr::AssignReply>({tr::AssignController{0, kThrottleId}});
    ASSERT_TRUE(a);
    EXPECT_EQ(a->result, 0);
    EXPECT_EQ(node_->train()->controller(), kThrottleId);
    // Another throttle takes over: the first one is told.
    throttle_.got.clear();
    EXPECT_TRUE(ask<tr::AssignReply>({tr::AssignController{0, kOtherId}}, &other_));
    const auto told = forwarded(throttle_);
    ASSERT_EQ(told.size(), 1u);
    EXPECT_TRUE(std::holds_alternative<tr::ControllerChangingNotify>(told.front().body));
    // Only the controller releases.
    send(throttle_, {tr::ReleaseController{0, kThrottleId}});
    EXPECT_EQ(node_->train()->controller(), kOtherId);
    send(other_, {tr::ReleaseController{0, kOtherId}});
    const auto q = ask<tr::ControllerReply>({tr::QueryController{}});
    ASSERT_TRUE(q);
    EXPECT_TRUE(q->controller.is_zero());
    EXPECT_EQ(q->flags, 0);
}

TEST_F(TrainNodeTest, ListenersKeepTheirOrderAndGetWhatTheirFlagsSay) {
    start(train_config());
    namespace lf = tr::listener_flags;
    auto c = ask<tr::ListenerChangeReply>({tr::AttachListener{lf::kReverse, kOtherId}});
    ASSERT_TRUE(c);
    EXPECT_EQ(c->code, 0);
    c = ask<tr::ListenerChangeReply>({tr::AttachListener{0, kTrainId}});
    ASSERT_TRUE(c);
    EXPECT_EQ(c->code, tr::error::kAlreadyExists);
    other_.got.clear();
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, false)}});
    send(throttle_, {tr::SetFunction{0, 1}});  // no Link F0: not forwarded
    auto f = forwarded(other_);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_TRUE(f.front().forwarded);
    EXPECT_EQ(std::get<tr::SetSpeed>(f.front().body).speed, tr::Speed::of(0.5, true));
    // New flags keep the place; Link F0 now forwards F0.
    EXPECT_TRUE(ask<tr::ListenerChangeReply>({tr::AttachListener{lf::kLinkF0, kOtherId}}));
    other_.got.clear();
    send(throttle_, {tr::SetFunction{0, 0}});
    EXPECT_EQ(forwarded(other_).size(), 1u);
    // The listener's own command is not sent back to it.
    other_.got.clear();
    send(other_, {tr::SetSpeed{tr::Speed::of(0, false)}});
    EXPECT_TRUE(forwarded(other_).empty());
    const auto q = ask<tr::ListenersReply>({tr::QueryListeners{0}});
    ASSERT_TRUE(q && q->entry);
    EXPECT_EQ(q->count, 1);
    EXPECT_EQ(q->entry->flags, lf::kLinkF0);
    c = ask<tr::ListenerChangeReply>({tr::DetachListener{0, kOtherId}});
    EXPECT_EQ(c->code, 0);
    c = ask<tr::ListenerChangeReply>({tr::DetachListener{0, kOtherId}});
    EXPECT_EQ(c->code, tr::error::kNotFound);
}

TEST_F(TrainNodeTest, ListenerNotForwardedDropsEveryForward) {
    start(train_config(0, {"listener-not-forwarded"}));
    ASSERT_TRUE(ask<tr::ListenerChangeReply>({tr::AttachListener{0, kOtherId}}));
    other_.got.clear();
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, false)}});
    EXPECT_TRUE(forwarded(other_).empty());
}

TEST_F(TrainNodeTest, ReserveFromTheHolderAgainIsAcceptedUnlessTheFaultSaysNo) {
    start(train_config());
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}})->result, 0);
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}})->result, 0);
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}}, &other_)->result, 1);
    send(throttle_, {tr::Release{}});
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}}, &other_)->result, 0);
}

TEST_F(TrainNodeTest, ReserveExclusiveRefusesTheHolderToo) {
    start(train_config(0, {"reserve-exclusive"}));
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}})->result, 0);
    EXPECT_EQ(ask<tr::ReserveReply>({tr::Reserve{}})->result, 1);
}

TEST_F(TrainNodeTest, SpeedByteOrderSwapsTheRepliedSpeeds) {
    start(train_config(0, {"speed-byte-order"}));
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.75, true)}});
    EXPECT_EQ(set_speed().bits(), 0x00BA);
}

TEST_F(TrainNodeTest, HeartbeatAsksTheControllerAndStopsTheTrainWhenUnanswered) {
    start(train_config(1));
    ASSERT_TRUE(ask<tr::AssignReply>({tr::AssignController{0, kThrottleId}}));
    EXPECT_TRUE(ask<tr::ListenerChangeReply>({tr::AttachListener{0, kOtherId}}));
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, true)}});
    throttle_.got.clear();
    net_.run_for(1100ms);
    EXPECT_EQ(node_->train()->heartbeats(), 1u);
    // Answered: it keeps going.
    send(throttle_, {tr::Noop{}});
    net_.run_for(900ms);
    EXPECT_EQ(node_->train()->set_speed(), tr::Speed::of(0.5, true));
    // Unanswered: stopped at the deadline, and the listener is told.
    other_.got.clear();
    net_.run_for(2500ms);
    EXPECT_EQ(node_->train()->set_speed(), tr::Speed::of(0, true));
    const auto f = forwarded(other_);
    ASSERT_FALSE(f.empty());
    EXPECT_TRUE(std::get<tr::SetSpeed>(f.back().body).speed.is_zero());
    // Stopped: no more requests.
    const auto before = node_->train()->heartbeats();
    net_.run_for(3s);
    EXPECT_EQ(node_->train()->heartbeats(), before);
}

TEST_F(TrainNodeTest, HeartbeatIgnoredKeepsTheTrainRunning) {
    start(train_config(1, {"heartbeat-ignored"}));
    ASSERT_TRUE(ask<tr::AssignReply>({tr::AssignController{0, kThrottleId}}));
    send(throttle_, {tr::SetSpeed{tr::Speed::of(0.5, false)}});
    net_.run_for(4s);
    EXPECT_GE(node_->train()->heartbeats(), 2u);
    EXPECT_EQ(node_->train()->set_speed(), tr::Speed::of(0.5, false));
}

TEST_F(TrainNodeTest, NoFdiSpaceKeepsTheFdiClaimButNotTheSpace) {
    start(train_config(0, {"no-fdi-space"}));
    EXPECT_TRUE(node_->served_protocols().has(Protocol::kFdi));
    EXPECT_EQ(node_->memory().space(tr::kFdiSpace), nullptr);
}

// The Producer Identified answers of the segment to a search, as seen by the throttle.
std::vector<Message> search(SimNetwork& net, Throttle& t, const ts::Query& q,
                            Duration wait = 100ms) {
    t.got.clear();
    Message m;
    m.mti = Mti::kIdentifyProducer;
    const auto raw = q.event().to_bytes();
    m.payload.assign(raw.begin(), raw.end());
    t.stack.send_message(m);
    net.run_for(wait);
    std::vector<Message> out;
    for (const Message& r : t.got)
        if (EventId::from_bytes(r.payload) == q.event()) out.push_back(r);
    return out;
}

TEST_F(TrainNodeTest, SearchMatchesTheAddressAndTheNamesDigits) {
    start(train_config());
    const auto exact = search(net_, throttle_, *ts::Query::of("1732", 0x60));
    ASSERT_EQ(exact.size(), 1u);
    EXPECT_EQ(exact.front().mti, Mti::kProducerIdentifiedValid);
    EXPECT_EQ(search(net_, throttle_, *ts::Query::of("17", 0x20)).front().mti,
              Mti::kProducerIdentifiedUnknown);
    EXPECT_EQ(search(net_, throttle_, *ts::Query::of("4014", 0x00)).size(), 1u);  // the name
    EXPECT_TRUE(search(net_, throttle_, *ts::Query::of("4014", 0x20)).empty());   // address only
    EXPECT_TRUE(search(net_, throttle_, *ts::Query::of("1732", 0x63)).empty());   // reserved
}

TEST_F(TrainNodeTest, ACommandStationCreatesATrainThatAnswersTheSearch) {
    NodeConfig station = train_config();
    station.node_id = NodeId{0x05'01'01'01'22'80ull};
    station.command_station = station.train;
    station.train.reset();
    std::vector<std::unique_ptr<SimNode>> created;
    start(std::move(station));
    node_->set_train_factory([&](const NodeConfig& c) {
        std::string error;
        auto n = SimNode::create(c, error);
        if (!n) return false;
        net_.add_stack(n->stack());
        n->stack().start(net_.now());
        created.push_back(std::move(n));
        return true;
    });
    const auto q =
        *ts::Query::of("12", ts::flags::kAllocate | ts::flags::kExact | ts::flags::kAddressOnly);
    const auto answers = search(net_, throttle_, q, 1s);
    ASSERT_EQ(created.size(), 1u);
    EXPECT_EQ(created.front()->node_id(), NodeId{0x05'01'01'01'22'81ull});
    ASSERT_FALSE(answers.empty());
    EXPECT_EQ(answers.front().mti, Mti::kProducerIdentifiedValid);
    EXPECT_EQ(answers.front().source.alias, created.front()->stack().alias());
    EXPECT_EQ(created.front()->snip().user_name, "DCC 12 short");
    // Found now, so a second allocation creates nothing.
    search(net_, throttle_, q, 1s);
    EXPECT_EQ(created.size(), 1u);
    // Reserved values and MFX create nothing.
    search(net_, throttle_, *ts::Query::of("13", 0xE3), 1s);
    search(net_, throttle_, *ts::Query::of("14", 0xE2), 1s);
    EXPECT_EQ(created.size(), 1u);
}

// The FDI the train scenarios serve is one `lcc-cdi validate` passes: schema and rules.
TEST(TrainScenarioFdi, ValidatesAgainstItsSchema) {
    const cdi::ValidatedFdi v =
        cdi::validate_fdi(test::read_source_file("scenarios/fdi/train.xml"));
    std::string found;
    for (const cdi::Diagnostic& d : v.diagnostics) found += cdi::located(d) + "\n";
    EXPECT_TRUE(v.diagnostics.empty()) << found;
    ASSERT_TRUE(v.document);
    EXPECT_EQ(v.document->functions.size(), 5u);
}

}  // namespace
}  // namespace olcb::simnode
