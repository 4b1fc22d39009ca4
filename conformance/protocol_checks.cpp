#include "conformance/protocol_checks.hpp"

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "cdi/parser.hpp"
#include "cdi/validator.hpp"
#include "memory/acdi.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/error_codes.hpp"

namespace olcb::conform {
namespace {

using memory::Space;
using memory::SpaceForm;

// An MTI the fact sheet does not assign, with the address bit set (its own OIR example).
constexpr std::uint16_t kUnknownAddressedMti = 0x04F9;
// An unassigned global MTI (no address or event bits): nodes must ignore it silently.
constexpr std::uint16_t kUnknownGlobalMti = 0x0930;
// A node ID that is not ours, for the lock and CID checks.
constexpr std::uint64_t kOtherNodeId = 0x0201'12FE'0001ull;
// Most bytes of the CDI (or of any node-supplied text) a message quotes.
constexpr std::size_t kMaxQuote = 80;
// Short replies a FAIL message lists before giving the total.
constexpr std::size_t kShortReadsListed = 3;
// 1-byte reads short_read_checks() makes per space to learn whether a short reply was the end.
constexpr std::size_t kMaxEndProbes = 8;

std::string hex(unsigned v, int width = 4) {
    char b[16];
    std::snprintf(b, sizeof b, "0x%0*X", width, v);
    return b;
}

// At most kMaxQuote bytes, cut before a UTF-8 continuation byte so the quote stays valid text.
std::string clip(std::string_view text) {
    if (text.size() <= kMaxQuote) return std::string(text);
    std::size_t n = kMaxQuote;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;
    return std::string(text.substr(0, n)) + "...";
}

std::string quoted(std::string_view text) {
    return "\"" + clip(text) + "\"";
}

// What an exchange did, in words; a failure without a code says so instead of "error 0x0000".
std::string describe(const MemResult& r) {
    if (r.timed_out) return "no answer";
    if (r.rejected)
        return r.error ? "Datagram Rejected " + hex(r.error)
                       : "Datagram Rejected without an error code";
    if (!r.ok) return r.error ? "error " + hex(r.error) : "failed without an error code";
    return std::to_string(r.data.size()) + " bytes";
}

// Judges a request the standard refuses with `want`; the message quotes what came instead.
struct Refusal {
    bool pass = false;
    std::string message;
    std::string seen;
};

Refusal judge_refusal(const MemResult& r, const std::string& what, std::uint16_t want) {
    const std::string standard = "; the standard gives " + hex(want);
    if (r.timed_out) return {false, what + ": no answer" + standard, "no answer"};
    if (r.ok) {
        const std::string got = r.data.empty() ? "accepted" : "returned " + describe(r);
        return {false, what + " " + got + standard, got};
    }
    const std::string code = r.error ? hex(r.error) : "no error code";
    if (r.error == want) return {true, what + " refused with " + code, code};
    return {false, what + " refused with " + code + standard, code};
}

// An ACDI block read field by field, each string up to its NUL: some nodes (OpenLcbCLib) serve
// only reads that start at a field and refuse the bytes after a string's NUL, which no tool
// needs. The block comes back whole, each string field padded with zeros after its NUL.
MemResult read_acdi_block(Session& s, const NodeInfo& node, Space space) {
    using namespace memory::acdi;
    struct Field {
        std::size_t offset, size;
    };
    static constexpr Field kManufacturer[] = {{kManufacturerVersionOffset, 1},
                                              {kManufacturerOffset, kManufacturerSize},
                                              {kModelOffset, kModelSize},
                                              {kHardwareVersionOffset, kHardwareVersionSize},
                                              {kSoftwareVersionOffset, kSoftwareVersionSize}};
    static constexpr Field kUser[] = {{kUserVersionOffset, 1},
                                      {kUserNameOffset, kUserNameSize},
                                      {kUserDescriptionOffset, kUserDescriptionSize}};
    const bool user = space == Space::kAcdiUser;
    const std::span<const Field> fields =
        user ? std::span<const Field>(kUser) : std::span<const Field>(kManufacturer);
    MemResult total;
    total.ok = true;
    total.data.assign(user ? kUserBlockSize : kManufacturerBlockSize, 0);
    for (const Field& f : fields) {
        MemResult r = s.read_range(node, space, static_cast<std::uint32_t>(f.offset),
                                   static_cast<std::uint32_t>(f.size), f.size > 1);
        total.temporary_rejects += r.temporary_rejects;
        if (!r.ok || r.data.empty()) {
            r.ok = false;
            return r;
        }
        std::copy_n(r.data.begin(), std::min(r.data.size(), f.size),
                    total.data.begin() + static_cast<std::ptrdiff_t>(f.offset));
    }
    return total;
}

// Get Address Space Information for space, remembered in ctx.spaces.
SpaceInfo query_space_info(Session& s, const NodeInfo& node, std::uint8_t space, CheckContext& ctx,
                           MemResult* result = nullptr) {
    memory::Message reply;
    const auto payload = memory::encode(memory::GetSpaceInfo{static_cast<Space>(space)});
    MemResult r = s.command(node, payload, &reply);
    ctx.temporary_rejects += r.temporary_rejects;
    SpaceInfo info;
    if (r.ok) {
        if (auto* p = std::get_if<memory::SpaceInfoReply>(&reply)) {
            info = {true, true, p->read_only, p->highest_address, p->lowest_address};
        } else if (std::holds_alternative<memory::SpaceInfoNotPresent>(reply)) {
            info.answered = true;
        }
    }
    ctx.spaces[space] = info;
    if (result) *result = std::move(r);
    return info;
}

// One string both sides should hold, named for the message.
struct Field {
    const char* name;
    const std::string* want;
    const std::string* got;
};

// "SNIP model "B" differs from <source> "A"" for the first field that differs; "" when none.
std::string first_difference(std::initializer_list<Field> fields, const std::string& source,
                             std::string& want, std::string& got) {
    for (const Field& f : fields) {
        if (*f.want == *f.got) continue;
        want = quoted(*f.want);
        got = quoted(*f.got);
        std::string message = std::string("SNIP ") + f.name;
        message.append(" ").append(got).append(" differs from ");
        message.append(source).append(" ").append(want);
        return message;
    }
    return {};
}

class Checks {
public:
    Checks(Session& s, const NodeInfo& node, const ProtocolOptions& o, CheckContext& ctx)
        : s_(s), node_(node), o_(o), ctx_(ctx) {}

