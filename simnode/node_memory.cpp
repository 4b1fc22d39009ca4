#include "simnode/node_memory.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <utility>

#include "cdi/float_codec.hpp"
#include "cdi/parser.hpp"
#include "cdi/validator.hpp"
#include "cdi/value_codec.hpp"

namespace olcb::simnode {
namespace {

constexpr std::uint8_t kCdiSpace = 0xFF;
constexpr std::uint8_t kAcdiFixedSpace = 0xFC;
constexpr std::uint8_t kAcdiUserSpace = 0xFB;
constexpr const char* kUniqueIdFile = "unique-id.img";

// Keeps the whole content in RAM in front of an inner space: writes stop here, reload() forgets
// them. Backs write-not-persisted and readonly-writable.
class RamOverlay : public memory::ForwardingSpace {
public:
    RamOverlay(memory::MemorySpace& inner, bool writable)
        : ForwardingSpace(inner), writable_(writable) {
        reload();
    }
    bool read_only() const override { return !writable_ && inner().read_only(); }
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
    void reload() {
        bytes_.assign(inner().size(), 0);
        const std::size_t got = inner().read(0, bytes_);
        bytes_.resize(got);
    }

private:
    bool writable_;
    std::vector<std::uint8_t> bytes_;
};

// write-dropped: answers like a successful write and stores nothing.
class DropWrites : public memory::ForwardingSpace {
public:
    using ForwardingSpace::ForwardingSpace;
    memory::WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        if (read_only()) return memory::WriteStatus::kReadOnly;
        if (!memory::fits(size(), address, in.size())) return memory::WriteStatus::kOutOfBounds;
        return memory::WriteStatus::kOk;
    }
};

// The encoding faults: each variable lying wholly inside a write is stored mis-encoded.
class MisEncode : public memory::ForwardingSpace {
public:
    MisEncode(memory::MemorySpace& inner, const cdi::Layout& layout, std::uint8_t space,
              const FaultSet& faults)
        : ForwardingSpace(inner), layout_(layout), space_(space), faults_(faults) {}
    memory::WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        std::vector<std::uint8_t> bytes(in.begin(), in.end());
        const std::uint64_t end = std::uint64_t{address} + bytes.size();
        for (std::uint64_t pos = address; pos < end;) {
            const cdi::Cursor c = layout_.find(space_, pos);
            if (c.valid() && c.address() >= address && c.address() + c.size() <= end &&
                c.size() > 0) {
                apply_encoding_faults(faults_, c.element(),
                                      std::span(bytes).subspan(c.address() - address, c.size()));
                pos = c.address() + c.size();
            } else {
                ++pos;
            }
        }
        return ForwardingSpace::write(address, bytes);
    }

private:
    const cdi::Layout& layout_;
    std::uint8_t space_;
    FaultSet faults_;
};

bool has_encoding_fault(const FaultSet& f) {
    return f.int_byte_order || f.string_unterminated || f.eventid_byte_order || f.float_width;
}

// One model per distinct text while any node uses it: 1,000 nodes of one CDI share one parse.
struct ModelCache {
    std::mutex mutex;
    std::map<std::string, std::weak_ptr<const CdiModel>> models;
};

ModelCache& model_cache() {
    static ModelCache cache;
    return cache;
}

