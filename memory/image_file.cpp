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

namespace {

// The files ImageFile::open() works on, and what it learns from them. The image closes first,
// the journal (and its lock) after it.
struct Opening {
    explicit Opening(const std::filesystem::path& image) : path(image) {}

    const std::filesystem::path& path;
    std::filesystem::path dir;
    std::filesystem::path journal_path;
    Fd dir_fd;
    Fd journal_fd;
    Fd image_fd;
    std::vector<std::uint8_t> bytes;  // the image's content, its size from the start
    std::uint64_t sequence = 0;       // the journal record's, 0 without one
};

// Opens the image's directory and its journal, locked; an error sentence on failure.
std::string open_journal(Opening& o) {
    o.dir = o.path.parent_path();
    if (o.dir.empty()) o.dir = ".";
    o.dir_fd.reset(::open(o.dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (o.dir_fd.get() < 0) return errno_text("cannot open image directory", o.dir);
    o.journal_path = o.path;
    o.journal_path += ".journal";
    o.journal_fd.reset(::open(o.journal_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644));
    if (o.journal_fd.get() < 0) return errno_text("cannot open journal", o.journal_path);
    // Two writers of one image would interleave journal records; the lock dies with the process.
    if (::flock(o.journal_fd.get(), LOCK_EX | LOCK_NB) != 0) {
        return errno == EWOULDBLOCK ? "image " + o.path.string() + " is in use by another process"
                                    : errno_text("cannot lock", o.journal_path);
    }
    return {};
}

// Creates the missing image from init and opens it.
std::string create_fresh(Opening& o, const ImageFile::Initialiser& init) {
    // A journal without its image belongs to an image that no longer exists.
    if (::ftruncate(o.journal_fd.get(), 0) != 0 || !sync_data(o.journal_fd.get())) {
        return errno_text("cannot clear journal", o.journal_path);
    }
    if (init) init(o.bytes);
    if (auto error = create_image(o.path, o.dir_fd.get(), o.bytes); !error.empty()) return error;
    o.image_fd.reset(::open(o.path.c_str(), O_RDWR | O_CLOEXEC));
    if (o.image_fd.get() < 0) return errno_text("cannot open image", o.path);
    return {};
}

// Reads the existing image, which must be a regular file of exactly the size asked for.
std::string read_image(Opening& o) {
    struct stat st {};
    if (::fstat(o.image_fd.get(), &st) != 0) return errno_text("cannot stat image", o.path);
    if (!S_ISREG(st.st_mode)) return "image " + o.path.string() + " is not a regular file";
    const std::size_t size = o.bytes.size();
    if (static_cast<std::uint64_t>(st.st_size) != size) {
        return "image " + o.path.string() + " has " + std::to_string(st.st_size) +
               " bytes, expected " + std::to_string(size);
    }
    if (pread_all(o.image_fd.get(), o.bytes, 0) != static_cast<ssize_t>(size)) {
        return errno_text("cannot read image", o.path);
    }
    return {};
}

std::string read_journal(const Opening& o, std::vector<std::uint8_t>& raw) {
    struct stat jst {};
    if (::fstat(o.journal_fd.get(), &jst) != 0) {
        return errno_text("cannot stat journal", o.journal_path);
    }
    // Read no more than the largest record an image of this size can have.
    const std::uint64_t limit = journal::kHeaderSize + o.bytes.size() + journal::kTrailerSize;
    raw.resize(static_cast<std::size_t>(std::min(static_cast<std::uint64_t>(jst.st_size), limit)));
    const ssize_t got = pread_all(o.journal_fd.get(), raw, 0);
    if (got < 0) return errno_text("cannot read journal", o.journal_path);
    raw.resize(static_cast<std::size_t>(got));
    return {};
}

// Makes the journal's record durable in the image, writing it again when the image lacks it.
std::string apply_record(Opening& o, const journal::Record& record, JournalState& state) {
    o.sequence = record.sequence;
    const auto target = std::span(o.bytes).subspan(record.offset, record.data.size());
    if (std::equal(target.begin(), target.end(), record.data.begin())) {
        // The bytes may sit only in the page cache (killed before the image sync): make them
        // durable before a later write overwrites the record that could repair them.
        if (!sync_data(o.image_fd.get())) return errno_text("cannot sync image", o.path);
        state = JournalState::kAlreadyApplied;
        return {};
    }
    if (!pwrite_all(o.image_fd.get(), record.data, record.offset) || !sync_data(o.image_fd.get())) {
        return errno_text("cannot replay journal into", o.path);
    }
    std::copy(record.data.begin(), record.data.end(), target.begin());
    state = JournalState::kReplayed;
    return {};
}

// Reads the existing image and replays its journal into it.
std::string load_existing(Opening& o, JournalState& state) {
    if (auto error = read_image(o); !error.empty()) return error;
    std::vector<std::uint8_t> raw;
    if (auto error = read_journal(o, raw); !error.empty()) return error;
    if (auto record = journal::decode(raw, o.bytes.size())) {
        if (auto error = apply_record(o, *record, state); !error.empty()) return error;
    } else if (!raw.empty()) {
        state = JournalState::kDiscarded;
    }
    // The journal may have just been created: make its directory entry durable.
    if (::fsync(o.dir_fd.get()) != 0) return errno_text("cannot sync directory", o.dir);
    return {};
}

}  // namespace

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
    Opening o(path);
    o.bytes.assign(size, 0);
    result.error = open_journal(o);
    if (!result.error.empty()) return result;
    o.image_fd.reset(::open(path.c_str(), O_RDWR | O_CLOEXEC));
    if (o.image_fd.get() < 0 && errno != ENOENT) {
        result.error = errno_text("cannot open image", path);
        return result;
    }
    if (o.image_fd.get() < 0) {
        result.error = create_fresh(o, init);
        result.created = result.error.empty();
    } else {
        result.error = load_existing(o, result.journal);
    }
    if (!result.error.empty()) return result;
    result.image.reset(new ImageFile(path, o.image_fd.release(), o.journal_fd.release(),
                                     std::move(o.bytes), o.sequence));
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
