#include "memory/image_file.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace olcb::memory {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint8_t> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path& path, std::span<const std::uint8_t> bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<long>(bytes.size()));
}

std::vector<std::uint8_t> filled(std::size_t size, std::uint8_t value) {
    return std::vector<std::uint8_t>(size, value);
}

class ImageFileTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = ::testing::TempDir() + "olcb_image_XXXXXX";
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        dir_ = pattern;
        path_ = dir_ / "space_fd.img";
    }
    void TearDown() override { fs::remove_all(dir_); }

    static void factory(std::span<std::uint8_t> image) {
        for (std::size_t i = 0; i < image.size(); ++i) image[i] = static_cast<std::uint8_t>(i);
    }

    ImageOpenResult open(std::size_t size = 256) { return ImageFile::open(path_, size, factory); }

    // Files in the directory whose names start "<image>.tmp".
    int temp_files() const {
        int n = 0;
        for (const auto& entry : fs::directory_iterator(dir_)) {
            if (entry.path().filename().string().starts_with("space_fd.img.tmp")) ++n;
        }
        return n;
    }

    // Creates the image with one write of value at offset 16 (8 bytes), then closes it.
    void prepare(std::uint8_t value) {
        ImageOpenResult result = open();
        ASSERT_TRUE(result.ok()) << result.error;
        ASSERT_EQ(result.image->write(16, filled(8, value)), ImageFile::Status::kOk);
    }

    std::vector<std::uint8_t> record(std::uint64_t sequence, std::uint32_t offset,
                                     std::span<const std::uint8_t> data) {
        std::vector<std::uint8_t> out;
        journal::encode(sequence, offset, data, out);
        return out;
    }

    fs::path dir_;
    fs::path path_;
};

TEST(Journal, Crc32CheckValue) {
    const std::string_view check = "123456789";
    EXPECT_EQ(journal::crc32(
                  std::span(reinterpret_cast<const std::uint8_t*>(check.data()), check.size())),
              0xCBF43926u);
    EXPECT_EQ(journal::crc32({}), 0u);
}

TEST(Journal, GoldenRecord) {
    std::vector<std::uint8_t> out;
    const std::array<std::uint8_t, 1> data{0xAA};
    journal::encode(1, 0x10, data, out);
    const std::vector<std::uint8_t> expected{0x4F, 0x4C, 0x4A, 0x31,  // "OLJ1"
                                             0x01, 0x00, 0x00, 0x00,
                                             0x00, 0x00, 0x00, 0x00,   // sequence 1
                                             0x10, 0x00, 0x00, 0x00,   // offset 0x10
                                             0x01, 0x00, 0x00, 0x00,   // length 1
                                             0xAA,                     // data
                                             0x48, 0xD5, 0x91, 0x93};  // CRC-32 0x9391D548
    EXPECT_EQ(out, expected);
    const auto decoded = journal::decode(out, 0x11);
    ASSERT_TRUE(decoded.has_value());
    EXPECT_EQ(*decoded, (journal::Record{1, 0x10, {0xAA}}));
}

TEST(Journal, DecodeRejectsTornForeignAndOutOfBounds) {
    std::vector<std::uint8_t> out;
    journal::encode(7, 4, std::vector<std::uint8_t>(10, 0x55), out);
    for (std::size_t cut = 0; cut < out.size(); ++cut) {
        EXPECT_FALSE(journal::decode(std::span(out).first(cut), 64).has_value()) << cut;
    }
    EXPECT_TRUE(journal::decode(out, 14).has_value());
    EXPECT_FALSE(journal::decode(out, 13).has_value());  // would not fit the image
    for (std::size_t i = 0; i < out.size(); ++i) {
        std::vector<std::uint8_t> flipped = out;
        flipped[i] ^= 0x01;
        EXPECT_FALSE(journal::decode(flipped, 64).has_value()) << i;
    }
    // Trailing bytes of an older, longer record do not matter.
    std::vector<std::uint8_t> longer = out;
    longer.insert(longer.end(), 30, 0x77);
    EXPECT_TRUE(journal::decode(longer, 64).has_value());
    // A huge length field does not make decode read or allocate beyond the input.
    std::vector<std::uint8_t> huge = out;
    huge[16] = huge[17] = huge[18] = huge[19] = 0xFF;
    EXPECT_FALSE(journal::decode(huge, 0xFFFFFFFF).has_value());
}

