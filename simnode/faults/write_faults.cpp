// Write faults: what the node does with a write it acknowledges.
#include <algorithm>
#include <memory>
#include <span>
#include <variant>
#include <vector>

#include "simnode/faults/fault_families.hpp"
#include "simnode/node_memory.hpp"

namespace olcb::simnode {

namespace {

constexpr std::uint8_t kConfigSpace = 0xFD;

// Keeps the whole content in RAM in front of an inner space: writes stop here, a restart forgets
// them.
template <bool Writable>
class RamOverlay : public SpaceLayer {
public:
    explicit RamOverlay(memory::MemorySpace& inner) : SpaceLayer(inner) { power_cycle(); }
    bool read_only() const override { return !Writable && inner().read_only(); }
    std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) override {
        return memory::read_clamped(bytes_, address, out);
    }
    memory::WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        if (read_only()) return memory::WriteStatus::kReadOnly;
        if (!memory::fits(bytes_.size(), address, in.size())) {
            return memory::WriteStatus::kOutOfBounds;
        }
        std::copy(in.begin(), in.end(), bytes_.begin() + address);
        return memory::WriteStatus::kOk;
    }
    void power_cycle() override {
        bytes_.assign(inner().size(), 0);
        bytes_.resize(inner().read(0, bytes_));
    }

private:
    std::vector<std::uint8_t> bytes_;
};

// Answers like a successful write and stores nothing.
class DropWrites : public SpaceLayer {
public:
    using SpaceLayer::SpaceLayer;
    memory::WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        if (read_only()) return memory::WriteStatus::kReadOnly;
        if (!memory::fits(size(), address, in.size())) return memory::WriteStatus::kOutOfBounds;
        return memory::WriteStatus::kOk;
    }
};

template <class Layer>
std::unique_ptr<SpaceLayer> make_layer(memory::MemorySpace& inner) {
    return std::make_unique<Layer>(inner);
}

void drop_writes(SpaceBuild& build, FaultValue) {
    if (!build.constant) build.acknowledging.push_back(make_layer<DropWrites>);
}

void keep_in_ram(SpaceBuild& build, FaultValue) {
    if (!build.constant) build.storage.push_back(make_layer<RamOverlay<false>>);
}

void constants_writable(SpaceBuild& build, FaultValue) {
    if (build.constant) build.storage.push_back(make_layer<RamOverlay<true>>);
}

void restart_at_nth(WriteTurn& turn, FaultValue v) {
    if (turn.index + 1 == v.value) turn.restart = true;
}

// A write crossing the end of its space: the part that fits is what the server stores; the
// rest is returned.
std::optional<std::vector<std::uint8_t>> cut_at_end(RequestTurn& turn,
                                                    memory::MemorySpace*& space) {
    auto* write = std::get_if<memory::Write>(&turn.asked.message);
    if (!turn.asked.ok() || write == nullptr) return std::nullopt;
    space = turn.life.memory().space(memory::to_u8(write->space));
    if (space == nullptr || space->read_only() || write->address >= space->size() ||
        write->data.size() <= space->size() - write->address) {
        return std::nullopt;
    }
    const std::size_t fits = space->size() - write->address;
    std::vector<std::uint8_t> tail(write->data.begin() + static_cast<std::ptrdiff_t>(fits),
                                   write->data.end());
    write->data.resize(fits);
    return tail;
}

// What lies past the end of 251 goes on into 253 at 251's size (0x80), since OpenMRN's 251 is
// the first 128 bytes of 253's file (real-world.md 1); of other spaces it is dropped.
void spill_into_next(RequestTurn& turn, FaultValue) {
    memory::MemorySpace* space = nullptr;
    auto tail = cut_at_end(turn, space);
    if (!tail) return;
    const bool acdi_user =
        std::get<memory::Write>(turn.asked.message).space == memory::Space::kAcdiUser;
    turn.accepted = [&life = turn.life, space, acdi_user, tail = std::move(*tail)] {
        memory::MemorySpace* next = life.memory().space(kConfigSpace);
        if (!acdi_user || next == nullptr || space->size() >= next->size()) return;
        const std::size_t room = next->size() - space->size();
        const auto spilled = std::span(tail).first(std::min(tail.size(), room));
        if (next->write(static_cast<std::uint32_t>(space->size()), spilled) !=
            memory::WriteStatus::kOk) {
            life.storage_error();
        }
    };
}

