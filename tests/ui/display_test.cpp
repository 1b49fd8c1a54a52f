// Display settings per project, driven with real key and mouse events: the exposure is kept in
// the project (undoable, saved, reopened) and left out of exports unless asked; overlays are
// off by default, toggled with H over the augmented view and never drawn over the photo.
#include <QAction>
#include <QApplication>
#include <QAbstractItemView>
#include <QComboBox>
#include <QFile>
#include <QImage>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QSlider>
#include <QTemporaryDir>
#include <QTest>
#include <QUndoStack>

#include "document.h"
#include "scene/project_io.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class DisplayTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void exposureIsKeptInTheProjectUndoableAndSaved();
    void exportsAreNotBakedWithTheExposureUnlessAsked();
    void overlaysAreNeverOverThePhotoAndHTogglesThemOverTheAugmentedView();
    void theViewTransformIsPickedInTheToolbarKeptInTheProjectAndUsedByExports();

private:
    void press(QWidget* target, int key, Qt::KeyboardModifiers modifiers = {});
    QSlider* slider() const { return w_->findChild<QSlider*>("exposureSlider"); }
    QLabel* label() const { return w_->findChild<QLabel*>("exposureLabel"); }
    QImage grabViewport() const { return w_->viewport()->grab().toImage(); }

    QTemporaryDir* dir_ = nullptr;
    RecordingReporter* reporter_ = nullptr;
    MainWindow* w_ = nullptr;
    QString project_;
};

void DisplayTest::init() {
    dir_ = new QTemporaryDir;
    reporter_ = new RecordingReporter;
    w_ = new MainWindow(test::test_options(reporter_, dir_->filePath("recovery")));
    w_->resize(1200, 800);
    w_->show();
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    project_ = test::write_small_sample(dir_->path());
    // The sample as written before display settings existed: no "display" key.
    QFile f(project_);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QJsonObject json = QJsonDocument::fromJson(f.readAll()).object();
    f.close();
    QVERIFY(json.contains("display"));
    json.remove("display");
    QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
    f.write(QJsonDocument(json).toJson());
    f.close();
    QVERIFY(w_->openProject(project_));
}

void DisplayTest::cleanup() {
    QVERIFY2(reporter_->errors.isEmpty(), qPrintable(reporter_->errors.join("; ")));
    w_->document()->undoStack()->setClean();
    delete w_;
    w_ = nullptr;
    delete reporter_;
    delete dir_;
}

void DisplayTest::press(QWidget* target, int key, Qt::KeyboardModifiers modifiers) {
    if (QApplication::activeWindow() != w_) {
        w_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(w_));
    }
    QTest::keyClick(target, Qt::Key(key), modifiers);
}

void DisplayTest::exposureIsKeptInTheProjectUndoableAndSaved() {
    QVERIFY(slider() && label());
    QCOMPARE(w_->document()->project().display.exposure, 0.0f);  // an older file reads as 0
    QCOMPARE(label()->text(), QString("+0.0 EV"));
    // Page Up on the slider: one page, 1 EV.
    QTest::mouseClick(slider(), Qt::LeftButton, {},
                      QPoint(slider()->width() / 2, slider()->height() / 2));
    QVERIFY(slider()->hasFocus());
    QCOMPARE(w_->document()->project().display.exposure, 0.0f);  // a click in the middle: 0
    press(slider(), Qt::Key_PageUp);
    press(slider(), Qt::Key_Right);  // and one step of 0.1
    QVERIFY(std::abs(w_->document()->project().display.exposure - 1.1f) < 1e-6f);
    QCOMPARE(label()->text(), QString("+1.1 EV"));
    QVERIFY(std::abs(w_->viewport()->exposure() - 1.1f) < 1e-6f);
    QVERIFY(w_->document()->isModified());
    press(slider(), Qt::Key_Z, Qt::ControlModifier);  // undo: back to 1 EV
    QVERIFY(std::abs(w_->document()->project().display.exposure - 1.0f) < 1e-6f);
    QCOMPARE(slider()->value(), 10);
    QCOMPARE(label()->text(), QString("+1.0 EV"));
    press(slider(), Qt::Key_S, Qt::ControlModifier);  // save
    QVERIFY(!w_->document()->isModified());
    const Project saved = load_project(project_.toStdString());
    QCOMPARE(saved.display.exposure, 1.0f);

    // Another window opens the file: the exposure comes back with it.
    MainWindow other(test::test_options(reporter_, dir_->filePath("recovery2")));
    QVERIFY(other.openProject(project_));
    QCOMPARE(other.document()->project().display.exposure, 1.0f);
    QCOMPARE(other.findChild<QSlider*>("exposureSlider")->value(), 10);
    QCOMPARE(other.findChild<QLabel*>("exposureLabel")->text(), QString("+1.0 EV"));
    QCOMPARE(other.viewport()->exposure(), 1.0f);
}

