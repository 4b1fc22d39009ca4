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
#include <map>
#include <mutex>
#include <set>
#include <string_view>
#include <system_error>
#include <utility>

#include "base/descriptor.hpp"
#include "base/file.hpp"

namespace olcb::memory {
namespace {

using base::Descriptor;

constexpr std::uint64_t kMaxImageSize = std::numeric_limits<std::uint32_t>::max();

std::string errno_text(const std::string& what, const std::filesystem::path& path) {
    return what + " " + path.string() + ": " + std::strerror(errno);
}

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

// Removes what a creation killed before its rename left ("<image>.tmp-XXXXXXXX", see
// base::write_file). Only while the directory lock is held, so no other creation is under way;
// unlink() removes a planted link, never its target.
void remove_stale_temps(const std::filesystem::path& path) {
    const std::string prefix = path.filename().string() + ".tmp-";
    const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : ".";
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
        if (it->path().filename().string().starts_with(prefix)) ::unlink(it->path().c_str());
    }
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

// A directory as the kernel knows it, whatever path reached it.
using DirectoryKey = std::pair<dev_t, ino_t>;

// The directories this process has images open in, one descriptor each, shared by all their
// images: it holds the flock that keeps a second process out of every image in the directory
// (the lock dies with the process, also after kill -9), and an image's files are opened relative
// to it. Sharing it is what makes a node's images cost one descriptor: the image and journal
// files themselves are open only during ImageFile::open() and write().
class DirectoryLocks {
public:
    // The directory's descriptor, with name counted as open in it; -1 with error set when the
    // image is open already in this process or another process holds the directory.
    int acquire(const std::filesystem::path& image, const std::string& name, DirectoryKey& key,
                std::string& error) {
        std::filesystem::path dir = image.parent_path();
        if (dir.empty()) dir = ".";
        Descriptor fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
        struct stat st {};
        if (fd.get() < 0 || ::fstat(fd.get(), &st) != 0) {
            error = errno_text("cannot open image directory", dir);
            return -1;
        }
        key = {st.st_dev, st.st_ino};
        const std::lock_guard lock(mutex_);
        if (const auto it = held_.find(key); it != held_.end()) {
            if (it->second.names.insert(name).second) return it->second.fd;
            error = "image " + image.string() + " is in use (open already in this process)";
            return -1;
        }
        // Two writers of one image would interleave journal records.
        if (::flock(fd.get(), LOCK_EX | LOCK_NB) != 0) {
            error = errno == EWOULDBLOCK
                        ? "image " + image.string() + " is in use by another process"
                        : errno_text("cannot lock image directory", dir);
            return -1;
        }
        Held& held = held_[key];
        held.fd = fd.release();
        held.names.insert(name);
        return held.fd;
    }

    // The image is closed; the last one in its directory closes it (and drops the lock).
    void release(const DirectoryKey& key, const std::string& name) {
        const std::lock_guard lock(mutex_);
        const auto it = held_.find(key);
        if (it == held_.end()) return;
        it->second.names.erase(name);
        if (!it->second.names.empty()) return;
        ::close(it->second.fd);
        held_.erase(it);
    }

private:
    struct Held {
        int fd = -1;
        std::set<std::string> names;  // the images open in the directory
    };
    std::mutex mutex_;
    std::map<DirectoryKey, Held> held_;
};

DirectoryLocks& directory_locks() {
    static DirectoryLocks locks;
    return locks;
}

}  // namespace

// One image's share of its directory's lock, and the names of its files in that directory.
class DirectoryLease {
public:
    DirectoryLease(DirectoryKey key, int dir_fd, std::string name)
        : key_(key), dir_fd_(dir_fd), name_(std::move(name)), journal_name_(name_ + ".journal") {}
    ~DirectoryLease() { directory_locks().release(key_, name_); }
    DirectoryLease(const DirectoryLease&) = delete;
    DirectoryLease& operator=(const DirectoryLease&) = delete;

    int open_image() const { return ::openat(dir_fd_, name_.c_str(), O_RDWR | O_CLOEXEC); }
    int open_journal(int flags = 0) const {
        return ::openat(dir_fd_, journal_name_.c_str(), O_RDWR | O_CLOEXEC | flags, 0644);
    }
    bool sync_directory() const { return ::fsync(dir_fd_) == 0; }

private:
    DirectoryKey key_;
    int dir_fd_;  // directory_locks()'s
    std::string name_;
    std::string journal_name_;
};

namespace {

// The files ImageFile::open() works on, and what it learns from them. The image closes first,
// the journal after it, the directory lease (and its lock) last.
struct Opening {
    explicit Opening(const std::filesystem::path& image) : path(image) {}

