// The render session: progressive images reach the sink; cancel and reset take effect.
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <vector>

#include "base/error.h"
#include "render/session.h"
#include "common/test_scenes.h"

using namespace dp;
using namespace dp::test;

namespace {

class RecordingSink : public RenderSink {
public:
    void on_update(const RenderUpdate& u) override {
        std::lock_guard<std::mutex> lock(m_);
        passes_.push_back(u.stats.passes);
        finished_.push_back(u.finished);
        RenderUpdate copy = u;
        copy.pull_images();
        last_size_ = copy.image.size();
        cv_.notify_all();
    }
    void on_stopped(bool cancelled, const std::string& error) override {
        std::lock_guard<std::mutex> lock(m_);
        stopped_ = true;
        cancelled_ = cancelled;
        error_ = error;
        cv_.notify_all();
    }
    void wait_for_passes(size_t n) {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [&] { return passes_.size() >= n || stopped_; });
    }
    std::mutex m_;
    std::condition_variable cv_;
    std::vector<int> passes_;
    std::vector<bool> finished_;
    size_t last_size_ = 0;
    bool stopped_ = false, cancelled_ = false;
    std::string error_;
};

std::shared_ptr<RenderScene> small_scene() {
    SunProbe sun;
    Project p = look_at_project(vec3(0, 3, 4), vec3(0, 0.5f, 0), 45);
    p.real.push_back(ground_plane(vec3(0.5f)));
    p.objects.push_back(sphere(vec3(0, 0.5f, 0), 0.5f, diffuse(vec3(0.5f))));
    return build(p, Image(48, 32, vec3(0.2f)), sun.image());
}

RenderSettings budget(int passes) {
    RenderSettings s = settings(20000, 1);
    s.passes = passes;
    return s;
}

}  // namespace

TEST(RenderSession, HandsOneImagePerPassToTheSinkAndFinishesOnBudget) {
    RecordingSink sink;
    RenderSession session(&sink);
    session.start(small_scene(), budget(3));
    session.wait();
    ASSERT_EQ(sink.passes_, (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(sink.finished_.back(), true);
    EXPECT_EQ(sink.finished_.front(), false);
    EXPECT_EQ(sink.last_size_, 48u * 32u);
    EXPECT_TRUE(sink.stopped_);
    EXPECT_FALSE(sink.cancelled_);
    EXPECT_TRUE(sink.error_.empty());
}

TEST(RenderSession, CancelStopsALongRunEarly) {
    RecordingSink sink;
    RenderSession session(&sink);
    session.start(small_scene(), budget(100000));
    sink.wait_for_passes(1);
    session.cancel();
    session.wait();
    EXPECT_TRUE(sink.stopped_);
    EXPECT_TRUE(sink.cancelled_);
    EXPECT_LT(sink.passes_.size(), 100000u);
    EXPECT_FALSE(session.running());
}

TEST(RenderSession, ResetRestartsRefinementFromTheFirstPass) {
    RecordingSink sink;
    RenderSession session(&sink);
    session.start(small_scene(), budget(100000));
    sink.wait_for_passes(3);
    session.reset(small_scene(), budget(2));
    session.wait();
    // After the reset the pass counter starts again at 1 and runs to the new budget.
    ASSERT_GE(sink.passes_.size(), 5u);
    EXPECT_EQ(sink.passes_[sink.passes_.size() - 2], 1);
    EXPECT_EQ(sink.passes_.back(), 2);
    EXPECT_TRUE(sink.finished_.back());
}

namespace {

/// Records whether any update came with images it did not ask for.
class CountingSink : public RenderSink {
public:
    void on_update(const RenderUpdate& u) override {
        ++updates;
        if (u.has_images()) ++with_images;
        if (u.finished) {
            RenderUpdate last = u;
            last.pull_images();
            final_pixels = last.image.size();
        }
    }
    std::atomic<int> updates{0}, with_images{0};
    std::atomic<size_t> final_pixels{0};
};

}  // namespace

TEST(RenderSession, BuildsNoImageForASinkThatPullsOnlyTheLastPass) {
    CountingSink sink;
    RenderSession session(&sink);
    session.start(small_scene(), budget(4));
    session.wait();
    EXPECT_EQ(sink.updates.load(), 4);
    EXPECT_EQ(sink.with_images.load(), 0);  // a pass's images exist only when pulled
    EXPECT_EQ(sink.final_pixels.load(), 48u * 32u);
}

TEST(RenderSession, KeepsTheFailureByKindForTheCaller) {
    // The CLI reports out of memory as such (not as "render failed: std::bad_alloc").
    RecordingSink sink;
    RenderSession session(&sink);
    session.set_renderer_factory([](std::shared_ptr<const RenderScene>, const RenderSettings&) -> std::unique_ptr<PassRenderer> {
        throw OutOfMemory("the photon map");
    });
    session.start(small_scene(), budget(1));
    session.wait();
    EXPECT_FALSE(sink.error_.empty());
    ASSERT_TRUE(session.failure());
    EXPECT_THROW(std::rethrow_exception(session.failure()), std::bad_alloc);

    session.set_renderer_factory(nullptr);
    session.start(small_scene(), budget(1));
    session.wait();
    EXPECT_FALSE(session.failure());  // a later run that succeeds clears it
}