    std::vector<CheckResult> run() {
        const std::size_t frame_start = s_.frame_mark();
        const TimePoint started = s_.link().now();
        frame_and_message();
        pip_and_snip();
        memory_basics();
        cdi();
        acdi();
        agreement();
        forms_and_bounds();
        lock();
        readonly_writes();
        unsolicited(frame_start, started);
        return std::move(out_);
    }

private:
    void add(std::string id, Category c, bool pass, std::string section, std::string msg,
             std::string expected = {}, std::string seen = {}) {
        out_.push_back({std::move(id), c, pass ? Status::kPass : Status::kFail, std::move(msg),
                        std::move(section), pass ? "" : std::move(expected),
                        pass ? "" : std::move(seen)});
    }
    void add_status(std::string id, Category c, Status st, std::string section, std::string msg) {
        out_.push_back({std::move(id), c, st, std::move(msg), std::move(section), {}, {}});
    }
    void skip(std::string id, Category c, std::string section, std::string why) {
        add_status(std::move(id), c, Status::kSkip, std::move(section), std::move(why));
    }
    // The node's alias now: a node that re-initialised may have taken another one.
    std::uint16_t alias() const { return s_.alias_of(node_); }

    bool from_node(const CanFrame& f) const {
        return f.extended && can::source_alias(f.id) == alias();
    }

    // --- frame / message: everything injected at once, answers collected in one window ---
    void frame_and_message() {
        const std::uint16_t me = s_.tool_alias();
        const std::uint16_t node = alias();
        const std::size_t fmark = s_.frame_mark();
        const std::size_t mmark = s_.message_mark();
        s_.inject(can::make_ame(me));
        s_.inject(can::make_ame(me, node_.id));
        s_.inject(can::make_cid(7, NodeId{kOtherNodeId}, node));
        CanFrame unknown_addr =
            can::make_frame(can::message_header(kUnknownAddressedMti & 0x0FFF, me),
                            std::array<std::uint8_t, 2>{static_cast<std::uint8_t>(node >> 8),
                                                        static_cast<std::uint8_t>(node & 0xFF)});
        s_.inject(unknown_addr);
        Message verify_addr;
        verify_addr.mti = Mti::kVerifyNodeIdAddressed;
        verify_addr.destination = NodeHandle{node_.id, node};
        s_.send(verify_addr);
        // Every answer is awaited up to the answer window (on a 1,000-node segment the node's
        // AMD sits behind 999 others); then the checks judge what came.
        std::size_t amd = 0, rid = 0;
        bool oir = false, verified = false;
        std::size_t frames_seen = fmark, messages_seen = mmark;
        auto tally = [&] {
            for (const CanFrame& f : s_.frames_since(frames_seen)) {
                if (!from_node(f) || !can::is_control(f.id)) continue;
                const auto kind = can::classify_control(f.id);
                if (kind == can::ControlFrame::kAmd && f.len == 6 &&
                    NodeId::from_bytes({f.data.data(), 6}) == node_.id)
                    ++amd;
                if (kind == can::ControlFrame::kRid) ++rid;
            }
            frames_seen = s_.frame_mark();
            for (const auto& r : s_.messages_since(messages_seen)) {
                const Message& m = r.message;
                if (m.source.alias != alias()) continue;
                if (m.mti == Mti::kOptionalInteractionRejected && m.payload.size() >= 4 &&
                    (m.payload[2] << 8 | m.payload[3]) == kUnknownAddressedMti &&
                    (m.payload[0] & 0x10))
                    oir = true;
                if ((m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) &&
                    NodeId::from_bytes(m.payload) == node_.id)
                    verified = true;
            }
            messages_seen = s_.message_mark();
            return amd >= 2 && rid >= 1 && oir && verified;
        };
        s_.link().run_until(tally, o_.answer_window);
        tally();
        add("frame.ame-answered", Category::kFrame, amd >= 2, "CanFrameTransferS 6.2.3",
            "AME (global and with the node ID) answered with AMD", "2 AMD frames",
            std::to_string(amd) + " AMD frame(s)");
        add("frame.cid-defended", Category::kFrame, rid >= 1, "CanFrameTransferS 6.2.5",
            "CID carrying the node's alias answered with RID", "RID", "no RID");
        add("message.oir-unknown-mti", Category::kMessage, oir, "MessageNetworkS 3.5.2",
            "unknown addressed MTI 0x04F9 answered with OIR (permanent error, MTI echoed)",
            "OIR 0x1xxx 04F9", "no such OIR");
        add("message.verify-addressed", Category::kMessage, verified, "MessageNetworkS 3.4.2",
            "Verify Node ID addressed answered with Verified Node ID", "Verified Node ID",
            "no answer");
        auto found = s_.find_node(node_.id, o_.answer_window);
        add("message.verify-global", Category::kMessage, found.has_value(), "MessageNetworkS 3.4.2",
            "Verify Node ID global with the node ID answered", "Verified Node ID", "no answer");
        // Silence: an unknown global MTI gets no answer.
        const std::size_t smark = s_.message_mark();
        s_.inject(can::make_frame(can::message_header(kUnknownGlobalMti, me)));
        s_.wait(o_.window);
        // An answer is a message to us (OIR, anything addressed): a global message from the node
        // in this window may answer another tool on the segment.
        bool answered = false;
        for (const auto& r : s_.messages_since(smark)) {
            const Message& m = r.message;
            if (m.source.alias == alias() && m.destination &&
                m.destination->alias == s_.tool_alias())
                answered = true;
        }
        add("message.unknown-global-ignored", Category::kMessage, !answered,
            "MessageNetworkS 3.5.2", "unknown global MTI 0x0930 ignored silently", "silence",
            "a message from the node");
    }

