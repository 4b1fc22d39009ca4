#include "simnode/sim_node.hpp"

#include <algorithm>
#include <iostream>
#include <set>
#include <span>
#include <type_traits>
#include <utility>
#include <variant>

#include "base/error_codes.hpp"
#include "cdi/schema_validator.hpp"
#include "cdi/variable_name.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/datagram_defs.hpp"

namespace olcb::simnode {
namespace {

constexpr std::uint8_t kConfigSpace = 0xFD;

// The global messages the node answers (its faults' message hooks see no others); the other
// nodes' announcements (Initialization Complete, Producer/Consumer Identified, ...) it ignores,
// so a driver of many nodes need not hand them to it.
constexpr Mti kAnsweredGlobals[] = {Mti::kVerifyNodeIdGlobal, Mti::kIdentifyEventsGlobal,
                                    Mti::kIdentifyProducer, Mti::kIdentifyConsumer};
// What a node with Broadcast Time clocks also takes: reports to follow, Set, Query, Start and
// Stop, and the consumers' identifications (a generator reports the minutes they ask for).
constexpr Mti kClockGlobals[] = {Mti::kEventReport,
                                 Mti::kProducerIdentifiedValid,
                                 Mti::kConsumerIdentifiedValid,
                                 Mti::kConsumerIdentifiedInvalid,
                                 Mti::kConsumerIdentifiedUnknown,
                                 Mti::kConsumerRangeIdentified};

}  // namespace

namespace {

// The stack of a node: what it serves and its stream transport, then what the faults' hooks
// change of it (its PIP, the duplicate-ID PCER, its alias after a restart).
NodeStackConfig stack_config_for(const NodeConfig& config, ProtocolSet served) {
    NodeStackConfig sc;
    sc.node_id = config.node_id;
    sc.protocols = served;
    sc.builtins.duplicate_id_pcer = true;  // optional (CAN 6), as OpenMRN nodes send it
    sc.streams = config.streams;
    // Incoming streams are taken (and their data dropped), as OlcbChecker's st checks expect.
    sc.stream.accept_unsolicited = true;
    ActiveFaults(config.faults).stack_config(sc);
    return sc;
}

}  // namespace

std::unique_ptr<SimNode> SimNode::create(NodeConfig config, std::string& error) {
    if (config.node_id.is_zero()) {
        error = "node ID must not be zero";
        return nullptr;
    }
    if (config.cdi.size() > cdi::kMaxCdiBytes) {
        error = "CDI: " + std::to_string(config.cdi.size()) + " bytes, over the limit of " +
                std::to_string(cdi::kMaxCdiBytes) + " (16 MiB)";
        return nullptr;
    }
    auto model = load_cdi_model(config.cdi, error);
    if (!model) {
        error = "CDI: " + error;
        return nullptr;
    }
    if (!config.watch_variable.empty()) {
        bool found = false;
        model->layout->visit([&](const cdi::Cursor& c) {
            found = cdi::names_variable(*model->layout, c, config.watch_variable);
            return !found;
        });
        if (!found) {
            error = "watch-variable '" + config.watch_variable +
                    "' names no variable of the CDI (see lcc-cdi layout)";
            return nullptr;
        }
    }
    // Real firmware serves CDIs that break the schema (a third of the device files of the corpus
    // do); refusing them would make the node useless for testing tools against such devices.
    // The owner reports cdi_problem() to the user instead.
    if (!config.identity) {
        Identity id;
        if (const auto& ident = model->document->identification) {
            id = Identity{ident->manufacturer, ident->model, ident->hardware_version,
                          ident->software_version};
        }
        config.identity = id;
    }

    MemoryOptions options;
    options.model = model;
    options.node_id = config.node_id;
    options.image_dir = config.image_dir;
    options.identity.manufacturer = config.identity->manufacturer;
    options.identity.model = config.identity->model;
    options.identity.hardware_version = config.identity->hardware_version;
    options.identity.software_version = config.identity->software_version;
    options.user_name = config.user_name;
    options.user_description = config.user_description;
    options.faults = config.faults;
    if (config.train) {
        options.function_space = kFunctionSpaceSize;
        if (ActiveFaults(config.faults).train().fdi_space) options.fdi = config.train->fdi;
    }
    auto memory = NodeMemory::open(std::move(options), error);
    if (!memory) return nullptr;

    // PIP says what the node really serves (fact sheet 3.1).
    ProtocolSet served{Protocol::kDatagram, Protocol::kSnip};
    if (config.memory_config) {
        served.set(Protocol::kMemoryConfiguration);
        served.set(Protocol::kCdi);
        if (memory->has_acdi()) served.set(Protocol::kAcdi);
    }
    if (!model->events.empty() || !config.clocks.empty()) served.set(Protocol::kEventExchange);
    if (config.streams) served.set(Protocol::kStream);
    if (config.train) {
        // It produces Is Train and consumes the emergency events (TrainControlS §6.4, §5).
        served.set(Protocol::kEventExchange);
        served.set(Protocol::kTractionControl);
        if (!config.train->fdi.empty()) served.set(Protocol::kFdi);
    }

    const NodeStackConfig sc = stack_config_for(config, served);
    return std::unique_ptr<SimNode>(new SimNode(std::move(config), sc, std::move(memory), served));
}

class SimNode::Life final : public NodeLife {
public:
    explicit Life(SimNode& node) : node_(node) {}
    TimePoint now() const override { return node_.stack_.now(); }
    void schedule(TimePoint at, std::function<void(TimePoint)> fn) override {
        node_.stack_.schedule(at, std::move(fn));
    }
    bool initialized() const override { return node_.stack_.initialized(); }
    void send(Message message) override { node_.stack_.send_message(std::move(message)); }
    void abort(std::chrono::milliseconds silence) override { node_.abort_node(silence); }
    bool watched_changed() const override { return node_.watched_changed(); }
    void factory_reset() override {
        if (node_.factory_reset()) ++node_.counters_.factory_resets;
    }
    NodeMemory& memory() override { return *node_.memory_; }
    void storage_error() override { ++node_.counters_.storage_errors; }

private:
    SimNode& node_;
};

SimNode::SimNode(NodeConfig config, NodeStackConfig stack_config,
                 std::unique_ptr<NodeMemory> memory, ProtocolSet served)
    : config_(std::move(config)),
      stack_(stack_config),
      memory_(std::move(memory)),
      server_([&] {
          memory::MemoryConfigServer::Config c;
          c.node_id = config_.node_id.value();
          c.unique_id_counter = memory_->unique_id_counter();
          c.streams = config_.streams;
          return c;
      }()),
      served_protocols_(served),
      faults_(config_.faults),
      life_(std::make_unique<Life>(*this)),
      answer_delay_(faults_.latency().latency, faults_.latency().jitter, config_.node_id.value()) {
    faults_.attach(stack_);
    memory_->serve(server_);
    startup_events_ = memory_->events();
    if (faults_.watches()) find_watched();
    const ClockQuirks quirks = faults_.clock();
    for (const ClockConfig& c : config_.clocks) clocks_.emplace_back(c, quirks);
    clock_send_ = [this](Message m) { stack_.send_message(std::move(m)); };
    stack_.set_message_handler([this](const Message& m) { return on_message(m); });
    std::vector<Mti> globals(std::begin(kAnsweredGlobals), std::end(kAnsweredGlobals));
    if (config_.train) {
        train_ =
            std::make_unique<TrainNode>(*config_.train, config_.node_id, *life_, faults_,
                                        [this](Message m) { return send_message(std::move(m)); });
        globals.push_back(Mti::kEventReport);  // the global emergency events
    }
    if (config_.command_station) {
        // To see whether a train answered a search before allocating one (TrainSearchS §6.2).
        globals.insert(globals.end(),
                       {Mti::kProducerIdentifiedValid, Mti::kProducerIdentifiedInvalid,
                        Mti::kProducerIdentifiedUnknown});
    }
    if (!clocks_.empty())
        globals.insert(globals.end(), std::begin(kClockGlobals), std::end(kClockGlobals));
    stack_.set_global_messages(std::move(globals));
    stack_.set_datagram_handler([this](const ReceivedDatagram& d) { on_datagram(d); });
    stack_.set_initialized_handler([this] { on_initialized(); });
    stack_.set_stream_handler([this](const StreamEvent& e) { on_stream_event(e); });
}

SimNode::~SimNode() = default;

std::optional<std::uint32_t> SimNode::watched_address() const {
    return watched_address_;
}

void SimNode::find_watched() {
    const std::string& wanted = config_.watch_variable;
    memory().model().layout->visit([&](const cdi::Cursor& c) {
        if (wanted.empty() ? c.space() != kConfigSpace || c.element().kind != cdi::ElementKind::kInt
                           : !cdi::names_variable(*memory().model().layout, c, wanted))
            return true;
        watched_space_ = static_cast<std::uint8_t>(c.space());
        watched_address_ = static_cast<std::uint32_t>(c.address());
        // Taken as the firmware's own constant: any other stored value is "not my version".
        watched_snapshot_ =
            memory_->read(watched_space_, *watched_address_, static_cast<std::uint32_t>(c.size()));
        return false;
    });
}

bool SimNode::watched_changed() const {
    if (!watched_address_) return false;
    return memory_->read(watched_space_, *watched_address_,
                         static_cast<std::uint32_t>(watched_snapshot_.size())) != watched_snapshot_;
}

memory::Snip SimNode::snip() const {
    memory::Snip s = memory_->snip();
    faults_.snip(s);
    return s;
}

std::vector<std::uint8_t> SimNode::snip_payload() const {
    return memory::encode_snip(snip());
}

void SimNode::reboot(TimePoint now) {
    power_up(now);
}

void SimNode::relogin(TimePoint now) {
    ++boot_generation_;
    answer_delay_.reset();
    stack_.restart(now);
}

// ---------------- messages ----------------

namespace {

// Whether msg asks this node for an answer (the ones the latency fault holds back).
bool asks_answer(const Message& msg) {
    if (std::find(std::begin(kAnsweredGlobals), std::end(kAnsweredGlobals), msg.mti) !=
        std::end(kAnsweredGlobals)) {
        return true;
    }
    return msg.destination.has_value() &&
           !NodeStack::never_rejected(static_cast<std::uint16_t>(msg.mti));
}

}  // namespace

bool SimNode::on_message(const Message& msg) {
    if (!answer_delay_.active() || !asks_answer(msg)) return answer_message(msg);
    const std::uint32_t generation = boot_generation_;
    stack_.schedule(answer_delay_.answer_at(stack_.now()), [this, generation, msg](TimePoint) {
        if (generation == boot_generation_) answer_late(msg);
    });
    return true;
}

// A held-back request, answered now: the stack's built-in answers included, since the latency
// fault switched them off.
void SimNode::answer_late(const Message& msg) {
    if (!stack_.initialized()) return;
    if (answer_builtin(msg) || answer_message(msg) || !msg.destination) return;
    Message oir;
    oir.mti = Mti::kOptionalInteractionRejected;
    oir.destination = NodeHandle{msg.source.id, msg.source.alias};
    const auto code = base::to_u16(base::ErrorCode::kUnknownMtiOrTransport);
    const auto mti = static_cast<std::uint16_t>(msg.mti);
    oir.payload = {static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code & 0xFF),
                   static_cast<std::uint8_t>(mti >> 8), static_cast<std::uint8_t>(mti & 0xFF)};
    stack_.send_message(std::move(oir));
}

