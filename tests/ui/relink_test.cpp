// Files that have moved: the project opens with the Missing Files dialog, the render waits,
// locating one file finds the rest of its folder, and the relink is one undoable edit.
#include <QAction>
#include <QDialogButtonBox>
#include <QDir>
#include <QFile>
#include <QLabel>
#include <QPushButton>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTest>
#include <QToolButton>
#include <QUndoStack>

#include "document.h"
#include "image/image_io.h"
#include "missing_files_dialog.h"
#include "render_controller.h"
#include "scene/project_io.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class RelinkTest : public QObject {
    Q_OBJECT
  private Q_SLOTS:
    void init();
    void cleanup();
    void locatingThePhotoFindsTheProbeAndTheProjectRendersAsBeforeItMoved();
    void cancelLeavesTheProjectAsOpenedAndWaitingForItsFiles();
    void filesMovedIntoASubfolderAreFoundWithoutAsking();
    void aProbeDeletedWhileOpenStopsTheRenderAndOffersTheDialog();
    void aChosenPathThatIsNoFileChangesNothing();
    void anotherProjectOpenedReplacesTheDialogWithItsOwnFiles();

  private:
    /// Opens `project` in a new window (it lives until cleanup).
    MainWindow* open(const QString& project);
    static QPushButton* button(MissingFilesDialog* d, QDialogButtonBox::StandardButton which);
    QString statusText(MainWindow* w) const;

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    QList<MainWindow*> windows_;
};

namespace {

/// The small sample in `dir` naming its photo and probe "photo.exr" and "city.exr", beside the
/// project file; the files themselves are put in `filesDir`.
QString write_moved_sample(const QString& dir, const QString& filesDir) {
    const QString path = test::write_small_sample(dir);
    Project p = load_project(path.toStdString());
    QDir().mkpath(filesDir);
    bool copied = QFile::copy(QString::fromStdString(p.resolve(p.photo.path).string()),
                              QDir(filesDir).filePath("photo.exr"));
    copied &= QFile::copy(QString::fromStdString(p.resolve(p.probe.path).string()),
                          QDir(filesDir).filePath("city.exr"));
    if (!copied) qFatal("cannot copy the sample's photo and probe");
    p.photo.path = "photo.exr";
    p.probe.path = "city.exr";
    save_project(p, path.toStdString());
    return path;
}

/// The latest full frame's photo and main image, after waiting for the render to finish.
bool rendered(MainWindow& w, Image& photo, Image& image) {
    if (!test::wait_refined(w)) return false;
    std::shared_ptr<const RenderFrame> f = w.renderer()->lastFullFrame();
    if (!f || !f->photo) return false;
    photo = *f->photo;
    image = f->update.image;
    return true;
}

}  // namespace

void RelinkTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter(false);
}

void RelinkTest::cleanup() {
    for (MainWindow* w : windows_) {
        w->document()->undoStack()->setClean();  // closes without asking
        delete w;
    }
    windows_.clear();
    delete reporter_;
    delete dir_;
}

MainWindow* RelinkTest::open(const QString& project) {
    auto* w = new MainWindow(test::test_options(
        reporter_, dir_->filePath(QStringLiteral("recovery%1").arg(windows_.size()))));
    windows_ << w;
    w->resize(1200, 800);
    w->show();
    if (!QTest::qWaitForWindowExposed(w)) qWarning("window not exposed");
    if (!w->openProject(project)) qWarning("project not opened");
    return w;
}

QPushButton* RelinkTest::button(MissingFilesDialog* d, QDialogButtonBox::StandardButton which) {
    auto* box = d->findChild<QDialogButtonBox*>();
    return box ? box->button(which) : nullptr;
}

QString RelinkTest::statusText(MainWindow* w) const {
    QStringList texts;
    for (QLabel* l : w->statusBar()->findChildren<QLabel*>()) texts << l->text();
    return texts.join(" | ");
}

