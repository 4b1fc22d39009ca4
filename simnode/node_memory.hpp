// The memory of a simulated node, built from its CDI: space 0xFF (the CDI and one NUL), one
// writable space per CDI segment space sized to its layout, ACDI 252/251, persisted as one image
// per writable space; the faults' hooks change what it serves and put their layers in front.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "memory/acdi.hpp"
#include "memory/image_file.hpp"
#include "memory/memory_config_server.hpp"
#include "memory/memory_space.hpp"
#include "memory/snip.hpp"
#include "openlcb/node_id.hpp"
#include "simnode/event_roles.hpp"
#include "simnode/faults.hpp"
#include "simnode/faults/fault_hooks.hpp"

namespace olcb::simnode {

/// Largest space a node builds (bounded memory whatever the CDI's replication says).
inline constexpr std::uint64_t kMaxSpaceSize = 16u << 20;
/// Most variables a CDI may have for a node to build its default images.
inline constexpr std::uint64_t kMaxVariables = 1u << 22;
/// Most event IDs a node advertises.
inline constexpr std::size_t kMaxEvents = 1024;

/// A parsed and laid-out CDI, shared (read-only) by every node serving the same text.
struct CdiModel {
    std::string text;  ///< the CDI text as given
    /// The model; never null (the layout points into it, so it stays where it is).
    std::unique_ptr<const cdi::Document> document;
    std::optional<cdi::Layout> layout;  ///< addresses of every variable
    bool valid = false;                 ///< schema, semantic and layout checks found no error
    std::string first_error;            ///< the first validation error ("" when valid)
    std::vector<EventSlot> events;      ///< eventid variables and their roles, document order
};

/// Parses, lays out and validates text; one model per distinct text is kept while in use.
/// nullptr with `error` set when the text cannot be parsed or laid out (validity is reported in
/// CdiModel::valid, not as an error). Thread-safe.
std::shared_ptr<const CdiModel> load_cdi_model(const std::string& text, std::string& error);

/// Everything NodeMemory is built from.
struct MemoryOptions {
    std::shared_ptr<const CdiModel> model;  ///< must not be null
    NodeId node_id;                         ///< source of default event IDs
    std::filesystem::path image_dir;        ///< empty: RAM only
    memory::AcdiManufacturer identity;      ///< space 252 strings (version taken from the CDI)
    std::string user_name;                  ///< space 251 name of a fresh image
    std::string user_description;           ///< space 251 description of a fresh image
    FaultSet faults;                        ///< the node's faults (those with memory hooks act)
    /// A train node's spaces (TrainControlS §7): this FDI text in 0xFA, read-only with one NUL
    /// after it ("" = none).
    std::string fdi;
    /// A train node's function space 0xF9 of this many bytes, in RAM (0 = none).
    std::uint32_t function_space = 0;
};

/// File name of the image of a space ("space-253.img").
std::string image_file_name(std::uint8_t space);

/// The spaces of one node.
class NodeMemory {
public:
    /// Builds the spaces, opening or creating the images; nullptr with `error` set on failure.
    static std::unique_ptr<NodeMemory> open(MemoryOptions options, std::string& error);
    ~NodeMemory();
    NodeMemory(const NodeMemory&) = delete;
    NodeMemory& operator=(const NodeMemory&) = delete;

    /// Registers every served space with server (0xFF, CDI spaces, 252/251 with <acdi/>).
    void serve(memory::MemoryConfigServer& server) const;
    /// The space served as number (faults included), or null.
    memory::MemorySpace* space(std::uint8_t number) const;
    /// The served space as built, without the fault wrappers: its real size and read-only flag,
    /// which a client's requests are judged by (simnode/audit); null when not served.
    const memory::MemorySpace* base_space(std::uint8_t number) const;
    /// Numbers of the served spaces, ascending.
    std::vector<std::uint8_t> served_spaces() const;
    /// Up to length bytes of a space read as a client would (empty when not there).
    std::vector<std::uint8_t> read(std::uint8_t number, std::uint32_t address,
                                   std::uint32_t length) const;
    /// SNIP content from spaces 252 and 251 as served (so SNIP and ACDI agree).
    memory::Snip snip() const;
    /// True when the CDI has <acdi/> (252 and 251 served).
    bool has_acdi() const;
    /// The factory content of a writable space (CDI defaults, default event IDs, user strings).
    std::vector<std::uint8_t> factory_image(std::uint8_t number) const;
    /// Restores every writable space to its factory content; false with `error` on I/O failure.
    bool factory_reset(std::string& error);
    /// Power cycle: forgets what only RAM held (write-not-persisted, readonly-writable).
    void reboot();
    /// The persisted Get Unique ID counter (never below the default event IDs handed out).
    std::uint32_t unique_id_counter() const { return unique_id_counter_; }
    /// write-past-end-grows: keeps bytes written past the end of space (from `offset` past it)
    /// where no read reaches them: in "<image>.past-end" beside the space's image (synced), or in
    /// RAM without an image directory. False on I/O failure.
    bool keep_past_end(std::uint8_t space, std::size_t offset, std::span<const std::uint8_t> bytes);
    /// What keep_past_end() kept for space (empty when nothing).
    std::vector<std::uint8_t> past_end(std::uint8_t space) const;
    /// Persists a new Get Unique ID counter; false on I/O failure.
    bool store_unique_id_counter(std::uint32_t counter);
    /// The CDI model.
    const CdiModel& model() const { return *options_.model; }
    /// Which event IDs the node identifies, as its faults say.
    const EventPolicy& event_policy() const { return event_policy_; }
    /// Event IDs and roles as the node reads them from its memory now (zero IDs and the slots
    /// the event policy hides skipped).
    std::vector<std::pair<EventId, EventRole>> events() const;
    /// The event slots a written range touches (for re-advertising; hidden slots skipped).
    std::vector<EventSlot> events_in(std::uint8_t space, std::uint32_t address,
                                     std::uint32_t length) const;

private:
    struct Slot;
    explicit NodeMemory(MemoryOptions options);
    bool build(std::string& error);
    bool add_writable(std::uint8_t number, std::uint64_t size, bool served, std::string& error,
                      bool ram_only = false);
    void add_constant(std::uint8_t number, std::vector<std::uint8_t> bytes);
    Slot* slot(std::uint8_t number) const;
    bool slot_hidden(const EventSlot& e) const;

    MemoryOptions options_;
    ActiveFaults faults_;
    EventPolicy event_policy_;
    AcdiVersions versions_;  // the ACDI version bytes, as the faults say
    std::vector<std::unique_ptr<Slot>> slots_;
    std::array<Slot*, 256> by_number_{};
    std::unique_ptr<memory::ImageFile> unique_id_image_;
    std::map<std::uint8_t, std::vector<std::uint8_t>> past_end_;  // keep_past_end() without images
    std::uint32_t unique_id_counter_ = 0;
    std::uint32_t default_event_count_ = 0;
};

}  // namespace olcb::simnode