// The bytes past the end are kept beside the space's image, where no read reaches, as
// OpenMRN's config file grows by them.
void keep_past_end(RequestTurn& turn, FaultValue) {
    memory::MemorySpace* space = nullptr;
    auto tail = cut_at_end(turn, space);
    if (!tail) return;
    const std::uint8_t number = memory::to_u8(std::get<memory::Write>(turn.asked.message).space);
    turn.accepted = [&life = turn.life, number, tail = std::move(*tail)] {
        if (!life.memory().keep_past_end(number, 0, tail)) life.storage_error();
    };
}

// A Write Under Mask becomes a Write of its data bytes (the masks ignored), and the node goes
// silent once it has answered.
void unmask(RequestTurn& turn, FaultValue v) {
    const auto* masked = std::get_if<memory::WriteUnderMask>(&turn.asked.message);
    if (!turn.asked.ok() || masked == nullptr) return;
    memory::Write whole{masked->space, masked->address, {}, masked->form};
    for (const memory::MaskedByte& b : masked->bytes) whole.data.push_back(b.value);
    turn.asked.message = std::move(whole);
    turn.silence_after = std::chrono::milliseconds(v.value);
}

// Writes within a space that are not stored as acknowledged.
std::vector<FaultDecl> stored_writes() {
    return {
        {
            .name = "write-dropped",
            .order = 120,
            .summary = "writes acknowledged but not stored",
            .rule_broken = "MemCfg write: Write Reply OK means the data was stored (fact sheet "
                           "5.2)",
            .client_sees = "every write is acknowledged OK, nothing changes; a "
                           "write-and-read-back shows it",
            .verdict = Verdict::kFail,
            .category = "encoding",
            .checks = {"encoding.eventid", "encoding.float", "encoding.int", "encoding.string"},
            .hooks = {.space = drop_writes},
        },
        {
            .name = "write-not-persisted",
            .order = 130,
            .summary = "writes kept in RAM only: lost on reboot",
            .rule_broken = "MemCfg + CDI: configuration is non-volatile (survives Reset/Reboot, "
                           "power loss)",
            .client_sees = "writes read back fine until Reset/Reboot or a restart, then the old "
                           "value is back (image on disk untouched); lcc-conform sees it with "
                           "`--reboot`",
            .verdict = Verdict::kWarn,
            .category = "encoding",
            .checks = {"encoding.persist-after-reboot"},
            .hooks = {.space = keep_in_ram},
        },
        {
            .name = "readonly-writable",
            .order = 140,
            .summary = "writes to spaces 0xFF and 252 accepted",
            .rule_broken = "MemCfg: 0xFF and 252 are read-only, writes get `0x1083` (fact sheet "
                           "5.2, 5.5)",
            .client_sees = "writes to 0xFF and 252 answered Write Reply OK and read back changed "
                           "(in RAM; a reboot restores them)",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.readonly-refused.ff"},
            .hooks = {.space = constants_writable},
        },
        {
            .name = "reboot-on-write",
            .order = 240,
            .param = {ParamKind::kNumber, "N", 1, 1, kMaxCount},
            .summary = "the Nth stored write restarts the node without its Write Reply (once)",
            .doc_parameter = "`N`, default 1",
            .rule_broken = "MemCfg write: the node answers Datagram Received OK with Reply "
                           "Pending, then the Write Reply, and stays up (fact sheet 5.2)",
            .client_sees = "the Nth stored write (one that gets Write Reply OK; rejected and "
                           "failed writes do not count) is stored and acknowledged OK with Reply "
                           "Pending, then the node restarts (CID..RID, AMD, Initialization "
                           "Complete) instead of sending the Write Reply; once per process, not "
                           "again at the 2N-th",
            .verdict = Verdict::kIncomplete,
            .category = "node",
            .checks = {"node.rebooted"},
            .hooks = {.written = restart_at_nth},
        },
    };
}