std::shared_ptr<const CdiModel> build_model(const std::string& text, std::string& error) {
    auto model = std::make_shared<CdiModel>();
    model->text = text;
    const std::string_view xml(model->text.data(),
                               std::min(model->text.size(), model->text.find('\0')));
    cdi::ParseResult parsed = cdi::parse(xml);
    if (!parsed.document) {
        error = "CDI does not parse";
        for (const auto& d : parsed.diagnostics) {
            if (d.severity == cdi::Severity::kError) {
                error = cdi::format_diagnostic("CDI", d);
                break;
            }
        }
        return nullptr;
    }
    model->document = std::move(*parsed.document);
    cdi::LayoutResult laid = cdi::build_layout(model->document);
    if (!laid.layout) {
        error = "CDI layout failed";
        for (const auto& d : laid.diagnostics) {
            if (d.severity == cdi::Severity::kError) {
                error = cdi::format_diagnostic("CDI", d);
                break;
            }
        }
        return nullptr;
    }
    model->layout.emplace(std::move(*laid.layout));
    if (model->layout->variable_count() > kMaxVariables) {
        error = "CDI has " + std::to_string(model->layout->variable_count()) +
                " variables after replication; at most " + std::to_string(kMaxVariables) +
                " are supported";
        return nullptr;
    }
    const cdi::ValidationReport report = cdi::validate(xml);
    model->valid = report.ok();
    for (const auto& d : report.diagnostics) {
        if (d.severity == cdi::Severity::kError) {
            model->first_error = cdi::format_diagnostic("CDI", d);
            break;
        }
    }
    model->events = event_slots(*model->layout, kMaxEvents);
    return model;
}

// Bytes a variable holds in a fresh image, or nullopt to leave zeros.
std::optional<std::vector<std::uint8_t>> default_bytes(const cdi::Element& e) {
    std::optional<cdi::Value> value;
    if (e.text_default) {
        auto parsed = cdi::parse_value_text(e, *e.text_default);
        if (parsed) value = std::move(parsed).value();
    } else if (e.int_default &&
               (e.kind == cdi::ElementKind::kInt || e.kind == cdi::ElementKind::kBit)) {
        value = cdi::Value::integer(*e.int_default);
    } else if (e.float_default && e.kind == cdi::ElementKind::kFloat) {
        value = cdi::Value::real(*e.float_default);
    }
    if (!value) return std::nullopt;
    auto bytes = cdi::encode(e, *value, cdi::CodecMode::kLenient);
    if (!bytes || bytes->size() != e.size) return std::nullopt;
    return std::move(bytes).value();
}

}  // namespace

struct NodeMemory::Slot {
    std::uint8_t number = 0;
    bool served = false;
    bool acdi_layout = false;  // 251/252: encoding faults never apply (SNIP reads them)
    std::unique_ptr<memory::ConstantSpace> constant;
    std::unique_ptr<memory::ImageSpace> image;
    std::unique_ptr<memory::RamSpace> ram;
    std::vector<std::unique_ptr<memory::MemorySpace>> wrappers;  // each wraps the previous
    std::vector<RamOverlay*> overlays;
    memory::MemorySpace* top = nullptr;

    // Forgets what only RAM held (a power cycle).
    void reload() const {
        for (RamOverlay* o : overlays) o->reload();
    }

    memory::MemorySpace& base() const {
        if (constant) return *constant;
        if (image) return *image;
        return *ram;
    }
    template <class T, class... Args>
    T* wrap(Args&&... args) {
        auto w = std::make_unique<T>(*top, std::forward<Args>(args)...);
        T* raw = w.get();
        wrappers.push_back(std::move(w));
        top = raw;
        return raw;
    }
};

std::shared_ptr<const CdiModel> load_cdi_model(const std::string& text, std::string& error) {
    ModelCache& cache = model_cache();
    std::lock_guard lock(cache.mutex);
    if (auto it = cache.models.find(text); it != cache.models.end()) {
        if (auto alive = it->second.lock()) return alive;
    }
    auto model = build_model(text, error);
    if (!model) return nullptr;
    std::erase_if(cache.models, [](const auto& entry) { return entry.second.expired(); });
    cache.models[text] = model;
    return model;
}

std::string image_file_name(std::uint8_t space) {
    return "space-" + std::to_string(space) + ".img";
}