bool SimNode::answer_builtin(const Message& msg) {
    Message reply;
    reply.mti = stack_.protocols().has(Protocol::kSimpleProtocol) ? Mti::kVerifiedNodeIdSimple
                                                                  : Mti::kVerifiedNodeId;
    const auto id = node_id().to_bytes();
    reply.payload.assign(id.begin(), id.end());
    switch (msg.mti) {
        case Mti::kVerifyNodeIdGlobal: {
            const auto asked = NodeId::from_bytes(msg.payload);
            if (!msg.payload.empty() && !(asked && *asked == node_id())) return true;
            break;
        }
        case Mti::kVerifyNodeIdAddressed:
            break;
        case Mti::kProtocolSupportInquiry: {
            reply.mti = Mti::kProtocolSupportReply;
            reply.destination = NodeHandle{msg.source.id, msg.source.alias};
            const auto flags = stack_.protocols().encode();
            reply.payload.assign(flags.begin(), flags.end());
            break;
        }
        default:
            return false;
    }
    stack_.send_message(std::move(reply));
    return true;
}

bool SimNode::answer_message(const Message& msg) {
    if (faults_.message(*life_, msg)) return true;
    if (!clocks_.empty()) clock_message(msg);
    if ((train_ || config_.command_station) && answer_train(msg)) return true;
    switch (msg.mti) {
        case Mti::kIdentifyEventsGlobal:
        case Mti::kIdentifyEventsAddressed:
            advertise_all();
            for (const BroadcastClock& c : clocks_) c.identify(clock_send_);
            return true;
        case Mti::kIdentifyProducer:
        case Mti::kIdentifyConsumer: {
            const auto asked = EventId::from_bytes(msg.payload);
            if (!asked) return true;  // malformed: nothing of ours to identify
            const bool producer = msg.mti == Mti::kIdentifyProducer;
            for (const auto& [id, role] : advertised_events()) {
                if (id == *asked && (producer ? produces(role) : consumes(role))) {
                    identified(id, producer);
                    break;
                }
            }
            return true;
        }
        case Mti::kSnipRequest: {
            Message reply;
            reply.mti = Mti::kSnipReply;
            reply.destination = NodeHandle{msg.source.id, msg.source.alias};
            reply.payload = snip_payload();
            stack_.send_message(std::move(reply));
            return true;
        }
        default:
            return false;
    }
}