TEST_F(ImageFileTest, FreshImageUsesInitialiser) {
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_TRUE(result.created);
    EXPECT_EQ(result.journal, JournalState::kEmpty);
    EXPECT_EQ(result.image->size(), 256u);
    EXPECT_EQ(result.image->bytes()[200], 200);
    EXPECT_EQ(result.image->path(), path_);
    const auto on_disk = read_file(path_);
    ASSERT_EQ(on_disk.size(), 256u);
    EXPECT_EQ(on_disk[200], 200);
    EXPECT_TRUE(fs::exists(result.image->journal_path()));
    EXPECT_FALSE(fs::exists(dir_ / "space_fd.img.tmp"));
}

TEST_F(ImageFileTest, FreshImageWithoutInitialiserIsZero) {
    ImageOpenResult result = ImageFile::open(path_, 32);
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(read_file(path_), filled(32, 0));
}

TEST_F(ImageFileTest, WriteIsOnDiskAndReadsBack) {
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    ImageFile& image = *result.image;
    ASSERT_EQ(image.write(100, filled(64, 0xA5)), ImageFile::Status::kOk);
    EXPECT_EQ(image.bytes()[100], 0xA5);
    EXPECT_EQ(image.bytes()[163], 0xA5);
    EXPECT_EQ(image.bytes()[164], 164);
    const auto on_disk = read_file(path_);
    EXPECT_EQ(on_disk[163], 0xA5);
    EXPECT_EQ(on_disk[99], 99);
    EXPECT_TRUE(image.last_error().empty());
}

TEST_F(ImageFileTest, OutOfBoundsWriteChangesNothing) {
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    ImageFile& image = *result.image;
    EXPECT_EQ(image.write(250, filled(7, 1)), ImageFile::Status::kOutOfBounds);
    EXPECT_EQ(image.write(257, filled(1, 1)), ImageFile::Status::kOutOfBounds);
    EXPECT_EQ(image.write(std::numeric_limits<std::size_t>::max(), filled(2, 1)),
              ImageFile::Status::kOutOfBounds);
    EXPECT_EQ(image.write(250, filled(6, 1)), ImageFile::Status::kOk);
    EXPECT_EQ(read_file(path_)[249], 249);
}

TEST_F(ImageFileTest, ReopenKeepsWrites) {
    prepare(0x11);
    ImageOpenResult again = open();
    ASSERT_TRUE(again.ok()) << again.error;
    EXPECT_FALSE(again.created);
    EXPECT_EQ(again.journal, JournalState::kAlreadyApplied);
    EXPECT_EQ(again.image->bytes()[16], 0x11);
    EXPECT_EQ(again.image->bytes()[23], 0x11);
    EXPECT_EQ(again.image->bytes()[24], 24);
    // Writing on continues the journal.
    ASSERT_EQ(again.image->write(0, filled(1, 0xEE)), ImageFile::Status::kOk);
    again.image.reset();
    EXPECT_EQ(open().image->bytes()[0], 0xEE);
}

TEST_F(ImageFileTest, TornJournalRecordIsDiscarded) {
    prepare(0x11);
    const auto complete = record(99, 16, filled(8, 0x22));
    // Cut anywhere: inside the header, inside the data, inside the CRC.
    for (const std::size_t cut :
         {std::size_t{3}, std::size_t{15}, std::size_t{20}, std::size_t{24}, complete.size() - 1}) {
        SCOPED_TRACE(cut);
        write_file(path_.string() + ".journal", std::span(complete).first(cut));
        ImageOpenResult result = open();
        ASSERT_TRUE(result.ok()) << result.error;
        EXPECT_EQ(result.journal, JournalState::kDiscarded);
        EXPECT_EQ(result.image->bytes()[16], 0x11);
        EXPECT_EQ(result.image->bytes()[23], 0x11);
        EXPECT_EQ(read_file(path_)[16], 0x11);
    }
}

TEST_F(ImageFileTest, TornRecordOverAnOlderLongerRecordIsDiscarded) {
    prepare(0x11);
    // The new, shorter record only partly overwrote the old one: the bytes mix.
    auto old_record = record(5, 16, filled(8, 0x11));
    const auto new_record = record(6, 16, filled(2, 0x33));
    std::copy(new_record.begin(), new_record.begin() + 22, old_record.begin());
    write_file(path_.string() + ".journal", old_record);
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(result.journal, JournalState::kDiscarded);
    EXPECT_EQ(result.image->bytes()[16], 0x11);
}