void DisplayTest::exportsAreNotBakedWithTheExposureUnlessAsked() {
    QVERIFY(test::wait_refined(*w_));
    const QString plain = dir_->filePath("plain.png");
    QVERIFY(test::export_and_wait(*w_, plain));
    QTest::mouseClick(slider(), Qt::LeftButton, {},
                      QPoint(slider()->width() / 2, slider()->height() / 2));
    press(slider(), Qt::Key_PageUp);
    press(slider(), Qt::Key_PageUp);  // +2 EV on screen
    QCOMPARE(w_->document()->project().display.exposure, 2.0f);
    QVERIFY(!w_->exportAppliesExposure());
    const QString atZero = dir_->filePath("at-zero.png");
    QVERIFY(test::export_and_wait(*w_, atZero));
    const QImage a(plain), b(atZero);
    QVERIFY(!a.isNull() && a.size() == b.size());
    QVERIFY(a == b);  // the render as it is, not the display's +2 EV
    // Asked for: the export is brighter.
    w_->action("exportExposure")->trigger();
    QVERIFY(w_->exportAppliesExposure());
    const QString baked = dir_->filePath("baked.png");
    QVERIFY(test::export_and_wait(*w_, baked));
    const QImage c(baked);
    // Brighter wherever the +0 EV export is not already white (the sample is a bright photo).
    int brighter = 0, darker = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const int ga = qGray(a.pixel(x, y)), gc = qGray(c.pixel(x, y));
            brighter += gc > ga;
            darker += gc < ga;
        }
    QCOMPARE(darker, 0);
    QVERIFY2(brighter > a.width() * a.height() / 2, qPrintable(QString::number(brighter)));
}

void DisplayTest::overlaysAreNeverOverThePhotoAndHTogglesThemOverTheAugmentedView() {
    QVERIFY(test::wait_refined(*w_));
    Viewport* v = w_->viewport();
    // Select the chrome ball by clicking it: its outline would be drawn if overlays were on.
    QPointF at;
    QVERIFY(v->widgetPosition(w_->document()->project().objects[1].transform.translation, at));
    QTest::mouseClick(v, Qt::LeftButton, {}, at.toPoint());
    QCOMPARE(w_->document()->selected(), 1);
    QVERIFY(v->hasFocus());
    QCOMPARE(int(v->viewMode()), int(ViewMode::Augmented));
    QVERIFY(!v->overlaysVisible());  // off by default
    const QImage clean = grabViewport();
    press(v, Qt::Key_H);
    QVERIFY(v->overlaysVisible());
    QVERIFY(w_->action("overlays")->isChecked());
    QVERIFY(w_->document()->project().objects[1].visible);  // H no longer hides the object
    const QImage withOverlays = grabViewport();
    QVERIFY(withOverlays != clean);
    // The photo: the same picture with the overlays on or off.
    press(v, Qt::Key_1);
    QCOMPARE(int(v->viewMode()), int(ViewMode::Photo));
    const QImage photoOn = grabViewport();
    press(v, Qt::Key_H);
    QVERIFY(!v->overlaysVisible());
    const QImage photoOff = grabViewport();
    QVERIFY(photoOn == photoOff);
    QVERIFY(photoOn != clean);  // it is the photo, not the augmented view
    // Back to the augmented view with overlays off: the clean picture again.
    press(v, Qt::Key_2);
    QVERIFY(grabViewport() == clean);
    // Shift+H hides the selected object now.
    press(v, Qt::Key_H, Qt::ShiftModifier);
    QVERIFY(!w_->document()->project().objects[1].visible);
}

void DisplayTest::theViewTransformIsPickedInTheToolbarKeptInTheProjectAndUsedByExports() {
    auto* box = w_->findChild<QComboBox*>("viewTransform");
    QVERIFY(box);
    QCOMPARE(box->currentText(), QString("Standard"));
    if (box->findText("Filmic") < 0) QSKIP("no OpenColorIO config with a Filmic view on this machine");
    QVERIFY(test::wait_refined(*w_));
    const QString standardExport = dir_->filePath("standard.png");
    QVERIFY(test::export_and_wait(*w_, standardExport));
    press(w_->viewport(), Qt::Key_1);  // the photo: its pixels change with the view only
    const QImage standard = grabViewport();

    // Open the box with a click and walk down to Filmic with the keyboard, as a person would.
    QTest::mouseClick(box, Qt::LeftButton);
    QVERIFY(QApplication::activePopupWidget());
    QWidget* list = box->view();  // the popup's list takes the keys
    for (int i = box->currentIndex(); i < box->findText("Filmic"); ++i) QTest::keyClick(list, Qt::Key_Down);
    QTest::keyClick(list, Qt::Key_Return);
    QVERIFY(!QApplication::activePopupWidget());
    QCOMPARE(w_->document()->project().display.view, std::string("Filmic"));
    QCOMPARE(w_->viewport()->view().view, std::string("Filmic"));
    const QImage filmic = grabViewport();
    QVERIFY(filmic != standard);
    QVERIFY(test::wait_refined(*w_));
    const QString filmicExport = dir_->filePath("filmic.png");
    QVERIFY(test::export_and_wait(*w_, filmicExport));
    QVERIFY(QImage(filmicExport) != QImage(standardExport));

    press(w_->viewport(), Qt::Key_Z, Qt::ControlModifier);  // one undo step back to Standard
    QCOMPARE(w_->document()->project().display.view, std::string("Standard"));
    QCOMPARE(box->currentText(), QString("Standard"));
    QVERIFY(grabViewport() == standard);
}

QTEST_MAIN(DisplayTest)
#include "display_test.moc"
