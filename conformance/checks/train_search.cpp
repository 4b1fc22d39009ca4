// Train Search (TrainSearchS §6): a train node answers a search for the digits of its name and
// stays silent for one it does not match or one with reserved values; a command station (named
// with --node and --command-station) creates a train node for an allocating search. Searches are
// Identify Producer messages of the range 09.00.99.FF.xx.xx.xx.xx, sent to the whole segment.
#include <algorithm>

#include "conformance/checks/checks.hpp"
#include "openlcb/train_search.hpp"

namespace olcb::conform::checks {
namespace {

namespace ts = olcb::train_search;
using namespace std::chrono_literals;

// How long an allocation may take: the station waits at least 200 ms for existing trains, then
// the new node reserves its alias (another 200 ms) before it answers.
constexpr Duration kAllocateWindow = 3s;
// Addresses the allocation checks try, the first no train answers is used (OlcbChecker uses
// 12 and 123, which a real layout may well have).
constexpr std::uint32_t kTestAddresses[] = {7301, 7302, 7303, 7304, 7305};

bool is_identified(Mti mti) {
    return mti == Mti::kProducerIdentifiedValid || mti == Mti::kProducerIdentifiedInvalid ||
           mti == Mti::kProducerIdentifiedUnknown;
}

// Who answered one search: every Producer Identified carrying its event.
struct SearchAnswers {
    std::vector<Message> answers;
    bool from(std::uint16_t alias) const {
        return std::any_of(answers.begin(), answers.end(),
                           [&](const Message& m) { return m.source.alias == alias; });
    }
};

// When a search stops waiting: never (the whole window), at the first answer, at the node's.
enum class Until : std::uint8_t { kWindow, kFirst, kNode };

// Sends the search and collects its answers until `until` or the window ends.
SearchAnswers search(CheckRun& run, const ts::Query& q, Duration window, Until until) {
    Session& s = run.session();
    Message m;
    m.mti = Mti::kIdentifyProducer;
    const auto raw = q.event().to_bytes();
    m.payload.assign(raw.begin(), raw.end());
    const std::size_t mark = s.message_mark();
    s.send(std::move(m));
    SearchAnswers a;
    const auto scan = [&] {
        a.answers.clear();
        for (const ReceivedMessage& r : s.messages_since(mark))
            if (is_identified(r.message.mti) && EventId::from_bytes(r.message.payload) == q.event())
                a.answers.push_back(r.message);
        if (until == Until::kFirst) return !a.answers.empty();
        return until == Until::kNode && a.from(run.alias());
    };
    s.run_until(scan, window);
    scan();
    return a;
}

// The first digit group of the train's name (at most six digits), "" when it has none.
std::string name_digits(const std::string& name) {
    std::string digits;
    for (char c : name) {
        if (c >= '0' && c <= '9') {
            if (digits.size() < 6) digits += c;
        } else if (!digits.empty()) {
            break;
        }
    }
    return digits;
}

// The node's name and the search for its digits; why set when there is none to make.
std::optional<ts::Query> name_query(CheckRun& run, std::string& name, std::string& why) {
    const auto& snip = run.probe<SnipProbe>().snip;
    if (!snip) {
        why = "no SNIP reply: the train's name is not known";
        return std::nullopt;
    }
    name = snip->user_name;
    const std::string digits = name_digits(name);
    if (digits.empty()) {
        why = "the train's name " + quoted(name) + " (SNIP user name) has no digits to search for";
        return std::nullopt;
    }
    return ts::Query::of(digits, 0);
}

// The answer to the name search: asked once (search.name-match, then the silence checks).
struct NameSearch {
    std::optional<ts::Query> query;
    std::string name;
    std::string why;  // no query to make
    SearchAnswers answers;
    bool answered = false;  // the node itself answered