bool SimNode::send_message(Message msg) {
    return stack_.send_message(std::move(msg)) != SendStatus::kUnknownDestination;
}

bool SimNode::answer_train(const Message& msg) {
    switch (msg.mti) {
        case Mti::kTractionControlCommand:
            if (!train_) return false;
            train_->on_command(msg);
            return true;
        case Mti::kEventReport:
            if (const auto id = EventId::from_bytes(msg.payload); id && train_)
                train_->on_event(*id);
            return false;  // also the node's own events, if any
        case Mti::kIdentifyProducer:
            return answer_search(msg);
        case Mti::kProducerIdentifiedValid:
        case Mti::kProducerIdentifiedInvalid:
        case Mti::kProducerIdentifiedUnknown:
            if (const auto id = EventId::from_bytes(msg.payload)) {
                if (const auto it = allocating_.find(*id); it != allocating_.end())
                    it->second = true;
            }
            return false;
        default:
            return false;
    }
}

bool SimNode::answer_search(const Message& msg) {
    const auto id = EventId::from_bytes(msg.payload);
    if (!id || !train_search::in_range(*id)) return false;
    const auto query = train_search::Query::from_event(*id);
    if (!query || query->has_reserved()) return true;  // reserved values match nothing (§6.3)
    if (train_) {
        train_search::TrainIdentity me = train_->config().identity;
        me.name = snip().user_name;
        if (train_search::matches(*query, me)) {
            // An exact query that matched is told apart from a partial match (§6.4).
            const bool exact = (query->flags & train_search::flags::kExact) != 0;
            Message m;
            m.mti = exact ? Mti::kProducerIdentifiedValid : Mti::kProducerIdentifiedUnknown;
            const auto raw = id->to_bytes();
            m.payload.assign(raw.begin(), raw.end());
            stack_.send_message(std::move(m));
        }
    }
    if (config_.command_station && (query->flags & train_search::flags::kAllocate) != 0)
        allocate(*query, *id);
    return true;
}

