#pragma once
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace dp::cli {

/// One progress report: `done` of `total` units (total 0: unbounded, e.g. a time budget).
struct ProgressState {
    const char* unit = "pass";  ///< what is counted: "pass", "rows"
    int64_t done = 0;
    int64_t total = 0;
    double budget_s = 0;        ///< > 0: time-limited; the bar and ETA follow the clock
    const char* rate_name = nullptr;  ///< e.g. "photons/s"; null: no rate shown
    double rate = 0;
    double estimated_error = -1;  ///< relative error left, as the renderer estimates it; < 0: unknown
};

/// Progress on stderr. On a terminal, one bar redrawn in place with '\r' (at most ten times a
/// second); otherwise plain lines that log files keep readable:
///   pass 3/16  photons/s 1.2e6  est. error 2.1%  elapsed 2.1s  eta 9.0s
/// Safe to call from several threads.
class Progress {
public:
    /// `plain_step`: in plain mode, print a line only when the completed fraction has grown by
    /// this much since the last one (0: every update). The last update is always printed.
    explicit Progress(double plain_step = 0);
    ~Progress();

    void update(const ProgressState& state);
    /// Ends the bar's line (terminal mode) so later output starts on a fresh line.
    void finish();
    /// Seconds since construction.
    double elapsed() const;

private:
    std::string format(const ProgressState& s, double elapsed) const;

    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_;
    bool tty_ = false;
    bool drawn_ = false;
    double plain_step_ = 0;
    double last_fraction_ = -1;
    double last_draw_s_ = -1;
};

}  // namespace dp::cli
