// The interactive session: the latest request wins, an edit is answered by a quick pass laid over
// the refined picture only where it can change it, refinement stops on budget or once clean,
// failures name the file. No window: the session is the core's.
#include <gtest/gtest.h>

#include <condition_variable>
#include <filesystem>
#include <mutex>
#include <thread>
#include <unistd.h>

#include "common/test_scenes.h"
#include "image/image_io.h"
#include "render/interactive_session.h"

using namespace dp;
using namespace dp::test;
namespace fs = std::filesystem;

namespace {

class Recorder : public ViewSink {
public:
    void on_frame(std::shared_ptr<RenderFrame> f) override {
        std::lock_guard<std::mutex> lock(m_);
        frames.push_back(std::move(f));
        cv_.notify_all();
    }
    void on_stopped(uint64_t generation, bool finished, const std::string& error) override {
        std::lock_guard<std::mutex> lock(m_);
        stops.push_back({generation, finished, error});
        cv_.notify_all();
    }
    /// Polls `done` (at most a minute), for what the sink is not told about.
    template <class F>
    static bool poll(F&& done) {
        for (int i = 0; i < 6000; ++i) {
            if (done()) return true;
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        return false;
    }
    /// Waits (at most a minute) until `done` holds, under the lock.
    template <class F>
    bool wait(F&& done) {
        std::unique_lock<std::mutex> lock(m_);
        return cv_.wait_for(lock, std::chrono::seconds(60), [&] { return done(); });
    }
    bool stopped(uint64_t generation) {
        return wait([&] {
            for (const Stop& s : stops)
                if (s.generation == generation) return true;
            return false;
        });
    }
    std::shared_ptr<RenderFrame> first_of(uint64_t generation) {
        std::shared_ptr<RenderFrame> found;
        wait([&] {
            for (const auto& f : frames)
                if (f->generation == generation) return bool(found = f);
            return false;
        });
        return found;
    }
    std::shared_ptr<RenderFrame> last_of(uint64_t generation) {
        std::lock_guard<std::mutex> lock(m_);
        for (auto it = frames.rbegin(); it != frames.rend(); ++it)
            if ((*it)->generation == generation) return *it;
        return nullptr;
    }
    struct Stop {
        uint64_t generation;
        bool finished;
        std::string error;
    };
    std::mutex m_;
    std::condition_variable cv_;
    std::vector<std::shared_ptr<RenderFrame>> frames;
    std::vector<Stop> stops;
};

class InteractiveSessionTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("dp_session_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
                std::to_string(::getpid()));
        fs::create_directories(dir_);
        SunProbe sun;
        Image probe = sun.image();
        for (size_t i = 0; i < probe.size(); ++i) probe[i] += vec3(0.3f);  // sky: soft shadows too
        project_ = look_at_project(vec3(0, 2.5f, 4), vec3(0, 0.4f, 0), 45);
        project_.real.push_back(ground_plane(vec3(0.5f)));
        project_.objects.push_back(sphere(vec3(-0.6f, 0.4f, 0), 0.4f, diffuse(vec3(0.6f))));
        const Image photo(96, 64, vec3(0.4f));
        save_exr((dir_ / "photo.exr").string(), {{"", &photo}});
        save_exr((dir_ / "probe.exr").string(), {{"", &probe}});
        project_.base_dir = dir_;
        project_.photo.path = "photo.exr";
        project_.probe.path = "probe.exr";
        project_.render = settings(20000, 1);
        project_.render.passes = 3;
        project_.render.threads = 2;
    }
    void TearDown() override {
        session_.reset();
        fs::remove_all(dir_);
    }
    InteractiveSession& session() {
        if (!session_) session_ = std::make_unique<InteractiveSession>(std::make_unique<SceneBuilder>(), &sink_);
        return *session_;
    }
    ViewRequest request(const Project& p, bool interactive = false) {
        ViewRequest r;
        r.project = p;
        r.generation = ++generation_;
        r.interactive = interactive;
        r.preview_scale = 0.5;
        return r;
    }
    /// Renders `p` to its budget; returns the generation.
    uint64_t refine(const Project& p) {
        ViewRequest r = request(p);
        session().reset(r);
        EXPECT_TRUE(sink_.stopped(r.generation));
        return r.generation;
    }
    Project moved(float x) const {
        Project p = project_;
        p.objects[0].transform.translation.x = x;
        return p;
    }

    fs::path dir_;
    Project project_;
    Recorder sink_;
    std::unique_ptr<InteractiveSession> session_;
    uint64_t generation_ = 0;
};

}  // namespace

