// GrabCut mattes: an occluder cut out of the photo from a rectangle drawn loosely around it.
#include <gtest/gtest.h>

#include "base/rng.h"
#include "reconstruction/holdout_matte.h"

using namespace dp;

namespace {

/// A photo of a mottled green-grey wall with a reddish board (with its own mottle) in front of
/// it; `board` gets 1 where the board is.
Image board_photo(int W, int H, std::vector<uint8_t>& board) {
    Image photo(W, H);
    board.assign(size_t(W) * H, 0);
    Rng rng(3, 4);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            // A board with a slanted left edge, so the cut must follow more than the rectangle.
            const bool in = y > H / 4 && y < 3 * H / 4 && x > W / 3 + (y - H / 4) / 3 && x < 3 * W / 4;
            board[size_t(y) * W + x] = in;
            const float n = 0.08f * (rng.uniform() - 0.5f);
            photo.at(x, y) = in ? vec3(0.45f + n, 0.12f + n, 0.08f) : vec3(0.18f + n, 0.25f + n, 0.2f + n);
        }
    return photo;
}

double iou(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
    size_t both = 0, either = 0;
    for (size_t i = 0; i < a.size(); ++i) both += a[i] && b[i], either += a[i] || b[i];
    return either ? double(both) / double(either) : 1.0;
}

}  // namespace

TEST(HoldoutMatte, ACutFromALooseRectangleFollowsTheBoardsEdges) {
    const int W = 160, H = 120;
    std::vector<uint8_t> board;
    const Image photo = board_photo(W, H, board);
    // A rectangle a few pixels loose all round the board.
    const auto labels = matte_labels_from_rect(W, H, W / 3 - 6, H / 4 - 6, 3 * W / 4 + 6, 3 * H / 4 + 6);
    const std::vector<uint8_t> cut = grabcut_matte(photo, labels);
    std::vector<uint8_t> rect(labels.size());
    for (size_t i = 0; i < labels.size(); ++i) rect[i] = labels[i] == MatteLabel::ProbablyOccluder;
    // Check: the cut matches the board far better than the rectangle it started from.
    EXPECT_GT(iou(cut, board), 0.97);
    EXPECT_LT(iou(rect, board), 0.8);
}

TEST(HoldoutMatte, AReducedCutIsScaledBackAndKeepsWhatWasMarkedSure) {
    const int W = 320, H = 240;
    std::vector<uint8_t> board;
    const Image photo = board_photo(W, H, board);
    auto labels = matte_labels_from_rect(W, H, W / 3 - 10, H / 4 - 10, 3 * W / 4 + 10, 3 * H / 4 + 10);
    // A stroke marked surely background across the board's middle row stays background.
    for (int x = 0; x < W; ++x) labels[size_t(H / 2) * W + x] = MatteLabel::Background;
    const std::vector<uint8_t> cut = grabcut_matte(photo, labels, 20000);  // cut at about a quarter
    EXPECT_GT(iou(cut, board), 0.9);
    for (int x = 0; x < W; ++x) ASSERT_EQ(cut[size_t(H / 2) * W + x], 0) << x;
}

TEST(HoldoutMatte, LabelsWithoutAnOccluderOrABackgroundAreRefused) {
    const Image photo(8, 8, vec3(0.5f));
    EXPECT_THROW(grabcut_matte(photo, matte_labels_from_rect(8, 8, 0, 0, 0, 0)), std::invalid_argument);
    EXPECT_THROW(grabcut_matte(photo, matte_labels_from_rect(8, 8, -5, -5, 20, 20)), std::invalid_argument);
    EXPECT_THROW(grabcut_matte(photo, std::vector<MatteLabel>(10, MatteLabel::Occluder)), std::invalid_argument);
}
