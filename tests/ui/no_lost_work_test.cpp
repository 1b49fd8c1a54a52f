// No lost work and keys that work: Save / Discard / Cancel before a modified project is
// replaced or closed (Esc is Cancel), exports of the state on screen, and the window's
// shortcuts whichever widget has the focus.
#include <QAction>
#include <QApplication>
#include <QCursor>
#include <QFileDialog>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QFileInfo>
#include <QStatusBar>
#include <QStatusTipEvent>
#include <QTest>
#include <QToolBar>
#include <QTimer>
#include <QUndoStack>

#include "autosave.h"
#include "document.h"
#include "image/image_io.h"
#include "number_field.h"
#include "scene/project_io.h"
#include "scene_panel.h"
#include "settings_panel.h"
#include "ui_test_support.h"
#include "viewport.h"

using namespace dp;
using namespace dp::ui;

class NoLostWorkTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void init();
    void cleanup();
    void newOnAModifiedProjectAsksAndEscKeepsEverything();
    void openRecentWithDiscardReplacesTheProjectAndOnlyThenDropsTheRecoveryFile();
    void quitAsksSaveWritesTheProjectAndCancelKeepsTheWindowOpen();
    void exportRightAfterAnEditWritesTheEditedState();
    void gInANumberFieldGrabsAndTheToolbarModeComesBack();
    void undoAndDeleteWorkWhileAFieldHasTheFocus();
    void saveAsAndTheKeyMapHaveTheirKeys();
    void anEditLeavesTheToolbarInPlaceAndItsUndoUndoes();
    void theExportDialogOpensBesideTheProject();
    void hoveringAButtonLeavesTheStatusLineAndItsMessage();

private:
    /// Answers the next modal dialog with `key` once it shows; records its buttons.
    void answerNextDialog(Qt::Key key);
    /// Answers the next Save / Discard / Cancel question by clicking `button`.
    void clickInNextDialog(QMessageBox::StandardButton button);
    void press(int key, Qt::KeyboardModifiers modifiers = {});
    void selectInList(int row);

    QTemporaryDir* dir_ = nullptr;
    MainWindow* w_ = nullptr;
    QString project_;
    QStringList dialogButtons_;
    QString dialogText_;
};

void NoLostWorkTest::init() {
    dir_ = new QTemporaryDir;
    dialogButtons_.clear();
    dialogText_.clear();
    // No injected reporter: the real message boxes, answered with keys and clicks.
    w_ = new MainWindow(test::test_options(nullptr, dir_->filePath("recovery")));
    w_->resize(1200, 800);
    w_->show();
    w_->activateWindow();
    QVERIFY(QTest::qWaitForWindowActive(w_));
    project_ = test::write_small_sample(dir_->path());
    QVERIFY(w_->openProject(project_));
}

void NoLostWorkTest::cleanup() {
    if (w_) w_->document()->undoStack()->setClean();  // closes without asking
    delete w_;
    w_ = nullptr;
    delete dir_;
}

void NoLostWorkTest::answerNextDialog(Qt::Key key) {
    QTimer::singleShot(100, this, [this, key] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) return;
        dialogText_ = box->text();
        for (QAbstractButton* b : box->buttons()) dialogButtons_ << b->text().remove('&');
        QTest::keyClick(box, key);
    });
}

void NoLostWorkTest::clickInNextDialog(QMessageBox::StandardButton button) {
    QTimer::singleShot(100, this, [this, button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        if (!box) return;
        dialogText_ = box->text();
        for (QAbstractButton* b : box->buttons()) dialogButtons_ << b->text().remove('&');
        QTest::mouseClick(box->button(button), Qt::LeftButton);
    });
}

void NoLostWorkTest::press(int key, Qt::KeyboardModifiers modifiers) {
    // The offscreen platform does not give the activation back after a modal dialog closes
    // (a window manager would): without it the window's shortcuts are not live.
    if (QApplication::activeWindow() != w_) {
        w_->activateWindow();
        QVERIFY(QTest::qWaitForWindowActive(w_));
    }
    QWidget* target = QApplication::focusWidget() ? QApplication::focusWidget() : w_;
    QTest::keyClick(target, Qt::Key(key), modifiers);
}

void NoLostWorkTest::selectInList(int row) {
    QListWidget* list = w_->scenePanel()->list();
    const QRect r = list->visualItemRect(list->item(row));
    QTest::mouseClick(list->viewport(), Qt::LeftButton, {}, r.center() + QPoint(20, 0));
    QCOMPARE(w_->document()->selected(), row);
}

