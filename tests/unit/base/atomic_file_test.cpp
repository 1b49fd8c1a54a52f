// Atomic writes: a file holds its old content or the complete new one, never a part.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include "base/atomic_file.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

struct TempDir {
    fs::path path;
    TempDir() {
        path = fs::temp_directory_path() / ("dp-atomic-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(reinterpret_cast<uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~TempDir() { fs::remove_all(path); }
    size_t entries() const { return size_t(std::distance(fs::directory_iterator(path), fs::directory_iterator())); }
};

std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(AtomicFile, ReplacesTheContentAndLeavesNoTemporaryFile) {
    TempDir d;
    const fs::path f = d.path / "out.json";
    write_file_atomically(f.string(), "old");
    write_file_atomically(f.string(), "new content");
    EXPECT_EQ(read(f), "new content");
    EXPECT_EQ(d.entries(), 1u);
}

TEST(AtomicFile, AWriterThatFailsLeavesTheOldFileWhole) {
    TempDir d;
    const fs::path f = d.path / "out.exr";
    write_file_atomically(f.string(), "the previous render");
    std::string temp_seen;
    EXPECT_THROW(write_atomically(f.string(),
                                  [&](const std::string& temp) {
                                      temp_seen = temp;
                                      std::ofstream(temp) << "half of a";
                                      throw std::runtime_error("disk full");
                                  }),
                 std::runtime_error);
    EXPECT_EQ(read(f), "the previous render");
    EXPECT_EQ(d.entries(), 1u);  // the temporary file is gone
    // Beside the target, with its extension (encoders pick the format by it).
    EXPECT_EQ(fs::path(temp_seen).parent_path(), d.path);
    EXPECT_EQ(fs::path(temp_seen).extension(), ".exr");
}

TEST(AtomicFile, ConcurrentWritersToOnePathEndWithOneCompleteFile) {
    TempDir d;
    const fs::path f = d.path / "shared.bin";
    std::vector<std::string> contents;
    for (int i = 0; i < 8; ++i) contents.push_back(std::string(size_t(200000 + i), char('a' + i)));
    std::vector<std::thread> writers;
    for (int i = 0; i < 8; ++i)
        writers.emplace_back([&, i] {
            for (int k = 0; k < 5; ++k) write_file_atomically(f.string(), contents[size_t(i)]);
        });
    for (std::thread& t : writers) t.join();
    const std::string got = read(f);
    bool one_of_them = false;
    for (const std::string& c : contents) one_of_them |= got == c;
    EXPECT_TRUE(one_of_them) << "a mixed or partial file of " << got.size() << " bytes";
    EXPECT_EQ(d.entries(), 1u);
}

TEST(AtomicFile, AMissingFolderIsAnErrorNamingTheFile) {
    TempDir d;
    const fs::path f = d.path / "no-such-folder" / "out.json";
    try {
        write_file_atomically(f.string(), "x");
        FAIL() << "expected an error";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
    }
}

TEST(AtomicFile, AnInterruptedWriteLosesOnlyItsTemporaryFile) {
    // What a second Ctrl-C does mid-write: the handler removes the temporaries in flight and
    // the process ends; here the write goes on and must fail without touching the target.
    TempDir d;
    const fs::path f = d.path / "out.exr";
    write_file_atomically(f.string(), "old");
    std::string temp_seen;
    EXPECT_THROW(write_atomically(f.string(),
                                  [&](const std::string& temp) {
                                      std::ofstream(temp) << "half of the new";
                                      temp_seen = temp;
                                      remove_temporaries_in_flight();
                                  }),
                 std::runtime_error);
    EXPECT_FALSE(temp_seen.empty());
    EXPECT_FALSE(fs::exists(temp_seen));
    EXPECT_EQ(read(f), "old");
    EXPECT_EQ(d.entries(), 1u);
}

TEST(AtomicFile, CleaningUpAfterAWriteLeavesTheNewFile) {
    TempDir d;
    const fs::path f = d.path / "out.txt";
    write_file_atomically(f.string(), "new");
    remove_temporaries_in_flight();  // nothing in flight: the finished file stays
    EXPECT_EQ(read(f), "new");
}
