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

// ---- temporary names near the file system's limit on one name ------------------------------

TEST(AtomicFileNames, AShortNameKeepsItsStemAndExtension) {
    EXPECT_EQ(temporary_file_name("render.exr", 255, 1234, 7), ".render.tmp-1234-7.exr");
    EXPECT_EQ(temporary_file_name("project.json", 255, 1, 0), ".project.tmp-1-0.json");
}

TEST(AtomicFileNames, NamesUpToTheLimitGetATemporaryWithinIt) {
    // 246 to 255 bytes: the plain tag (".", ".tmp-PID-N") would push each past 255.
    for (size_t length = 240; length <= 255; ++length) {
        const std::string name = std::string(length - 4, 'n') + ".exr";
        const std::string temp = temporary_file_name(name, 255, 4194304, 4294967295u);
        EXPECT_LE(temp.size(), 255u) << length;
        EXPECT_EQ(temp[0], '.') << "hidden";
        EXPECT_EQ(temp.substr(temp.size() - 4), ".exr") << "the encoder picks the format by it";
        EXPECT_NE(temp.find(".tmp-4194304-4294967295"), std::string::npos) << temp;
    }
}

TEST(AtomicFileNames, LongNamesAreHashedApart) {
    const std::string a = std::string(250, 'a') + ".exr", b = std::string(249, 'a') + "b.exr";
    const std::string ta = temporary_file_name(a, 255, 1, 0), tb = temporary_file_name(b, 255, 1, 0);
    EXPECT_NE(ta, tb);
    EXPECT_LT(ta.size(), 64u) << "the stem is replaced by its hash: " << ta;
    EXPECT_EQ(ta, temporary_file_name(a, 255, 1, 0)) << "the hash is the name's, not random";
    // Hashed only where the tag does not fit: a name one byte shorter than needed keeps its stem.
    const std::string fits = std::string(255 - 1 - 8 - 4, 'f') + ".exr";  // "." + stem + ".tmp-1-0" + ".exr"
    EXPECT_EQ(temporary_file_name(fits, 255, 1, 0), "." + fits.substr(0, fits.size() - 4) + ".tmp-1-0.exr");
    const std::string one_more = std::string(255 - 1 - 8 - 4 + 1, 'f') + ".exr";
    EXPECT_LT(temporary_file_name(one_more, 255, 1, 0).size(), 64u);
}

TEST(AtomicFileNames, AnExtensionTooLongForTheLimitIsDropped) {
    const std::string name = "a." + std::string(250, 'e');
    const std::string temp = temporary_file_name(name, 255, 99, 3);
    EXPECT_LE(temp.size(), 255u);
    EXPECT_EQ(temp.substr(temp.size() - 9), ".tmp-99-3");
}

TEST(AtomicFileNames, TheLimitComesFromTheFileSystem) {
    TempDir d;
    const size_t limit = file_name_limit(d.path.string());
    EXPECT_GE(limit, 14u);  // POSIX's least
    EXPECT_LE(limit, 4096u);
}

TEST(AtomicFileNames, FilesNamedUpToTheLimitAreWrittenAndReplaced) {
    TempDir d;
    const size_t limit = file_name_limit(d.path.string());
    for (size_t length = limit - 9; length <= limit; ++length) {
        const fs::path f = d.path / (std::string(length - 5, 'p') + ".json");
        ASSERT_NO_THROW(write_file_atomically(f.string(), "old")) << length;
        ASSERT_NO_THROW(write_file_atomically(f.string(), "new")) << length;
        EXPECT_EQ(read(f), "new");
    }
    EXPECT_EQ(d.entries(), 10u) << "no temporary file left behind";
}
