#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace dp {

/// What a pixel is known to be before a matte is cut: OpenCV GrabCut's four labels.
enum class MatteLabel : uint8_t {
    Background = 0,          ///< surely not the occluder (outside the rectangle, a background stroke)
    Occluder = 1,            ///< surely the occluder (an occluder stroke)
    ProbablyBackground = 2,
    ProbablyOccluder = 3,    ///< inside the rectangle, until the cut says otherwise
};

/// Labels for a `width` x `height` photo from a rectangle drawn around the occluder: probably
/// the occluder inside [x0, x1) x [y0, y1) (clamped to the frame), surely background outside.
std::vector<MatteLabel> matte_labels_from_rect(int width, int height, int x0, int y0, int x1, int y1);

/// Cuts the occluder out of `photo` (linear, judged as sRGB, as people see it) by OpenCV's
/// GrabCut from `labels` (one per photo pixel; strokes already marked surely one or the other).
/// Photos over `max_pixels` are cut at a reduced size and the result scaled back (GrabCut's
/// time grows with the pixels). Returns one byte per pixel, 1 for the occluder. Throws std::invalid_argument
/// for labels of another size, or when the labels hold no possible occluder or no background.
std::vector<uint8_t> grabcut_matte(const Image& photo, const std::vector<MatteLabel>& labels,
                                   double max_pixels = 400000, int iterations = 5);

/// Writes a mask (one byte per pixel of a `width` x `height` frame, non-zero where the occluder
/// is) as a black-and-white PNG in the folder "<project stem>.holdouts" beside `project_file`,
/// named after the holdout `name` and the mask's content: each version of a mask keeps its own
/// file, so an undo finds the old one. Returns the path relative to the project's folder, as
/// holdouts[].mask takes it. Throws InputError naming the file when it cannot be written.
std::string save_holdout_mask(const std::vector<uint8_t>& covered, int width, int height,
                              const std::string& project_file, const std::string& name);

}  // namespace dp