std::vector<std::uint8_t> served_cdi_bytes(std::string_view text, const FaultSet& faults) {
    std::string xml(text.substr(0, std::min(text.size(), text.find('\0'))));
    if (faults.cdi_invalid) {
        // Two schema violations a reader notices at once: no declaration, an unknown element.
        if (xml.rfind("<?xml", 0) == 0) {
            auto end = xml.find("?>");
            end = end == std::string::npos ? 0 : end + 2;
            while (end < xml.size() && (xml[end] == '\n' || xml[end] == '\r')) ++end;
            xml.erase(0, end);
        }
        if (auto root = xml.find("<cdi"); root != std::string::npos) {
            if (auto close = xml.find('>', root); close != std::string::npos) {
                xml.insert(close + 1, "\n<simnodeUnknownElement/>");
            }
        }
    }
    std::vector<std::uint8_t> bytes(xml.begin(), xml.end());
    if (!faults.cdi_unterminated) bytes.push_back(0);
    if (faults.cdi_padding) {
        static constexpr std::uint8_t kPadding[] = {0,   0,   0,   0,   0,   0,   0,    'P',
                                                    'A', 'D', 'D', 'I', 'N', 'G', 0xFF, 0xFE};
        bytes.insert(bytes.end(), std::begin(kPadding), std::end(kPadding));
    }
    return bytes;
}

void apply_encoding_faults(const FaultSet& faults, const cdi::Element& element,
                           std::span<std::uint8_t> bytes) {
    switch (element.kind) {
        case cdi::ElementKind::kInt:
            if (faults.int_byte_order) std::reverse(bytes.begin(), bytes.end());
            break;
        case cdi::ElementKind::kEventId:
            if (faults.eventid_byte_order) std::reverse(bytes.begin(), bytes.end());
            break;
        case cdi::ElementKind::kString:
            if (faults.string_unterminated) {
                auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
                std::fill(nul, bytes.end(), std::uint8_t{' '});
            }
            break;
        case cdi::ElementKind::kFloat: {
            if (!faults.float_width) break;
            if (bytes.size() == 2) {
                bytes[1] &= 0xF8;  // no smaller float: drop the three lowest mantissa bits
                break;
            }
            auto value = cdi::decode_float(bytes);
            if (!value) break;
            const double narrowed = cdi::round_to_float_size(*value, bytes.size() / 2);
            auto out = cdi::encode_float(narrowed, bytes.size(), cdi::CodecMode::kLenient);
            if (out && out->size() == bytes.size())
                std::copy(out->begin(), out->end(), bytes.begin());
            break;
        }
        default:
            break;
    }
}

NodeMemory::NodeMemory(MemoryOptions options) : options_(std::move(options)) {}

NodeMemory::~NodeMemory() = default;

std::unique_ptr<NodeMemory> NodeMemory::open(MemoryOptions options, std::string& error) {
    if (!options.model || !options.model->layout) {
        error = "no CDI model";
        return nullptr;
    }
    std::unique_ptr<NodeMemory> memory(new NodeMemory(std::move(options)));
    if (!memory->build(error)) return nullptr;
    return memory;
}

bool NodeMemory::has_acdi() const {
    return options_.model->document.acdi.has_value();
}

NodeMemory::Slot* NodeMemory::slot(std::uint8_t number) const {
    return by_number_[number];
}

void NodeMemory::add_constant(std::uint8_t number, std::vector<std::uint8_t> bytes) {
    auto s = std::make_unique<Slot>();
    s->number = number;
    s->served = true;
    s->acdi_layout = number == kAcdiFixedSpace;
    s->constant = std::make_unique<memory::ConstantSpace>(std::move(bytes));
    s->top = s->constant.get();
    if (options_.faults.readonly_writable) s->overlays.push_back(s->wrap<RamOverlay>(true));
    by_number_[number] = s.get();
    slots_.push_back(std::move(s));
}

