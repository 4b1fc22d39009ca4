// An address space as the Memory Configuration server sees it: a byte array with a size and a
// read-only flag. The server talks only to this interface, so an owner can wrap a space (e.g. to
// inject faults) without touching the server.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "memory/image_file.hpp"

namespace olcb::memory {

/// Outcome of MemorySpace::write(); a write is all or nothing.
enum class WriteStatus : std::uint8_t {
    kOk,           ///< every byte written (and, for persistent spaces, on disk)
    kReadOnly,     ///< the space cannot be written; nothing changed
    kOutOfBounds,  ///< the range does not fit in the space; nothing changed
    kIoError,      ///< storage failed; the caller must not acknowledge the write
};

/// Short English name of a write status.
std::string_view to_string(WriteStatus status);

/// A memory space: valid addresses are lowest_address() .. size() - 1.
class MemorySpace {
public:
    virtual ~MemorySpace() = default;
    /// Number of addressable bytes counted from address 0 (highest address + 1).
    virtual std::uint32_t size() const = 0;
    /// True when writes are refused.
    virtual bool read_only() const = 0;
    /// Lowest valid address (reported in space information when non-zero).
    virtual std::uint32_t lowest_address() const { return 0; }
    /// Optional description sent in the space information reply ("" = none).
    virtual std::string_view description() const { return {}; }
    /// Copies up to out.size() bytes from address; returns how many (0 when out of range).
    virtual std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) = 0;
    /// Writes all of in at address or nothing; returns only once the data is stored durably.
    virtual WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) = 0;
};

/// A space whose bytes live in memory, a fixed number of them: what ConstantSpace and RamSpace
/// share; they differ only in whether write() changes them.
class VectorSpace : public MemorySpace {
public:
    std::uint32_t size() const override;
    std::string_view description() const override { return description_; }
    std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) override;
    /// The whole content.
    std::span<const std::uint8_t> bytes() const { return bytes_; }

protected:
    VectorSpace(std::vector<std::uint8_t> bytes, std::string description);
    /// The content, for a writable space's write().
    std::span<std::uint8_t> mutable_bytes() { return bytes_; }

private:
    std::vector<std::uint8_t> bytes_;
    std::string description_;
};

/// Read-only space holding constant bytes (CDI, ACDI 252).
class ConstantSpace : public VectorSpace {
public:
    /// A space holding exactly bytes.
    explicit ConstantSpace(std::vector<std::uint8_t> bytes, std::string description = {});
    /// A CDI space: the XML text (cut at its first NUL) followed by exactly one NUL.
    static ConstantSpace from_cdi(std::string_view xml, std::string description = {});

    bool read_only() const override { return true; }
    WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override;
};

/// Writable space kept in RAM only (tests, nodes without an image directory).
class RamSpace : public VectorSpace {
public:
    /// A space starting with the given content; its size never changes.
    explicit RamSpace(std::vector<std::uint8_t> initial, std::string description = {});

    bool read_only() const override { return false; }
    WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override;
};

/// Writable space persisted in an ImageFile: write() returns after the data is on disk.
class ImageSpace : public MemorySpace {
public:
    /// Takes ownership of an open image (must not be null).
    explicit ImageSpace(std::unique_ptr<ImageFile> image, std::string description = {});

    std::uint32_t size() const override;
    bool read_only() const override { return false; }
    std::string_view description() const override { return description_; }
    std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) override;
    WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override;
    /// The underlying image (e.g. for factory reset or its last error).
    ImageFile& image() { return *image_; }

private:
    std::unique_ptr<ImageFile> image_;
    std::string description_;
};

/// Forwards every call to an inner space; derive from it to change one behaviour (faults).
class ForwardingSpace : public MemorySpace {
public:
    /// Wraps inner, which must outlive this object.
    explicit ForwardingSpace(MemorySpace& inner) : inner_(inner) {}

    std::uint32_t size() const override { return inner_.size(); }
    bool read_only() const override { return inner_.read_only(); }
    std::uint32_t lowest_address() const override { return inner_.lowest_address(); }
    std::string_view description() const override { return inner_.description(); }
    std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) override {
        return inner_.read(address, out);
    }
    WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
        return inner_.write(address, in);
    }
    /// The wrapped space.
    MemorySpace& inner() const { return inner_; }

private:
    MemorySpace& inner_;
};

/// Copies up to out.size() bytes of bytes from address; shared by byte-array spaces.
std::size_t read_clamped(std::span<const std::uint8_t> bytes, std::uint32_t address,
                         std::span<std::uint8_t> out);

/// True when [address, address + length) lies inside a space of size bytes.
constexpr bool fits(std::uint64_t size, std::uint32_t address, std::size_t length) {
    return address <= size && length <= size - address;
}

}  // namespace olcb::memory