    void pip_and_snip() {
        ctx_.pip = s_.protocol_support(node_);
        add("message.pip-answered", Category::kMessage, ctx_.pip.has_value(),
            "MessageNetworkS 3.4.4", "Protocol Support Inquiry answered", "Protocol Support Reply",
            "no reply");
        auto raw = s_.snip_payload(node_);
        snip_answered_ = raw.has_value();
        if (raw) {
            ctx_.snip = memory::decode_snip(*raw);
            const bool v = (*raw)[0] == 4 && ctx_.snip->user_version == 2;
            add("snip.version-bytes", Category::kSnip, v, "SimpleNodeInformationS 5.1",
                "SNIP version bytes 4 and 2", "4, 2",
                std::to_string((*raw)[0]) + ", " + std::to_string(ctx_.snip->user_version));
        } else {
            skip("snip.version-bytes", Category::kSnip, "SimpleNodeInformationS 5.1",
                 "no SNIP reply");
        }
    }

    SpaceInfo space_info(std::uint8_t space) {
        MemResult r;
        SpaceInfo info = query_space_info(s_, node_, space, ctx_, &r);
        r.temporary_rejects = 0;  // counted by query_space_info
        note(r);
        return info;
    }

    void note(const MemResult& r) {
        ctx_.temporary_rejects += r.temporary_rejects;
        if (r.ok || (!r.rejected && !r.timed_out)) memory_works_ = true;
    }

    void memory_basics() {
        memory::Message reply;
        MemResult r = s_.command(node_, memory::encode(memory::GetConfigOptions{}), &reply);
        note(r);
        if (auto* p = std::get_if<memory::ConfigOptionsReply>(&reply); r.ok && p) ctx_.options = *p;
        add("memory.config-options", Category::kMemory, ctx_.options.has_value(),
            "MemoryConfigurationS 4.13", "Get Configuration Options answered", "reply 20 82",
            r.ok ? "a reply other than 20 82" : describe(r));
        for (std::uint8_t sp : {0xFF, 0xFC, 0xFB}) space_info(sp);
        const SpaceInfo& ff = ctx_.spaces[0xFF];
        add("cdi.space-info", Category::kCdi, ff.present && ff.read_only,
            "MemoryConfigurationS 4.14", "Space Info for 0xFF: present and read-only",
            "present, read-only", ff.present ? "writable" : "not present");
    }