TEST_F(ImageFileTest, CompleteUnappliedRecordIsReplayed) {
    prepare(0x11);
    write_file(path_.string() + ".journal", record(99, 16, filled(8, 0x22)));
    {
        ImageOpenResult result = open();
        ASSERT_TRUE(result.ok()) << result.error;
        EXPECT_EQ(result.journal, JournalState::kReplayed);
        EXPECT_EQ(result.image->bytes()[16], 0x22);
        EXPECT_EQ(result.image->bytes()[24], 24);
        EXPECT_EQ(read_file(path_)[23], 0x22);  // applied to the file, not only in memory
    }
    ImageOpenResult again = open();
    ASSERT_TRUE(again.ok()) << again.error;
    EXPECT_EQ(again.journal, JournalState::kAlreadyApplied);
    EXPECT_EQ(again.image->bytes()[16], 0x22);
}

TEST_F(ImageFileTest, RecordNotFittingTheImageIsDiscarded) {
    prepare(0x11);
    write_file(path_.string() + ".journal", record(99, 250, filled(8, 0x22)));
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(result.journal, JournalState::kDiscarded);
    EXPECT_EQ(result.image->bytes()[250], 250);
}

TEST_F(ImageFileTest, StaleJournalWithoutImageIsIgnored) {
    prepare(0x11);
    fs::remove(path_);
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_TRUE(result.created);
    EXPECT_EQ(result.image->bytes()[16], 16);
    result.image.reset();
    ImageOpenResult again = open();
    EXPECT_EQ(again.journal, JournalState::kEmpty);
    EXPECT_EQ(again.image->bytes()[16], 16);
}

TEST_F(ImageFileTest, LeftoverTempFileFromCrashedCreationIsRemoved) {
    const fs::path leftover = path_.string() + ".tmp-crashed0";
    write_file(leftover, filled(3, 0x99));
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(read_file(path_).size(), 256u);
    EXPECT_FALSE(fs::exists(leftover));
    EXPECT_EQ(temp_files(), 0);
}

// A link planted where older versions wrote their fixed temporary file is neither followed nor
// removed: creation writes a file of its own under a fresh name.
TEST_F(ImageFileTest, LinkAtTheOldTempNameIsNotFollowed) {
    const fs::path target = dir_ / "target";
    write_file(target, filled(5, 0x5A));
    const fs::path link = path_.string() + ".tmp";
    fs::create_symlink(target, link);
    ImageOpenResult result = open();
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(read_file(path_).size(), 256u);
    EXPECT_EQ(read_file(target), filled(5, 0x5A));
    EXPECT_TRUE(fs::is_symlink(link));
    EXPECT_EQ(temp_files(), 1);  // the link itself
}

TEST_F(ImageFileTest, WrongSizeIsRefused) {
    prepare(0x11);
    ImageOpenResult result = open(512);
    EXPECT_FALSE(result.ok());
    EXPECT_NE(result.error.find("has 256 bytes, expected 512"), std::string::npos) << result.error;
}

TEST_F(ImageFileTest, MissingDirectoryIsAnError) {
    ImageOpenResult result = ImageFile::open(dir_ / "nope" / "x.img", 16);
    EXPECT_FALSE(result.ok());
    EXPECT_NE(result.error.find("nope"), std::string::npos) << result.error;
}

TEST_F(ImageFileTest, DirectoryInPlaceOfImageIsAnError) {
    fs::create_directory(path_);
    ImageOpenResult result = open();
    EXPECT_FALSE(result.ok());
    EXPECT_FALSE(result.error.empty());
}

TEST_F(ImageFileTest, SecondOpenWhileInUseIsRefused) {
    ImageOpenResult first = open();
    ASSERT_TRUE(first.ok()) << first.error;
    ImageOpenResult second = open();
    EXPECT_FALSE(second.ok());
    EXPECT_NE(second.error.find("in use"), std::string::npos) << second.error;
    first.image.reset();
    EXPECT_TRUE(open().ok());
}

int open_descriptors() {
    return static_cast<int>(
        std::distance(fs::directory_iterator("/proc/self/fd"), fs::directory_iterator()));
}