namespace {

// What a command station waits for an existing train to answer before it creates one (at least
// 200 ms, TrainSearchS §6.2).
constexpr auto kAllocateWait = std::chrono::milliseconds(250);
// Node IDs after its own a command station tries for a new train (others may be taken).
constexpr std::uint64_t kCreateAttempts = 16;

// The train an allocating query describes; nullopt when it names none this station can create
// (not exactly one number, an address its protocol does not have, MFX: no user address).
std::optional<train_search::TrainIdentity> allocatable(const train_search::Query& q) {
    std::string digits;
    int runs = 0;
    bool in_run = false;
    for (std::uint8_t n : q.nibbles) {
        if (n > 9) {
            in_run = false;
            continue;
        }
        if (!in_run) ++runs;
        in_run = true;
        digits += static_cast<char>('0' + n);
    }
    if (runs != 1 || digits.size() > 5) return std::nullopt;
    const auto value = static_cast<std::uint32_t>(std::stoul(digits));
    train_search::TrainIdentity t;
    t.protocol =
        train_search::requested_protocol(q.flags).value_or(train_search::TrackProtocol::kDcc);
    t.address = value;
    switch (t.protocol) {
        case train_search::TrackProtocol::kDcc:
            t.long_address = train_search::requests_long_address(q.flags) || value >= 128;
            if (value == 0 || value > 10239 || (!t.long_address && value > 127))
                return std::nullopt;
            return t;
        case train_search::TrackProtocol::kMarklinMotorola:
            if (value == 0 || value > 255) return std::nullopt;
            return t;
        case train_search::TrackProtocol::kNative:
            return t;
        case train_search::TrackProtocol::kMfx:
            break;
    }
    return std::nullopt;
}

std::string train_name(const train_search::TrainIdentity& t) {
    switch (t.protocol) {
        case train_search::TrackProtocol::kDcc:
            return "DCC " + std::to_string(t.address) + (t.long_address ? "" : " short");
        case train_search::TrackProtocol::kMarklinMotorola:
            return "MM " + std::to_string(t.address);
        default:
            return "Train " + std::to_string(t.address);
    }
}

}  // namespace