    void cdi() {
        const SpaceInfo& ff = ctx_.spaces[0xFF];
        const std::uint32_t len =
            ff.present ? std::min(ff.highest_address + 1, o_.max_cdi_bytes) : o_.max_cdi_bytes;
        MemResult r = s_.read_range(node_, Space::kCdi, 0, len, true, ctx_.cdi_progress);
        note(r);
        cdi_read_ok_ = r.ok && !r.data.empty();
        add("cdi.read", Category::kCdi, cdi_read_ok_, "MemoryConfigurationS 4.4",
            "space 0xFF read in 64-byte reads", "data", r.ok ? "no data" : describe(r));
        cdi_forms_ok_ = r.reply_in_request_form;
        ctx_.cdi_nul_found = !r.data.empty() && r.data.back() == 0;
        ctx_.cdi_bytes = r.data;
        if (ctx_.cdi_nul_found) ctx_.cdi_bytes.pop_back();
        if (!cdi_read_ok_) return;
        // Reply timing and datagram order, measured on the CDI reads.
        add("datagram.ok-before-reply", Category::kDatagram, r.datagram_ok_seen,
            "DatagramTransportS 6.2", "Datagram Received OK precedes every read reply",
            "OK then reply", "reply without a prior OK");
        add("datagram.reply-pending", Category::kDatagram, r.reply_pending,
            "MemoryConfigurationS 4.4", "Datagram Received OK of a read has Reply Pending",
            "flag 0x80", "flag clear");
        add("memory.reply-latency", Category::kMemory, r.reply_latency <= o_.max_reply_latency,
            "MessageNetworkS 3.3", "read replies within 750 ms", "<= 750 ms",
            std::to_string(
                std::chrono::duration_cast<std::chrono::milliseconds>(r.reply_latency).count()) +
                " ms");
        add("cdi.nul-terminated", Category::kCdi, ctx_.cdi_nul_found, "CDI 5; MemoryConfigurationS",
            "space 0xFF holds a NUL-terminated string", "a NUL", "no NUL");
        if (ctx_.cdi_nul_found && ff.present) {
            const bool at = ff.highest_address == ctx_.cdi_bytes.size();
            add("cdi.nul-at-highest", Category::kCdi, at, "MemoryConfigurationS 4.14",
                "the NUL is at the highest address Space Info gives",
                hex(static_cast<unsigned>(ctx_.cdi_bytes.size()), 8), hex(ff.highest_address, 8));
        }
        const std::string_view text(reinterpret_cast<const char*>(ctx_.cdi_bytes.data()),
                                    ctx_.cdi_bytes.size());
        const bool bom = text.starts_with("\xEF\xBB\xBF");
        add("cdi.no-bom", Category::kCdi, !bom, "CDI 5", "no byte-order mark", "no BOM", "BOM");
        add("cdi.utf8", Category::kCdi, is_valid_utf8(ctx_.cdi_bytes), "CDI 5", "valid UTF-8",
            "UTF-8", "invalid byte sequence");
        xml_declaration(text);
        cdi::ValidationReport report = cdi::validate(text);
        add("cdi.well-formed", Category::kCdi, report.schema.well_formed, "CDI 5",
            "well-formed XML", "well-formed", "not well-formed");
        std::size_t errors = 0;
        for (const auto& d : report.diagnostics) {
            const std::string where = d.line ? "line " + std::to_string(d.line) + ": " : "";
            if (d.severity == cdi::Severity::kError) {
                ++errors;
                add("cdi.valid", Category::kCdi, false, "CDI 5 / schema", where + d.message,
                    "no error", d.message);
            } else {
                add_status("cdi.valid", Category::kCdi, Status::kWarn, "CDI 5", where + d.message);
            }
        }
        if (errors == 0)
            add("cdi.valid", Category::kCdi, true, "CDI 5 / schema",
                "valid against the declared schema and the semantic rules");
        auto parsed = cdi::parse(text);
        if (parsed.document) {
            ctx_.document = std::make_unique<cdi::Document>(std::move(*parsed.document));
            auto lr = cdi::build_layout(*ctx_.document);
            if (lr.layout) ctx_.layout = std::move(lr.layout);
            const std::string& loc = ctx_.document->schema_location;
            const bool sane = (loc.starts_with("http://openlcb.org/schema/cdi/") ||
                               loc.starts_with("https://openlcb.org/schema/cdi/")) &&
                              loc.ends_with(".xsd");
            if (loc.empty())
                add_status("cdi.schema-location", Category::kCdi, Status::kWarn, "CDI 5",
                           "no xsi:noNamespaceSchemaLocation");
            else
                add("cdi.schema-location", Category::kCdi, sane, "CDI 5",
                    "schema location names an openlcb.org CDI schema",
                    "http://openlcb.org/schema/cdi/.../cdi.xsd", clip(loc));
        }
    }

    // Judges the first line only: a one-line CDI goes on with <cdi ...> after the declaration.
    void xml_declaration(std::string_view text) {
        static constexpr std::string_view kDeclaration = "<?xml version=\"1.0\"?>";
        const std::string_view first = text.substr(0, text.find('\n'));
        if (first.starts_with(kDeclaration)) {
            add("cdi.xml-declaration", Category::kCdi, true, "CDI 5",
                "first line starts with the XML declaration <?xml version=\"1.0\"?>");
            return;
        }
        const bool declaration = first.starts_with("<?xml") &&
                                 (first.size() == 5 || std::string_view(" \t\r?").find(first[5]) !=
                                                           std::string_view::npos);
        if (declaration) {
            const std::size_t end = first.find("?>");
            const std::string_view decl =
                end == std::string_view::npos ? first : first.substr(0, end + 2);
            add_status("cdi.xml-declaration", Category::kCdi, Status::kWarn, "CDI 5",
                       "first line is an XML declaration other than <?xml version=\"1.0\"?>: " +
                           clip(decl));
            return;
        }
        std::string_view line = first;
        if (line.ends_with('\r')) line.remove_suffix(1);
        add("cdi.xml-declaration", Category::kCdi, false, "CDI 5",
            "first line is not the XML declaration <?xml version=\"1.0\"?>",
            std::string(kDeclaration), quoted(line));
    }

