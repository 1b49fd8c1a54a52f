#include "new_project_dialog.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QMimeData>
#include <QPushButton>

namespace dp::ui {

namespace {

QWidget* with_browse(QLineEdit* edit, const QString& caption, const QString& filter) {
    auto* w = new QWidget;
    auto* row = new QHBoxLayout(w);
    row->setContentsMargins(0, 0, 0, 0);
    row->addWidget(edit, 1);
    auto* b = new QPushButton(QObject::tr("Browse..."));
    b->setToolTip(caption);
    row->addWidget(b);
    QObject::connect(b, &QPushButton::clicked, edit, [edit, caption, filter] {
        const QString f =
            QFileDialog::getOpenFileName(edit->window(), caption, edit->text(), filter);
        if (!f.isEmpty()) edit->setText(f);
    });
    return w;
}

}  // namespace

NewProjectDialog::NewProjectDialog(QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("New Project"));
    setAcceptDrops(true);
    auto* form = new QFormLayout(this);
    auto* hint =
        new QLabel(tr("Choose the photograph to augment and a light probe captured where "
                      "the objects will stand (or drop both files here)."));
    hint->setWordWrap(true);
    form->addRow(hint);
    photo_ = new QLineEdit;
    photo_->setToolTip(tr("The photograph (EXR, HDR, PNG, JPEG or TIFF)"));
    form->addRow(tr("Photograph"),
                 with_browse(photo_, tr("Open photograph"),
                             tr("Images (*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff)")));
    probe_ = new QLineEdit;
    probe_->setToolTip(tr("An HDR light probe (EXR or Radiance HDR)"));
    form->addRow(tr("Light probe"),
                 with_browse(probe_, tr("Open light probe"), tr("HDR images (*.exr *.hdr)")));
    format_ = new QComboBox;
    format_->addItems({tr("Lat-long (equirectangular)"), tr("Mirror ball")});
    format_->setToolTip(tr("How the probe image maps directions"));
    form->addRow(tr("Probe format"), format_);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    form->addRow(buttons);
}

QString NewProjectDialog::photoPath() const {
    return photo_->text();
}
QString NewProjectDialog::probePath() const {
    return probe_->text();
}
bool NewProjectDialog::mirrorBall() const {
    return format_->currentIndex() == 1;
}
void NewProjectDialog::setPhotoPath(const QString& path) {
    photo_->setText(path);
}
void NewProjectDialog::setProbePath(const QString& path) {
    probe_->setText(path);
}

void NewProjectDialog::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void NewProjectDialog::dropEvent(QDropEvent* e) {
    for (const QUrl& url : e->mimeData()->urls()) {
        const QString f = url.toLocalFile();
        // The first file dropped is the photo, the next the probe.
        if (photo_->text().isEmpty())
            photo_->setText(f);
        else
            probe_->setText(f);
    }
}

}  // namespace dp::ui
