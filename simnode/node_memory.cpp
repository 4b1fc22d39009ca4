#include "simnode/node_memory.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <utility>

#include "cdi/parser.hpp"
#include "cdi/validator.hpp"
#include "cdi/value_codec.hpp"

namespace olcb::simnode {
namespace {

constexpr std::uint8_t kCdiSpace = 0xFF;
constexpr std::uint8_t kFdiSpace = 0xFA;       // TrainControlS §7.2
constexpr std::uint8_t kFunctionSpace = 0xF9;  // TrainControlS §7.1
constexpr std::uint8_t kAcdiFixedSpace = 0xFC;
constexpr std::uint8_t kAcdiUserSpace = 0xFB;
constexpr const char* kUniqueIdFile = "unique-id.img";

// The faults' store hooks: each variable lying wholly inside a write is stored as they say.
class MisEncode : public memory::ForwardingSpace {
public:
    MisEncode(memory::MemorySpace& inner, const cdi::Layout& layout, std::uint8_t space,
              const ActiveFaults& faults)
        : ForwardingSpace(inner), layout_(layout), space_(space), faults_(faults) {}
    memory::WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        std::vector<std::uint8_t> bytes(in.begin(), in.end());
        const std::uint64_t end = std::uint64_t{address} + bytes.size();
        for (std::uint64_t pos = address; pos < end;) {
            const cdi::Cursor c = layout_.find(space_, pos);
            if (c.valid() && c.address() >= address && c.address() + c.size() <= end &&
                c.size() > 0) {
                faults_.store(c.element(),
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
    const ActiveFaults& faults_;  // the node's, which outlives its spaces
};

// One model per distinct text while any node uses it: 1,000 nodes of one CDI share one parse.
struct ModelCache {
    std::mutex mutex;
    std::map<std::string, std::weak_ptr<const CdiModel>> models;
};

ModelCache& model_cache() {
    static ModelCache cache;
    return cache;
}

// The first error of diagnostics, formatted ("" when none).
std::string first_error(const std::vector<cdi::Diagnostic>& diagnostics) {
    for (const auto& d : diagnostics) {
        if (d.severity == cdi::Severity::kError) return cdi::format_diagnostic("CDI", d);
    }
    return "";
}

// One parse serves the model, its layout and its validation.
std::shared_ptr<const CdiModel> build_model(const std::string& text, std::string& error) {
    auto model = std::make_shared<CdiModel>();
    model->text = text;
    const std::string_view xml(model->text.data(),
                               std::min(model->text.size(), model->text.find('\0')));
    cdi::ValidatedCdi checked = cdi::validate_model(xml);
    model->first_error = first_error(checked.report.diagnostics);
    model->valid = checked.report.ok();
    if (!checked.document) {
        error = model->first_error.empty() ? "CDI does not parse" : model->first_error;
        return nullptr;
    }
    if (!checked.layout) {
        error = model->first_error.empty() ? "CDI layout failed" : model->first_error;
        return nullptr;
    }
    model->document = std::move(checked.document);
    model->layout.emplace(std::move(*checked.layout));
    if (model->layout->variable_count() > kMaxVariables) {
        error = "CDI has " + std::to_string(model->layout->variable_count()) +
                " variables after replication; at most " + std::to_string(kMaxVariables) +
                " are supported";
        return nullptr;
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
    std::vector<SpaceLayer*> layers;                             // the faults' wrappers
    memory::MemorySpace* top = nullptr;

    // Forgets what only RAM held (a power cycle).
    void reload() const {
        for (SpaceLayer* layer : layers) layer->power_cycle();
    }

    memory::MemorySpace& base() const {
        if (constant) return *constant;
        if (image) return *image;
        return *ram;
    }
    void wrap(std::unique_ptr<memory::MemorySpace> w) {
        top = w.get();
        wrappers.push_back(std::move(w));
    }
    void add_layers(const std::vector<SpaceBuild::Make>& makes) {
        for (const SpaceBuild::Make make : makes) {
            std::unique_ptr<SpaceLayer> layer = make(*top);
            layers.push_back(layer.get());
            wrap(std::move(layer));
        }
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

NodeMemory::NodeMemory(MemoryOptions options)
    : options_(std::move(options)), faults_(options_.faults), event_policy_(faults_.events()) {}

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
    return options_.model->document->acdi.has_value();
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
    SpaceBuild layers{number, true, {}, {}};
    faults_.space(layers);
    s->add_layers(layers.storage);
    s->add_layers(layers.acknowledging);
    by_number_[number] = s.get();
    slots_.push_back(std::move(s));
}

bool NodeMemory::add_writable(std::uint8_t number, std::uint64_t size, bool served,
                              std::string& error, bool ram_only) {
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
    if (!options_.image_dir.empty() && served && !ram_only) {
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
        const std::uint8_t version = versions_.user;
        std::uint8_t stored = 0;
        if (s->top->read(0, std::span(&stored, 1)) == 1 && stored != version &&
            s->top->write(0, std::span(&version, 1)) != memory::WriteStatus::kOk) {
            error = "space 251: cannot store the ACDI version byte";
            return false;
        }
    }
    SpaceBuild layers{number, false, {}, {}};
    faults_.space(layers);
    s->add_layers(layers.storage);
    if (faults_.stores() && !s->acdi_layout && served) {
        s->wrap(std::make_unique<MisEncode>(*s->top, *options_.model->layout, number, faults_));
    }
    s->add_layers(layers.acknowledging);
    by_number_[number] = s.get();
    slots_.push_back(std::move(s));
    return true;
}

bool NodeMemory::build(std::string& error) {
    const CdiModel& model = *options_.model;
    const bool acdi = has_acdi();
    versions_.fixed = static_cast<std::uint8_t>(acdi ? model.document->acdi->fixed
                                                     : memory::acdi::kManufacturerVersion);
    versions_.user =
        static_cast<std::uint8_t>(acdi ? model.document->acdi->var : memory::acdi::kUserVersion);
    faults_.acdi(versions_);
    // Default event IDs take Get Unique ID suffixes 0..n-1, so those never repeat them.
    model.layout->visit([this](const cdi::Cursor& c) {
        if (c.element().kind == cdi::ElementKind::kEventId && !c.element().text_default) {
            ++default_event_count_;
        }
    });

    add_constant(kCdiSpace, faults_.served_cdi(model.text));

    memory::AcdiManufacturer fixed = options_.identity;
    fixed.version = versions_.fixed;
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

    // A train's function values are its running state, not configuration: RAM only.
    if (options_.function_space > 0 && slot(kFunctionSpace) == nullptr &&
        !add_writable(kFunctionSpace, options_.function_space, true, error, true)) {
        return false;
    }
    if (!options_.fdi.empty() && slot(kFdiSpace) == nullptr) {
        std::vector<std::uint8_t> fdi(options_.fdi.begin(), options_.fdi.end());
        fdi.push_back(0);
        add_constant(kFdiSpace, std::move(fdi));
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
        if (!acdi_layout) faults_.store(e, *value);
        std::copy(value->begin(), value->end(),
                  bytes.begin() + static_cast<std::ptrdiff_t>(c.address()));
    });
    if (number == kAcdiUserSpace) {
        memory::AcdiUser user;
        user.version = versions_.user;
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
    const auto index = static_cast<std::size_t>(&e - options_.model->events.data());
    return event_policy_.hidden != nullptr && event_policy_.hidden(index);
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