TEST_F(InteractiveSessionTest, AnswersWithAQuickPassThenRefinesToTheBudgetAndSleeps) {
    const uint64_t g = refine(project_);
    std::vector<std::shared_ptr<RenderFrame>> frames;
    {
        std::lock_guard<std::mutex> lock(sink_.m_);
        frames = sink_.frames;
        ASSERT_EQ(sink_.stops.size(), 1u);
        EXPECT_TRUE(sink_.stops[0].finished);
        EXPECT_EQ(sink_.stops[0].error, "");
    }
    ASSERT_GE(frames.size(), 2u);
    EXPECT_TRUE(frames.front()->preview);
    EXPECT_LT(frames.front()->update.image.width(), 96);  // reduced size
    EXPECT_FALSE(frames.back()->preview);
    EXPECT_EQ(frames.back()->update.image.width(), 96);
    EXPECT_EQ(frames.back()->update.stats.passes, 3);
    EXPECT_TRUE(frames.back()->update.finished);
    for (const auto& f : frames) EXPECT_EQ(f->generation, g);
    EXPECT_TRUE(Recorder::poll([&] { return session().idle(); }));
}

TEST_F(InteractiveSessionTest, AnEditIsLaidOverTheRefinedPictureOnlyWhereItCanChangeIt) {
    refine(project_);
    std::shared_ptr<RenderFrame> base = sink_.last_of(generation_);
    // A quick pass and a drag frame of the moved object: both keep every pixel the move
    // cannot change to the bit, and replace where the object was and where it is now.
    for (bool interactive : {false, true}) {
        ASSERT_TRUE(base && !base->preview && !base->composited());
        ViewRequest r = request(moved(interactive ? 0.9f : 0.6f), interactive);
        session().reset(r);
        const std::shared_ptr<RenderFrame> f = sink_.first_of(r.generation);
        ASSERT_TRUE(f);
        EXPECT_TRUE(f->preview);
        ASSERT_TRUE(f->composited()) << "interactive " << interactive;
        EXPECT_EQ(f->base_generation, base->generation);
        const Image& shown = f->image();
        ASSERT_EQ(shown.width(), base->update.image.width());
        size_t kept = 0, replaced = 0;
        for (size_t i = 0; i < shown.size(); ++i) {
            if ((*f->shown_from_edit)[i]) {
                ++replaced;
                continue;
            }
            ++kept;
            ASSERT_EQ(shown[i], base->update.image[i]) << "pixel " << i;
        }
        EXPECT_GT(kept, shown.size() / 4);
        EXPECT_GT(replaced, 100u);
        // Where the object was (left) and where it is now (right) are both the edit's.
        auto edit_at = [&](const vec3& p) {
            const Camera cam = project_.camera.build(96, 64);
            vec2 px;
            EXPECT_TRUE(cam.project(p, px));
            return (*f->shown_from_edit)[size_t(px.y) * 96 + size_t(px.x)] != 0;
        };
        EXPECT_TRUE(edit_at(vec3(interactive ? 0.6f : -0.6f, 0.4f, 0)));
        EXPECT_TRUE(edit_at(vec3(interactive ? 0.9f : 0.6f, 0.4f, 0)));
        if (interactive) continue;
        ASSERT_TRUE(sink_.stopped(r.generation));
        base = sink_.last_of(r.generation);  // the refined picture the drag is laid over
    }
}

