// Persistent, crash-safe image of one memory space: a raw file of exactly the space's size plus a
// one-record write-ahead journal beside it ("<image>.journal"). See docs/persistence.md.
//
// Why a journal and not write-new-file + rename: a rename rewrites the whole image for every
// 64-byte write (megabytes for big spaces) and needs a directory fsync; the journal costs two small
// writes and two fdatasync() calls whatever the image size. Protocol of write():
//   1. write the record (magic, sequence, offset, length, data, CRC-32) at journal offset 0,
//      fdatasync(journal)                      -- from here the write survives a crash;
//   2. pwrite the data into the image, fdatasync(image);
//   3. only then return (the caller acknowledges).
// The journal always holds the latest write, so replaying it is idempotent and it never needs to
// be cleared; a torn record (kill or power loss during step 1) fails its CRC and is discarded,
// leaving the previous value, which step 2 of the previous write had already made durable.
// Fresh images are written by base::write_file (a new file under a fresh random name, fsynced,
// renamed, the directory fsynced).
//
// Descriptors: every image this process has open in one directory shares one descriptor of that
// directory, which holds the flock keeping a second process out of all of them; the image and
// its journal are open only inside open() and write(). A node (one directory) costs one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace olcb::memory {

/// How ImageFile::open() found the journal.
enum class JournalState : std::uint8_t {
    kEmpty,           ///< no record
    kAlreadyApplied,  ///< a valid record whose bytes the image already held
    kReplayed,        ///< a valid record not yet in the image: applied now
    kDiscarded,       ///< a torn or invalid record: ignored, image unchanged
};

class ImageFile;
class DirectoryLease;  // image_file.cpp: an image's share of its directory's lock

/// Outcome of ImageFile::open().
struct ImageOpenResult {
    std::unique_ptr<ImageFile> image;  ///< null on error
    std::string error;                 ///< why opening failed ("" on success)
    bool created = false;              ///< a fresh image was made with the initialiser
    JournalState journal = JournalState::kEmpty;
    /// True when the image is open.
    bool ok() const { return image != nullptr; }
};

/// The persistent image of one space, held in memory and mirrored on disk. Not thread-safe: the
/// crash-safety argument needs each write() to finish before the next starts.
class ImageFile {
public:
    /// Fills a fresh image (all zeros on entry) with its factory content.
    using Initialiser = std::function<void(std::span<std::uint8_t> image)>;

    /// Outcome of write().
    enum class Status : std::uint8_t { kOk, kOutOfBounds, kIoError };

    /// Opens path (its directory must exist), replaying the journal, or creates it with size
    /// bytes filled by init (zeros when init is empty). An existing image of another size, one
    /// open already in this process, or any image in a directory another process has images
    /// open in, is refused ("... is in use ...").
    static ImageOpenResult open(const std::filesystem::path& path, std::size_t size,
                                const Initialiser& init = {});

    ~ImageFile();
    ImageFile(const ImageFile&) = delete;
    ImageFile& operator=(const ImageFile&) = delete;

    /// Size of the image in bytes.
    std::size_t size() const { return bytes_.size(); }
    /// Current content (what a reopen would show).
    std::span<const std::uint8_t> bytes() const { return bytes_; }
    /// Path of the image file.
    const std::filesystem::path& path() const { return path_; }
    /// Path of its journal.
    const std::filesystem::path& journal_path() const { return journal_path_; }

    /// Stores data at offset atomically and durably (see the header comment); all or nothing.
    /// After an I/O error the image refuses further writes (its disk state is uncertain); when
    /// its files cannot even be opened (EMFILE) only this write fails, nothing on disk changed.
    Status write(std::size_t offset, std::span<const std::uint8_t> data);
    /// Rewrites the whole image with init's content (factory reset), atomically.
    Status reinitialise(const Initialiser& init);
    /// Description of the last I/O error ("" when none).
    const std::string& last_error() const { return last_error_; }

private:
    ImageFile(std::filesystem::path path, std::unique_ptr<DirectoryLease> lease,
              std::vector<std::uint8_t> bytes, std::uint64_t sequence);

    std::filesystem::path path_;
    std::filesystem::path journal_path_;
    std::unique_ptr<DirectoryLease> lease_;
    std::vector<std::uint8_t> bytes_;
    std::vector<std::uint8_t> record_;  // reused so a write does not allocate
    std::uint64_t sequence_ = 0;
    bool failed_ = false;
    std::string last_error_;
};

/// The journal record format (little-endian), public so tools and tests can craft records.
namespace journal {
inline constexpr std::uint32_t kMagic = 0x314A4C4F;  ///< "OLJ1" as bytes in the file
inline constexpr std::size_t kHeaderSize = 20;       ///< magic, sequence(8), offset(4), length(4)
inline constexpr std::size_t kTrailerSize = 4;       ///< CRC-32 of header + data

/// One decoded journal record.
struct Record {
    std::uint64_t sequence = 0;
    std::uint32_t offset = 0;
    std::vector<std::uint8_t> data;
    friend bool operator==(const Record&, const Record&) = default;
};

/// CRC-32 (IEEE 802.3, reflected, as zlib computes it).
std::uint32_t crc32(std::span<const std::uint8_t> bytes);

/// Appends the encoded record to out.
void encode(std::uint64_t sequence, std::uint32_t offset, std::span<const std::uint8_t> data,
            std::vector<std::uint8_t>& out);

/// Decodes the record at the start of bytes when it is complete, its CRC matches and it fits an
/// image of image_size bytes; nullopt for a torn, foreign or empty journal.
std::optional<Record> decode(std::span<const std::uint8_t> bytes, std::size_t image_size);
}  // namespace journal

}  // namespace olcb::memory
