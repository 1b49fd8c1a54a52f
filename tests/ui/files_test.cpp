// Save / reopen round trips and autosave recovery after the process is killed mid-edit.
#include <QAction>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QMenu>
#include <QProcess>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>
#include <cstdio>

#include "autosave.h"
#include "document.h"
#include "material_panel.h"
#include "mesh_files.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class FilesTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void savedProjectReopensIdenticalAndUnmodified();
    void saveAsElsewhereKeepsAssetsReachable();
    void autosaveRecoversTheEditsOfAKilledProcess();
    void cleanCloseLeavesNothingToRecover();
    void saveAndExportNeverWriteOverAFileTheProjectReads();
    void recentFilesAreRememberedBetweenRuns();
    void theImportFilterOffersExactlyTheFormatsTheLoaderReads();
};

namespace {

/// The edits every test makes: a box, a sphere recoloured and moved.
void make_edits(MainWindow& w) {
    w.action("addBox")->trigger();
    w.action("addSphere")->trigger();
    Project p = w.document()->project();
    p.objects.back().transform.translation = vec3(-0.3f, 0.3f, 1.2f);
    p.objects.back().name = "moved sphere";
    w.document()->edit("move", p);
    w.materialPanel()->setDiffuseColour(QColor(10, 200, 30));
}

}  // namespace

void FilesTest::savedProjectReopensIdenticalAndUnmodified() {
    QTemporaryDir dir;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    make_edits(w);
    QVERIFY(w.document()->isModified());
    const QString saved = dir.filePath("saved.json");
    QVERIFY(w.saveProjectAs(saved));
    QVERIFY(!w.document()->isModified());
    QCOMPARE(w.document()->path(), saved);

    MainWindow again(test::test_options(&reporter, dir.filePath("recovery2")));
    QVERIFY(again.openProject(saved));
    QVERIFY(again.document()->project() == w.document()->project());
    QVERIFY(to_json(again.document()->project()) == to_json(w.document()->project()));
    QVERIFY(!again.document()->isModified());
    QVERIFY(reporter.errors.isEmpty());
}

void FilesTest::saveAsElsewhereKeepsAssetsReachable() {
    QTemporaryDir dir, other;
    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    // The sample as shipped: its photo path is relative to its own folder.
    QVERIFY(w.openProject(QString(DP_SOURCE_DIR) + "/resources/sample/sample.json"));
    const QString saved = other.filePath("moved.json");
    QVERIFY(w.saveProjectAs(saved));
    const Project reopened = load_project(saved.toStdString());
    QVERIFY(std::filesystem::exists(reopened.resolve(reopened.photo.path)));
}

void FilesTest::autosaveRecoversTheEditsOfAKilledProcess() {
    QTemporaryDir dir;
    const QString project = test::write_small_sample(dir.path());
    const QString recovery = dir.filePath("recovery");
    QProcess child;
    child.start(QCoreApplication::applicationFilePath(), {"--child", recovery, project});
    QVERIFY(child.waitForStarted());
    QByteArray out;
    QVERIFY(QTest::qWaitFor(
        [&] {
            child.waitForReadyRead(50);
            out += child.readAllStandardOutput();
            return out.contains("autosaved");
        },
        30000));
    child.kill();  // no clean close: only the autosave is left
    QVERIFY(child.waitForFinished());

    RecordingReporter yes(true);
    MainWindow w(test::recovering_options(&yes, recovery));
    w.checkRecovery();
    QCOMPARE(yes.questions.size(), 1);
    QVERIFY(w.document()->isOpen());
    QVERIFY(w.document()->isModified());
    QCOMPARE(w.document()->path(), project);
    const Project& p = w.document()->project();
    QCOMPARE(int(p.objects.size()), 5);
    QCOMPARE(p.objects.back().name, std::string("moved sphere"));
    QCOMPARE(p.objects.back().transform.translation.z, 1.2f);
    QVERIFY(p.objects.back().material.albedo.rgb.y > 0.5f);
}

void FilesTest::cleanCloseLeavesNothingToRecover() {
    QTemporaryDir dir;
    RecordingReporter no(false);  // "save before closing?" no
    MainWindow w(test::test_options(&no, dir.filePath("recovery")));
    QVERIFY(w.openProject(test::write_small_sample(dir.path())));
    make_edits(w);
    QVERIFY(w.autosave()->writeNow());
    QVERIFY(w.autosave()->ownCopy().has_value());
    QVERIFY(w.close());
    QVERIFY(!w.autosave()->ownCopy().has_value());
}

