#include "missing_files_dialog.h"

#include <QDialogButtonBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QGridLayout>
#include <QLabel>
#include <QPushButton>
#include <QScrollArea>
#include <QVBoxLayout>
#include <algorithm>

namespace dp::ui {

namespace fs = std::filesystem;

namespace {

QString native(const fs::path& p) {
    return QDir::toNativeSeparators(QString::fromStdString(p.string()));
}

}  // namespace

MissingFilesDialog::MissingFilesDialog(const Project& project, QWidget* parent)
    : QDialog(parent), baseDir_(project.base_dir) {
    setObjectName("missingFilesDialog");
    chooser_ = [](QWidget* p, const QString& caption, const QString& folder, const QString& name) {
        return QFileDialog::getOpenFileName(p, caption, QDir(folder).filePath(name),
                                            tr("%1;;All files (*)").arg(name));
    };
    for (InputFile& f : input_files(project)) {
        Row row;
        row.file = std::move(f);
        rows_.push_back(std::move(row));
    }
    const bool anyMissing =
        std::any_of(rows_.begin(), rows_.end(), [](const Row& r) { return r.file.missing; });
    setWindowTitle(anyMissing ? tr("Missing Files") : tr("Relink Files"));

    auto* layout = new QVBoxLayout(this);
    summary_ = new QLabel;
    summary_->setObjectName("missingSummary");
    summary_->setWordWrap(true);
    layout->addWidget(summary_);
    auto* table = new QWidget;
    auto* grid = new QGridLayout(table);
    grid->setColumnStretch(2, 1);
    const QStringList headers = {tr("File"), tr("Stored as"), tr("Now"), QString()};
    for (int c = 0; c < headers.size(); ++c)
        grid->addWidget(new QLabel(QStringLiteral("<b>%1</b>").arg(headers[c])), 0, c);
    for (int i = 0; i < rowCount(); ++i) {
        Row& row = rows_[size_t(i)];
        auto* what = new QLabel(QString::fromStdString(row.file.ref.what));
        what->setToolTip(QString::fromStdString(row.file.ref.field));
        auto* stored = new QLabel(QString::fromStdString(row.file.stored));
        stored->setToolTip(native(row.file.resolved));
        stored->setTextInteractionFlags(Qt::TextSelectableByMouse);
        row.status = new QLabel;
        row.status->setObjectName(QStringLiteral("status%1").arg(i));
        row.status->setTextInteractionFlags(Qt::TextSelectableByMouse);
        row.locate = new QPushButton(tr("Locate..."));
        row.locate->setObjectName(QStringLiteral("locate%1").arg(i));
        row.locate->setToolTip(
            tr("Choose the file; the other missing files are then looked for "
               "in its folder too"));
        connect(row.locate, &QPushButton::clicked, this, [this, i] { chooseFor(i); });
        grid->addWidget(what, i + 1, 0);
        grid->addWidget(stored, i + 1, 1);
        grid->addWidget(row.status, i + 1, 2);
        grid->addWidget(row.locate, i + 1, 3);
    }
    auto* scroll = new QScrollArea;
    scroll->setWidget(table);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    layout->addWidget(scroll, 1);
    note_ = new QLabel;
    note_->setObjectName("relinkNote");
    note_->setWordWrap(true);
    layout->addWidget(note_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    buttons->button(QDialogButtonBox::Ok)
        ->setToolTip(tr("Use the files found and located (one undoable edit)"));
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);

    folders_.push_back(baseDir_);
    search();
    resize(760, std::min(520, 180 + 34 * rowCount()));
}

QString MissingFilesDialog::field(int row) const {
    return QString::fromStdString(rows_.at(size_t(row)).file.ref.field);
}

QString MissingFilesDialog::what(int row) const {
    return QString::fromStdString(rows_.at(size_t(row)).file.ref.what);
}

QString MissingFilesDialog::storedPath(int row) const {
    return QString::fromStdString(rows_.at(size_t(row)).file.stored);
}

QString MissingFilesDialog::newPath(int row) const {
    return rows_.at(size_t(row)).newPath;
}

bool MissingFilesDialog::isMissing(int row) const {
    const Row& r = rows_.at(size_t(row));
    return r.file.missing && r.newPath.isEmpty();
}

int MissingFilesDialog::missingCount() const {
    int n = 0;
    for (int i = 0; i < rowCount(); ++i) n += isMissing(i);
    return n;
}

QPushButton* MissingFilesDialog::locateButton(int row) const {
    return rows_.at(size_t(row)).locate;
}

bool MissingFilesDialog::locate(int row, const QString& file) {
    const QFileInfo info(file);
    if (!info.isFile()) {
        note_->setText(
            tr("%1 is not a file: nothing was changed.").arg(QDir::toNativeSeparators(file)));
        return false;
    }
    Row& r = rows_.at(size_t(row));
    r.newPath = info.absoluteFilePath();
    r.byHand = true;
    note_->clear();
    // The folder the user pointed at is the likeliest home of the rest: searched first.
    const fs::path folder = fs::path(info.absolutePath().toStdString()).lexically_normal();
    folders_.erase(std::remove(folders_.begin(), folders_.end(), folder), folders_.end());
    folders_.insert(folders_.begin(), folder);
    search();
    return true;
}

void MissingFilesDialog::chooseFor(int row) {
    const Row& r = rows_.at(size_t(row));
    const QString name = QString::fromStdString(fs::path(r.file.stored).filename().string());
    const QString folder = QString::fromStdString(folders_.front().string());
    const QString file =
        chooser_(this, tr("Locate the %1 (%2)").arg(what(row), name), folder, name);
    if (!file.isEmpty()) locate(row, file);
}

void MissingFilesDialog::search() {
    for (Row& r : rows_) {
        // Files found earlier are found again: a folder located since comes first.
        if (r.file.missing && !r.byHand) {
            const std::string name = fs::path(r.file.stored).filename().string();
            const auto found = find_file_named(name, folders_);
            r.newPath = found ? QString::fromStdString(found->string()) : QString();
        }
        showRow(r);
    }
    showSummary();
}

void MissingFilesDialog::showRow(Row& r) {
    QString text, colour;
    if (!r.newPath.isEmpty()) {
        text = (r.byHand ? tr("located: %1") : tr("found: %1"))
                   .arg(QDir::toNativeSeparators(r.newPath));
        colour = QStringLiteral("#2e7d32");
    } else if (r.file.missing) {
        text = tr("missing");
        colour = QStringLiteral("#c62828");
    } else {
        text = tr("there");
    }
    r.status->setText(text);
    r.status->setToolTip(text);
    r.status->setStyleSheet(colour.isEmpty() ? QString() : QStringLiteral("color: %1").arg(colour));
}

void MissingFilesDialog::showSummary() {
    const int missing = missingCount();
    const bool changed =
        std::any_of(rows_.begin(), rows_.end(), [](const Row& r) { return !r.newPath.isEmpty(); });
    if (missing > 0)
        summary_->setText((missing == 1
                               ? tr("1 file the project reads cannot be found")
                               : tr("%1 files the project reads cannot be found").arg(missing)) +
                          tr(", and the render waits for them. Locate one: the others are then "
                             "looked for in its folder."));
    else if (changed)
        summary_->setText(tr("Every file is there. OK relinks the project to the files found."));
    else
        summary_->setText(
            tr("Every file the project reads is there. Locate... points one "
               "elsewhere."));
}

Project MissingFilesDialog::relinked(const Project& project) const {
    Project p = project;
    for (const Row& r : rows_)
        if (!r.newPath.isEmpty())
            set_input_path(p, r.file.ref.field,
                           path_for_project(project.base_dir, r.newPath.toStdString()));
    return p;
}

}  // namespace dp::ui