// A node's images share one descriptor, its directory's; files are open only while written.
TEST_F(ImageFileTest, ImagesOfOneDirectoryHoldOneDescriptor) {
    const int before = open_descriptors();
    std::vector<std::unique_ptr<ImageFile>> images;
    for (const char* name : {"a.img", "b.img", "c.img"}) {
        ImageOpenResult result = ImageFile::open(dir_ / name, 64);
        ASSERT_TRUE(result.ok()) << result.error;
        images.push_back(std::move(result.image));
    }
    EXPECT_EQ(open_descriptors(), before + 1);
    for (auto& image : images) ASSERT_EQ(image->write(1, filled(2, 7)), ImageFile::Status::kOk);
    EXPECT_EQ(open_descriptors(), before + 1);
    images.clear();
    EXPECT_EQ(open_descriptors(), before);
}

// The lock is the directory's: another process cannot open any image in it, this one can open
// its other images.
TEST_F(ImageFileTest, OtherProcessIsRefusedTheDirectory) {
    int ready[2];
    int done[2];
    ASSERT_EQ(::pipe(ready), 0);
    ASSERT_EQ(::pipe(done), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        ImageOpenResult held = ImageFile::open(dir_ / "other.img", 16);
        const char c = held.ok() ? 'y' : 'n';
        if (::write(ready[1], &c, 1) != 1) ::_exit(2);
        char ignored = 0;
        if (::read(done[0], &ignored, 1) < 0) ::_exit(3);
        ::_exit(0);
    }
    char c = 0;
    ASSERT_EQ(::read(ready[0], &c, 1), 1);
    EXPECT_EQ(c, 'y');
    ImageOpenResult refused = open();
    EXPECT_FALSE(refused.ok());
    EXPECT_NE(refused.error.find("in use by another process"), std::string::npos) << refused.error;
    ASSERT_EQ(::write(done[1], "x", 1), 1);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    for (const int fd : {ready[0], ready[1], done[0], done[1]}) ::close(fd);
    EXPECT_TRUE(open().ok());
}

// The child: fills every descriptor the limit allows, writes (which must fail alone), frees two
// and writes again (which must work). Its exit status names the step that went wrong.
[[noreturn]] void write_without_descriptors(const fs::path& path) {
    ImageOpenResult result = ImageFile::open(path, 64);
    if (!result.ok()) ::_exit(2);
    const rlimit limit{64, 64};
    if (::setrlimit(RLIMIT_NOFILE, &limit) != 0) ::_exit(3);
    std::vector<int> spare;
    for (int fd = 0; (fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC)) >= 0;) spare.push_back(fd);
    if (spare.size() < 2) ::_exit(4);
    const std::vector<std::uint8_t> value(4, 0x42);
    if (result.image->write(8, value) != ImageFile::Status::kIoError) ::_exit(5);
    if (result.image->last_error().find("Too many open files") == std::string::npos) ::_exit(6);
    if (result.image->bytes()[8] == 0x42) ::_exit(7);
    ::close(spare.back());
    ::close(spare[spare.size() - 2]);
    if (result.image->write(8, value) != ImageFile::Status::kOk) ::_exit(8);
    ::_exit(0);
}

TEST_F(ImageFileTest, WriteWithoutDescriptorsFailsAloneAndLaterWritesWork) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) write_without_descriptors(path_);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status)) << status;
    EXPECT_EQ(WEXITSTATUS(status), 0);
    ImageOpenResult result = ImageFile::open(path_, 64);
    ASSERT_TRUE(result.ok()) << result.error;
    EXPECT_EQ(result.image->bytes()[11], 0x42);
}

TEST_F(ImageFileTest, ReinitialiseRestoresFactoryContent) {
    prepare(0x11);
    {
        ImageOpenResult result = open();
        ASSERT_TRUE(result.ok()) << result.error;
        ASSERT_EQ(result.image->reinitialise(factory), ImageFile::Status::kOk);
        EXPECT_EQ(result.image->bytes()[16], 16);
    }
    ImageOpenResult again = open();
    ASSERT_TRUE(again.ok()) << again.error;
    EXPECT_EQ(again.image->bytes()[16], 16);
    EXPECT_EQ(read_file(path_)[17], 17);
}

