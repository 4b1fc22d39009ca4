#include "base/file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <system_error>
#include <utility>

#include "base/descriptor.hpp"

namespace olcb::base {

namespace {

std::optional<std::string> fail(const std::filesystem::path& path, int err, std::string& error) {
    error = "cannot read " + path.string() + ": " + std::strerror(err);
    return std::nullopt;
}

namespace fs = std::filesystem;

// Random names colliding this often in a row are being planted, not met by chance.
constexpr int kTempAttempts = 16;
// Base-36 characters of a temporary name: 36^8, about 2.8e12 names.
constexpr int kTempSuffixLength = 8;

bool fail_open(const fs::path& path, int err, std::string& error) {
    error = "cannot open " + path.string() + " for writing: " + std::strerror(err);
    return false;
}

bool fail_write(const fs::path& path, int err, std::string& error) {
    error = "cannot write " + path.string() + ": " + std::strerror(err);
    return false;
}

std::string random_suffix() {
    std::uint64_t bits = 0;
    if (::getrandom(&bits, sizeof bits, 0) != static_cast<ssize_t>(sizeof bits)) {
        // No getrandom (a kernel before 3.17): the clock. O_EXCL keeps a guessed name harmless;
        // randomness only keeps a planted name from blocking the write.
        bits = static_cast<std::uint64_t>(
                   std::chrono::steady_clock::now().time_since_epoch().count()) ^
               (static_cast<std::uint64_t>(::getpid()) << 32);
    }
    constexpr char kDigits[] = "0123456789abcdefghijklmnopqrstuvwxyz";
    std::string out;
    for (int i = 0; i < kTempSuffixLength; ++i) {
        out += kDigits[bits % 36];
        bits /= 36;
    }
    return out;
}

bool write_all(int fd, std::string_view bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = EIO;
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    return true;
}

// /dev/stdout, /dev/fd/N and /proc/self/fd/N reach a file the process has open through /proc:
// renaming over such a name would replace the link (root may write /dev), not write the output.
bool through_proc(const fs::path& path) {
    std::error_code ec;
    const fs::path dir = fs::canonical(path.has_parent_path() ? path.parent_path() : ".", ec);
    if (!ec && dir.string().starts_with("/proc/")) return true;
    const fs::path target = fs::read_symlink(path, ec);
    return !ec && target.string().starts_with("/proc/");
}

// A FIFO, device or socket (a pipe, /dev/null, a terminal) has no content to replace, and
// renaming a file over it would take it away from whoever else uses it.
bool is_stream(const fs::path& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0) return false;  // missing: created
    if (S_ISDIR(info.st_mode)) return false;             // the rename says "Is a directory"
    return !S_ISREG(info.st_mode) || through_proc(path);
}

bool write_in_place(const fs::path& path, std::string_view bytes, std::string& error) {
    // No O_CREAT: it exists, and nothing is created here.
    Descriptor fd(::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC));
    if (fd.get() < 0) return fail_open(path, errno, error);
    if (!write_all(fd.get(), bytes) || fd.close() != 0) return fail_write(path, errno, error);
    return true;
}

// A new file beside `path` under a fresh name; -1 with `error` set when none could be made.
int create_temp(const fs::path& path, std::string& temp, std::string& error) {
    int err = EEXIST;
    for (int attempt = 0; attempt < kTempAttempts && err == EEXIST; ++attempt) {
        temp = path.string() + ".tmp-" + random_suffix();
        // O_EXCL: never an existing file or link; O_NOFOLLOW says the same for links, twice.
        const int fd =
            ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd >= 0) return fd;
        err = errno;
    }
    fail_open(path, err, error);
    return -1;
}

// Removes the temporary file on every way out but success; it is ours, created exclusively.
class TempFile {
public:
    explicit TempFile(std::string path) : path_(std::move(path)) {}
    ~TempFile() {
        if (!path_.empty()) ::unlink(path_.c_str());
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    void keep() { path_.clear(); }

private:
    std::string path_;
};

bool sync_directory(const fs::path& path) {
    const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
    const Descriptor fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (fd.get() < 0) return false;
    // Some file systems cannot sync a directory (EINVAL); the file itself is synced then.
    return ::fsync(fd.get()) == 0 || errno == EINVAL;
}

bool replace_file(const fs::path& path, std::string_view bytes, std::string& error) {
    std::string temp;
    Descriptor fd(create_temp(path, temp, error));
    if (fd.get() < 0) return false;
    TempFile owned(temp);
    if (!write_all(fd.get(), bytes) || ::fsync(fd.get()) != 0 || fd.close() != 0)
        return fail_write(path, errno, error);
    // rename() replaces a link at `path` itself, never its target.
    if (::rename(temp.c_str(), path.c_str()) != 0) return fail_write(path, errno, error);
    owned.keep();
    // Until its directory is synced, a crash may bring back the old file or none.
    if (!sync_directory(path)) return fail_write(path, errno, error);
    return true;
}

}  // namespace

std::optional<std::string> read_file(const std::filesystem::path& path, std::string& error) {
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) return fail(path, errno, error);
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) return fail(path, errno, error);
    // A directory opens but cannot be read; say so instead of returning nothing.
    if (S_ISDIR(info.st_mode)) return fail(path, EISDIR, error);
    std::string bytes;
    if (S_ISREG(info.st_mode) && info.st_size > 0)
        bytes.reserve(static_cast<std::size_t>(info.st_size));
    char chunk[65536];
    for (;;) {
        const ssize_t got = ::read(fd.get(), chunk, sizeof chunk);
        if (got < 0) {
            if (errno == EINTR) continue;
            return fail(path, errno, error);
        }
        if (got == 0) break;
        bytes.append(chunk, static_cast<std::size_t>(got));
    }
    return bytes;
}

bool write_file(const std::filesystem::path& path, std::string_view bytes, std::string& error) {
    return is_stream(path) ? write_in_place(path, bytes, error) : replace_file(path, bytes, error);
}

}  // namespace olcb::base
