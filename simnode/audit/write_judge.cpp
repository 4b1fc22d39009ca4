#include "simnode/audit/write_judge.hpp"

#include <algorithm>
#include <utility>

#include "base/hex.hpp"
#include "cdi/value_codec.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

std::string place(std::uint8_t space, std::uint64_t address) {
    return base::hex_digits(space, 2) + ":" + base::hex_digits(address, 8);
}

// "<int> 'Settings/Trim' (0xFD @0x00000001)"
std::string describe(std::uint8_t space, const VariableRef& v) {
    const std::string where = " (" + base::hex(space, 2) + " @" + base::hex(v.address, 8) + ")";
    return "<" +
           std::string(v.element->tag.empty() ? cdi::kind_name(v.element->kind)
                                              : v.element->tag.c_str()) +
           "> '" + v.name + "'" + where;
}

void add_frames(std::vector<CanFrame>& to, std::span<const CanFrame> frames) {
    for (const CanFrame& f : frames) {
        if (to.size() >= kMaxFindingFrames) return;
        to.push_back(f);
    }
}

// Which rule a value check_value refused breaks: the map's, or the kind's own limits.
RuleId refused_rule(const cdi::Element& e, const cdi::Value& value) {
    if (e.kind == cdi::ElementKind::kAction) return RuleId::kCdiActionValue;
    if (e.map) {
        cdi::Element without_map = e;
        without_map.map.reset();
        if (cdi::check_value(without_map, value)) return RuleId::kCdiNotInMap;
    }
    switch (e.kind) {
        case cdi::ElementKind::kFloat:
            return RuleId::kCdiFloatOutOfRange;
        case cdi::ElementKind::kString:
            return RuleId::kCdiStringInvalid;
        case cdi::ElementKind::kEventId:
            return RuleId::kCdiNotInMap;
        default:
            return RuleId::kCdiIntOutOfRange;
    }
}

// The CDI's verdict on a variable's whole new bytes; nullopt when they are allowed (or the
// element has no value rules: a <blob>, an unknown element, a size the standard forbids).
std::optional<Verdict> judge_value(std::uint8_t space, const VariableRef& v,
                                   std::span<const std::uint8_t> bytes) {
    const cdi::Element& e = *v.element;
    if (!cdi::value_kind_of(e) || !cdi::value_size(e)) return std::nullopt;
    const auto value = cdi::decode(e, bytes, cdi::CodecMode::kStrict);
    if (!value) {
        if (e.kind != cdi::ElementKind::kString) return std::nullopt;
        return Verdict{RuleId::kCdiStringInvalid,
                       "wrote " + describe(space, v) + ": " + value.error().message,
                       place(space, v.address),
                       {}};
    }
    const auto status = cdi::check_value(e, *value);
    if (status) return std::nullopt;
    return Verdict{refused_rule(e, *value),
                   "wrote " + cdi::format_value(e, *value) + " to " + describe(space, v) + ": " +
                       status.error().message,
                   place(space, v.address),
                   {}};
}

bool holds_nul(std::span<const std::uint8_t> bytes) {
    return std::find(bytes.begin(), bytes.end(), std::uint8_t{0}) != bytes.end();
}

}  // namespace

std::vector<Verdict> WriteJudge::write(const NodeProfile& node, std::uint8_t space,
                                       std::uint32_t address, std::span<const std::uint8_t> data,
                                       std::span<const CanFrame> frames, bool judge_values) {
    std::vector<Verdict> out;
    if (pending_ && !(pending_->space == space && pending_->next() == address)) {
        finish(out, std::move(*pending_));
        pending_.reset();
    }
    const std::uint64_t end = std::uint64_t{address} + data.size();
    std::optional<std::uint64_t> uncovered_from;
    const auto report_uncovered = [&](std::uint64_t to) {
        Verdict v{RuleId::kMemoryWriteUncovered, "", place(space, *uncovered_from), {}};
        v.message = "wrote " + std::to_string(to - *uncovered_from) + " byte(s) at " +
                    base::hex(space, 2) + " @" + base::hex(*uncovered_from, 8) +
                    " that no variable of the CDI covers";
        add_frames(v.frames, frames);
        out.push_back(std::move(v));
        uncovered_from.reset();
    };
    for (std::uint64_t pos = address; pos < end;) {
        const auto v = node.variable_at(space, pos);
        if (!v) {
            if (!uncovered_from) uncovered_from = pos;
            ++pos;
            continue;
        }
        if (uncovered_from) report_uncovered(pos);
        const std::uint64_t stop = std::min(v->end(), end);
        take(out, *v, space, pos, data.subspan(pos - address, stop - pos), frames, judge_values);
        pos = stop;
    }
    if (uncovered_from) report_uncovered(end);
    return out;
}

void WriteJudge::take(std::vector<Verdict>& out, const VariableRef& v, std::uint8_t space,
                      std::uint64_t at, std::span<const std::uint8_t> bytes,
                      std::span<const CanFrame> frames, bool judge_values) {
    const bool keep = v.size <= kMaxJudgedVariable;
    Piece piece;
    if (pending_ && pending_->space == space && pending_->variable.address == v.address &&
        pending_->next() == at) {
        piece = std::move(*pending_);
        pending_.reset();
        piece.judge_values = piece.judge_values && judge_values;
    } else if (at > v.address) {
        Verdict verdict{RuleId::kMemoryWriteStraddles,
                        "write starts at byte " + std::to_string(at - v.address) + " of " +
                            describe(space, v) + ", whose first byte(s) it does not write",
                        place(space, v.address),
                        {}};
        add_frames(verdict.frames, frames);
        out.push_back(std::move(verdict));
        return;
    } else {
        piece = Piece{space, v, 0, {}, {}, judge_values};
    }
    piece.covered += bytes.size();
    if (keep) piece.bytes.insert(piece.bytes.end(), bytes.begin(), bytes.end());
    add_frames(piece.frames, frames);
    if (piece.covered < v.size) {
        pending_ = std::move(piece);
        return;
    }
    if (!keep || !piece.judge_values) return;
    if (auto verdict = judge_value(space, v, piece.bytes)) {
        verdict->frames = std::move(piece.frames);
        out.push_back(std::move(*verdict));
    }
}

void WriteJudge::finish(std::vector<Verdict>& out, Piece piece) {
    const VariableRef& v = piece.variable;
    // CDI §5.1.4.3: a string is written from its first byte with at least one NUL; what follows
    // the NUL does not matter, so the bytes after it read as the padding they stand for.
    if (v.element->kind == cdi::ElementKind::kString && v.size <= kMaxJudgedVariable &&
        holds_nul(piece.bytes)) {
        if (!piece.judge_values) return;
        piece.bytes.resize(v.size, 0);
        if (auto verdict = judge_value(piece.space, v, piece.bytes)) {
            verdict->frames = std::move(piece.frames);
            out.push_back(std::move(*verdict));
        }
        return;
    }
    Verdict verdict{RuleId::kMemoryWriteStraddles,
                    "wrote " + std::to_string(piece.covered) + " of the " + std::to_string(v.size) +
                        " bytes of " + describe(piece.space, v) +
                        (v.element->kind == cdi::ElementKind::kString ? " without a NUL" : ""),
                    place(piece.space, v.address), std::move(piece.frames)};
    out.push_back(std::move(verdict));
}

std::vector<Verdict> WriteJudge::flush() {
    std::vector<Verdict> out;
    if (pending_) {
        finish(out, std::move(*pending_));
        pending_.reset();
    }
    return out;
}

}  // namespace olcb::simnode::audit
