#pragma once
// Shared set-up for the studio's Qt tests: a small copy of the sample project, window options
// that keep renders quick, and helpers to wait for the renderer and compare exports.
#include <QPointF>
#include <QString>
#include <QWidget>
#include <memory>

#include "error_reporter.h"
#include "image/image.h"
#include "main_window.h"

namespace dp::ui::test {

/// Writes a copy of the bundled sample project into `dir` with `photons` per pass and `passes`
/// passes (its photo path made absolute); returns the file's path.
QString write_small_sample(const QString& dir, int photons = 30000, int passes = 4);

/// Options for a test window: `width` x `height` renders, no settings, no recovery prompt.
StudioOptions test_options(ErrorReporter* reporter, const QString& recoveryDir, int width = 256,
                           int height = 128);

/// test_options with the recovery question on (StudioOptions::checkRecovery).
StudioOptions recovering_options(ErrorReporter* reporter, const QString& recoveryDir);

/// A left-button drag as a hand makes it: press at `from`, `moves` mouse moves along the line to
/// `to`, one every `msPerMove` milliseconds, release at `to`.
void drag(QWidget* widget, QPointF from, QPointF to, int moves, int msPerMove = 16);

/// Shows `w` at 1200x700, waits for its window, and opens `project`; false if either fails.
bool show_and_open(MainWindow& w, const QString& project);

/// Processes events until the latest request has finished refining; false on timeout.
bool wait_refined(MainWindow& w, int timeoutMs = 30000);

/// Exports through MainWindow::exportImage and waits for the file (an export right after an
/// edit waits for the edited state's pass); false if it failed or timed out.
bool export_and_wait(MainWindow& w, const QString& path, int timeoutMs = 30000);

/// Mean absolute luminance difference between two images over the pixels where `mask` is
/// `inside` (mask: non-zero bytes, one per pixel; empty means all pixels).
double mean_abs_diff(const Image& a, const Image& b, const std::vector<uint8_t>& mask = {},
                     bool inside = true);

}  // namespace dp::ui::test