// The SIGKILL test: a child writes a stream of values and acknowledges each on a pipe once
// write() returned; the parent kills it with SIGKILL at a random point and checks every
// acknowledged value survived and no slot holds a torn (mixed) value.
constexpr std::size_t kSlots = 16;
constexpr std::size_t kSlotSize = 64;
constexpr std::size_t kImageSize = 4096;
constexpr std::uint64_t kMaxWrites = 100000;

std::size_t slot_offset(std::size_t slot) {
    return slot * (kImageSize / kSlots);
}

// The child: writes sequence numbers 1, 2, ... (each repeated over a whole slot) round the slots,
// acknowledging each on ack_fd; its exit status says what failed.
[[noreturn]] void write_and_acknowledge(const fs::path& path, int ack_fd) {
    ImageOpenResult result = ImageFile::open(path, kImageSize);
    if (!result.ok()) ::_exit(2);
    std::array<std::uint8_t, kSlotSize> value{};
    for (std::uint64_t seq = 1; seq <= kMaxWrites; ++seq) {
        for (std::size_t i = 0; i < kSlotSize; i += 8) std::memcpy(&value[i], &seq, 8);
        const std::size_t slot = seq % kSlots;
        if (result.image->write(slot_offset(slot), value) != ImageFile::Status::kOk) ::_exit(3);
        if (::write(ack_fd, &seq, sizeof seq) != sizeof seq) ::_exit(4);
    }
    ::_exit(0);
}

struct Acknowledged {
    std::map<std::size_t, std::uint64_t> acked;  // slot -> last acknowledged sequence
    std::uint64_t last = 0;
};

// Reads the child's acknowledgements until the pipe closes, killing it after kill_after.
Acknowledged read_acks_killing_at(int ack_fd, pid_t child, std::uint64_t kill_after) {
    Acknowledged acks;
    std::uint64_t seq = 0;
    bool killed = false;
    while (::read(ack_fd, &seq, sizeof seq) == sizeof seq) {
        acks.acked[seq % kSlots] = seq;
        acks.last = seq;
        if (!killed && seq >= kill_after) {
            ::kill(child, SIGKILL);
            killed = true;
        }
    }
    return acks;
}

// Every slot holds one whole value: the acknowledged one or the one write in flight when killed.
void check_slots(const fs::path& path, const Acknowledged& acks) {
    ImageOpenResult result = ImageFile::open(path, kImageSize);
    ASSERT_TRUE(result.ok()) << result.error;
    for (std::size_t slot = 0; slot < kSlots; ++slot) {
        const auto bytes = result.image->bytes().subspan(slot_offset(slot), 64);
        std::uint64_t value = 0;
        std::memcpy(&value, bytes.data(), 8);
        for (std::size_t i = 8; i < kSlotSize; i += 8) {
            std::uint64_t word = 0;
            std::memcpy(&word, bytes.data() + i, 8);
            ASSERT_EQ(word, value) << "torn value in slot " << slot;
        }
        const std::uint64_t expected = acks.acked.count(slot) ? acks.acked.at(slot) : 0;
        EXPECT_TRUE(value == expected || (value == acks.last + 1 && value % kSlots == slot))
            << "slot " << slot << " holds " << value << ", acknowledged " << expected;
    }
}

TEST_F(ImageFileTest, SurvivesSigkillDuringWrites) {
    constexpr int kRounds = 20;
    const unsigned seed = std::random_device{}();
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);

    for (int round = 0; round < kRounds; ++round) {
        SCOPED_TRACE("round " + std::to_string(round));
        fs::remove(path_);
        fs::remove(path_.string() + ".journal");
        int fds[2];
        ASSERT_EQ(::pipe(fds), 0);
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            ::close(fds[0]);
            write_and_acknowledge(path_, fds[1]);
        }
        ::close(fds[1]);
        const std::uint64_t kill_after = std::uniform_int_distribution<std::uint64_t>(1, 12)(rng);
        const Acknowledged acks = read_acks_killing_at(fds[0], child, kill_after);
        ::close(fds[0]);
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        ASSERT_TRUE(WIFSIGNALED(status)) << "child status " << status;
        ASSERT_GE(acks.last, kill_after);
        ASSERT_NO_FATAL_FAILURE(check_slots(path_, acks));
    }
}

}  // namespace
}  // namespace olcb::memory