    static NameSearch ask(CheckRun& run) {
        NameSearch n;
        n.query = name_query(run, n.name, n.why);
        if (!n.query) return n;
        n.answers = search(run, *n.query, run.options().answer_window, Until::kNode);
        n.answered = n.answers.from(run.alias());
        return n;
    }
};

// The exact search for the address --train-address gives, asked once.
struct AddressSearch {
    std::optional<ts::Query> query;
    bool answered = false;

    static AddressSearch ask(CheckRun& run) {
        AddressSearch a;
        const auto& address = run.options().train_address;
        if (!address) return a;
        a.query =
            ts::Query::of(std::to_string(*address), ts::flags::kExact | ts::flags::kAddressOnly);
        a.answered =
            search(run, *a.query, run.options().answer_window, Until::kNode).from(run.alias());
        return a;
    }
};

// A search the node answered (its address's, else its name's), for the silence checks.
std::optional<ts::Query> answered_search(CheckRun& run) {
    const AddressSearch& a = run.probe<AddressSearch>();
    if (a.answered) return a.query;
    const NameSearch& n = run.probe<NameSearch>();
    if (n.answered) return n.query;
    return std::nullopt;
}

void search_name_match(CheckRun& run, const CheckSpec& spec) {
    const NameSearch& n = run.probe<NameSearch>();
    if (!n.query) return run.out(spec).skip(n.why);
    const std::string asked =
        "search " + quoted(n.query->to_string()) + " (name " + quoted(n.name) + ")";
    if (n.answered) return run.out(spec).pass(asked + " answered with Producer Identified");
    // A train that does not implement the search at all stays silent too: only recommended.
    run.out(spec).warn(asked +
                       ": no answer. A train node matching a search shall answer it "
                       "(TrainSearchS §6.1); Train Search is strongly recommended for "
                       "train nodes (TrainControlS §3)");
}

void search_address_match(CheckRun& run, const CheckSpec& spec) {
    const AddressSearch& a = run.probe<AddressSearch>();
    if (!a.query)
        return run.out(spec).skip("the train's address is not known: give --train-address");
    const std::string asked = "exact search for address " + quoted(a.query->to_string());
    if (a.answered) return run.out(spec).pass(asked + " answered with Producer Identified");
    run.out(spec).warn(asked +
                       ": no answer. A train node matching a search shall answer it "
                       "(TrainSearchS §6.1); Train Search is strongly recommended for "
                       "train nodes (TrainControlS §3)");
}

constexpr const char* kNoSearchAnswered =
    "depends on search.address-match and search.name-match: the node answers no search, so its "
    "silence proves nothing";

// A search that cannot match the node must stay unanswered; silence proves something only when
// the node answered a search for its own address or name.
void expect_silence(CheckRun& run, const CheckSpec& spec, const ts::Query& q,
                    const std::string& what) {
    if (!answered_search(run)) return run.out(spec).skip(kNoSearchAnswered);
    const SearchAnswers a = search(run, q, run.options().window, Until::kNode);
    run.out(spec).judge(!a.from(run.alias()),
                        a.from(run.alias()) ? "the node answered " + what : what + ": no answer",
                        "no Producer Identified", "Producer Identified " + q.event().to_string());
}

void search_no_match_silent(CheckRun& run, const CheckSpec& spec) {
    // No DCC train has address 999999 (14-bit addresses end at 10239).
    const auto q =
        ts::Query::of("999999", ts::flags::kExact | ts::flags::kAddressOnly | ts::protocol::kDcc);
    expect_silence(run, spec, *q, "exact search for DCC address 999999");
}

void search_reserved_ignored(CheckRun& run, const CheckSpec& spec) {
    const auto answered = answered_search(run);
    if (!answered) return run.out(spec).skip(kNoSearchAnswered);
    // The answered search with the reserved track protocol 0b00/0/11.
    ts::Query q = *answered;
    q.flags = static_cast<std::uint8_t>(q.flags | 0x03);
    expect_silence(run, spec, q,
                   "search " + quoted(answered->to_string()) + " with the reserved protocol 0x03");
}

// "" when allocations may run; else why the check SKIPs.
std::string may_allocate(CheckRun& run) {
    if (!run.options().named || !run.options().command_station)
        return "makes a command station create train nodes (which stay): runs only on a node "
               "named with --node and --command-station";
    if (run.options().read_only) return "--read-only: no train node is created";
    return {};
}

// An address no train answers an exact search for; nullopt when all candidates are taken.
std::optional<std::uint32_t> free_address(CheckRun& run, std::uint32_t skip = 0) {
    for (std::uint32_t a : kTestAddresses) {
        if (a == skip) continue;
        const auto q =
            ts::Query::of(std::to_string(a), ts::flags::kExact | ts::flags::kAddressOnly);
        if (search(run, *q, run.options().window, Until::kFirst).answers.empty()) return a;
    }
    return std::nullopt;
}

// Allocates address with these flags: the Producer Identified Valid answers (none: why set).
std::optional<Message> allocate(CheckRun& run, const ts::Query& q, std::string& why) {
    const SearchAnswers a = search(run, q, kAllocateWindow, Until::kFirst);
    for (const Message& m : a.answers)
        if (m.mti == Mti::kProducerIdentifiedValid) return m;
    why = a.answers.empty() ? "no answer in 3 s"
                            : "answered with " + std::string(mti_name(a.answers.front().mti)) +
                                  ", not Producer Identified Valid";
    return std::nullopt;
}

void search_allocate(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_allocate(run); !why.empty()) return run.out(spec).skip(why);
    const auto address = free_address(run);
    if (!address) return run.out(spec).skip("every test address (7301-7305) has a train already");
    const std::string digits = std::to_string(*address);
    const auto q =
        ts::Query::of(digits, ts::flags::kAllocate | ts::flags::kExact | ts::flags::kAddressOnly);
    std::string why;
    const auto created = allocate(run, *q, why);
    if (!created)
        return run.out(spec).fail("allocating search for address " + digits + ": " + why,
                                  "Producer Identified Valid from a new train node (§6.2)", why);
    const auto find = ts::Query::of(digits, ts::flags::kExact | ts::flags::kAddressOnly);
    const SearchAnswers found = search(run, *find, run.options().answer_window, Until::kFirst);
    if (!found.from(created->source.alias))
        return run.out(spec).fail(
            "the train created for " + digits + " does not answer a search for it",
            "Producer Identified (§6.1)", "no answer from it");
    run.out(spec).pass("allocating search for " + digits +
                       " answered Producer Identified Valid by a new train node, which answers "
                       "a search for it (it stays)");
}

void search_allocate_partial(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_allocate(run); !why.empty()) return run.out(spec).skip(why);
    const auto address = free_address(run);
    if (!address) return run.out(spec).skip("every test address (7301-7305) has a train already");
    const std::string digits = std::to_string(*address);
    std::string why;
    if (!allocate(run,
                  *ts::Query::of(
                      digits, ts::flags::kAllocate | ts::flags::kExact | ts::flags::kAddressOnly),
                  why))
        return run.out(spec).skip("depends on search.allocate: " + why);
    for (std::size_t len : {std::size_t{1}, std::size_t{2}, digits.size() - 1}) {
        const auto q = ts::Query::of(digits.substr(0, len), ts::flags::kAddressOnly);
        const SearchAnswers a = search(run, *q, run.options().answer_window, Until::kFirst);
        if (a.answers.empty())
            return run.out(spec).fail("partial search " + quoted(q->to_string()) +
                                          " found no train, though " + digits + " exists",
                                      "a Producer Identified (§6.3: a prefix matches)",
                                      "no answer");
    }
    run.out(spec).pass("prefix searches 1, 2 and " + std::to_string(digits.size() - 1) +
                       " digits of " + digits + " each answered");
}

