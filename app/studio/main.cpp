// `diffphoton-studio`: the desktop app. Besides the window, `--screenshot` renders a project
// and saves a picture of the real window (used for the documentation).
#include <QAction>
#include <QApplication>
#include <QCommandLineParser>
#include <QDockWidget>
#include <QElapsedTimer>
#include <QTimer>
#include <cstdio>

#include "document.h"
#include "error_reporter.h"
#include "main_window.h"
#include "render_controller.h"
#include "viewport.h"

using namespace dp::ui;

namespace {

/// Waits (processing events) until the latest request finished refining or `ms` passed.
void wait_for_render(MainWindow& w, int ms) {
    QElapsedTimer t;
    t.start();
    while (!w.renderer()->finished() && t.elapsed() < ms)
        QApplication::processEvents(QEventLoop::AllEvents, 50);
}

}  // namespace

int main(int argc, char** argv) {
    QApplication app(argc, argv);
    QApplication::setOrganizationName("diffphoton");
    QApplication::setApplicationName("studio");
    QApplication::setApplicationVersion("0.1.0");

    QCommandLineParser cli;
    cli.setApplicationDescription(
        "Place virtual objects into a photograph and watch them settle in.");
    cli.addHelpOption();
    cli.addVersionOption();
    cli.addPositionalArgument("project", "Project file to open");
    QCommandLineOption shot("screenshot", "Render, save a picture of the window to <png>, quit.",
                            "png");
    QCommandLineOption view("view", "With --screenshot: photo, augmented or dl.", "mode",
                            "augmented");
    QCommandLineOption select("select", "With --screenshot: select object <index>.", "index", "-1");
    QCommandLineOption size("size", "Window size WxH.", "size", "1400x860");
    QCommandLineOption raise(
        "raise",
        "With --screenshot: bring a dock to the front (renderDock, probeDock, cameraDock).",
        "dock");
    QCommandLineOption exposure("exposure", "Display exposure in stops.", "stops");
    QCommandLineOption wait("wait", "With --screenshot: longest wait for the render (ms).", "ms",
                            "60000");
    QCommandLineOption overlays("overlays", "Show the overlays (grid, proxies, outlines).");
    cli.addOptions({shot, view, select, size, raise, exposure, wait, overlays});
    cli.process(app);

    StudioOptions options;
    RecordingReporter quiet(false);
    const bool screenshot = cli.isSet(shot);
    if (screenshot) {
        options.reporter = &quiet;
        options.checkRecovery = false;
        options.useSettings = false;
    }
    MainWindow window(options);
    const QStringList wh = cli.value(size).split('x');
    if (wh.size() == 2) window.resize(wh[0].toInt(), wh[1].toInt());
    window.show();
    if (!cli.positionalArguments().isEmpty()) window.openProject(cli.positionalArguments().first());
    // The project's own display exposure unless the command line gives one.
    if (cli.isSet(exposure)) window.setDisplayExposure(cli.value(exposure).toFloat());
    if (cli.isSet(overlays)) window.setOverlaysVisible(true);
    if (!screenshot) {
        QTimer::singleShot(0, &window, [&window] { window.checkRecovery(); });
        return app.exec();
    }
    const QString mode = cli.value(view).toLower();
    // Through the toolbar's actions, so the picture shows the matching button pressed.
    window.action(mode == "photo" ? "viewPhoto"
                  : mode == "dl"  ? "viewdL"
                                  : "viewAugmented")
        ->trigger();
    window.document()->select(cli.value(select).toInt());
    if (auto* dock = window.findChild<QDockWidget*>(cli.value(raise))) dock->raise();
    wait_for_render(window, cli.value(wait).toInt());
    // With the denoised view on (the default), the picture an artist sees once the render
    // settles is the denoised one: wait for it too.
    QElapsedTimer denoiseWait;
    denoiseWait.start();
    while (mode != "photo" && mode != "dl" && window.viewport()->denoise() && !window.viewport()->showingDenoised() &&
           denoiseWait.elapsed() < cli.value(wait).toInt())
        QApplication::processEvents(QEventLoop::AllEvents, 50);
    QApplication::processEvents();
    const bool ok = window.grab().save(cli.value(shot));
    for (const QString& e : quiet.errors) std::fprintf(stderr, "error: %s\n", qPrintable(e));
    std::printf("%s %s\n", ok ? "wrote" : "cannot write", qPrintable(cli.value(shot)));
    window.document()->undoStack()->setClean();
    return ok && quiet.errors.isEmpty() ? 0 : 1;
}
