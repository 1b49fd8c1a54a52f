// Bad input through the GUI: a clear message, and the project left as it was.
#include <QApplication>
#include <QFile>
#include <QImage>
#include <QMessageBox>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QUndoStack>

#include "document.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class BadInputTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void unreadablePhotoIsReportedAndChangesNothing();
    void probeThatIsNotHdrIsReportedAndChangesNothing();
    void meshThatFailsToLoadIsReportedAndChangesNothing();
    void invalidProjectFileIsReportedAndChangesNothing();
    void errorsReachTheUserAsAMessageBox();

private:
    void expectUnchanged(const char* mustMention);
    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
    Project before_;
    int undoSteps_ = 0;
};

void BadInputTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery")));
    QVERIFY(w_->openProject(test::write_small_sample(dir_->path())));
    w_->addObject(Shape::Kind::Sphere);
    before_ = w_->document()->project();
    undoSteps_ = w_->document()->undoStack()->count();
}

void BadInputTest::cleanup() {
    delete w_;
    delete reporter_;
    delete dir_;
}

void BadInputTest::expectUnchanged(const char* mustMention) {
    QCOMPARE(reporter_->errors.size(), 1);
    QVERIFY2(reporter_->errors[0].contains(mustMention), qPrintable(reporter_->errors[0]));
    QVERIFY(w_->document()->project() == before_);
    QCOMPARE(w_->document()->undoStack()->count(), undoSteps_);
}

void BadInputTest::unreadablePhotoIsReportedAndChangesNothing() {
    const QString photo = dir_->filePath("photo.png");
    QFile f(photo);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("this is not a PNG");
    f.close();
    const QString probe = "/usr/share/blender/datafiles/studiolights/world/city.exr";
    QVERIFY(!w_->newProject(photo, probe));
    expectUnchanged("photo.png");
}

void BadInputTest::probeThatIsNotHdrIsReportedAndChangesNothing() {
    const QString probe = dir_->filePath("probe.png");
    QImage img(64, 32, QImage::Format_RGB32);
    img.fill(QColor(200, 200, 200));
    QVERIFY(img.save(probe));
    QVERIFY(!w_->newProject(QString(DP_SOURCE_DIR) + "/resources/sample/photo.exr", probe));
    expectUnchanged("HDR");
}

void BadInputTest::meshThatFailsToLoadIsReportedAndChangesNothing() {
    const QString mesh = dir_->filePath("broken.obj");
    QFile f(mesh);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("v 0 0 0\nv 1 0 0\nf 1 2 7\n");  // a face with a vertex that does not exist
    f.close();
    QVERIFY(!w_->importMesh(mesh));
    expectUnchanged("broken.obj");
}

void BadInputTest::invalidProjectFileIsReportedAndChangesNothing() {
    const QString project = dir_->filePath("bad.json");
    QFile f(project);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("{ \"schema_version\": 1, \"photo\": 3 }");
    f.close();
    QVERIFY(!w_->openProject(project));
    expectUnchanged("bad.json");
}

void BadInputTest::errorsReachTheUserAsAMessageBox() {
    // Without an injected reporter the studio shows a modal QMessageBox: read it and close it.
    MainWindow w(test::test_options(nullptr, dir_->filePath("recovery3")));
    QString text;
    QTimer::singleShot(50, [&] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) return;
        text = box->text();
        box->accept();
    });
    QVERIFY(!w.openProject(dir_->filePath("missing.json")));
    QVERIFY2(text.contains("missing.json"), qPrintable(text));
}

QTEST_MAIN(BadInputTest)
#include "bad_input_test.moc"
