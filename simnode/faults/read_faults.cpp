// Read faults: reads, Get Address Space Information, and the form and reject codes of memory
// replies.
#include <algorithm>
#include <span>
#include <type_traits>
#include <variant>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// How far space-info-short undercuts the real highest address.
constexpr std::uint32_t kSpaceInfoShortBy = 16;
// What read-past-end-garbage returns for each byte past the end of 0xFD.
constexpr std::uint8_t kPastEndGarbage = 0xA5;

// field-reads-only: where the ACDI fields of 252 and 251 start and how long they are (fact
// sheet 7); the first of each space is the version byte.
struct AcdiField {
    std::uint32_t address, size;
};
constexpr AcdiField kManufacturerFields[] = {{0, 1}, {1, 41}, {42, 41}, {83, 21}, {104, 21}};
constexpr AcdiField kUserFields[] = {{0, 1}, {1, 63}, {64, 64}};

// field-reads-only: cuts a Read Reply of 251/252 to the field it starts at (a string up to and
// including its NUL) or to 1 byte off a field start.
void cut_to_field(ReplyTurn& turn, FaultValue) {
    auto* r = turn.decision.reply ? std::get_if<memory::ReadReply>(&*turn.decision.reply) : nullptr;
    if (r == nullptr) return;
    std::span<const AcdiField> fields;
    if (r->space == memory::Space::kAcdiManufacturer) {
        fields = kManufacturerFields;
    } else if (r->space == memory::Space::kAcdiUser) {
        fields = kUserFields;
    } else {
        return;
    }
    std::size_t keep = 1;
    for (const AcdiField& field : fields) {
        if (r->address != field.address) continue;
        const std::size_t within = std::min<std::size_t>(field.size, r->data.size());
        const auto end = r->data.begin() + static_cast<std::ptrdiff_t>(within);
        const auto nul = std::find(r->data.begin(), end, std::uint8_t{0});
        keep = static_cast<std::size_t>((nul == end ? end : nul + 1) - r->data.begin());
    }
    if (r->data.size() > keep) r->data.resize(keep);
}

// A read starting at/after the end gets Read Reply OK with `count` fill bytes instead of the
// 0x1082 failure (in the failure's form, which reply-form may have changed already).
void fill_past_end(ReplyTurn& turn, std::uint8_t fill, bool config_space_only) {
    memory::Decision& d = turn.decision;
    const auto* fail = d.reply ? std::get_if<memory::ReadReplyFail>(&*d.reply) : nullptr;
    const auto* read = turn.asked.ok() ? std::get_if<memory::Read>(&turn.asked.message) : nullptr;
    if (fail == nullptr || read == nullptr || fail->error != memory::ErrorCode::kOutOfBounds)
        return;
    if (config_space_only && read->space != memory::Space::kConfig) return;
    d.reply = memory::ReadReply{read->space, read->address,
                                std::vector<std::uint8_t>(read->count & 0x7F, fill), fail->form};
}

void zeros_past_end(ReplyTurn& turn, FaultValue) {
    fill_past_end(turn, 0, false);
}

void garbage_past_end(ReplyTurn& turn, FaultValue) {
    fill_past_end(turn, kPastEndGarbage, true);
}

memory::SpaceInfoReply* space_info(ReplyTurn& turn) {
    memory::Decision& d = turn.decision;
    return d.reply ? std::get_if<memory::SpaceInfoReply>(&*d.reply) : nullptr;
}

void short_highest(ReplyTurn& turn, FaultValue) {
    if (auto* info = space_info(turn))
        info->highest_address -= std::min(info->highest_address, kSpaceInfoShortBy);
}

// The size, as OpenMRN's FileMemorySpace says.
void size_as_highest(ReplyTurn& turn, FaultValue) {
    auto* info = space_info(turn);
    if (info != nullptr &&
        (info->space == memory::Space::kAcdiUser || info->space == memory::Space::kConfig)) {
        ++info->highest_address;
    }
}

// The other form for a short-form-capable space; byte-6-only spaces keep theirs.
void other_form(ReplyTurn& turn, FaultValue) {
    if (!turn.decision.reply) return;
    std::visit(
        [](auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, memory::ReadReply> ||
                          std::is_same_v<T, memory::ReadReplyFail> ||
                          std::is_same_v<T, memory::WriteReply> ||
                          std::is_same_v<T, memory::WriteReplyFail>) {
                if (!memory::has_short_form(m.space)) return;
                m.form = memory::resolve_form(m.space, m.form) == memory::SpaceForm::kShort
                             ? memory::SpaceForm::kByte6
                             : memory::SpaceForm::kShort;
            }
        },
        *turn.decision.reply);
}

// The server gives 0x1081 only to reads and writes, 0x1083 only to writes.
template <memory::ErrorCode Code>
void reject_0x1041(ReplyTurn& turn, FaultValue) {
    memory::Decision& d = turn.decision;
    if (!d.accepted && d.reject_error == Code)
        d.reject_error = memory::ErrorCode::kSubcommandUnknown;
}