void RelinkTest::locatingThePhotoFindsTheProbeAndTheProjectRendersAsBeforeItMoved() {
    // Three folders below the project: further than the search looks by itself.
    const QString moved = dir_->filePath("moved/deep/er");
    const QString project = write_moved_sample(dir_->path(), moved);
    const Project asWritten = load_project(project.toStdString());
    MainWindow* w = open(project);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d && d->isVisible());
    QCOMPARE(d->rowCount(), 2);
    QCOMPARE(d->field(0), QString("photo.path"));
    QCOMPARE(d->what(0), QString("photo"));
    QCOMPARE(d->storedPath(0), QString("photo.exr"));
    QCOMPARE(d->field(1), QString("probe.path"));
    QCOMPARE(d->what(1), QString("light probe"));
    QCOMPARE(d->storedPath(1), QString("city.exr"));
    QVERIFY(d->isMissing(0) && d->isMissing(1));
    QCOMPARE(d->findChild<QLabel*>("status1")->text(), QString("missing"));
    QCOMPARE(w->missingFiles(), (QStringList{"photo.path", "probe.path"}));
    QVERIFY2(statusText(w).contains("Waiting for 2 missing files"), qPrintable(statusText(w)));

    QStringList asked;
    d->setChooser([&](QWidget*, const QString&, const QString& folder, const QString& name) {
        asked << QDir::cleanPath(folder) << name;
        return QDir(moved).filePath("photo.exr");
    });
    QTest::mouseClick(d->locateButton(0), Qt::LeftButton);
    QCOMPARE(asked, (QStringList{QDir::cleanPath(dir_->path()), "photo.exr"}));
    QCOMPARE(d->newPath(0), QDir(moved).filePath("photo.exr"));
    QCOMPARE(d->newPath(1), QDir(moved).filePath("city.exr"));  // from the photo's folder
    QCOMPARE(d->missingCount(), 0);
    QVERIFY(d->findChild<QLabel*>("status1")->text().startsWith("found: "));
    QVERIFY(w->document()->project() == asWritten);  // nothing applied before OK

    QTest::mouseClick(button(d, QDialogButtonBox::Ok), Qt::LeftButton);
    QVERIFY(!d->isVisible());
    // Inside the project's folder: stored relative to it.
    QCOMPARE(w->document()->project().photo.path, std::string("moved/deep/er/photo.exr"));
    QCOMPARE(w->document()->project().probe.path, std::string("moved/deep/er/city.exr"));
    QCOMPARE(w->document()->undoStack()->count(), 1);
    QVERIFY(w->missingFiles().isEmpty());
    QVERIFY(!w->findChild<QToolButton*>("missingFiles")->isVisible());
    Image photo, image;
    QVERIFY(rendered(*w, photo, image));

    // The same project with its files where it names them.
    const QString unmovedDir = dir_->filePath("unmoved");
    QDir().mkpath(unmovedDir);
    MainWindow* u = open(write_moved_sample(unmovedDir, unmovedDir));
    QVERIFY(u->missingFiles().isEmpty());
    QVERIFY(!u->relinkDialog());
    Image photoBefore, imageBefore;
    QVERIFY(rendered(*u, photoBefore, imageBefore));
    QCOMPARE(photo.width(), photoBefore.width());
    QCOMPARE(photo.height(), photoBefore.height());
    QCOMPARE(test::mean_abs_diff(photo, photoBefore), 0.0);
    const double diff = test::mean_abs_diff(image, imageBefore);
    QVERIFY2(diff < 1e-6, qPrintable(QString("the renders differ by %1").arg(diff)));

    // Undo (its key, as a user would) puts the old paths back, and the render waits again.
    w->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w));
    QTest::keyClick(w, Qt::Key_Z, Qt::ControlModifier);
    QVERIFY(w->document()->project() == asWritten);
    QCOMPARE(w->missingFiles().size(), 2);
    QVERIFY(w->findChild<QToolButton*>("missingFiles")->isVisible());
    QVERIFY(!w->relinkDialog());  // an undo does not ask: the button and the status say it
}

void RelinkTest::cancelLeavesTheProjectAsOpenedAndWaitingForItsFiles() {
    const QString project = write_moved_sample(dir_->path(), dir_->filePath("a/b/c"));
    const Project asWritten = load_project(project.toStdString());
    MainWindow* w = open(project);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d && d->isVisible());
    QCOMPARE(d->missingCount(), 2);
    QTest::mouseClick(button(d, QDialogButtonBox::Cancel), Qt::LeftButton);
    QVERIFY(!d->isVisible());
    QVERIFY(w->document()->project() == asWritten);
    QCOMPARE(w->document()->undoStack()->count(), 0);
    QVERIFY(!w->document()->isModified());
    QCOMPARE(w->missingFiles(), (QStringList{"photo.path", "probe.path"}));
    auto* missing = w->findChild<QToolButton*>("missingFiles");
    QVERIFY(missing->isVisible());
    QVERIFY2(missing->text().contains("2 missing files"), qPrintable(missing->text()));
    QVERIFY2(statusText(w).contains("Waiting for 2 missing files"), qPrintable(statusText(w)));
    QTest::qWait(300);
    QVERIFY(!w->renderer()->lastFullFrame());  // nothing was rendered
    QVERIFY(reporter_->errors.isEmpty());

    // Edits are still taken; the render goes on waiting.
    w->action("addSphere")->trigger();
    QCOMPARE(w->document()->undoStack()->count(), 1);
    QTest::qWait(300);
    QVERIFY(!w->renderer()->lastFullFrame());
    QVERIFY(reporter_->errors.isEmpty());
    // An export says why it cannot be written.
    QVERIFY(!w->exportImage(dir_->filePath("out.png")));
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains("Relink"), qPrintable(reporter_->errors[0]));

    // The status bar's button and File > Relink Files... bring the dialog back.
    QTest::mouseClick(missing, Qt::LeftButton);
    QVERIFY(w->relinkDialog() && w->relinkDialog()->isVisible());
    QCOMPARE(w->relinkDialog()->missingCount(), 2);
    w->relinkDialog()->reject();
    QVERIFY(QTest::qWaitFor([&] { return !w->relinkDialog(); }));
    w->action("relink")->trigger();
    QVERIFY(w->relinkDialog() && w->relinkDialog()->isVisible());
}

