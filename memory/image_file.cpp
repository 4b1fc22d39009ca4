#include "memory/image_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <limits>
#include <utility>

namespace olcb::memory {
namespace {

constexpr std::uint64_t kMaxImageSize = std::numeric_limits<std::uint32_t>::max();

std::string errno_text(const std::string& what, const std::filesystem::path& path) {
    return what + " " + path.string() + ": " + std::strerror(errno);
}

// Closes a descriptor on scope exit unless released.
class Fd {
public:
    explicit Fd(int fd = -1) : fd_(fd) {}
    ~Fd() {
        if (fd_ >= 0) ::close(fd_);
    }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    int get() const { return fd_; }
    int release() { return std::exchange(fd_, -1); }
    void reset(int fd) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = fd;
    }

private:
    int fd_;
};

bool pwrite_all(int fd, std::span<const std::uint8_t> data, std::uint64_t offset) {
    while (!data.empty()) {
        const ssize_t n = ::pwrite(fd, data.data(), data.size(), static_cast<off_t>(offset));
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data = data.subspan(static_cast<std::size_t>(n));
        offset += static_cast<std::uint64_t>(n);
    }
    return true;
}

// Reads up to out.size() bytes; returns how many were read before end of file, -1 on error.
ssize_t pread_all(int fd, std::span<std::uint8_t> out, std::uint64_t offset) {
    std::size_t done = 0;
    while (done < out.size()) {
        const ssize_t n =
            ::pread(fd, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
        if (n < 0) {
            if (errno == EINTR) continue;
            return -1;
        }
        if (n == 0) break;
        done += static_cast<std::size_t>(n);
    }
    return static_cast<ssize_t>(done);
}

bool sync_data(int fd) {
    while (::fdatasync(fd) != 0) {
        if (errno != EINTR) return false;
    }
    return true;
}

void put_le(std::vector<std::uint8_t>& out, std::uint64_t value, std::size_t size) {
    for (std::size_t i = 0; i < size; ++i)
        out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
}

std::uint64_t get_le(std::span<const std::uint8_t> bytes, std::size_t at, std::size_t size) {
    std::uint64_t value = 0;
    for (std::size_t i = size; i-- > 0;) value = (value << 8) | bytes[at + i];
    return value;
}

constexpr std::array<std::uint32_t, 256> make_crc_table() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
        table[i] = c;
    }
    return table;
}

constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

// Writes a fresh image beside path and renames it into place, so a crash leaves either no
// image (created again next time) or a complete one.
std::string create_image(const std::filesystem::path& path, int dir_fd,
                         std::span<const std::uint8_t> content) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    Fd fd(::open(tmp.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
    if (fd.get() < 0) return errno_text("cannot create", tmp);
    if (!pwrite_all(fd.get(), content, 0)) return errno_text("cannot write", tmp);
    if (!sync_data(fd.get())) return errno_text("cannot sync", tmp);
    fd.reset(-1);
    if (::rename(tmp.c_str(), path.c_str()) != 0) return errno_text("cannot rename", tmp);
    if (::fsync(dir_fd) != 0) return errno_text("cannot sync directory of", path);
    return {};
}

}  // namespace