void SimNode::allocate(train_search::Query query, EventId asked) {
    if (!train_factory_ || allocating_.contains(asked)) return;
    const auto identity = allocatable(query);
    if (!identity) return;
    allocating_[asked] = false;
    const std::uint32_t generation = boot_generation_;
    stack_.schedule(stack_.now() + kAllocateWait,
                    [this, generation, asked, identity = *identity](TimePoint) {
                        const auto it = allocating_.find(asked);
                        if (it == allocating_.end()) return;
                        const bool answered = it->second;
                        allocating_.erase(it);
                        if (answered || generation != boot_generation_) return;
                        NodeConfig c;
                        c.cdi = config_.cdi;
                        c.cdi_file = config_.cdi_file;
                        c.identity = config_.identity;
                        c.user_name = train_name(identity);
                        c.faults = config_.faults;
                        c.streams = config_.streams;
                        c.memory_config = config_.memory_config;
                        c.train = *config_.command_station;
                        c.train->identity = identity;
                        c.train->created_by = asked;
                        for (std::uint64_t k = 1; k <= kCreateAttempts; ++k) {
                            c.node_id = NodeId(config_.node_id.value() + created_.size() + k);
                            if (train_factory_(c)) {
                                created_.push_back(c.node_id);
                                return;
                            }
                        }
                        log("node " + config_.node_id.to_string() +
                            ": could not create a train for " + asked.to_string());
                    });
}

void SimNode::identified(EventId id, bool producer) {
    Message m;
    m.mti = producer ? Mti::kProducerIdentifiedUnknown : Mti::kConsumerIdentifiedUnknown;
    const auto raw = id.to_bytes();
    m.payload.assign(raw.begin(), raw.end());
    stack_.send_message(std::move(m));
}

void SimNode::advertise_all() {
    std::set<EventId> producers;
    std::set<EventId> consumers;
    for (const auto& [id, role] : advertised_events()) {
        if (produces(role) && producers.insert(id).second) identified(id, true);
        if (consumes(role) && consumers.insert(id).second) identified(id, false);
    }
}

std::vector<std::pair<EventId, EventRole>> SimNode::advertised_events() const {
    // Read now, so a written event ID counts at once.
    auto events = memory_->event_policy().frozen_at_start ? startup_events_ : memory_->events();
    if (train_) {
        events.emplace_back(train::kIsTrain, EventRole::kProducer);
        for (EventId e : {train::kEmergencyStopAll, train::kClearEmergencyStopAll,
                          train::kEmergencyOffAll, train::kClearEmergencyOffAll})
            events.emplace_back(e, EventRole::kConsumer);
    }
    return events;
}

