// Times ImageFile::write, 64-byte writes into a 4 KiB image in DIR (each one: journal record,
// image bytes, two fdatasync). Built by bench/image_write_compare.sh against two source trees'
// libraries, so one program measures before and after; not part of the CMake build.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "memory/image_file.hpp"

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: image_write DIR WRITES\n");
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    const int writes = std::stoi(argv[2]);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    constexpr std::size_t kImageSize = 4096;
    auto opened = olcb::memory::ImageFile::open(dir / "space-253.img", kImageSize);
    if (!opened.ok()) {
        std::fprintf(stderr, "image_write: %s\n", opened.error.c_str());
        return 1;
    }
    std::vector<std::uint8_t> data(64, 0);
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < writes; ++i) {
        data[0] = static_cast<std::uint8_t>(i);
        const auto offset = (static_cast<std::size_t>(i) * data.size()) % kImageSize;
        if (opened.image->write(offset, data) != olcb::memory::ImageFile::Status::kOk) {
            std::fprintf(stderr, "image_write: %s\n", opened.image->last_error().c_str());
            return 1;
        }
    }
    const std::chrono::duration<double, std::micro> took = std::chrono::steady_clock::now() - start;
    std::printf("%.1f us per write\n", took.count() / writes);
    return 0;
}