void NoLostWorkTest::newOnAModifiedProjectAsksAndEscKeepsEverything() {
    w_->action("addSphere")->trigger();
    const Project edited = w_->document()->project();
    QVERIFY(w_->autosave()->writeNow());
    answerNextDialog(Qt::Key_Escape);
    press(Qt::Key_N, Qt::ControlModifier);
    QCOMPARE(dialogButtons_.size(), 3);
    QVERIFY2(dialogButtons_.contains("Save") && dialogButtons_.contains("Discard") &&
                 dialogButtons_.contains("Cancel"),
             qPrintable(dialogButtons_.join(",")));
    QVERIFY(QApplication::activeModalWidget() == nullptr);  // no New Project dialog after Esc
    QVERIFY(w_->document()->isModified());
    QVERIFY(w_->document()->project() == edited);
    QVERIFY(w_->autosave()->ownCopy().has_value());  // Esc deleted nothing

    // Open (Ctrl+O) is asked the same way.
    dialogButtons_.clear();
    answerNextDialog(Qt::Key_Escape);
    press(Qt::Key_O, Qt::ControlModifier);
    QCOMPARE(dialogButtons_.size(), 3);
    QVERIFY(w_->document()->project() == edited);
}

void NoLostWorkTest::openRecentWithDiscardReplacesTheProjectAndOnlyThenDropsTheRecoveryFile() {
    QDir().mkpath(dir_->filePath("other"));
    const QString other = test::write_small_sample(dir_->filePath("other"));
    QVERIFY(w_->openProject(other));
    QVERIFY(w_->openProject(project_));  // "other" is now in Open Recent
    w_->action("addBox")->trigger();
    QVERIFY(w_->autosave()->writeNow());
    QMenu* recent = w_->findChild<QMenu*>("recentMenu");
    QAction* item = recent->actions().value(1);
    QVERIFY(item);
    QCOMPARE(item->toolTip(), QFileInfo(other).absoluteFilePath());

    answerNextDialog(Qt::Key_Escape);
    item->trigger();
    QCOMPARE(dialogButtons_.size(), 3);
    QCOMPARE(w_->document()->path(), QFileInfo(project_).absoluteFilePath());
    QVERIFY(w_->autosave()->ownCopy().has_value());

    clickInNextDialog(QMessageBox::Discard);
    item->trigger();
    QCOMPARE(w_->document()->path(), QFileInfo(other).absoluteFilePath());
    QVERIFY(!w_->document()->isModified());
    QVERIFY(!w_->autosave()->ownCopy().has_value());
}

void NoLostWorkTest::quitAsksSaveWritesTheProjectAndCancelKeepsTheWindowOpen() {
    w_->action("addSphere")->trigger();
    const size_t objects = w_->document()->project().objects.size();
    answerNextDialog(Qt::Key_Escape);
    press(Qt::Key_Q, Qt::ControlModifier);
    QCOMPARE(dialogButtons_.size(), 3);
    QVERIFY(w_->isVisible());
    QVERIFY(w_->document()->isModified());

    clickInNextDialog(QMessageBox::Save);
    press(Qt::Key_Q, Qt::ControlModifier);
    QVERIFY(!w_->isVisible());
    QCOMPARE(load_project(project_.toStdString()).objects.size(), objects);
    QVERIFY(!w_->autosave()->ownCopy().has_value());
}

void NoLostWorkTest::exportRightAfterAnEditWritesTheEditedState() {
    // One object, refined; then it is hidden and the export asked for at once.
    Project one = load_project(project_.toStdString());
    one.objects.resize(1);
    save_project(one, project_.toStdString());
    QVERIFY(w_->openProject(project_));
    QVERIFY(test::wait_refined(*w_));
    const QString before = dir_->filePath("before.exr");
    QVERIFY(test::export_and_wait(*w_, before));
    const Image alphaBefore = load_exr_layer(before.toStdString(), "alpha");
    double covered = 0;
    for (size_t i = 0; i < alphaBefore.size(); ++i) covered += alphaBefore[i].x;
    QVERIFY(covered > 20);  // the ball is in the picture

    selectInList(0);
    press(Qt::Key_H, Qt::ShiftModifier);  // hide it
    QVERIFY(!w_->document()->project().objects[0].visible);
    const QString after = dir_->filePath("after.exr");
    QSignalSpy done(w_, &MainWindow::exportFinished);
    QVERIFY(w_->exportImage(after));
    QVERIFY(w_->exportPending());  // the last full pass still shows the ball
    QVERIFY(done.wait(30000));
    QVERIFY(done.last().at(1).toBool());
    QVERIFY(!w_->exportPending());
    const Image alphaAfter = load_exr_layer(after.toStdString(), "alpha");
    for (size_t i = 0; i < alphaAfter.size(); ++i) QCOMPARE(alphaAfter[i].x, 0.0f);

    // What the core renders for the edited project: with nothing virtual, the photo itself.
    QVERIFY(test::wait_refined(*w_));
    const QString refined = dir_->filePath("refined.exr");
    QVERIFY(test::export_and_wait(*w_, refined));
    const Image a = load_exr_layer(before.toStdString(), "");
    const Image b = load_exr_layer(after.toStdString(), "");
    const Image c = load_exr_layer(refined.toStdString(), "");
    const double stale = test::mean_abs_diff(a, c), exported = test::mean_abs_diff(b, c);
    QVERIFY2(exported < 0.1 * stale,
             qPrintable(QString("export differs by %1, the previous state by %2")
                            .arg(exported)
                            .arg(stale)));
}