    void acdi() {
        if (!ctx_.document || !ctx_.document->acdi) return;
        const auto& a = *ctx_.document->acdi;
        MemResult m = read_acdi_block(s_, node_, Space::kAcdiManufacturer);
        note(m);
        if (m.ok) ctx_.acdi_manufacturer = m.data;
        MemResult u = read_acdi_block(s_, node_, Space::kAcdiUser);
        note(u);
        if (u.ok) ctx_.acdi_user = u.data;
        add("acdi.manufacturer-version", Category::kAcdi,
            m.ok && !m.data.empty() && m.data[0] == a.fixed, "CDI 5.1.2",
            "space 252 byte 0 equals <acdi fixed>", std::to_string(a.fixed),
            m.ok && !m.data.empty() ? std::to_string(m.data[0]) : "unreadable: " + describe(m));
        add("acdi.user-version", Category::kAcdi, u.ok && !u.data.empty() && u.data[0] == a.var,
            "CDI 5.1.2", "space 251 byte 0 equals <acdi var>", std::to_string(a.var),
            u.ok && !u.data.empty() ? std::to_string(u.data[0]) : "unreadable: " + describe(u));
        // A CDI that lays its own variables over the ACDI blocks (some real devices put
        // configuration in space 252) makes the node disagree with ACDI whatever it does: that
        // is the CDI's fault, reported once here, and the ACDI size check is moot.
        std::string conflict;
        if (ctx_.layout) {
            for (const auto& ext : ctx_.layout->extents()) {
                if (ext.begin == ext.end) continue;
                if (ext.space == 0xFC || (ext.space == 0xFB && (ext.begin < 1 || ext.end > 128))) {
                    conflict += (conflict.empty() ? "" : ", ") + std::string("space ") +
                                std::to_string(ext.space) + " bytes " + std::to_string(ext.begin) +
                                ".." + std::to_string(ext.end - 1);
                }
            }
        }
        add("cdi.acdi-spaces", Category::kCdi, conflict.empty(), "CDI 5.1.2",
            "CDI segments leave the ACDI blocks of spaces 252/251 to <acdi/>",
            "no variable in 252; 251 variables within 1..127", conflict);
        const SpaceInfo& fc = ctx_.spaces[0xFC];
        const SpaceInfo& fb = ctx_.spaces[0xFB];
        if (!conflict.empty()) {
            add_status("acdi.space-info", Category::kAcdi, Status::kSkip, "CDI 5.1.2",
                       "skipped: the CDI's own segments overlap the ACDI blocks (cdi.acdi-spaces)");
            return;
        }
        add("acdi.space-info", Category::kAcdi,
            fc.present && fc.read_only && fc.highest_address == 124 && fb.present &&
                fb.highest_address == 127,
            "CDI 5.1.2; MemoryConfigurationS 4.14",
            "Space Info: 252 read-only highest 124, 251 highest 127", "124 RO / 127",
            std::to_string(fc.highest_address) + (fc.read_only ? " RO / " : " RW / ") +
                std::to_string(fb.highest_address));
    }

    void agreement() {
        const cdi::Document* doc = ctx_.document.get();
        if (ctx_.pip) {
            const ProtocolSet p = *ctx_.pip;
            add("pip.snip-bit", Category::kPip, p.has(Protocol::kSnip) == snip_answered_,
                "MessageNetworkS 3.4.4", "PIP SNIP bit agrees with the SNIP answer",
                snip_answered_ ? "bit set" : "bit clear", "differs");
            add("pip.datagram-bit", Category::kPip, p.has(Protocol::kDatagram) == memory_works_,
                "MessageNetworkS 3.4.4", "PIP Datagram bit agrees with datagram answers",
                memory_works_ ? "bit set" : "bit clear", "differs");
            add("pip.memory-config-bit", Category::kPip,
                p.has(Protocol::kMemoryConfiguration) == memory_works_, "MessageNetworkS 3.4.4",
                "PIP Memory Configuration bit agrees with memory answers",
                memory_works_ ? "bit set" : "bit clear", "differs");
            add("pip.cdi-bit", Category::kPip, p.has(Protocol::kCdi) == cdi_read_ok_,
                "MessageNetworkS 3.4.4", "PIP CDI bit agrees with space 0xFF",
                cdi_read_ok_ ? "bit set" : "bit clear", "differs");
            if (doc) {
                const bool has = doc->acdi.has_value();
                add("pip.acdi-bit", Category::kPip, p.has(Protocol::kAcdi) == has, "CDI 5.1.2",
                    "PIP ACDI bit iff the CDI has <acdi/>", has ? "bit set" : "bit clear",
                    "differs");
            }
        }
        snip_agreement();
        if (ctx_.options) {
            const std::uint16_t c = ctx_.options->available_commands;
            const bool r252 = ctx_.acdi_manufacturer.has_value();
            const bool r251 = ctx_.acdi_user.has_value();
            const bool w251 = r251 && !ctx_.spaces[0xFB].read_only;
            const bool ok = ((c & 0x0800) != 0) == r252 && ((c & 0x0400) != 0) == r251 &&
                            ((c & 0x0200) != 0) == w251;
            add("memory.options-acdi-flags", Category::kMemory, ok, "MemoryConfigurationS 4.13",
                "Options flags 0x0800/0x0400/0x0200 agree with spaces 252/251", "agree", hex(c));
        }
        if (ctx_.layout) {
            for (const auto& e : ctx_.layout->extents()) {
                const auto sp = static_cast<std::uint8_t>(e.space);
                SpaceInfo info = space_info(sp);
                const bool big = info.present && e.end > 0 && info.highest_address + 1 >= e.end;
                add("memory.space-info-layout", Category::kMemory, big, "MemoryConfigurationS 4.14",
                    "Space Info of space " + std::to_string(sp) + " covers the CDI layout",
                    "highest >= " + std::to_string(e.end - 1),
                    info.present ? std::to_string(info.highest_address) : "not present");
                // Prefer a space with both forms, so the form check covers the short one.
                if (!data_space_ || (sp >= 0xFD && *data_space_ < 0xFD)) data_space_ = sp;
            }
        }
    }

