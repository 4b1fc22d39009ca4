#include "memory/memory_space.hpp"

#include <algorithm>
#include <limits>
#include <utility>

namespace olcb::memory {
namespace {

std::uint32_t clamp_size(std::size_t size) {
    return static_cast<std::uint32_t>(
        std::min<std::size_t>(size, std::numeric_limits<std::uint32_t>::max()));
}

}  // namespace

std::string_view to_string(WriteStatus status) {
    switch (status) {
        case WriteStatus::kOk:
            return "ok";
        case WriteStatus::kReadOnly:
            return "read-only";
        case WriteStatus::kOutOfBounds:
            return "out of bounds";
        case WriteStatus::kIoError:
            return "I/O error";
    }
    return "";
}

std::size_t read_clamped(std::span<const std::uint8_t> bytes, std::uint32_t address,
                         std::span<std::uint8_t> out) {
    if (address >= bytes.size()) return 0;
    const std::size_t n = std::min(out.size(), bytes.size() - address);
    std::copy_n(bytes.begin() + address, n, out.begin());
    return n;
}

VectorSpace::VectorSpace(std::vector<std::uint8_t> bytes, std::string description)
    : bytes_(std::move(bytes)), description_(std::move(description)) {}

std::uint32_t VectorSpace::size() const {
    return clamp_size(bytes_.size());
}

std::size_t VectorSpace::read(std::uint32_t address, std::span<std::uint8_t> out) {
    return read_clamped(bytes_, address, out);
}

ConstantSpace::ConstantSpace(std::vector<std::uint8_t> bytes, std::string description)
    : VectorSpace(std::move(bytes), std::move(description)) {}

ConstantSpace ConstantSpace::from_cdi(std::string_view xml, std::string description) {
    // Clients stop reading at the first NUL, so the space ends with exactly one.
    xml = xml.substr(0, xml.find('\0'));
    std::vector<std::uint8_t> bytes(xml.begin(), xml.end());
    bytes.push_back(0);
    return ConstantSpace(std::move(bytes), std::move(description));
}

WriteStatus ConstantSpace::write(std::uint32_t, std::span<const std::uint8_t>) {
    return WriteStatus::kReadOnly;
}

RamSpace::RamSpace(std::vector<std::uint8_t> initial, std::string description)
    : VectorSpace(std::move(initial), std::move(description)) {}

WriteStatus RamSpace::write(std::uint32_t address, std::span<const std::uint8_t> in) {
    if (!fits(size(), address, in.size())) return WriteStatus::kOutOfBounds;
    std::copy(in.begin(), in.end(), mutable_bytes().begin() + address);
    return WriteStatus::kOk;
}

ImageSpace::ImageSpace(std::unique_ptr<ImageFile> image, std::string description)
    : image_(std::move(image)), description_(std::move(description)) {}

std::uint32_t ImageSpace::size() const {
    return clamp_size(image_->size());
}

std::size_t ImageSpace::read(std::uint32_t address, std::span<std::uint8_t> out) {
    return read_clamped(image_->bytes(), address, out);
}

WriteStatus ImageSpace::write(std::uint32_t address, std::span<const std::uint8_t> in) {
    switch (image_->write(address, in)) {
        case ImageFile::Status::kOk:
            return WriteStatus::kOk;
        case ImageFile::Status::kOutOfBounds:
            return WriteStatus::kOutOfBounds;
        case ImageFile::Status::kIoError:
            break;
    }
    return WriteStatus::kIoError;
}

}  // namespace olcb::memory
