// The cgroup memory limit, read from fake /proc/self/cgroup texts and cgroup folders.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/cgroup_memory.h"
#include "base/memory.h"

using namespace dp;
namespace fs = std::filesystem;

namespace {

constexpr uint64_t kGiB = uint64_t(1) << 30;

/// A folder standing for /sys/fs/cgroup, removed afterwards.
struct FakeMount {
    fs::path path;
    FakeMount() {
        path = fs::temp_directory_path() / ("dp-cgroup-" + std::to_string(::getpid()) + "-" +
                                            std::to_string(reinterpret_cast<uintptr_t>(this)));
        fs::create_directories(path);
    }
    ~FakeMount() { fs::remove_all(path); }
    /// Writes `text` to `relative` under the mount, making its folders.
    void write(const std::string& relative, const std::string& text) const {
        const fs::path file = path / relative;
        fs::create_directories(file.parent_path());
        std::ofstream(file) << text;
    }
};

}  // namespace

TEST(CgroupMemory, ParsesALimitFile) {
    EXPECT_EQ(parse_memory_limit("2147483648\n"), 2 * kGiB);
    EXPECT_EQ(parse_memory_limit(" 1024 "), 1024u);
    EXPECT_EQ(parse_memory_limit("max\n"), 0u);
    EXPECT_EQ(parse_memory_limit(""), 0u);
    EXPECT_EQ(parse_memory_limit("0"), 0u);
    EXPECT_EQ(parse_memory_limit("-5"), 0u);
    EXPECT_EQ(parse_memory_limit("12k"), 0u);
    EXPECT_EQ(parse_memory_limit("9223372036854771712\n"), 0u);  // v1's "no limit"
    EXPECT_EQ(parse_memory_limit("99999999999999999999999"), 0u);
}

TEST(CgroupMemory, V2TakesTheLowestLimitOfTheGroupAndThoseAboveIt) {
    FakeMount m;
    m.write("user.slice/memory.max", "1073741824\n");
    m.write("user.slice/job.scope/memory.max", "max\n");
    EXPECT_EQ(cgroup_memory_limit("0::/user.slice/job.scope\n", m.path), kGiB);
    m.write("user.slice/job.scope/memory.max", "536870912\n");
    EXPECT_EQ(cgroup_memory_limit("0::/user.slice/job.scope\n", m.path), kGiB / 2);
}

TEST(CgroupMemory, V2ContainerSeesItsGroupAsTheRoot) {
    FakeMount m;
    m.write("memory.max", "2147483648\n");
    EXPECT_EQ(cgroup_memory_limit("0::/\n", m.path), 2 * kGiB);
    // The host's path of the group, which the container's mount does not hold.
    EXPECT_EQ(cgroup_memory_limit("0::/system.slice/docker-1.scope\n", m.path), 2 * kGiB);
}

TEST(CgroupMemory, V1ReadsTheMemoryHierarchy) {
    FakeMount m;
    m.write("memory/docker/abc/memory.limit_in_bytes", "268435456\n");
    m.write("memory/memory.limit_in_bytes", "9223372036854771712\n");
    m.write("cpu/docker/abc/memory.limit_in_bytes", "1\n");  // not the memory controller's
    EXPECT_EQ(cgroup_memory_limit("4:cpu,cpuacct:/docker/abc\n3:memory:/docker/abc\n0::/\n", m.path),
              kGiB / 4);
    EXPECT_EQ(cgroup_memory_limit("3:cpuset,memory:/docker/abc\n", m.path), kGiB / 4);
}

TEST(CgroupMemory, NoLimitIsZero) {
    FakeMount m;
    m.write("memory.max", "max\n");
    m.write("memory/memory.limit_in_bytes", "9223372036854771712\n");
    EXPECT_EQ(cgroup_memory_limit("", m.path), 0u);
    EXPECT_EQ(cgroup_memory_limit("0::/\n", m.path), 0u);
    EXPECT_EQ(cgroup_memory_limit("4:memory:/process/1\n0::/\n", m.path), 0u);
    EXPECT_EQ(cgroup_memory_limit("0::/\n", m.path / "missing"), 0u);
    EXPECT_EQ(cgroup_memory_limit("garbage\n1:name=systemd:/\n", m.path), 0u);
}

TEST(CgroupMemory, APathLeavingTheMountIsNotFollowed) {
    FakeMount m;
    m.write("inside/memory.max", "4096\n");
    fs::create_directories(m.path / "inside" / "group");
    EXPECT_EQ(cgroup_memory_limit("0::/../inside\n", m.path / "inside" / "group"), 0u);
    // A ':' inside the path is part of it.
    m.write("inside/a:b/memory.max", "8192\n");
    EXPECT_EQ(cgroup_memory_limit("0::/a:b\n", m.path / "inside"), 4096u);
    m.write("inside/memory.max", "max\n");
    EXPECT_EQ(cgroup_memory_limit("0::/a:b\n", m.path / "inside"), 8192u);
}

TEST(CgroupMemory, UsableMemoryIsAtMostPhysicalMemory) {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    ASSERT_GT(pages, 0);
    EXPECT_GT(usable_memory_bytes(), 0u);
    EXPECT_LE(usable_memory_bytes(), uint64_t(pages) * uint64_t(page));
}