    // SNIP against ACDI and against the CDI <identification>, naming the first field that differs.
    void snip_agreement() {
        const cdi::Document* doc = ctx_.document.get();
        if (ctx_.snip && ctx_.acdi_manufacturer && ctx_.acdi_user) {
            const memory::Snip from =
                memory::snip_from_acdi(*ctx_.acdi_manufacturer, *ctx_.acdi_user);
            const memory::Snip& sn = *ctx_.snip;
            std::string want, got;
            std::string diff = first_difference(
                {{"manufacturer", &from.manufacturer, &sn.manufacturer},
                 {"model", &from.model, &sn.model},
                 {"hardware version", &from.hardware_version, &sn.hardware_version},
                 {"software version", &from.software_version, &sn.software_version}},
                "ACDI 252", want, got);
            if (diff.empty())
                diff = first_difference(
                    {{"user name", &from.user_name, &sn.user_name},
                     {"user description", &from.user_description, &sn.user_description}},
                    "ACDI 251", want, got);
            add("snip.matches-acdi", Category::kSnip, diff.empty(),
                "SimpleNodeInformationS; CDI 5.1.2",
                diff.empty() ? "SNIP strings equal the ACDI 252/251 strings" : diff, want, got);
        }
        if (ctx_.snip && doc && doc->identification) {
            const auto& id = *doc->identification;
            const memory::Snip& sn = *ctx_.snip;
            std::string want, got;
            const std::string diff =
                first_difference({{"manufacturer", &id.manufacturer, &sn.manufacturer},
                                  {"model", &id.model, &sn.model},
                                  {"hardware version", &id.hardware_version, &sn.hardware_version},
                                  {"software version", &id.software_version, &sn.software_version}},
                                 "CDI <identification>", want, got);
            add("snip.matches-cdi", Category::kSnip, diff.empty(), "CDI 5.1.1",
                diff.empty() ? "SNIP strings equal the CDI <identification>" : diff, want, got);
        }
    }

    void forms_and_bounds() {
        const std::uint8_t sp = data_space_.value_or(0xFF);
        const auto space = static_cast<Space>(sp);
        const bool shortable = sp >= 0xFD;
        MemResult a = s_.read(node_, space, 0, 8, SpaceForm::kByte6);
        note(a);
        add("memory.read-byte6-form", Category::kMemory, a.ok, "MemoryConfigurationS 4.4",
            "read of space " + std::to_string(sp) + " in the byte-6 form", "data", describe(a));
        bool forms = a.ok && a.reply_in_request_form && cdi_forms_ok_;
        if (shortable) {
            MemResult b = s_.read(node_, space, 0, 8, SpaceForm::kShort);
            note(b);
            add("memory.read-short-form", Category::kMemory, b.ok, "MemoryConfigurationS 4.4",
                "read of space " + std::to_string(sp) + " in the short form", "data", describe(b));
            forms = forms && b.ok && b.reply_in_request_form;
        }
        add("memory.reply-form", Category::kMemory, forms, "MemoryConfigurationS 4.4",
            "replies use the form of the request", "same form", "other form");
        const SpaceInfo& ff = ctx_.spaces[0xFF];
        if (ff.present && ff.highest_address >= 3) {
            MemResult e = s_.read(node_, Space::kCdi, ff.highest_address - 3, 8);
            note(e);
            add("memory.read-short-at-end", Category::kMemory, e.ok && e.data.size() == 4,
                "MemoryConfigurationS 4.4", "read across the end of 0xFF returns the 4 bytes left",
                "4 bytes", describe(e));
            MemResult p = s_.read(node_, Space::kCdi, ff.highest_address + 1, 8);
            note(p);
            const Refusal past = judge_refusal(p, "read past the end of 0xFF", 0x1082);
            add("memory.read-past-end", Category::kMemory, past.pass, "MemoryConfigurationS 4.4",
                past.message, "0x1082", past.seen);
        }
        std::set<std::uint8_t> used = {0xFF, 0xFE, 0xFD, 0xFC, 0xFB, 0xFA, 0xF9, 0xF8, 0xEF};
        if (ctx_.layout)
            for (const auto& e : ctx_.layout->extents())
                used.insert(static_cast<std::uint8_t>(e.space));
        std::uint8_t unknown = 0x50;
        while (used.count(unknown)) ++unknown;
        MemResult u = s_.read(node_, static_cast<Space>(unknown), 0, 8);
        note(u);
        const Refusal refused =
            judge_refusal(u, "read of unknown space " + std::to_string(unknown), 0x1081);
        add("memory.unknown-space", Category::kMemory, refused.pass, "MemoryConfigurationS 4.4",
            refused.message, "0x1081", refused.seen);
    }

