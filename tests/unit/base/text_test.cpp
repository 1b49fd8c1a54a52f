// Text helpers for messages: suggestions, byte counts, shortened paths.
#include <gtest/gtest.h>

#include <string>

#include "base/error.h"
#include "base/text.h"

using namespace dp;

TEST(Text, ShortPathsAreQuotedWhole) {
    EXPECT_EQ(shorten_path("/home/me/photo.exr"), "/home/me/photo.exr");
    const std::string exact(kMaxPathInMessage, 'a');
    EXPECT_EQ(shorten_path(exact), exact);
}

TEST(Text, LongPathsKeepTheirStartAndEnd) {
    const std::string path = "/data/" + std::string(10000, 'x') + "/scene/photo.exr";
    const std::string s = shorten_path(path);
    EXPECT_LE(s.size(), kMaxPathInMessage);
    EXPECT_GE(s.size(), kMaxPathInMessage - 4);
    EXPECT_EQ(s.rfind("/data/", 0), 0u);
    EXPECT_NE(s.find("\u2026"), std::string::npos);
    EXPECT_EQ(s.substr(s.size() - 16), "/scene/photo.exr");
}

TEST(Text, CutsFallBetweenUtf8Characters) {
    std::string path;
    for (int i = 0; i < 300; ++i) path += "\u00e9";  // two bytes each
    const std::string s = shorten_middle(path, 101);
    EXPECT_LE(s.size(), 101u);
    // Every byte sequence is whole: the string is é...é…é...é.
    std::string rebuilt;
    for (size_t i = 0; i < s.size();) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        const size_t len = c < 0x80 ? 1 : c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
        ASSERT_LE(i + len, s.size());
        for (size_t k = 1; k < len; ++k) ASSERT_EQ(static_cast<unsigned char>(s[i + k]) & 0xC0, 0x80);
        i += len;
    }
}

TEST(Text, InputErrorsShortenTheFileTheyName) {
    const std::string path = "/" + std::string(200000, 'p') + "/photo.exr";
    const InputError e(path, "photo.path", "file not found");
    EXPECT_LT(std::string(e.what()).size(), kMaxPathInMessage + 100);
    EXPECT_NE(std::string(e.what()).find("photo.exr: field 'photo.path': file not found"), std::string::npos);
    EXPECT_EQ(e.file(), path);  // the full path stays for callers that need it
}

TEST(Text, FormatBytes) {
    EXPECT_EQ(format_bytes(3.2e6), "3.2 MB");
    EXPECT_EQ(format_bytes(21e9), "21.0 GB");
}