void RelinkTest::filesMovedIntoASubfolderAreFoundWithoutAsking() {
    const QString project = write_moved_sample(dir_->path(), dir_->filePath("assets/hdr"));
    MainWindow* w = open(project);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d);
    QCOMPARE(d->missingCount(), 0);
    QCOMPARE(d->newPath(0), dir_->filePath("assets/hdr/photo.exr"));
    QCOMPARE(d->newPath(1), dir_->filePath("assets/hdr/city.exr"));
    QTest::keyClick(d, Qt::Key_Return);  // OK is the default button
    QCOMPARE(w->document()->project().photo.path, std::string("assets/hdr/photo.exr"));
    QCOMPARE(w->document()->project().probe.path, std::string("assets/hdr/city.exr"));
    QVERIFY(w->missingFiles().isEmpty());
    QVERIFY(test::wait_refined(*w));
    QVERIFY(w->renderer()->lastFullFrame());
}

void RelinkTest::aProbeDeletedWhileOpenStopsTheRenderAndOffersTheDialog() {
    const QString project = write_moved_sample(dir_->path(), dir_->path());
    MainWindow* w = open(project);
    QVERIFY(!w->relinkDialog());
    QVERIFY(test::wait_refined(*w));
    // Moved behind the studio's back, two folders down.
    QVERIFY(QDir().mkpath(dir_->filePath("probes/sky")));
    QVERIFY(QFile::rename(dir_->filePath("city.exr"), dir_->filePath("probes/sky/city.exr")));
    Project turned = w->document()->project();
    turned.probe.rotation_deg.y += 20;
    w->document()->edit("turn the probe", turned);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d && d->isVisible());
    QCOMPARE(w->missingFiles(), QStringList{"probe.path"});
    QVERIFY(!d->isMissing(0));  // the photo is where it was
    QCOMPARE(d->newPath(1), dir_->filePath("probes/sky/city.exr"));
    QVERIFY(reporter_->errors.isEmpty());
    QTest::mouseClick(button(d, QDialogButtonBox::Ok), Qt::LeftButton);
    QCOMPARE(w->document()->project().probe.path, std::string("probes/sky/city.exr"));
    QCOMPARE(w->document()->project().probe.rotation_deg.y, turned.probe.rotation_deg.y);
    QVERIFY(test::wait_refined(*w));
    QVERIFY(reporter_->errors.isEmpty());
}

void RelinkTest::aChosenPathThatIsNoFileChangesNothing() {
    const QString project = write_moved_sample(dir_->path(), dir_->filePath("x/y/z"));
    MainWindow* w = open(project);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d);
    d->setChooser([&](QWidget*, const QString&, const QString&, const QString&) {
        return dir_->filePath("x/y");  // a folder
    });
    QTest::mouseClick(d->locateButton(0), Qt::LeftButton);
    QVERIFY(d->isMissing(0));
    QVERIFY(d->findChild<QLabel*>("relinkNote")->text().contains("is not a file"));
    d->setChooser(
        [](QWidget*, const QString&, const QString&, const QString&) { return QString(); });
    QTest::mouseClick(d->locateButton(1), Qt::LeftButton);  // the file dialog cancelled
    QCOMPARE(d->missingCount(), 2);
    QTest::mouseClick(button(d, QDialogButtonBox::Ok), Qt::LeftButton);
    QCOMPARE(w->document()->undoStack()->count(), 0);  // nothing to relink: no step
    QCOMPARE(w->missingFiles().size(), 2);
}

void RelinkTest::anotherProjectOpenedReplacesTheDialogWithItsOwnFiles() {
    const QString first = write_moved_sample(dir_->path(), dir_->filePath("p/q/r"));
    MainWindow* w = open(first);
    MissingFilesDialog* d = w->relinkDialog();
    QVERIFY(d && d->isVisible());
    QDir().mkpath(dir_->filePath("second"));
    const QString second = write_moved_sample(dir_->filePath("second"), dir_->filePath("s/t/u"));
    Project p = load_project(second.toStdString());
    p.photo.path = "other.exr";
    save_project(p, second.toStdString());
    QVERIFY(w->openProject(second));
    QVERIFY(!d->isVisible());  // it listed the first project's files
    QVERIFY(w->relinkDialog() && w->relinkDialog() != d && w->relinkDialog()->isVisible());
    QCOMPARE(w->relinkDialog()->storedPath(0), QString("other.exr"));
}

QTEST_MAIN(RelinkTest)
#include "relink_test.moc"
