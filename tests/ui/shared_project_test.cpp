// Two studios on one project, each in its own process: a save over a file the other studio
// changed asks (Keep Mine, Take Theirs, Save As, Cancel) and each answer does what it says;
// each studio's recovery copy is its own, so a SIGKILL of one leaves its copy for the next start
// while a clean quit of the other deletes only its own.
#include <QAction>
#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileDialog>
#include <QLineEdit>
#include <QMessageBox>
#include <QProcess>
#include <QPushButton>
#include <QSocketNotifier>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QUndoStack>
#include <cstdio>
#include <functional>
#include <unistd.h>

#include "autosave.h"
#include "document.h"
#include "scene/project_io.h"
#include "ui_test_support.h"

using namespace dp;
using namespace dp::ui;

namespace {

/// Adds a sphere named `name`, as one undoable edit.
void add_named_sphere(MainWindow& w, const std::string& name) {
    w.action("addSphere")->trigger();
    Project p = w.document()->project();
    p.objects.back().name = name;
    w.document()->edit("name", p);
}

bool has_object(const Project& p, const std::string& name) {
    for (const VirtualObject& o : p.objects)
        if (o.name == name) return true;
    return false;
}

QByteArray bytes_of(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

/// Another studio process (this executable with --studio), driven by lines on its stdin; each
/// command is answered with one line on its stdout.
class OtherStudio {
public:
    OtherStudio(const QString& recovery, const QString& project, const QString& name) {
        process_.start(QCoreApplication::applicationFilePath(), {"--studio", recovery, project, name});
    }
    ~OtherStudio() {
        if (process_.state() != QProcess::NotRunning) {
            process_.kill();
            process_.waitForFinished();
        }
    }
    /// The next line starting with `prefix` (empty if none came within 30 s).
    QString waitFor(const QString& prefix) {
        QString found;
        (void)QTest::qWaitFor(
            [&] {
                process_.waitForReadyRead(20);
                buffer_ += process_.readAllStandardOutput();
                while (buffer_.contains('\n')) {
                    const qsizetype end = buffer_.indexOf('\n');
                    const QString line = QString::fromUtf8(buffer_.left(end));
                    buffer_.remove(0, end + 1);
                    if (line.startsWith(prefix)) {
                        found = line;
                        return true;
                    }
                }
                return false;
            },
            30000);
        return found;
    }
    QString command(const QString& line, const QString& answerPrefix) {
        process_.write((line + "\n").toUtf8());
        return waitFor(answerPrefix);
    }
    QProcess& process() { return process_; }

private:
    QProcess process_;
    QByteArray buffer_;
};

/// Answers the modal dialogs that show next, in order, each with its own action (a click, a
/// file name); records each one's text and buttons.
class DialogScript : public QObject {
public:
    using Action = std::function<void(QWidget*)>;
    explicit DialogScript(std::vector<Action> actions) : actions_(std::move(actions)) {
        connect(&timer_, &QTimer::timeout, this, [this] { poll(); });
        timer_.start(30);
    }
    QStringList texts, buttons;
    bool done() const { return next_ == actions_.size(); }

private:
    void poll() {
        QWidget* modal = QApplication::activeModalWidget();
        if (!modal || modal == last_ || done()) return;
        last_ = modal;
        if (auto* box = qobject_cast<QMessageBox*>(modal)) {
            texts << box->text();
            for (QAbstractButton* b : box->buttons()) buttons << b->text().remove('&');
        }
        actions_[next_++](modal);
    }
    std::vector<Action> actions_;
    size_t next_ = 0;
    QTimer timer_;
    QWidget* last_ = nullptr;
};

/// Clicks the message box's button labelled `text`, as a hand would.
DialogScript::Action click(const QString& text) {
    return [text](QWidget* w) {
        for (QAbstractButton* b : static_cast<QMessageBox*>(w)->buttons())
            if (b->text().remove('&') == text) QTest::mouseClick(b, Qt::LeftButton);
    };
}

/// Types `path` into the file dialog and presses Enter.
DialogScript::Action chooseFile(const QString& path) {
    return [path](QWidget* w) {
        auto* dialog = static_cast<QFileDialog*>(w);
        QLineEdit* name = dialog->findChild<QLineEdit*>("fileNameEdit");
        if (!name) return;
        name->setText(path);
        QTest::keyClick(name, Qt::Key_Return);
    };
}

}  // namespace

class SharedProjectTest : public QObject {
    Q_OBJECT
private Q_SLOTS:
    void aSaveOverTheOtherStudiosSaveAsksAndEachAnswerKeepsItsPromise();
    void aKilledStudiosCopyIsOfferedAndACleanQuitRemovesOnlyItsOwn();
};

void SharedProjectTest::aSaveOverTheOtherStudiosSaveAsksAndEachAnswerKeepsItsPromise() {
    QTemporaryDir dir;
    const QString project = test::write_small_sample(dir.path());
    OtherStudio other(dir.filePath("recovery-other"), project, "from the other studio");
    QVERIFY(!other.waitFor("ready").isEmpty());

    // No injected reporter: the real message boxes, answered by clicks.
    MainWindow w(test::test_options(nullptr, dir.filePath("recovery")));
    QVERIFY(test::show_and_open(w, project));
    add_named_sphere(w, "from this studio");
    QCOMPARE(other.command("save keep", "saved"), QString("saved 1 asked 0"));
    const QByteArray theirs = bytes_of(project);
    QVERIFY(has_object(load_project(project.toStdString()), "from the other studio"));

    {   // Cancel: nothing written, nothing lost.
        DialogScript script({click("Cancel")});
        QVERIFY(!w.saveProject());
        QVERIFY(script.done());
        QVERIFY2(script.texts.value(0).contains("changed on disk"), qPrintable(script.texts.join("|")));
        for (const char* b : {"Keep Mine", "Take Theirs", "Save As...", "Cancel"})
            QVERIFY2(script.buttons.contains(b), qPrintable(script.buttons.join(",")));
        QCOMPARE(bytes_of(project), theirs);
        QVERIFY(w.document()->isModified());
        QVERIFY(has_object(w.document()->project(), "from this studio"));
    }
    {   // Take Theirs: the file as it is, with this studio's edits one Undo away.
        DialogScript script({click("Take Theirs")});
        QVERIFY(w.saveProject());
        QVERIFY(script.done());
        QCOMPARE(bytes_of(project), theirs);
        QVERIFY(!w.document()->isModified());
        QVERIFY(has_object(w.document()->project(), "from the other studio"));
        QVERIFY(!has_object(w.document()->project(), "from this studio"));
        w.document()->undoStack()->undo();
        QVERIFY(has_object(w.document()->project(), "from this studio"));
        w.document()->undoStack()->redo();
    }
    // Now in step with the file: a save asks nothing, and then the other studio is the one
    // that asks, and keeps its own.
    add_named_sphere(w, "second edit here");
    QVERIFY(w.saveProject());
    QVERIFY(has_object(load_project(project.toStdString()), "second edit here"));
    QCOMPARE(other.command("save keep", "saved"), QString("saved 1 asked 1"));
    const Project kept = load_project(project.toStdString());
    QVERIFY(has_object(kept, "from the other studio") && !has_object(kept, "second edit here"));

    {   // Save As: both versions kept.
        add_named_sphere(w, "third edit here");
        const QByteArray before = bytes_of(project);
        const QString elsewhere = dir.filePath("mine.json");
        DialogScript script({click("Save As..."), chooseFile(elsewhere)});
        QVERIFY(w.saveProject());
        QVERIFY(script.done());
        QCOMPARE(bytes_of(project), before);
        QCOMPARE(w.document()->path(), elsewhere);
        QVERIFY(has_object(load_project(elsewhere.toStdString()), "third edit here"));
    }
    {   // Keep Mine: this studio's project replaces the file.
        QVERIFY(w.openProject(project));
        add_named_sphere(w, "fourth edit here");
        QCOMPARE(other.command("rename again", "saved"), QString("saved 1 asked 0"));
        DialogScript script({click("Keep Mine")});
        QVERIFY(w.saveProject());
        QVERIFY(script.done());
        QVERIFY(has_object(load_project(project.toStdString()), "fourth edit here"));
    }
}

void SharedProjectTest::aKilledStudiosCopyIsOfferedAndACleanQuitRemovesOnlyItsOwn() {
    QTemporaryDir dir;
    const QString project = test::write_small_sample(dir.path());
    const QString recovery = dir.filePath("recovery");  // shared by every studio here
    OtherStudio killed(recovery, project, "from the killed studio");
    OtherStudio quits(recovery, project, "from the studio that quits");
    OtherStudio idle(recovery, project, "never autosaved");  // killed before its first autosave
    QVERIFY(!killed.waitFor("ready").isEmpty() && !quits.waitFor("ready").isEmpty() &&
            !idle.waitFor("ready").isEmpty());
    const QString killedCopy = killed.command("autosave", "autosaved").section(' ', 1);
    const QString quitsCopy = quits.command("autosave", "autosaved").section(' ', 1);
    QVERIFY(QFile::exists(killedCopy) && QFile::exists(quitsCopy) && killedCopy != quitsCopy);

    killed.process().kill();  // SIGKILL: no clean close, only its copy is left
    QVERIFY(killed.process().waitForFinished());
    idle.process().kill();  // leaves a stale lock and no copy
    QVERIFY(idle.process().waitForFinished());
    QVERIFY(QFile::exists(killedCopy));

    // A new studio while the other still runs: offered the killed one's copy, and only that.
    RecordingReporter yes(true);
    MainWindow w(test::recovering_options(&yes, recovery));
    w.checkRecovery();
    QCOMPARE(yes.questions.size(), 1);
    QVERIFY(w.document()->isModified());
    QCOMPARE(w.document()->path(), project);
    QVERIFY(has_object(w.document()->project(), "from the killed studio"));
    QVERIFY(!has_object(w.document()->project(), "from the studio that quits"));
    QVERIFY(!QFile::exists(killedCopy));  // now this window's own copy
    QVERIFY(w.autosave()->ownCopy().has_value());
    QVERIFY(QFile::exists(quitsCopy));

    // A clean quit (Discard) of the other studio deletes its copy and no other.
    QCOMPARE(quits.command("quit", "closed"), QString("closed"));
    QVERIFY(quits.process().waitForFinished());
    QCOMPARE(quits.process().exitCode(), 0);
    QVERIFY(!QFile::exists(quitsCopy));
    QVERIFY(w.autosave()->ownCopy().has_value());

    // A third studio finds nothing to offer: the one copy left belongs to a running studio.
    RecordingReporter third(true);
    MainWindow w3(test::recovering_options(&third, recovery));
    w3.checkRecovery();
    QVERIFY2(third.questions.isEmpty(), qPrintable(third.questions.join("|")));
    QVERIFY(!w3.document()->isOpen());
    // Nothing left behind but the two running studios' locks: the killed ones' are gone.
    QCOMPARE(QDir(recovery).entryList({"*.lock"}, QDir::Files).size(), 2);
}

namespace {

/// The other studio: opens the project, adds a sphere named argv[4], says "ready", then obeys
/// "save keep|cancel", "rename again" (another edit, saved), "autosave" and "quit" (a clean
/// close that discards) from stdin.
int run_studio(int argc, char** argv) {
    QApplication app(argc, argv);
    RecordingReporter reporter(false);  // "save before closing?": discard
    MainWindow w(test::test_options(&reporter, argv[2]));
    if (!w.openProject(argv[3])) return 1;
    add_named_sphere(w, argv[4]);
    auto say = [](const QString& line) {
        std::printf("%s\n", qPrintable(line));
        std::fflush(stdout);
    };
    say("ready");
    QSocketNotifier input(STDIN_FILENO, QSocketNotifier::Read);
    QByteArray pending;
    QObject::connect(&input, &QSocketNotifier::activated, [&] {
        char chunk[256];
        const ssize_t n = ::read(STDIN_FILENO, chunk, sizeof chunk);
        if (n <= 0) return app.exit(1);
        pending.append(chunk, n);
        while (pending.contains('\n')) {
            const QString line = QString::fromUtf8(pending.left(pending.indexOf('\n')));
            pending.remove(0, pending.indexOf('\n') + 1);
            if (line == "rename again") add_named_sphere(w, "renamed again");
            if (line.startsWith("save") || line == "rename again") {
                reporter.conflictAnswer = line.endsWith("keep") ? ErrorReporter::ConflictChoice::KeepMine
                                                                : ErrorReporter::ConflictChoice::Cancel;
                const qsizetype asked = reporter.questions.size();
                const bool saved = w.saveProject();
                say(QString("saved %1 asked %2").arg(saved).arg(reporter.questions.size() - asked));
            } else if (line == "autosave") {
                w.autosave()->writeNow();
                say("autosaved " + w.autosave()->projectFile());
            } else if (line == "quit") {
                w.close();
                say("closed");
                app.quit();
            }
        }
    });
    return app.exec();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc == 5 && std::string(argv[1]) == "--studio") return run_studio(argc, argv);
    QApplication app(argc, argv);
    SharedProjectTest t;
    return QTest::qExec(&t, argc, argv);
}

#include "shared_project_test.moc"
