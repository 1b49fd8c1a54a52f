// The single-photo calibration methods on photographs rendered by the reference path tracer
// with a known camera: focal length within 1%, rotation within 0.5 degree, position within 1%
// of distance (the unit tests run the same checks on drawn photos).
#include <gtest/gtest.h>

#include "unit/calibration/single_photo_checks.h"

using namespace dp;
using namespace dp::test;

namespace {

const GroundBoard& board() {
    static const GroundBoard b;
    return b;
}

/// Two oblique views, 640x480 with a 600 px focal length, 8 samples per pixel.
const std::vector<BoardPhoto>& photos() {
    static const std::vector<BoardPhoto> p = board_photos(
        board(), {{1.0, 1.1, 1.1}, {1.2, 1.0, -0.6}}, 640, 480, 600.0,
        [](const GroundBoard& b, const CameraSpec& c, int w, int h) {
            return b.render(c, w, h, 8);
        });
    return p;
}

}  // namespace

TEST(PathTracedCalibration, OneChessboardPhotoRecoversThePoseAndTheFocalLength) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_chessboard_one_photo(board(), p);
    }
}

TEST(PathTracedCalibration, ARectangleRecoversTheCamera) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_rectangle(board(), p);
    }
}

TEST(PathTracedCalibration, VanishingLinesRecoverTheCamera) {
    for (const BoardPhoto& p : photos()) {
        SCOPED_TRACE(p.view.source);
        check_vanishing(board(), p);
    }
}