void SimNode::advertise(const EventSlot* begin, const EventSlot* end) {
    for (const EventSlot* e = begin; e != end; ++e) {
        const auto raw = memory_->read(static_cast<std::uint8_t>(e->space),
                                       static_cast<std::uint32_t>(e->address), 8);
        const auto id = EventId::from_bytes(raw);
        if (!id || id->value() == 0) continue;
        if (produces(e->role)) identified(*id, true);
        if (consumes(e->role)) identified(*id, false);
    }
}

void SimNode::on_initialized() {
    advertise_all();
    if (train_ && config_.train->created_by) {
        // The search that created it learns its node (TrainSearchS §6.2).
        Message m;
        m.mti = Mti::kProducerIdentifiedValid;
        const auto raw = config_.train->created_by->to_bytes();
        m.payload.assign(raw.begin(), raw.end());
        stack_.send_message(std::move(m));
    }
    for (BroadcastClock& c : clocks_) c.started(stack_.now(), clock_send_);
    arm_clocks();
    if (!std::exchange(started_, true)) faults_.started(*life_);
}

// ---------------- Broadcast Time clocks ----------------

void SimNode::clock_message(const Message& msg) {
    if (msg.destination || msg.mti == Mti::kIdentifyEventsGlobal) return;
    for (BroadcastClock& c : clocks_) c.on_message(msg, stack_.now(), clock_send_);
    arm_clocks();
}

// One owner timer at the clocks' earliest deadline; a later arm that finds it earlier or equal
// leaves it, an earlier deadline supersedes it (the superseded timer then does nothing).
void SimNode::arm_clocks() {
    std::optional<TimePoint> next;
    for (const BroadcastClock& c : clocks_) {
        const auto d = c.next_deadline();
        if (d && (!next || *d < *next)) next = d;
    }
    if (!next || (clock_timer_ && *clock_timer_ <= *next)) return;
    clock_timer_ = next;
    stack_.schedule(*next, [this, at = *next](TimePoint now) {
        if (clock_timer_ != at) return;
        clock_timer_.reset();
        for (BroadcastClock& c : clocks_) c.poll(now, clock_send_);
        arm_clocks();
    });
}

void SimNode::abort_node(std::chrono::milliseconds silence) {
    ++counters_.aborts;
    ++boot_generation_;
    answer_delay_.reset();
    const std::uint32_t generation = boot_generation_;
    stack_.go_silent(stack_.now());
    stack_.schedule(stack_.now() + silence, [this, generation](TimePoint now) {
        if (generation == boot_generation_) power_up(now);
    });
}

bool SimNode::factory_reset() {
    std::string error;
    if (memory_->factory_reset(error)) return true;
    ++counters_.storage_errors;
    log("node " + config_.node_id.to_string() + ": factory reset not stored: " + error);
    return false;
}

void SimNode::log(const std::string& line) const {
    if (log_) {
        log_(line);
    } else {
        std::cerr << "simnode: " << line << "\n";
    }
}

void SimNode::power_up(TimePoint now) {
    memory_->reboot();
    if (train_) train_->power_up();
    faults_.powering_up(*life_);
    server_.reset();
    startup_events_ = memory_->events();
    ++boot_generation_;
    answer_delay_.reset();
    stream_reads_.clear();
    // The transport is untouched: TCP clients stay connected and see a fresh start-up.
    stack_.restart(now);
}

// ---------------- stream reads ----------------

void SimNode::start_stream_read(std::uint16_t src, const memory::StreamRead& read) {
    // The OK with Reply Pending went out; the reply follows once the requester took the stream.
    auto id = stack_.open_stream(NodeHandle{NodeId{}, src}, 0, read.destination_stream_id);
    if (!id) {
        send_reply(src, memory::MemoryConfigServer::stream_fail(
                            read, memory::ErrorCode::kBufferUnavailable));
        return;
    }
    stream_reads_[*id] = PendingStreamRead{src, read};
}