// What reads and Space Info return.
std::vector<FaultDecl> read_contents() {
    return {
        {
            .name = "read-past-end",
            .order = 150,
            .summary = "a read at/after the end of a space returns zeros, not 0x1082",
            .rule_broken = "MemCfg: a read starting at/after the end fails with `0x1082` (fact "
                           "sheet 5.3)",
            .client_sees = "such a read gets Read Reply OK with `count` zero bytes, so a client "
                           "never sees the end",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-past-end.ff", "memory.read-past-end.fd",
                       "memory.read-past-end.fc", "memory.read-past-end.fb"},
            .hooks = {.reply = zeros_past_end},
        },
        {
            .name = "read-past-end-garbage",
            .order = 330,
            .summary = "a read of 0xFD at/after its end returns count 0xA5 bytes, not 0x1082",
            .rule_broken = "MemCfg: a read starting at/after the end fails with `0x1082` (fact "
                           "sheet 5.3)",
            .client_sees = "on space 0xFD only, such a read gets Read Reply OK with `count` "
                           "bytes of `0xA5` (at the end, or 0x100 past it alike); a read "
                           "crossing the end is still cut short there, other spaces still fail "
                           "`0x1082`",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-past-end.fd"},
            .hooks = {.reply = garbage_past_end},
        },
        {
            .name = "space-info-short",
            .order = 160,
            .summary = "Get Address Space Information reports a too small highest address",
            .rule_broken = "MemCfg Get Address Space Information: highest address covers every "
                           "byte the CDI layout uses (fact sheet 5.4)",
            .client_sees = "every present space reports a highest address 16 lower than real",
            .verdict = Verdict::kFail,
            .category = "acdi",
            .checks = {"acdi.space-info"},
            .hooks = {.reply = short_highest},
        },
        {
            .name = "highest-unreadable",
            .order = 370,
            .summary = "Space Info of 251 and 253 reports the size as highest address (one too "
                       "high)",
            .rule_broken = "MemCfg Get Address Space Information: the highest address is the "
                           "last readable byte, size − 1 (fact sheet 5.4). Model of OpenMRN's "
                           "`FileMemorySpace` (`real-world.md` §1)",
            .client_sees = "Space Info of 251 and 253 reports their size as highest address "
                           "(251: 128, default 253: 179); a read at that address fails `0x1082`. "
                           "0xFF and 252 report as usual",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.read-at-highest.fd", "memory.read-at-highest.fb"},
            .hooks = {.reply = size_as_highest},
        },
        {
            .name = "field-reads-only",
            .order = 290,
            .summary = "spaces 251/252 return one ACDI field per read, 1 byte off a field start",
            .rule_broken = "MemCfg read: a read returns `count` bytes, fewer only at the end of "
                           "the space (fact sheet 5.3); ACDI 252/251 are plain byte spaces (fact "
                           "sheet 7). Model of OpenLcbCLib (`real-world.md` §5)",
            .client_sees = "reads of 252/251 that start at a field (252: 0, 1, 42, 83, 104; 251: "
                           "0, 1, 64) return that field only: the version byte alone, a string "
                           "up to and including its first NUL (the whole field if it has none), "
                           "never more than asked; a read starting anywhere else inside the "
                           "space returns 1 byte; all as Read Reply OK (a 64-byte read of 252 at "
                           "0 returns 1 byte). Reads at/after the end still fail `0x1082`",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.short-read.fb", "memory.short-read.fc"},
            .hooks = {.reply = cut_to_field},
        },
    };
}

// The form and reject codes of memory replies.
std::vector<FaultDecl> reply_codes() {
    return {
        {
            .name = "reply-form",
            .order = 170,
            .summary = "replies in byte-6 form to short-form requests and vice versa",
            .rule_broken = "MemCfg: answer in the form of the request (fact sheet 5.1, 11)",
            .client_sees = "reads/writes of 0xFD–0xFF in the short form are answered in the "
                           "byte-6 form and vice versa (252/251 have only the byte-6 form)",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.reply-form"},
            .hooks = {.reply = other_form},
        },
        {
            .name = "unknown-space-0x1041",
            .order = 300,
            .summary = "read/write of an unknown space rejected 0x1041, not 0x1081",
            .rule_broken = "MemCfg: a read or write of an unknown space is rejected `0x1081` "
                           "(fact sheet 5.2)",
            .client_sees = "Datagram Rejected `0x1041` (subcommand unknown) instead, as "
                           "OpenLcbCLib does (`real-world.md` §5); Get Address Space Information "
                           "of an unknown space still answers \"not present\"",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.unknown-space"},
            .hooks = {.reply = reject_0x1041<memory::ErrorCode::kSpaceUnknown>},
        },
        {
            .name = "readonly-0x1041",
            .order = 310,
            .summary = "write to a read-only space rejected 0x1041, not 0x1083",
            .rule_broken = "MemCfg: a write to a read-only space is rejected `0x1083` (fact "
                           "sheet 5.2, 5.5)",
            .client_sees = "writes to 0xFF and 252 get Datagram Rejected `0x1041` instead, as "
                           "OpenLcbCLib does (`real-world.md` §5)",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.readonly-refused.ff", "memory.readonly-refused.fc"},
            .hooks = {.reply = reject_0x1041<memory::ErrorCode::kReadOnly>},
        },
    };
}

}  // namespace

std::vector<FaultDecl> read_faults() {
    auto all = read_contents();
    for (FaultDecl& d : reply_codes()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
