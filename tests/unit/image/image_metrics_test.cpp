#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "image/image_metrics.h"

using namespace dp;

TEST(ImageMetrics, AConstantOffsetGivesThatRmseAndItsRatioToTheMeanLuminance) {
    Image truth(4, 3, vec3(2.0f)), a(4, 3, vec3(2.1f));
    ImageError e = image_error(a, truth);
    EXPECT_NEAR(e.rmse, 0.1, 1e-6);
    EXPECT_NEAR(e.rel_rmse, 0.05, 1e-6);
    EXPECT_EQ(e.pixels, 12u);
}

TEST(ImageMetrics, TheMaskRestrictsThePixelsCompared) {
    Image truth(2, 1, vec3(1.0f)), a(2, 1, vec3(1.0f));
    a[1] = vec3(3.0f);
    EXPECT_NEAR(image_error(a, truth, {true, false}).rmse, 0.0, 1e-12);
    ImageError e = image_error(a, truth, {false, true});
    EXPECT_NEAR(e.rmse, 2.0, 1e-6);
    EXPECT_EQ(e.pixels, 1u);
    EXPECT_EQ(image_error(a, truth, {false, false}).pixels, 0u);
}

TEST(ImageMetrics, ANonFinitePixelIsAnInfiniteError) {
    Image truth(2, 2, vec3(1.0f)), a = truth;
    a[3].y = std::numeric_limits<float>::quiet_NaN();
    EXPECT_TRUE(std::isinf(image_error(a, truth).rmse));
}

TEST(ImageMetrics, ChangedPixelsAreThoseSeenThroughObjectsOrChangedByMoreThanTheThreshold) {
    Image photo(4, 1, vec3(1.0f)), truth = photo, alpha(4, 1);
    truth[1] = vec3(0.995f);  // below 1%
    truth[2] = vec3(0.9f);    // a shadow
    alpha[3] = vec3(0.25f);   // partly covered by an object
    std::vector<bool> m = changed_pixels(photo, truth, alpha);
    EXPECT_EQ(m, (std::vector<bool>{false, false, true, true}));
}

TEST(ImageMetrics, SizeMismatchesAreRejected) {
    EXPECT_THROW(image_error(Image(2, 2), Image(2, 3)), std::invalid_argument);
    EXPECT_THROW(mean_image(Image(2, 2), Image(3, 2)), std::invalid_argument);
}