    void lock() {
        MemResult last;
        auto lock_cmd = [&](std::uint64_t id) -> std::optional<std::uint64_t> {
            memory::Message reply;
            last = s_.command(node_, memory::encode(memory::Lock{id}), &reply);
            note(last);
            if (auto* p = std::get_if<memory::LockReply>(&reply); last.ok && p) return p->node_id;
            return std::nullopt;
        };
        const std::uint64_t me = s_.tool_id().value();
        auto first = lock_cmd(me);
        if (!first && !last.ok && !last.timed_out) {
            // Refusing an optional command is allowed; the code it gave is still worth a look.
            const std::string code = last.error ? hex(last.error) : "no error code";
            add_status("memory.lock", Category::kMemory, Status::kWarn, "MemoryConfigurationS 4.15",
                       "Lock/Reserve rejected with " + code +
                           " (optional command; lcc-conform writes without the lock)");
            return;
        }
        if (!first) {
            skip("memory.lock", Category::kMemory, "MemoryConfigurationS 4.15",
                 "Lock/Reserve not answered (optional)");
            return;
        }
        if (*first != me && *first != 0) {
            // Another tool holds the lock: zeros would release it behind that tool's back.
            skip("memory.lock", Category::kMemory, "MemoryConfigurationS 4.15",
                 "the node is locked by " + NodeId(*first).to_string() + ": lock check not run");
            return;
        }
        auto second = lock_cmd(kOtherNodeId);
        auto released = lock_cmd(0);
        const bool ok = *first == me && second && *second == me && released && *released == 0;
        add("memory.lock", Category::kMemory, ok, "MemoryConfigurationS 4.15",
            "reserve holds our ID, another ID does not take it, zeros release it", "ours, ours, 0",
            "differs");
        if (released && *released != 0) lock_cmd(0);
    }

    void readonly_writes() {
        if (o_.read_only) {
            skip("memory.readonly-refused", Category::kMemory, "MemoryConfigurationS 4.6",
                 "--read-only");
            return;
        }
        for (std::uint8_t sp : {0xFF, 0xFC}) {
            const SpaceInfo& info = ctx_.spaces[sp];
            if (!info.present) continue;
            // Rewrite the byte already there: nothing changes even on a faulty node.
            MemResult r = s_.read(node_, static_cast<Space>(sp), 0, 1);
            note(r);
            if (!r.ok || r.data.empty()) continue;
            MemResult w = s_.write(node_, static_cast<Space>(sp), 0, r.data);
            note(w);
            const Refusal refused =
                judge_refusal(w, "write to read-only space " + std::to_string(sp), 0x1083);
            add("memory.readonly-refused", Category::kMemory, refused.pass,
                "MemoryConfigurationS 4.6", refused.message, "0x1083", refused.seen);
        }
        // Temporary rejects are legal (the retried request succeeded, or another check failed),
        // but a node that needs them on an idle bus is worth a look: warn, never fail.
        add_status("datagram.temporary-rejects", Category::kDatagram,
                   ctx_.temporary_rejects == 0 ? Status::kPass : Status::kWarn,
                   "DatagramTransportS 6.3",
                   ctx_.temporary_rejects == 0
                       ? "no datagram was rejected temporarily"
                       : std::to_string(ctx_.temporary_rejects) +
                             " datagrams rejected temporarily (0x2xxx) and retried");
    }

    void unsolicited(std::size_t frame_mark, TimePoint started) {
        // The run itself is the quiet window; top it up so periodic chatter cannot slip through.
        const Duration elapsed = s_.link().now() - started;
        if (elapsed < o_.quiet_window) s_.wait(o_.quiet_window - elapsed);
        // Frames, not messages: our stack answers some (Verify Node ID) without passing them on.
        static constexpr Mti kNeverUnasked[] = {
            Mti::kVerifyNodeIdGlobal,   Mti::kVerifyNodeIdAddressed,
            Mti::kIdentifyEventsGlobal, Mti::kIdentifyEventsAddressed,
            Mti::kIdentifyConsumer,     Mti::kIdentifyProducer,
            Mti::kEventReport,          Mti::kProtocolSupportInquiry,
            Mti::kSnipRequest,          Mti::kLearnEvent};
        std::string seen;
        for (const CanFrame& f : s_.frames_since(frame_mark)) {
            if (!from_node(f) || !can::is_message(f.id) ||
                can::frame_format(f.id) != can::FrameFormat::kGlobalAddressed)
                continue;
            for (Mti m : kNeverUnasked) {
                if (can::can_mti(f.id) == (to_u16(m) & 0x0FFF) && seen.empty())
                    seen = std::string(mti_name(m));
            }
        }
        add("message.no-unsolicited", Category::kMessage, seen.empty(), "architecture interop",
            "no unsolicited traffic from the node during the run", "silence", seen);
    }