bool NodeMemory::add_writable(std::uint8_t number, std::uint64_t size, bool served,
                              std::string& error) {
    if (size > kMaxSpaceSize) {
        error = "space " + std::to_string(number) + " needs " + std::to_string(size) +
                " bytes; at most " + std::to_string(kMaxSpaceSize) + " are supported";
        return false;
    }
    auto s = std::make_unique<Slot>();
    s->number = number;
    s->served = served;
    s->acdi_layout = number == kAcdiUserSpace && has_acdi();
    const auto init = [this, number](std::span<std::uint8_t> image) {
        const auto bytes = factory_image(number);
        std::copy_n(bytes.begin(), std::min(bytes.size(), image.size()), image.begin());
    };
    if (!options_.image_dir.empty() && served) {
        auto opened = memory::ImageFile::open(options_.image_dir / image_file_name(number),
                                              static_cast<std::size_t>(size), init);
        if (!opened.ok()) {
            error = "space " + std::to_string(number) + ": " + opened.error;
            return false;
        }
        s->image = std::make_unique<memory::ImageSpace>(std::move(opened.image));
        s->top = s->image.get();
    } else {
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size), 0);
        init(bytes);
        s->ram = std::make_unique<memory::RamSpace>(std::move(bytes));
        s->top = s->ram.get();
    }
    if (s->acdi_layout) {
        // The version byte is the firmware's, not the user's: set it whatever the image says.
        const auto& acdi = *options_.model->document.acdi;
        const auto version =
            static_cast<std::uint8_t>(acdi.var + (options_.faults.acdi_version ? 1 : 0));
        std::uint8_t stored = 0;
        if (s->top->read(0, std::span(&stored, 1)) == 1 && stored != version &&
            s->top->write(0, std::span(&version, 1)) != memory::WriteStatus::kOk) {
            error = "space 251: cannot store the ACDI version byte";
            return false;
        }
    }
    const FaultSet& f = options_.faults;
    if (f.write_not_persisted) s->overlays.push_back(s->wrap<RamOverlay>(false));
    if (has_encoding_fault(f) && !s->acdi_layout && served) {
        s->wrap<MisEncode>(*options_.model->layout, number, f);
    }
    if (f.write_dropped) s->wrap<DropWrites>();
    by_number_[number] = s.get();
    slots_.push_back(std::move(s));
    return true;
}

bool NodeMemory::build(std::string& error) {
    const CdiModel& model = *options_.model;
    const FaultSet& f = options_.faults;
    // Default event IDs take Get Unique ID suffixes 0..n-1, so those never repeat them.
    model.layout->visit([this](const cdi::Cursor& c) {
        if (c.element().kind == cdi::ElementKind::kEventId && !c.element().text_default) {
            ++default_event_count_;
        }
    });

    add_constant(kCdiSpace, served_cdi_bytes(model.text, f));

    const bool acdi = has_acdi();
    memory::AcdiManufacturer fixed = options_.identity;
    fixed.version = static_cast<std::uint8_t>(
        (acdi ? model.document.acdi->fixed : memory::acdi::kManufacturerVersion) +
        (f.acdi_version ? 1 : 0));
    const auto block = memory::encode_acdi_manufacturer(fixed);
    std::vector<std::uint8_t> fixed_bytes(block.begin(), block.end());
    if (auto ext = model.layout->extent(kAcdiFixedSpace); ext && ext->end > fixed_bytes.size()) {
        fixed_bytes.resize(static_cast<std::size_t>(std::min(ext->end, kMaxSpaceSize)), 0);
    }
    add_constant(kAcdiFixedSpace, std::move(fixed_bytes));
    slot(kAcdiFixedSpace)->served = acdi;

    bool have_user = false;
    for (const cdi::SpaceExtent& ext : model.layout->extents()) {
        if (ext.space == kCdiSpace || ext.space == kAcdiFixedSpace || ext.end == 0) continue;
        std::uint64_t size = ext.end;
        if (ext.space == kAcdiUserSpace) {
            size = std::max<std::uint64_t>(size, memory::acdi::kUserBlockSize);
            have_user = true;
        }
        if (!add_writable(static_cast<std::uint8_t>(ext.space), size, true, error)) return false;
    }
    // Without a 251 segment the user block exists for SNIP; served only with <acdi/>.
    if (!have_user && !add_writable(kAcdiUserSpace, memory::acdi::kUserBlockSize, acdi, error)) {
        return false;
    }

    unique_id_counter_ = default_event_count_;
    if (!options_.image_dir.empty()) {
        auto opened = memory::ImageFile::open(options_.image_dir / kUniqueIdFile, 4);
        if (!opened.ok()) {
            error = std::string(kUniqueIdFile) + ": " + opened.error;
            return false;
        }
        unique_id_image_ = std::move(opened.image);
        const auto b = unique_id_image_->bytes();
        const std::uint32_t stored = static_cast<std::uint32_t>(b[0]) << 24 |
                                     static_cast<std::uint32_t>(b[1]) << 16 |
                                     static_cast<std::uint32_t>(b[2]) << 8 | b[3];
        unique_id_counter_ = std::max(stored, unique_id_counter_);
    }
    return true;
}