void NoLostWorkTest::gInANumberFieldGrabsAndTheToolbarModeComesBack() {
    QVERIFY(test::wait_refined(*w_));
    w_->action("gizmoRotate")->trigger();  // the toolbar's mode, as clicked
    selectInList(0);
    const vec3 start = w_->document()->project().objects[0].transform.translation;
    const int steps = w_->document()->undoStack()->count();
    NumberField* field = w_->scenePanel()->transformField(0);
    QTest::mouseClick(field, Qt::LeftButton);
    QVERIFY(field->hasFocus());
    Viewport* v = w_->viewport();
    QPointF at;
    QVERIFY(v->widgetPosition(start, at));
    QCursor::setPos(v->mapToGlobal(at.toPoint()));  // the hand moves over the viewport
    press(Qt::Key_G);
    QVERIFY(v->transforming());
    QVERIFY(w_->action("gizmoMove")->isChecked());  // the toolbar shows the operation
    for (int i = 1; i <= 12; ++i) {
        QTest::mouseMove(v, (at + QPointF(4.0 * i, 2.0 * i)).toPoint());
        QTest::qWait(16);
    }
    QTest::keyClick(v, Qt::Key_Return);
    QVERIFY(!v->transforming());
    const vec3 moved = w_->document()->project().objects[0].transform.translation;
    QVERIFY(glm::length(moved - start) > 0.05f);
    QCOMPARE(w_->document()->undoStack()->count(), steps + 1);
    QVERIFY(w_->action("gizmoRotate")->isChecked());
    QCOMPARE(int(v->gizmoMode()), int(GizmoMode::Rotate));

    // Esc cancels: the object goes back, the toolbar mode too.
    const vec3 scale = w_->document()->project().objects[0].transform.scale;
    press(Qt::Key_S);
    QVERIFY(v->transforming());
    QVERIFY(w_->action("gizmoScale")->isChecked());
    QTest::mouseMove(v, (at + QPointF(60, 0)).toPoint());
    QTest::qWait(16);
    QTest::keyClick(v, Qt::Key_Escape);
    QVERIFY(w_->document()->project().objects[0].transform.translation == moved);
    QVERIFY(w_->document()->project().objects[0].transform.scale == scale);
    QVERIFY(w_->action("gizmoRotate")->isChecked());
}