void SimNode::on_stream_event(const StreamEvent& event) {
    auto it = stream_reads_.find(event.id);
    if (it == stream_reads_.end()) return;  // an incoming stream: nothing to serve
    const PendingStreamRead& pending = it->second;
    switch (event.kind) {
        case StreamEvent::Kind::kOpened: {
            send_reply(pending.requester, memory::MemoryConfigServer::stream_reply(
                                              pending.read, event.source_id, event.dest_id));
            const std::vector<std::uint8_t> data = server_.stream_data(pending.read);
            stack_.write_stream(event.id, data);
            stack_.close_stream(event.id);
            return;
        }
        case StreamEvent::Kind::kRejected:
        case StreamEvent::Kind::kTimedOut:
            if (!event.outgoing || event.buffer == 0) {
                // Never accepted: the requester still waits for the reply datagram.
                const std::uint16_t silent =
                    event.kind == StreamEvent::Kind::kTimedOut
                        ? base::to_u16(base::ErrorCode::kTimeout)
                        : base::to_u16(base::ErrorCode::kBufferUnavailable);
                const std::uint16_t code = event.code != 0 ? event.code : silent;
                send_reply(pending.requester,
                           memory::MemoryConfigServer::stream_fail(
                               pending.read, static_cast<memory::ErrorCode>(code)));
            }
            stream_reads_.erase(it);
            return;
        case StreamEvent::Kind::kCompleted:
        case StreamEvent::Kind::kTerminated:
            stream_reads_.erase(it);
            return;
        default:
            return;
    }
}

// ---------------- datagrams ----------------

void SimNode::on_datagram(const ReceivedDatagram& d) {
    if (!answer_delay_.active()) {
        answer_datagram(d);
        return;
    }
    // The stack keeps the datagram's buffer (and rejects another from the same source) until
    // the late answer, as a slow node would.
    const std::uint32_t generation = boot_generation_;
    stack_.schedule(answer_delay_.answer_at(stack_.now()), [this, generation, d](TimePoint) {
        if (generation == boot_generation_) answer_datagram(d);
    });
}

void SimNode::answer_datagram(const ReceivedDatagram& d) {
    DatagramTurn turn{counters_.datagrams++, std::nullopt};
    faults_.datagram(turn);
    const std::uint16_t src = d.source_alias;
    if (turn.reject) {
        ++counters_.temporary_rejects;
        stack_.reject_datagram(src, *turn.reject);
        return;
    }
    if (d.payload.empty() || d.payload[0] != memory::kDatagramType || !config_.memory_config) {
        stack_.reject_datagram(src, base::to_u16(base::ErrorCode::kCommandUnknown));
        return;
    }
    memory::Decision decision = decide(src, d.payload);
    if (!decision.accepted) {
        stack_.reject_datagram(src, memory::to_u16(decision.reject_error));
        return;
    }
    const memory::SideEffects& fx = decision.effects;
    WriteTurn written{stored_writes_, false};
    if (fx.written) {
        ++stored_writes_;
        faults_.written(written);
    }
    const bool write_reboot = written.restart;
    if (write_reboot) decision.reply.reset();  // the OK still says Reply Pending
    if (!std::exchange(unacknowledged_, false)) send_answer(src, decision);
    if (fx.stream_read) start_stream_read(src, *fx.stream_read);
    if (const auto silence = std::exchange(silence_after_answer_, {}); silence.count() > 0) {
        abort_node(silence);
        return;
    }

    if (fx.reboot || fx.factory_reset || write_reboot) {
        if (fx.factory_reset) {
            ++counters_.factory_resets;  // done in decide(), before the acknowledgement
        } else if (fx.reboot) {
            ++counters_.reboots;
        } else {
            ++counters_.write_reboots;
        }
        power_up(stack_.now());
        return;
    }
    if (fx.written) after_write(*fx.written);
}

void SimNode::after_write(const memory::WrittenRange& written) {
    if (!written.changed) return;
    if (written.space == memory::Space::kAcdiUser) {
        stack_.reinitialize(stack_.now());  // SNIP changed: caches must refresh
    } else if (!memory_->event_policy().frozen_at_start) {
        const auto touched =
            memory_->events_in(memory::to_u8(written.space), written.address, written.length);
        advertise(touched.data(), touched.data() + touched.size());
    }
}