std::vector<std::uint8_t> NodeMemory::factory_image(std::uint8_t number) const {
    const Slot* s = slot(number);
    std::uint64_t size = 0;
    if (s != nullptr) {
        size = s->base().size();
    } else if (auto ext = options_.model->layout->extent(number)) {
        size = ext->end;
    }
    if (number == kAcdiUserSpace)
        size = std::max<std::uint64_t>(size, memory::acdi::kUserBlockSize);
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(std::min(size, kMaxSpaceSize)), 0);
    const bool acdi_layout = number == kAcdiUserSpace && has_acdi();
    std::uint32_t next_event = 0;
    options_.model->layout->visit([&](const cdi::Cursor& c) {
        const cdi::Element& e = c.element();
        std::optional<std::vector<std::uint8_t>> value;
        if (e.kind == cdi::ElementKind::kEventId && !e.text_default) {
            const auto id = EventId(options_.node_id, static_cast<std::uint16_t>(next_event++));
            const auto raw = id.to_bytes();
            value.emplace(raw.begin(), raw.end());
        }
        if (c.space() != number) return;
        if (!value) value = default_bytes(e);
        // An empty string still gets the string faults (string-unterminated pads it).
        if (!value && e.kind == cdi::ElementKind::kString) value.emplace(e.size, 0);
        if (!value || c.address() + value->size() > bytes.size()) return;
        if (!acdi_layout) apply_encoding_faults(options_.faults, e, *value);
        std::copy(value->begin(), value->end(),
                  bytes.begin() + static_cast<std::ptrdiff_t>(c.address()));
    });
    if (number == kAcdiUserSpace) {
        memory::AcdiUser user;
        user.version = static_cast<std::uint8_t>(
            (has_acdi() ? options_.model->document.acdi->var : memory::acdi::kUserVersion) +
            (options_.faults.acdi_version ? 1 : 0));
        user.name = options_.user_name;
        user.description = options_.user_description;
        const auto block = memory::encode_acdi_user(user);
        std::copy(block.begin(), block.end(), bytes.begin());
    }
    return bytes;
}

void NodeMemory::serve(memory::MemoryConfigServer& server) const {
    for (const auto& s : slots_) {
        if (s->served) server.add_space(static_cast<memory::Space>(s->number), *s->top);
    }
}

memory::MemorySpace* NodeMemory::space(std::uint8_t number) const {
    const Slot* s = slot(number);
    return s != nullptr && s->served ? s->top : nullptr;
}

const memory::MemorySpace* NodeMemory::base_space(std::uint8_t number) const {
    const Slot* s = slot(number);
    return s != nullptr && s->served ? &s->base() : nullptr;
}