// Writes past a space's end, and Write Under Mask.
std::vector<FaultDecl> crossing_writes() {
    return {
        {
            .name = "write-past-end-spills",
            .order = 340,
            .summary = "writes crossing a space's end accepted; 251's excess bytes land in 253 "
                       "at 0x80, past its first 128 bytes (251 is the start of 253's file, as on "
                       "OpenMRN)",
            .rule_broken = "none of MemCfg requires refusing a write that crosses the end (§4.3 "
                           "defines `0x1082` for it, the TN recommends it); storing bytes no "
                           "read reaches, or in another space, is what a tool must not trigger "
                           "unasked. Model of OpenMRN's file-backed 251 (`real-world.md` §1)",
            .client_sees = "a write to 251 starting inside it and running past byte 127 gets "
                           "Write Reply OK: the bytes up to 127 go to 251, the rest into space "
                           "253 at 0x80 on (251 is the first 128 bytes of 253's file, as on "
                           "OpenMRN, so they land on its \"Internal data\" version); a crossing "
                           "write of any other writable space gets Write Reply OK, the bytes "
                           "that fit are stored, the rest dropped. A write *starting* at/after "
                           "the end still fails `0x1082`. lcc-conform crosses an end only with "
                           "`--write-past-end`",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.write-past-end.fb"},
            .hooks = {.request = spill_into_next},
        },
        {
            .name = "write-past-end-grows",
            .order = 350,
            .summary = "writes crossing a space's end accepted; the excess bytes are kept beside "
                       "the image (FILE.past-end) where no read reaches them, as OpenMRN's "
                       "config file grows",
            .rule_broken = "as `write-past-end-spills`. Model of OpenMRN's 253 (`real-world.md` "
                           "§1): its config file grows by the bytes written past the end, which "
                           "survive a restart and no read reaches",
            .client_sees = "a crossing write of any writable space gets Write Reply OK: the "
                           "bytes that fit are stored, the rest kept beside the space's image in "
                           "`space-N.img.past-end` (synced; in RAM without an image directory), "
                           "never readable through any space; Space Info is unchanged. "
                           "lcc-conform crosses an end only with `--write-past-end`, then says "
                           "which bytes the node may keep and never calls its memory "
                           "byte-identical",
            .verdict = Verdict::kWarn,
            .category = "memory",
            .checks = {"memory.write-past-end.fd", "memory.write-past-end.fb"},
            .hooks = {.request = keep_past_end},
        },
        {
            .name = "mask-ignored",
            .order = 360,
            .param = {ParamKind::kNumber, "MS", 5000, 1, kMaxDelayMs},
            .summary = "Write Under Mask stores the data bytes whole, ignoring the masks; then "
                       "silent MS ms and a restart",
            .doc_parameter = "`MS`, default 5000 (1..600000)",
            .rule_broken = "MemCfg §4.10: Write Under Mask changes only the bits its mask selects",
            .client_sees = "a Write Under Mask stores its data bytes whole, as a plain write, "
                           "answers as usual, then the node is silent for MS ms and restarts "
                           "(memory kept). A careful client saved the byte first and puts it "
                           "back when the node answers again, or keeps its backup and says how "
                           "to restore it",
            .verdict = Verdict::kIncomplete,
            .category = "memory",
            .checks = {"memory.write-under-mask"},
            .hooks = {.request = unmask},
        },
    };
}

}  // namespace

std::vector<FaultDecl> write_faults() {
    auto all = stored_writes();
    for (FaultDecl& d : crossing_writes()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
