#include "util/file_io.h"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <random>
#include <stdexcept>
#include <system_error>

namespace streak {

namespace {

// A name beside the target, so the final rename stays within one file system.
std::string tempPathFor(const std::string& path) {
    static const unsigned processTag = std::random_device{}();
    static std::atomic<unsigned> counter{0};
    char suffix[32];
    std::snprintf(suffix, sizeof(suffix), ".tmp-%08x-%x", processTag, counter++);
    return path + suffix;
}

}  // namespace

std::string errnoReason(int err) { return std::error_code(err, std::generic_category()).message(); }

void writeFileAtomically(const std::string& path, std::span<const char> bytes) {
    const std::string temp = tempPathFor(path);
    std::FILE* file = std::fopen(temp.c_str(), "wbx");  // x: never clobber another writer's temp
    if (!file) throw std::runtime_error(errnoReason(errno));

    int err = 0;
    if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) err = errno ? errno : EIO;
    if (std::fclose(file) != 0 && err == 0) err = errno ? errno : EIO;
    if (err != 0) {
        std::remove(temp.c_str());
        throw std::runtime_error(errnoReason(err));
    }

    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) {
        std::remove(temp.c_str());
        throw std::runtime_error(ec.message());
    }
}

}  // namespace streak
