#include "base/atomic_file.h"
#include "base/text.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace dp {
namespace {

namespace fs = std::filesystem;

std::runtime_error file_error(const std::string& path, const std::string& what) {
    return std::runtime_error("cannot write '" + shorten_path(path) + "': " + what + " (" + std::strerror(errno) + ")");
}

/// FNV-1a, 64 bits: a short stand-in for a name too long to repeat in the temporary's.
uint64_t name_hash(const std::string& name) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : name) h = (h ^ c) * 0x100000001b3ull;
    return h;
}

/// A name no other writer uses: hidden, beside the target, the target's extension kept.
std::string temporary_name(const fs::path& target) {
    static std::atomic<unsigned> counter{0};
    fs::path folder = target.parent_path();
    const size_t limit = file_name_limit(folder.empty() ? "." : folder.string());
    const std::string name =
        temporary_file_name(target.filename().string(), limit, (unsigned long)::getpid(), counter++);
    return (folder / name).string();
}

void sync_file(const std::string& path, const std::string& target) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw file_error(target, "cannot reopen the temporary file");
    const bool ok = ::fsync(fd) == 0;
    ::close(fd);
    if (!ok) throw file_error(target, "cannot flush it to disk");
}

void sync_folder(const fs::path& folder) {
    // The rename is durable only once the folder's entry is; failure here loses nothing.
    const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    ::fsync(fd);
    ::close(fd);
}

/// The temporary paths being written, for remove_temporaries_in_flight: fixed slots a signal
/// handler can read without allocating or locking. A slot's path is complete while its state is
/// kInUse; a path longer than a slot, or a write beyond the slots, is simply not cleaned up.
constexpr int kSlots = 8;
constexpr size_t kSlotBytes = 4096;
enum SlotState : int { kFree, kFilling, kInUse };
std::atomic<int> slot_state[kSlots];
char slot_path[kSlots][kSlotBytes];
static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");

/// Registers `temp` while it lives; the destructor (the write done, renamed or failed) frees
/// the slot first, so the handler never removes a file that became the target.
class InFlight {
public:
    explicit InFlight(const std::string& temp) {
        if (temp.size() >= kSlotBytes) return;
        for (int i = 0; i < kSlots; ++i) {
            int expected = kFree;
            if (!slot_state[i].compare_exchange_strong(expected, kFilling)) continue;
            std::memcpy(slot_path[i], temp.c_str(), temp.size() + 1);
            slot_state[i].store(kInUse);
            slot_ = i;
            return;
        }
    }
    ~InFlight() { release(); }
    /// Before the rename: from then on the temporary name may be gone or be the target.
    void release() {
        if (slot_ >= 0) slot_state[slot_].store(kFree);
        slot_ = -1;
    }
    InFlight(const InFlight&) = delete;
    InFlight& operator=(const InFlight&) = delete;

private:
    int slot_ = -1;
};

}  // namespace

std::string temporary_file_name(const std::string& target_name, size_t name_max, unsigned long pid,
                                unsigned count) {
    const fs::path target(target_name);
    const std::string tag = ".tmp-" + std::to_string(pid) + "-" + std::to_string(count);
    const std::string stem = target.stem().string(), ext = target.extension().string();
    // The dot and the tag add 9 bytes and the digits of the process id and the count (up to 24
    // on Linux): a name near the limit (NAME_MAX, usually 255) would fail "File name too long".
    std::string name = "." + stem + tag + ext;
    if (name.size() <= name_max) return name;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)name_hash(target_name));
    name = "." + std::string(hex) + tag + ext;
    if (name.size() <= name_max) return name;
    return "." + std::string(hex) + tag;  // an extension of some 200 bytes: no encoder reads it
}

size_t file_name_limit(const std::string& folder) {
    errno = 0;
    const long from_pathconf = ::pathconf(folder.c_str(), _PC_NAME_MAX);
    if (from_pathconf > 0) return size_t(from_pathconf);
    struct statvfs vfs {};
    if (::statvfs(folder.c_str(), &vfs) == 0 && vfs.f_namemax > 0) return size_t(vfs.f_namemax);
    return 255;
}

void remove_temporaries_in_flight() noexcept {
    for (int i = 0; i < kSlots; ++i)
        if (slot_state[i].load() == kInUse) ::unlink(slot_path[i]);
}

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
    const fs::path target(path);
    const std::string temp = temporary_name(target);
    InFlight in_flight(temp);
    try {
        write(temp);
        sync_file(temp, path);
        in_flight.release();
        if (::rename(temp.c_str(), path.c_str()) != 0) throw file_error(path, "cannot replace it");
    } catch (...) {
        std::error_code ec;
        fs::remove(temp, ec);
        throw;
    }
    sync_folder(target.parent_path());
}

void write_file_atomically(const std::string& path, const std::string& bytes) {
    write_atomically(path, [&](const std::string& temp) {
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) throw file_error(path, "cannot create a temporary file beside it");
        size_t done = 0;
        while (done < bytes.size()) {
            const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) {
                ::close(fd);
                throw file_error(path, "writing failed");
            }
            done += size_t(n);
        }
        if (::close(fd) != 0) throw file_error(path, "writing failed");
    });
}

}  // namespace dp
