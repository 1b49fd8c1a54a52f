#pragma once
#include <QSize>
#include <QString>

namespace dp::ui {

class ErrorReporter;

/// How a studio window is set up; the defaults suit a person at a desktop, tests and the
/// screenshot tool change them.
struct StudioOptions {
    QString recoveryDir;             ///< autosave folder ("": the per-user application data folder)
    int autosaveMs = 30000;          ///< autosave interval
    QSize renderSize;                ///< full render size (invalid: the photo's size)
    double previewFraction = 0.125;  ///< photons of the quick pass relative to the project's
    double previewScale = 0.5;       ///< size of the quick pass relative to the full render
    /// Refine without a pass budget until the noise is below the target (the Render tab's
    /// "Stop at noise"); false: stop at the project's passes or time budget, as the CLI does.
    bool endless = true;
    /// The augmented view denoised (View > Denoise), where Open Image Denoise is installed.
    bool denoise = true;
    ErrorReporter* reporter = nullptr;  ///< not owned; null: message boxes
    bool checkRecovery = true;          ///< offer to recover autosaved work on start
    bool useSettings = true;            ///< restore and store window state and recent files
};

}  // namespace dp::ui