void FilesTest::saveAndExportNeverWriteOverAFileTheProjectReads() {
    QTemporaryDir dir;
    // The photo copied beside the project, so a failing check could only harm a copy.
    Project p = load_project(test::write_small_sample(dir.path()).toStdString());
    const QString photo = dir.filePath("photo.exr");
    QVERIFY(QFile::copy(QString::fromStdString(p.photo.path), photo));
    p.photo.path = photo.toStdString();
    const QString project = dir.filePath("own.json");
    save_project(p, project.toStdString());
    const QString link = dir.filePath("link.exr");  // another name for the photo
    QVERIFY(QFile::link(photo, link));
    QFile f(photo);
    QVERIFY(f.open(QIODevice::ReadOnly));
    const QByteArray before = f.readAll();
    f.close();

    RecordingReporter reporter;
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    QVERIFY(w.openProject(project));
    make_edits(w);
    QVERIFY(!w.saveProjectAs(photo));
    QVERIFY(!w.saveProjectAs(link));
    QVERIFY(!w.exportImage(link));
    QVERIFY(!w.exportImage(project.chopped(5) + ".json"));  // the project file itself
    QCOMPARE(reporter.errors.size(), 4);
    for (int i = 0; i < 3; ++i)
        QVERIFY2(reporter.errors[i].contains("photo (photo.path)"), qPrintable(reporter.errors[i]));
    QVERIFY2(reporter.errors[3].contains("own.json"), qPrintable(reporter.errors[3]));
    QVERIFY(f.open(QIODevice::ReadOnly));
    QCOMPARE(f.readAll(), before);
    QVERIFY(w.document()->isModified());
    QCOMPARE(w.document()->path(), project);
}

void FilesTest::recentFilesAreRememberedBetweenRuns() {
    QTemporaryDir dir;
    QSettings::setDefaultFormat(QSettings::IniFormat);
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, dir.filePath("settings"));
    RecordingReporter no(false);
    StudioOptions o = test::test_options(&no, dir.filePath("recovery"));
    o.useSettings = true;
    const QString a = test::write_small_sample(dir.path());
    QDir().mkpath(dir.filePath("b"));
    const QString b = test::write_small_sample(dir.filePath("b"));
    {
        MainWindow w(o);
        QVERIFY(w.openProject(a));
        QVERIFY(w.openProject(b));
        QVERIFY(w.close());  // a clean close stores the settings
    }
    MainWindow again(o);
    QMenu* recent = again.findChild<QMenu*>("recentMenu");
    QVERIFY(recent);
    const QList<QAction*> items = recent->actions();
    QCOMPARE(items.size(), 2);
    QCOMPARE(items[0]->toolTip(), QFileInfo(b).absoluteFilePath());  // most recent first
    QCOMPARE(items[1]->toolTip(), QFileInfo(a).absoluteFilePath());
    items[1]->trigger();  // opens it
    QCOMPARE(again.document()->path(), QFileInfo(a).absoluteFilePath());
    QCOMPARE(again.viewport()->exposure(), 0.0f);  // the display exposure is the project's
}

namespace {

/// The child process of the recovery test: opens the project, edits, waits for the autosave,
/// says so, and keeps running until killed.
int run_child(int argc, char** argv) {
    QApplication app(argc, argv);
    RecordingReporter reporter;
    StudioOptions o = test::test_options(&reporter, argv[2]);
    o.autosaveMs = 100;
    MainWindow w(o);
    if (!w.openProject(argv[3])) return 1;
    make_edits(w);
    QObject::connect(w.autosave(), &Autosave::written, [] {
        std::printf("autosaved\n");
        std::fflush(stdout);
    });
    return app.exec();
}

}  // namespace

void FilesTest::theImportFilterOffersExactlyTheFormatsTheLoaderReads() {
    const QString filter = mesh_file_filter();
    // The formats the loader keeps Assimp's readers for, and every one of them.
    for (const char* kept : {"obj", "ply", "gltf", "glb", "stl", "fbx"})
        QVERIFY2(filter.contains(QString(" *.%1").arg(kept)) ||
                     filter.contains(QString("(*.%1").arg(kept)),
                 qPrintable(filter));
    // Formats Assimp reads but the loader refuses for hardening.
    for (const char* dropped : {"3ds", "dae", "blend", "x", "ase", "lwo", "md5mesh"})
        QVERIFY2(!filter.contains(QString("*.%1 ").arg(dropped)) &&
                     !filter.contains(QString("*.%1)").arg(dropped)),
                 qPrintable(filter));
    QCOMPARE(filter.count("*."), int(mesh_file_extensions().size()));
    QVERIFY(is_mesh_file("/tmp/Chair.FBX"));
    QVERIFY(is_mesh_file("scene.glb"));
    QVERIFY(!is_mesh_file("scene.dae"));
    QVERIFY(!is_mesh_file("photo.exr"));
}

int main(int argc, char** argv) {
    if (argc == 4 && std::string(argv[1]) == "--child") return run_child(argc, argv);
    QApplication app(argc, argv);
    FilesTest t;
    return QTest::qExec(&t, argc, argv);
}

#include "files_test.moc"