    const std::filesystem::path& path;
    std::filesystem::path journal_path;
    std::unique_ptr<DirectoryLease> lease;
    Descriptor journal_fd;
    Descriptor image_fd;
    std::vector<std::uint8_t> bytes;  // the image's content, its size from the start
    std::uint64_t sequence = 0;       // the journal record's, 0 without one
};

// Takes the image's directory lock and opens its journal; an error sentence on failure.
std::string open_journal(Opening& o) {
    const std::string name = o.path.filename().string();
    DirectoryKey key;
    std::string error;
    const int dir_fd = directory_locks().acquire(o.path, name, key, error);
    if (dir_fd < 0) return error;
    o.lease = std::make_unique<DirectoryLease>(key, dir_fd, name);
    o.journal_path = o.path;
    o.journal_path += ".journal";
    o.journal_fd.reset(o.lease->open_journal(O_CREAT));
    if (o.journal_fd.get() < 0) return errno_text("cannot open journal", o.journal_path);
    return {};
}

// Creates the missing image from init and opens it.
std::string create_fresh(Opening& o, const ImageFile::Initialiser& init) {
    // A journal without its image belongs to an image that no longer exists.
    if (::ftruncate(o.journal_fd.get(), 0) != 0 || !sync_data(o.journal_fd.get())) {
        return errno_text("cannot clear journal", o.journal_path);
    }
    if (init) init(o.bytes);
    remove_stale_temps(o.path);
    // A new file under a fresh name, synced, renamed into place and its directory synced: a
    // crash leaves no image (created again next time) or a complete one, and a file or link
    // planted at a temporary name is never opened or followed.
    std::string error;
    const std::string_view content(reinterpret_cast<const char*>(o.bytes.data()), o.bytes.size());
    if (!base::write_file(o.path, content, error)) return error;
    o.image_fd.reset(o.lease->open_image());
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
    if (!o.lease->sync_directory()) {
        return errno_text("cannot sync directory of", o.path);
    }
    return {};
}

}  // namespace

ImageFile::ImageFile(std::filesystem::path path, std::unique_ptr<DirectoryLease> lease,
                     std::vector<std::uint8_t> bytes, std::uint64_t sequence)
    : path_(std::move(path)),
      lease_(std::move(lease)),
      bytes_(std::move(bytes)),
      sequence_(sequence) {
    journal_path_ = path_;
    journal_path_ += ".journal";
    record_.reserve(journal::kHeaderSize + 64 + journal::kTrailerSize);
}

ImageFile::~ImageFile() = default;

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
    o.image_fd.reset(o.lease->open_image());
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
    result.image.reset(new ImageFile(path, std::move(o.lease), std::move(o.bytes), o.sequence));
    return result;
}

ImageFile::Status ImageFile::write(std::size_t offset, std::span<const std::uint8_t> data) {
    if (failed_) return Status::kIoError;
    if (offset > bytes_.size() || data.size() > bytes_.size() - offset) {
        return Status::kOutOfBounds;
    }
    if (data.empty()) return Status::kOk;
    // Both files are opened before anything is written: when they cannot be (no descriptor
    // left, EMFILE), this write fails alone and the disk is as it was, so later ones may work.
    const Descriptor journal_fd(lease_->open_journal());
    if (journal_fd.get() < 0) {
        last_error_ = errno_text("cannot open journal", journal_path_);
        return Status::kIoError;
    }
    const Descriptor image_fd(lease_->open_image());
    if (image_fd.get() < 0) {
        last_error_ = errno_text("cannot open image", path_);
        return Status::kIoError;
    }
    record_.clear();
    journal::encode(++sequence_, static_cast<std::uint32_t>(offset), data, record_);
    if (!pwrite_all(journal_fd.get(), record_, 0) || !sync_data(journal_fd.get())) {
        failed_ = true;
        last_error_ = errno_text("cannot write journal", journal_path_);
        return Status::kIoError;
    }
    if (!pwrite_all(image_fd.get(), data, offset) || !sync_data(image_fd.get())) {
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