void NoLostWorkTest::undoAndDeleteWorkWhileAFieldHasTheFocus() {
    selectInList(2);
    const Project start = w_->document()->project();
    NumberField* x = w_->scenePanel()->transformField(0);
    QTest::mouseClick(x, Qt::LeftButton);
    QTest::keyClick(x, Qt::Key_A, Qt::ControlModifier);
    QTest::keyClicks(x, "0.25");
    QTest::keyClick(x, Qt::Key_Return);
    QCOMPARE(w_->document()->project().objects[2].transform.translation.x, 0.25f);
    QVERIFY(x->hasFocus());
    press(Qt::Key_Z, Qt::ControlModifier);  // the document's undo, not the field's
    QVERIFY(w_->document()->project() == start);
    QCOMPARE(x->value(), double(start.objects[2].transform.translation.x));
    press(Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(w_->document()->project().objects[2].transform.translation.x, 0.25f);
    press(Qt::Key_Y, Qt::ControlModifier);  // nothing more to redo; nothing breaks

    // In the name field letters are typing: X types, it does not delete.
    auto* name = w_->scenePanel()->findChild<QLineEdit*>();
    QVERIFY(name);
    QTest::mouseClick(name, Qt::LeftButton);
    QVERIFY(name->hasFocus());
    QTest::keyClick(name, Qt::Key_End);
    press(Qt::Key_X);
    QVERIFY(name->text().endsWith('x'));
    QCOMPARE(w_->document()->project().objects.size(), start.objects.size());
    press(Qt::Key_Z, Qt::ControlModifier);  // still the document's: the move is undone
    QVERIFY(w_->document()->project() == start);

    // In a number field X is no digit: it deletes the selected object (undoably).
    QTest::mouseClick(x, Qt::LeftButton);
    press(Qt::Key_X);
    QCOMPARE(w_->document()->project().objects.size(), start.objects.size() - 1);
    press(Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(w_->document()->project().objects.size(), start.objects.size());
}

void NoLostWorkTest::saveAsAndTheKeyMapHaveTheirKeys() {
    QVERIFY(w_->action("saveAs")->shortcuts().contains(QKeySequence("Ctrl+Shift+S")));
    bool sawFileDialog = false;
    QTimer::singleShot(200, this, [&] {
        auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
        sawFileDialog = dialog != nullptr;
        if (dialog) dialog->reject();
    });
    QTest::mouseClick(w_->settingsPanel()->radiusField(), Qt::LeftButton);
    QVERIFY(w_->settingsPanel()->radiusField()->hasFocus());
    press(Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
    QVERIFY(sawFileDialog);

    QMenu* help = w_->menuBar()->findChild<QMenu*>("helpMenu");
    QVERIFY(help);
    QVERIFY(help->actions().contains(w_->action("keyMap")));
    press(Qt::Key_F1);
    QMessageBox* map = nullptr;
    QVERIFY(QTest::qWaitFor([&] { return (map = w_->findChild<QMessageBox*>("keyMapDialog")); }));
    for (const char* needle : {"Grab", "Ctrl+Shift+S", "Ctrl+Z", "Esc"})
        QVERIFY2(map->text().contains(needle), needle);
    // Every key an action of the window answers to is listed, with the action's name.
    int keyed = 0;
    for (QAction* a : w_->findChildren<QAction*>()) {
        if (a->shortcuts().isEmpty() || a->objectName().isEmpty()) continue;
        ++keyed;
        const QString key = a->shortcuts().first().toString(QKeySequence::NativeText).toHtmlEscaped();
        const QString what = a->text().remove(QLatin1Char('&')).toHtmlEscaped();
        QVERIFY2(map->text().contains(QStringLiteral("<b>%1").arg(key)) && map->text().contains(what),
                 qPrintable(a->objectName() + ": " + key + " " + what));
    }
    QVERIFY(keyed > 20);
    QVERIFY(map->text().contains(QStringLiteral("<b>D</b>")));  // Denoise, once left out
    map->close();
}

void NoLostWorkTest::anEditLeavesTheToolbarInPlaceAndItsUndoUndoes() {
    auto* bar = w_->findChild<QToolBar*>("toolbar");
    QWidget* undo = bar->widgetForAction(w_->findChild<QAction*>("undoToolbar"));
    QWidget* move = bar->widgetForAction(w_->action("gizmoMove"));
    QVERIFY(undo && move);
    QVERIFY(!undo->isEnabled());
    const QPoint before = move->mapTo(w_, QPoint(0, 0));
    const Project original = w_->document()->project();
    // An edit through the Sphere action, as clicked: the menu's Undo now names it.
    w_->action("addSphere")->trigger();
    QTRY_VERIFY(undo->isEnabled());
    QVERIFY(w_->action("undo")->text().size() > QStringLiteral("&Undo").size());
    QCOMPARE(move->mapTo(w_, QPoint(0, 0)), before);  // nothing after Undo moved
    QVERIFY2(undo->toolTip().startsWith("Undo "), qPrintable(undo->toolTip()));
    QTest::mouseClick(undo, Qt::LeftButton);
    QVERIFY(w_->document()->project() == original);
    QTRY_VERIFY(!undo->isEnabled());
}

void NoLostWorkTest::theExportDialogOpensBesideTheProject() {
    QString opened;
    QTimer::singleShot(200, this, [&] {
        if (auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget())) {
            opened = dialog->directory().absolutePath() + "/" + dialog->selectedFiles().value(0).section('/', -1);
            dialog->reject();
        }
    });
    w_->action("export")->trigger();
    const QFileInfo project(project_);
    QCOMPARE(opened, project.dir().absolutePath() + "/" + project.completeBaseName() + ".png");
}

void NoLostWorkTest::hoveringAButtonLeavesTheStatusLineAndItsMessage() {
    QStatusBar* bar = w_->statusBar();
    auto* status = w_->findChild<QLabel*>("renderStatus");
    QVERIFY(status && status->isVisible());
    bar->showMessage("a message to read", 15000);
    // What hovering the toolbar's Move button and the File menu's first item sends.
    auto* toolbar = w_->findChild<QToolBar*>("toolbar");
    QWidget* move = toolbar->widgetForAction(w_->action("gizmoMove"));
    QTest::mouseMove(move);
    QStatusTipEvent tip(w_->action("gizmoMove")->toolTip());
    QApplication::sendEvent(move, &tip);
    QStatusTipEvent none(QString{});  // a menu item without a tip
    QApplication::sendEvent(w_->menuBar(), &none);
    QCOMPARE(bar->currentMessage(), QString("a message to read"));
    bar->clearMessage();
    QVERIFY(status->isVisible());
}

QTEST_MAIN(NoLostWorkTest)
#include "no_lost_work_test.moc"
