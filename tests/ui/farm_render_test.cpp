// File > Render on Farm... as a person uses it: the dialog's fields typed, Render clicked, the
// progress counted shard by shard while the studio keeps answering, the merged image shown and
// equal to one process's render byte for byte; and a render cancelled, nothing written.
#include <QAction>
#include <QElapsedTimer>
#include <QFile>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QProcess>
#include <QPushButton>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>

#include "document.h"
#include "farm_dialog.h"
#include "image/image_io.h"
#include "main_window.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

class FarmRenderTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void initTestCase() { qputenv("DIFFPHOTON", DP_CLI); }
    void aRenderOnTheFarmIsShownAndEqualsOneProcesssRender();
    void aCancelledRenderWritesNothing();

private:
    /// Opens the small sample in `w`, then File > Render on Farm... with `passes`, `shard` and
    /// the merged image `out` typed in; the dialog in `d`.
    static void openDialog(MainWindow& w, const QTemporaryDir& dir, const QString& passes, const QString& shard,
                           const QString& out, FarmDialog*& d) {
        QVERIFY(test::show_and_open(w, test::write_small_sample(dir.path(), 4000, 4)));
        w.action("renderOnFarm")->trigger();
        d = w.farmDialog();
        QVERIFY(QTest::qWaitForWindowExposed(d));
        type(d, "farmPasses", passes);
        type(d, "farmShard", shard);
        type(d, "farmOutput", out);
    }
    /// Types `text` into the field named `name` of `d` as a person would.
    static void type(QWidget* d, const char* name, const QString& text) {
        QWidget* field = d->findChild<QWidget*>(name);
        QVERIFY(field);
        field->setFocus();
        if (auto* spin = qobject_cast<QSpinBox*>(field)) spin->selectAll();
        if (auto* line = qobject_cast<QLineEdit*>(field)) line->selectAll();
        QTest::keyClicks(field, text);
        QTest::keyClick(field, Qt::Key_Tab);
    }
};

void FarmRenderTest::aRenderOnTheFarmIsShownAndEqualsOneProcesssRender() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    const QString out = dir.filePath("farm.exr");
    FarmDialog* d = nullptr;
    openDialog(w, dir, "6", "2", out, d);
    QVERIFY(d);

    // The studio answers while the farm works: a timer's ticks are never held up long.
    QElapsedTimer clock;
    qint64 last = 0, worst = 0;
    QTimer tick;
    QObject::connect(&tick, &QTimer::timeout, [&] {
        worst = std::max(worst, clock.elapsed() - last);
        last = clock.elapsed();
    });
    QList<int> seen;
    QObject::connect(d->findChild<QProgressBar*>("farmProgress"), &QProgressBar::valueChanged,
                     [&](int v) { seen << v; });
    bool written = false, ended = false;
    QObject::connect(d, &FarmDialog::ended, [&](bool ok) { ended = true, written = ok; });
    clock.start();
    tick.start(20);
    QTest::mouseClick(d->findChild<QPushButton*>("farmStart"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(ended, 180000);
    tick.stop();
    const QString status = d->findChild<QLabel*>("farmStatus")->text();
    qInfo("farm: %s; progress values %s; longest gap between 20 ms ticks %lld ms", qPrintable(status),
          qPrintable([&] {
              QStringList s;
              for (int v : seen) s << QString::number(v);
              return s.join(',');
          }()),
          worst);
    QVERIFY2(written, qPrintable(status));
    QCOMPARE(d->shardsTotal(), 3);
    QCOMPARE(d->shardsDone(), 3);
    QVERIFY(seen.contains(1) && seen.contains(2) && seen.contains(3));  // shard by shard
    QVERIFY2(worst < 500, qPrintable(QString("the studio stalled %1 ms").arg(worst)));

    // The image shown is the merged file's, and the file is one process's render to the byte.
    QVERIFY(!d->preview().isNull());
    const Image merged = load_image(out.toStdString(), "farm");
    QCOMPARE(d->preview().width(), merged.width());
    const QString single = dir.filePath("single.exr");
    QProcess cli;
    cli.start(DP_CLI, {"render", w.document()->path(), "--passes", "6", "--adaptive", "off", "-o", single});
    QVERIFY(cli.waitForFinished(120000));
    QCOMPARE(cli.exitCode(), 0);
    QFile a(out), b(single);
    QVERIFY(a.open(QIODevice::ReadOnly) && b.open(QIODevice::ReadOnly));
    QVERIFY2(a.readAll() == b.readAll(), "the farm's merge differs from one process's render");
    QVERIFY2(reporter.errors.isEmpty(), qPrintable(reporter.errors.join("\n")));
    w.document()->undoStack()->setClean();
}

void FarmRenderTest::aCancelledRenderWritesNothing() {
    QTemporaryDir dir;
    RecordingReporter reporter(false);
    MainWindow w(test::test_options(&reporter, dir.filePath("recovery")));
    const QString out = dir.filePath("cancelled.exr");
    FarmDialog* d = nullptr;
    openDialog(w, dir, "400", "2", out, d);
    QVERIFY(d);
    bool ended = false, written = true;
    QObject::connect(d, &FarmDialog::ended, [&](bool ok) { ended = true, written = ok; });
    QTest::mouseClick(d->findChild<QPushButton*>("farmStart"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(d->shardsDone() >= 1, 120000);  // under way
    QTest::mouseClick(d->findChild<QPushButton*>("farmCancel"), Qt::LeftButton);
    QTRY_VERIFY_WITH_TIMEOUT(ended, 30000);
    QVERIFY(!written);
    QVERIFY(!d->running());
    QVERIFY(!QFile::exists(out));
    QVERIFY(d->findChild<QLabel*>("farmStatus")->text().startsWith("Cancelled"));
    QVERIFY(d->findChild<QPushButton*>("farmStart")->isEnabled());
    w.document()->undoStack()->setClean();
}

QTEST_MAIN(FarmRenderTest)
#include "farm_render_test.moc"