std::vector<std::uint8_t> NodeMemory::served_spaces() const {
    std::vector<std::uint8_t> out;
    for (const auto& s : slots_) {
        if (s->served) out.push_back(s->number);
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::uint8_t> NodeMemory::read(std::uint8_t number, std::uint32_t address,
                                           std::uint32_t length) const {
    const Slot* s = slot(number);
    if (s == nullptr) return {};
    std::vector<std::uint8_t> out(std::min<std::uint64_t>(length, kMaxSpaceSize), 0);
    out.resize(s->top->read(address, out));
    return out;
}

memory::Snip NodeMemory::snip() const {
    return memory::snip_from_acdi(read(kAcdiFixedSpace, 0, memory::acdi::kManufacturerBlockSize),
                                  read(kAcdiUserSpace, 0, memory::acdi::kUserBlockSize));
}

bool NodeMemory::factory_reset(std::string& error) {
    for (const auto& s : slots_) {
        if (s->constant) {
            s->reload();
            continue;
        }
        const auto bytes = factory_image(s->number);
        if (s->image) {
            const auto status = s->image->image().reinitialise([&](std::span<std::uint8_t> img) {
                std::copy_n(bytes.begin(), std::min(bytes.size(), img.size()), img.begin());
            });
            if (status != memory::ImageFile::Status::kOk) {
                error =
                    "space " + std::to_string(s->number) + ": " + s->image->image().last_error();
                return false;
            }
        } else if (s->ram->write(0, bytes) != memory::WriteStatus::kOk) {
            error = "space " + std::to_string(s->number) + ": reset failed";
            return false;
        }
        s->reload();
    }
    return true;
}

void NodeMemory::reboot() {
    for (const auto& s : slots_) s->reload();
}

bool NodeMemory::keep_past_end(std::uint8_t space, std::size_t offset,
                               std::span<const std::uint8_t> bytes) {
    if (options_.image_dir.empty()) {
        std::vector<std::uint8_t>& kept = past_end_[space];
        if (kept.size() < offset + bytes.size()) kept.resize(offset + bytes.size(), 0);
        std::copy(bytes.begin(), bytes.end(), kept.begin() + static_cast<std::ptrdiff_t>(offset));
        return true;
    }
    const std::string path = (options_.image_dir / (image_file_name(space) + ".past-end")).string();
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return false;
    const ssize_t n = ::pwrite(fd, bytes.data(), bytes.size(), static_cast<off_t>(offset));
    const bool ok = n == static_cast<ssize_t>(bytes.size()) && ::fsync(fd) == 0;
    ::close(fd);
    return ok;
}

std::vector<std::uint8_t> NodeMemory::past_end(std::uint8_t space) const {
    if (options_.image_dir.empty()) {
        const auto it = past_end_.find(space);
        return it == past_end_.end() ? std::vector<std::uint8_t>{} : it->second;
    }
    std::ifstream in(options_.image_dir / (image_file_name(space) + ".past-end"), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool NodeMemory::store_unique_id_counter(std::uint32_t counter) {
    if (unique_id_image_) {
        const std::uint8_t b[4] = {
            static_cast<std::uint8_t>(counter >> 24), static_cast<std::uint8_t>(counter >> 16),
            static_cast<std::uint8_t>(counter >> 8), static_cast<std::uint8_t>(counter)};
        if (unique_id_image_->write(0, b) != memory::ImageFile::Status::kOk) return false;
    }
    unique_id_counter_ = counter;
    return true;
}

bool NodeMemory::slot_hidden(const EventSlot& e) const {
    // events-missing: slots 1, 3, 5... of the CDI's document order.
    return options_.faults.events_missing && (&e - options_.model->events.data()) % 2 == 1;
}

std::vector<std::pair<EventId, EventRole>> NodeMemory::events() const {
    std::vector<std::pair<EventId, EventRole>> out;
    for (const EventSlot& e : options_.model->events) {
        if (slot_hidden(e)) continue;
        const Slot* s = slot(static_cast<std::uint8_t>(e.space));
        if (s == nullptr || e.address > 0xFFFFFFFFu) continue;
        std::array<std::uint8_t, 8> raw{};
        if (s->top->read(static_cast<std::uint32_t>(e.address), raw) != raw.size()) continue;
        const auto id = EventId::from_bytes(raw);
        if (!id || id->value() == 0) continue;  // an all-zero event ID means "not set"
        out.emplace_back(*id, e.role);
    }
    return out;
}

std::vector<EventSlot> NodeMemory::events_in(std::uint8_t space, std::uint32_t address,
                                             std::uint32_t length) const {
    std::vector<EventSlot> out;
    const std::uint64_t end = std::uint64_t{address} + length;
    for (const EventSlot& e : options_.model->events) {
        if (e.space == space && e.address < end && e.address + 8 > address && !slot_hidden(e)) {
            out.push_back(e);
        }
    }
    return out;
}

}  // namespace olcb::simnode