namespace journal {

std::uint32_t crc32(std::span<const std::uint8_t> bytes) {
    std::uint32_t c = 0xFFFFFFFFu;
    for (const std::uint8_t b : bytes) c = kCrcTable[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

void encode(std::uint64_t sequence, std::uint32_t offset, std::span<const std::uint8_t> data,
            std::vector<std::uint8_t>& out) {
    const std::size_t start = out.size();
    put_le(out, kMagic, 4);
    put_le(out, sequence, 8);
    put_le(out, offset, 4);
    put_le(out, data.size(), 4);
    out.insert(out.end(), data.begin(), data.end());
    put_le(out, crc32(std::span(out).subspan(start)), 4);
}

std::optional<Record> decode(std::span<const std::uint8_t> bytes, std::size_t image_size) {
    if (bytes.size() < kHeaderSize + kTrailerSize) return std::nullopt;
    if (get_le(bytes, 0, 4) != kMagic) return std::nullopt;
    const std::uint64_t offset = get_le(bytes, 12, 4);
    const std::uint64_t length = get_le(bytes, 16, 4);
    if (offset > image_size || length > image_size - offset) return std::nullopt;
    if (bytes.size() - kHeaderSize - kTrailerSize < length) return std::nullopt;
    const std::size_t body = kHeaderSize + static_cast<std::size_t>(length);
    if (crc32(bytes.first(body)) != get_le(bytes, body, 4)) return std::nullopt;
    Record record;
    record.sequence = get_le(bytes, 4, 8);
    record.offset = static_cast<std::uint32_t>(offset);
    record.data.assign(bytes.begin() + kHeaderSize, bytes.begin() + static_cast<long>(body));
    return record;
}

}  // namespace journal

ImageFile::ImageFile(std::filesystem::path path, int image_fd, int journal_fd,
                     std::vector<std::uint8_t> bytes, std::uint64_t sequence)
    : path_(std::move(path)),
      image_fd_(image_fd),
      journal_fd_(journal_fd),
      bytes_(std::move(bytes)),
      sequence_(sequence) {
    journal_path_ = path_;
    journal_path_ += ".journal";
    record_.reserve(journal::kHeaderSize + 64 + journal::kTrailerSize);
}

ImageFile::~ImageFile() {
    if (image_fd_ >= 0) ::close(image_fd_);
    if (journal_fd_ >= 0) ::close(journal_fd_);  // also drops the flock
}

ImageOpenResult ImageFile::open(const std::filesystem::path& path, std::size_t size,
                                const Initialiser& init) {
    ImageOpenResult result;
    if (size > kMaxImageSize) {
        result.error = "image " + path.string() + " too large (" + std::to_string(size) +
                       " bytes; at most 2^32 - 1)";
        return result;
    }
    std::filesystem::path dir = path.parent_path();
    if (dir.empty()) dir = ".";
    Fd dir_fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (dir_fd.get() < 0) {
        result.error = errno_text("cannot open image directory", dir);
        return result;
    }
    std::filesystem::path journal_path = path;
    journal_path += ".journal";
    Fd journal_fd(::open(journal_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644));
    if (journal_fd.get() < 0) {
        result.error = errno_text("cannot open journal", journal_path);
        return result;
    }
    // Two writers of one image would interleave journal records; the lock dies with the process.
    if (::flock(journal_fd.get(), LOCK_EX | LOCK_NB) != 0) {
        result.error = errno == EWOULDBLOCK
                           ? "image " + path.string() + " is in use by another process"
                           : errno_text("cannot lock", journal_path);
        return result;
    }

    std::vector<std::uint8_t> bytes(size, 0);
    std::uint64_t sequence = 0;
    Fd image_fd(::open(path.c_str(), O_RDWR | O_CLOEXEC));
    if (image_fd.get() < 0 && errno != ENOENT) {
        result.error = errno_text("cannot open image", path);
        return result;
    }
    if (image_fd.get() < 0) {
        // A journal without its image belongs to an image that no longer exists.
        if (::ftruncate(journal_fd.get(), 0) != 0 || !sync_data(journal_fd.get())) {
            result.error = errno_text("cannot clear journal", journal_path);
            return result;
        }
        if (init) init(bytes);
        if (auto error = create_image(path, dir_fd.get(), bytes); !error.empty()) {
            result.error = std::move(error);
            return result;
        }
        image_fd.reset(::open(path.c_str(), O_RDWR | O_CLOEXEC));
        if (image_fd.get() < 0) {
            result.error = errno_text("cannot open image", path);
            return result;
        }
        result.created = true;
    } else {
        struct stat st {};
        if (::fstat(image_fd.get(), &st) != 0) {
            result.error = errno_text("cannot stat image", path);
            return result;
        }
        if (!S_ISREG(st.st_mode)) {
            result.error = "image " + path.string() + " is not a regular file";
            return result;
        }
        if (static_cast<std::uint64_t>(st.st_size) != size) {
            result.error = "image " + path.string() + " has " + std::to_string(st.st_size) +
                           " bytes, expected " + std::to_string(size);
            return result;
        }
        if (pread_all(image_fd.get(), bytes, 0) != static_cast<ssize_t>(size)) {
            result.error = errno_text("cannot read image", path);
            return result;
        }
        struct stat jst {};
        if (::fstat(journal_fd.get(), &jst) != 0) {
            result.error = errno_text("cannot stat journal", journal_path);
            return result;
        }
        // Read no more than the largest record an image of this size can have.
        const std::uint64_t limit = journal::kHeaderSize + size + journal::kTrailerSize;
        std::vector<std::uint8_t> raw(
            static_cast<std::size_t>(std::min<std::uint64_t>(jst.st_size, limit)));
        const ssize_t got = pread_all(journal_fd.get(), raw, 0);
        if (got < 0) {
            result.error = errno_text("cannot read journal", journal_path);
            return result;
        }
        raw.resize(static_cast<std::size_t>(got));
        if (auto record = journal::decode(raw, size)) {
            sequence = record->sequence;
            const auto target = std::span(bytes).subspan(record->offset, record->data.size());
            if (std::equal(target.begin(), target.end(), record->data.begin())) {
                // The bytes may sit only in the page cache (killed before the image sync): make
                // them durable before a later write overwrites the record that could repair them.
                if (!sync_data(image_fd.get())) {
                    result.error = errno_text("cannot sync image", path);
                    return result;
                }
                result.journal = JournalState::kAlreadyApplied;
            } else {
                if (!pwrite_all(image_fd.get(), record->data, record->offset) ||
                    !sync_data(image_fd.get())) {
                    result.error = errno_text("cannot replay journal into", path);
                    return result;
                }
                std::copy(record->data.begin(), record->data.end(), target.begin());
                result.journal = JournalState::kReplayed;
            }
        } else if (!raw.empty()) {
            result.journal = JournalState::kDiscarded;
        }
        // The journal may have just been created: make its directory entry durable.
        if (::fsync(dir_fd.get()) != 0) {
            result.error = errno_text("cannot sync directory", dir);
            return result;
        }
    }
    result.image.reset(
        new ImageFile(path, image_fd.release(), journal_fd.release(), std::move(bytes), sequence));
    return result;
}

ImageFile::Status ImageFile::write(std::size_t offset, std::span<const std::uint8_t> data) {
    if (failed_) return Status::kIoError;
    if (offset > bytes_.size() || data.size() > bytes_.size() - offset) {
        return Status::kOutOfBounds;
    }
    if (data.empty()) return Status::kOk;
    record_.clear();
    journal::encode(++sequence_, static_cast<std::uint32_t>(offset), data, record_);
    if (!pwrite_all(journal_fd_, record_, 0) || !sync_data(journal_fd_)) {
        failed_ = true;
        last_error_ = errno_text("cannot write journal", journal_path_);
        return Status::kIoError;
    }
    if (!pwrite_all(image_fd_, data, offset) || !sync_data(image_fd_)) {
        failed_ = true;
        last_error_ = errno_text("cannot write image", path_);
        return Status::kIoError;
    }
    std::copy(data.begin(), data.end(), bytes_.begin() + static_cast<long>(offset));
    return Status::kOk;
}

ImageFile::Status ImageFile::reinitialise(const Initialiser& init) {
    std::vector<std::uint8_t> fresh(bytes_.size(), 0);
    if (init) init(fresh);
    return write(0, fresh);
}

}  // namespace olcb::memory