void search_allocate_reserved(CheckRun& run, const CheckSpec& spec) {
    if (const auto why = may_allocate(run); !why.empty()) return run.out(spec).skip(why);
    const auto address = free_address(run);
    if (!address) return run.out(spec).skip("every test address (7301-7305) has a train already");
    const std::string digits = std::to_string(*address);
    auto with_c =
        *ts::Query::of(digits, ts::flags::kAllocate | ts::flags::kExact | ts::flags::kAddressOnly);
    with_c.nibbles[5] = 0xC;  // a reserved nibble
    std::vector<ts::Query> asks{with_c};
    for (const std::uint8_t flags : {std::uint8_t{0xF0}, std::uint8_t{0xF8}, std::uint8_t{0xE3}})
        asks.push_back(*ts::Query::of(digits, flags));
    for (const ts::Query& q : asks) {
        const SearchAnswers a = search(run, q, run.options().answer_window, Until::kFirst);
        if (!a.answers.empty())
            return run.out(spec).fail("the allocating search " + q.event().to_string() +
                                          " with reserved values was answered",
                                      "no answer: reserved values match nothing (§6.3)",
                                      std::string(mti_name(a.answers.front().mti)));
    }
    run.out(spec).pass(
        "allocating searches with a reserved nibble and the reserved protocol "
        "values 0xF0, 0xF8, 0xE3 were ignored (no train created)");
}

}  // namespace