    Session& s_;
    NodeInfo node_;
    const ProtocolOptions& o_;
    CheckContext& ctx_;
    std::vector<CheckResult> out_;
    bool snip_answered_ = false;
    bool memory_works_ = false;
    bool cdi_read_ok_ = false;
    bool cdi_forms_ok_ = true;
    std::optional<std::uint8_t> data_space_;
};

// The short replies of one space that were not the end of it. One that nothing was read after is
// settled by a 1-byte read where it ended (data: not the end; 0x1082: the end), then by Space Info.
std::vector<const ShortRead*> short_reads_inside(Session& s, const NodeInfo& node,
                                                 std::uint8_t space, CheckContext& ctx) {
    auto open = [&](const ShortRead& r) {
        return r.node == node.id && r.space == space && !r.continued && !r.at_end;
    };
    std::optional<SpaceInfo> info;
    auto inside = [&](const ShortRead& r) {
        if (!info) {
            auto known = ctx.spaces.find(space);
            info = known != ctx.spaces.end() && known->second.answered
                       ? known->second
                       : query_space_info(s, node, space, ctx);
        }
        return info->present && r.address + std::uint64_t{r.got} <= info->highest_address;
    };
    std::set<std::uint64_t> probed;
    const std::size_t count = s.short_reads().size();  // the probes below may add more
    for (std::size_t i = 0; i < count && probed.size() < kMaxEndProbes; ++i) {
        const ShortRead r = s.short_reads()[i];
        const std::uint64_t end = r.address + std::uint64_t{r.got};
        if (!open(r) || !inside(r) || !probed.insert(end).second) continue;
        s.read(node, static_cast<Space>(space), static_cast<std::uint32_t>(end), 1);
    }
    std::vector<const ShortRead*> out;
    for (std::size_t i = 0; i < count; ++i) {
        const ShortRead& r = s.short_reads()[i];
        if (r.node != node.id || r.space != space) continue;
        if (r.continued || (open(r) && inside(r))) out.push_back(&r);
    }
    return out;
}

CheckResult short_read_check(Session& s, const NodeInfo& node, std::uint8_t space,
                             CheckContext& ctx) {
    char id[8];
    std::snprintf(id, sizeof id, "%02x", space);
    CheckResult c{std::string("memory.short-read.") + id,
                  Category::kMemory,
                  Status::kPass,
                  "",
                  "MemoryConfigurationS 4.4",
                  "",
                  ""};
    const std::string name = hex(space, 2);
    const std::uint64_t reads = s.reads(node.id, space);
    const std::vector<const ShortRead*> bad = short_reads_inside(s, node, space, ctx);
    if (bad.empty()) {
        c.message = std::to_string(reads) + " reads of space " + name +
                    " returned the count asked or ended at the end of the space";
        return c;
    }
    std::string list;
    for (std::size_t i = 0; i < bad.size() && i < kShortReadsListed; ++i) {
        list += (i ? "; " : "") + std::string("at ") + hex(bad[i]->address, 8) + " asked " +
                std::to_string(bad[i]->asked) + " got " + std::to_string(bad[i]->got);
    }
    c.status = Status::kFail;
    c.message = "space " + name + ": " + std::to_string(bad.size()) + " of " +
                std::to_string(reads) + " reads returned fewer bytes than asked away from the " +
                "end of the space (" + list + (bad.size() > kShortReadsListed ? "; ..." : "") + ")";
    c.expected =
        "the count asked: only the end of the space may shorten a Read Reply "
        "(MemoryConfigurationS 4.4)";
    c.seen = std::to_string(bad.size()) + " short replies, first " + list.substr(0, list.find(';'));
    return c;
}

}  // namespace

std::vector<CheckResult> short_read_checks(Session& session, const NodeInfo& node,
                                           CheckContext& ctx) {
    std::vector<CheckResult> out;
    for (unsigned sp = 0; sp <= 0xFF; ++sp) {
        const auto space = static_cast<std::uint8_t>(sp);
        if (session.reads(node.id, space) > 0)
            out.push_back(short_read_check(session, node, space, ctx));
    }
    return out;
}

bool is_valid_utf8(std::span<const std::uint8_t> b) {
    std::size_t i = 0;
    while (i < b.size()) {
        const std::uint8_t c = b[i];
        std::size_t n = 0;
        std::uint32_t cp = 0;
        if (c < 0x80) {
            ++i;
            continue;
        } else if ((c & 0xE0) == 0xC0) {
            n = 1;
            cp = c & 0x1F;
        } else if ((c & 0xF0) == 0xE0) {
            n = 2;
            cp = c & 0x0F;
        } else if ((c & 0xF8) == 0xF0) {
            n = 3;
            cp = c & 0x07;
        } else {
            return false;
        }
        for (std::size_t k = 1; k <= n; ++k) {
            if (i + k >= b.size() || (b[i + k] & 0xC0) != 0x80) return false;
            cp = cp << 6 | (b[i + k] & 0x3F);
        }
        static constexpr std::uint32_t kMin[] = {0, 0x80, 0x800, 0x10000};
        if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
        i += n + 1;
    }
    return true;
}

std::vector<CheckResult> run_protocol_checks(Session& session, const NodeInfo& node,
                                             const ProtocolOptions& options, CheckContext& ctx) {
    if (!ctx.timing) return Checks(session, node, options, ctx).run();
    // The node's measured latency widens every window; none gets shorter than asked.
    ProtocolOptions o = options;
    o.window = std::max(o.window, ctx.timing->silence);
    o.answer_window = std::max(o.answer_window, ctx.timing->answer);
    o.quiet_window = std::max(o.quiet_window, ctx.timing->quiet);
    return Checks(session, node, o, ctx).run();
}

}  // namespace olcb::conform