memory::WriteStatus SimNode::write_memory(std::uint8_t space, std::uint32_t address,
                                          std::span<const std::uint8_t> bytes) {
    memory::MemorySpace* s = memory_->space(space);
    if (s == nullptr) return memory::WriteStatus::kOutOfBounds;
    const auto length = static_cast<std::uint32_t>(bytes.size());
    const std::vector<std::uint8_t> before = memory_->read(space, address, length);
    const memory::WriteStatus status = s->write(address, bytes);
    if (status != memory::WriteStatus::kOk) return status;
    const bool changed =
        before.size() != bytes.size() || !std::equal(before.begin(), before.end(), bytes.begin());
    after_write({static_cast<memory::Space>(space), address, length, changed});
    return status;
}

// The datagram is decoded here once; the faults change the typed request and the typed reply,
// which send_answer() encodes once.
memory::Decision SimNode::decide(std::uint16_t src, std::span<const std::uint8_t> payload) {
    memory::DecodeResult asked = memory::decode(payload);
    RequestTurn turn{asked, *life_, std::nullopt, {}, {}};
    faults_.request(turn);
    if (turn.answer) return std::move(*turn.answer);
    memory::Source source;
    source.alias = src;
    source.node_id = stack_.alias_cache().node_of(src).value_or(NodeId{}).value();
    memory::Decision decision = server_.handle(source, asked);
    if (decision.accepted && turn.accepted) turn.accepted();
    if (decision.accepted) silence_after_answer_ = turn.silence_after;
    unacknowledged_ = faults_.reply(asked, decision);
    const memory::SideEffects& fx = decision.effects;
    if (decision.accepted && fx.unique_id_counter &&
        !memory_->store_unique_id_counter(*fx.unique_id_counter)) {
        ++counters_.storage_errors;
        log("node " + config_.node_id.to_string() + ": unique ID counter not stored");
        decision = memory::Decision::reject(memory::ErrorCode::kPermanent);
    }
    if (fx.not_stored) {
        ++counters_.storage_errors;
        log("node " + config_.node_id.to_string() + ": write of " +
            std::to_string(fx.not_stored->length) + " bytes to space " +
            std::to_string(memory::to_u8(fx.not_stored->space)) + " at " +
            std::to_string(fx.not_stored->address) + " not stored; refused with 0x1000");
    }
    // Performed before the acknowledgement, so an acknowledged reset is one on disk.
    if (decision.accepted && fx.factory_reset && !factory_reset()) {
        decision = memory::Decision::reject(memory::ErrorCode::kPermanent);
    }
    return decision;
}

void SimNode::send_answer(std::uint16_t src, memory::Decision& decision) {
    const std::uint8_t flags =
        datagram::ok_flags(decision.reply_pending, decision.reply_timeout_exponent);
    AnswerPlan plan;
    plan.index = replies_;
    faults_.answer(plan);
    if (plan.no_ok) {
        // The buffer must still be freed, or the node rejects every datagram after the fourth.
        stack_.release_datagram(src);
        if (decision.reply) {
            ++replies_;
            send_reply(src, decision.reply_bytes());
        }
        return;
    }
    if (!decision.reply) {
        stack_.accept_datagram(src, flags);
        return;
    }
    ++replies_;
    std::vector<std::uint8_t> reply = decision.reply_bytes();
    if (plan.reply_first) {
        send_reply(src, std::move(reply));
        stack_.accept_datagram(src, flags);
    } else if (plan.delay.count() > 0) {
        stack_.accept_datagram(src, flags);
        const std::uint32_t generation = boot_generation_;
        stack_.schedule(stack_.now() + plan.delay,
                        [this, generation, src, reply = std::move(reply)](TimePoint) {
                            if (generation == boot_generation_) send_reply(src, reply);
                        });
    } else {
        stack_.accept_datagram(src, flags);
        send_reply(src, std::move(reply));
    }
}

void SimNode::send_reply(std::uint16_t dest, std::vector<std::uint8_t> reply) {
    stack_.send_datagram(dest, reply, stack_.now());
}

}  // namespace olcb::simnode
