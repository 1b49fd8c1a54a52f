#include "progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "common.h"

namespace dp::cli {

Progress::Progress(double plain_step)
    : start_(std::chrono::steady_clock::now()),
      tty_(::isatty(STDERR_FILENO) == 1),
      plain_step_(plain_step) {}

Progress::~Progress() { finish(); }

double Progress::elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::string Progress::format(const ProgressState& s, double elapsed) const {
    std::string line = std::string(s.unit) + " " + std::to_string(s.done);
    if (s.budget_s <= 0 && s.total > 0) line += "/" + std::to_string(s.total);
    if (s.rate_name) line += "  " + std::string(s.rate_name) + " " + sci(s.rate);
    if (s.estimated_error >= 0) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "  est. error %.2g%%", 100 * s.estimated_error);
        line += buf;
    }
    line += "  elapsed " + duration(elapsed);
    if (s.budget_s > 0) line += "/" + duration(s.budget_s);
    double eta = -1;
    if (s.budget_s > 0)
        eta = std::max(0.0, s.budget_s - elapsed);
    else if (s.total > 0 && s.done > 0)
        eta = elapsed / double(s.done) * double(s.total - s.done);
    line += "  eta " + (eta >= 0 ? duration(eta) : std::string("?"));
    return line;
}

void Progress::update(const ProgressState& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double t = elapsed();
    double fraction = 0;
    if (s.budget_s > 0)
        fraction = t / s.budget_s;
    else if (s.total > 0)
        fraction = double(s.done) / double(s.total);
    fraction = std::clamp(fraction, 0.0, 1.0);
    const bool last = s.total > 0 && s.done >= s.total;

    if (!tty_) {
        if (!last && plain_step_ > 0 && fraction < last_fraction_ + plain_step_) return;
        last_fraction_ = fraction;
        std::fprintf(stderr, "%s\n", format(s, t).c_str());
        return;
    }
    if (!last && last_draw_s_ >= 0 && t - last_draw_s_ < 0.1) return;
    last_draw_s_ = t;
    constexpr int kWidth = 24;
    const int filled = int(fraction * kWidth + 0.5);
    std::string bar = "[" + std::string(size_t(filled), '#') +
                      std::string(size_t(kWidth - filled), '-') + "] ";
    // "\033[K" clears what a longer previous line left behind.
    std::fprintf(stderr, "\r%s%s\033[K", bar.c_str(), format(s, t).c_str());
    std::fflush(stderr);
    drawn_ = true;
}

void Progress::finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (tty_ && drawn_) std::fputc('\n', stderr);
    drawn_ = false;
}

}  // namespace dp::cli