TEST_F(InteractiveSessionTest, TheLatestRequestWinsAndStopDeliversNothingMore) {
    Project slow = project_;
    slow.render.passes = 1000;
    ViewRequest a = request(slow);
    session().reset(a);
    ASSERT_TRUE(sink_.first_of(a.generation));
    ViewRequest b = request(moved(0.5f));
    session().reset(b);
    EXPECT_TRUE(sink_.stopped(b.generation));
    {
        std::lock_guard<std::mutex> lock(sink_.m_);
        for (const auto& s : sink_.stops) EXPECT_NE(s.generation, a.generation);  // replaced, not finished
        // Nothing of the replaced request after the new one's first frame.
        bool seen_b = false;
        for (const auto& f : sink_.frames) {
            seen_b |= f->generation == b.generation;
            if (seen_b) {
                EXPECT_EQ(f->generation, b.generation);
            }
        }
    }
    ViewRequest c = request(slow);
    session().reset(c);
    ASSERT_TRUE(sink_.first_of(c.generation));
    session().stop();
    ASSERT_TRUE(Recorder::poll([&] { return session().idle(); }));
    size_t count;
    {
        std::lock_guard<std::mutex> lock(sink_.m_);
        count = sink_.frames.size();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    std::lock_guard<std::mutex> lock(sink_.m_);
    EXPECT_EQ(sink_.frames.size(), count);
    for (const auto& s : sink_.stops) EXPECT_NE(s.generation, c.generation);
}

TEST_F(InteractiveSessionTest, EndlessRefinementStopsOnceCleanAndSaysSo) {
    session().scheduler().set_noise_target(0.5);  // reached within the first passes
    ViewRequest r = request(project_);
    r.endless = true;
    session().reset(r);
    ASSERT_TRUE(sink_.stopped(r.generation));
    const auto last = sink_.last_of(r.generation);
    ASSERT_TRUE(last);
    EXPECT_TRUE(last->update.finished);
    EXPECT_GE(last->update.stats.passes, RenderScheduler::kMinPassesBeforeStop);
    EXPECT_LE(last->update.stats.estimated_rel_error, 0.5);
    std::lock_guard<std::mutex> lock(sink_.m_);
    EXPECT_TRUE(sink_.stops.back().finished);
}

TEST_F(InteractiveSessionTest, AMaterialEditBuildsNoSceneAndAMoveDoes) {
    refine(project_);
    const int built = session().scenes_built();
    Project red = project_;
    red.objects[0].material.albedo.rgb = vec3(0.8f, 0.1f, 0.1f);
    refine(red);
    EXPECT_EQ(session().scenes_built(), built);
    refine(moved(0.3f));
    EXPECT_GT(session().scenes_built(), built);
}

TEST_F(InteractiveSessionTest, AfterForgetPictureNothingIsLaidOverTheOldPicture) {
    refine(project_);
    session().forget_picture();
    ViewRequest r = request(moved(0.6f));
    session().reset(r);
    const auto f = sink_.first_of(r.generation);
    ASSERT_TRUE(f);
    EXPECT_FALSE(f->composited());
}

TEST_F(InteractiveSessionTest, AMissingFileFailsTheRequestNamingIt) {
    Project p = project_;
    p.photo.path = "gone.exr";
    ViewRequest r = request(p);
    session().reset(r);
    ASSERT_TRUE(sink_.stopped(r.generation));
    std::lock_guard<std::mutex> lock(sink_.m_);
    EXPECT_FALSE(sink_.stops.back().finished);
    EXPECT_NE(sink_.stops.back().error.find("gone.exr"), std::string::npos) << sink_.stops.back().error;
    EXPECT_TRUE(sink_.frames.empty());
}

TEST_F(InteractiveSessionTest, AMaterialStrokeShowsTheObjectAtFullSizeRenderingOnlyItsRegion) {
    refine(project_);
    const std::shared_ptr<RenderFrame> base = sink_.last_of(generation_);
    Project red = project_;
    red.objects[0].material.albedo.rgb = vec3(0.8f, 0.1f, 0.1f);
    ViewRequest r = request(red, true);
    session().reset(r);
    const auto f = sink_.first_of(r.generation);
    ASSERT_TRUE(f);
    ASSERT_TRUE(f->composited());
    // Rendered at the full 96 x 64, not at the drag's reduced size, and only around the object.
    EXPECT_EQ(f->update.image.width(), 96);
    EXPECT_GT(f->update.stats.pixels_gathered, 0u);
    EXPECT_LT(f->update.stats.pixels_gathered, size_t(96 * 64) / 2);
    // The ball is red in the shown picture, and the picture away from it is the refined one.
    const Camera cam = project_.camera.build(96, 64);
    vec2 px;
    ASSERT_TRUE(cam.project(vec3(-0.6f, 0.4f, 0.4f), px));  // the ball's front
    const vec3 c = f->image()[size_t(px.y) * 96 + size_t(px.x)];
    EXPECT_GT(c.x, 2.0f * c.y) << c.x << " " << c.y;
    size_t kept = 0;
    for (size_t i = 0; i < f->image().size(); ++i) kept += !(*f->shown_from_edit)[i] && f->image()[i] == base->image()[i];
    EXPECT_GT(kept, f->image().size() / 4);
}

TEST_F(InteractiveSessionTest, TheViewerCanEndAnEndlessRefinementAsClean) {
    session().scheduler().set_noise_target(1e-9);  // never reached by the renderer's own estimate
    ViewRequest r = request(project_);
    r.endless = true;
    session().reset(r);
    ASSERT_TRUE(sink_.wait([&] { return sink_.frames.size() >= 3; }));
    session().finish_clean(r.generation);
    ASSERT_TRUE(sink_.stopped(r.generation));
    std::lock_guard<std::mutex> lock(sink_.m_);
    EXPECT_TRUE(sink_.stops.back().finished);
    EXPECT_TRUE(sink_.frames.back()->update.finished);
}