std::vector<CheckSpec> train_search_checks() {
    const auto train = [](CheckSpec s) {
        s.needs = Protocol::kTractionControl;
        return s;
    };
    return {
        train({"search.name-match", 756, Category::kSearch, "TrainSearchS §6.1, §6.3",
               Strength::kShall,
               "a train node matching a search answers Producer Identified (Train Search is "
               "strongly recommended for trains: no answer at all is a WARN)",
               "", "search for the first digits of the SNIP user name: the node answers",
               search_name_match}),
        train({"search.address-match", 757, Category::kSearch, "TrainSearchS §6.1, §6.3",
               Strength::kShall,
               "a train node answers an exact search for its address (no answer at all is a "
               "WARN: Train Search is strongly recommended)",
               "", "(--train-address N) exact address-only search for N: the node answers",
               search_address_match}),
        train({"search.no-match-silent", 758, Category::kSearch, "TrainSearchS §6.1",
               Strength::kShall, "a train node does not answer a search it does not match", "",
               "exact search for DCC address 999999: no answer from the node",
               search_no_match_silent}),
        train({"search.reserved-ignored", 759, Category::kSearch, "TrainSearchS §5.2, §6.3",
               Strength::kShall, "a search with reserved values matches nothing", "ts40",
               "the answered address or name search with the reserved protocol value 0x03: no "
               "answer",
               search_reserved_ignored}),
        {"search.allocate", 761, Category::kSearch, "TrainSearchS §6.1, §6.2", Strength::kShall,
         "a command station answers an allocating search no train answers with a new train "
         "node's Producer Identified Valid; the train then answers searches",
         "ts10",
         "(--node --command-station) exact search for a free test address, allocate it, search "
         "again: answered by the new train",
         search_allocate},
        {"search.allocate-partial", 762, Category::kSearch, "TrainSearchS §6.3", Strength::kShall,
         "a search whose digits are a prefix of a train's address matches it", "ts20",
         "(--node --command-station) allocate a test address, search its first 1, 2 and n-1 "
         "digits (not exact): each answered",
         search_allocate_partial},
        {"search.allocate-reserved", 763, Category::kSearch, "TrainSearchS §5.2, §6.2, §6.3",
         Strength::kShall,
         "an allocating search with reserved values (nibbles 0xA-0xE, protocol 0b1x.., 0x03) "
         "creates nothing and is not answered",
         "ts30, ts40",
         "(--node --command-station) allocate with a 0xC nibble and with flags 0xF0, 0xF8, 0xE3: "
         "no answer",
         search_allocate_reserved},
    };
}

}  // namespace olcb::conform::checks
