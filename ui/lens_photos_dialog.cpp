#include "lens_photos_dialog.h"

#include <QDialogButtonBox>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMimeData>
#include <QPushButton>
#include <QVBoxLayout>

namespace dp::ui {

LensPhotosDialog::LensPhotosDialog(QWidget* parent) : QDialog(parent) {
    setObjectName("lensPhotosDialog");
    setWindowTitle(tr("Lens from several photos"));
    setAcceptDrops(true);
    auto* layout = new QVBoxLayout(this);
    auto* hint = new QLabel(
        tr("Photos of the same chessboard taken with the same camera and zoom as the project's "
           "photo, which is used too: 10 or more, the board tilted different ways and in "
           "different parts of the frame. Drop files here or add them."));
    hint->setWordWrap(true);
    layout->addWidget(hint);
    list_ = new QListWidget;
    list_->setObjectName("lensPhotoList");
    list_->setSelectionMode(QAbstractItemView::ExtendedSelection);
    layout->addWidget(list_, 1);
    count_ = new QLabel;
    layout->addWidget(count_);
    auto* typed = new QHBoxLayout;
    path_ = new QLineEdit;
    path_->setObjectName("lensPhotoPath");
    path_->setPlaceholderText(tr("Path of a photo, then Enter"));
    auto* add = new QPushButton(tr("Add"));
    add->setObjectName("lensPhotoAdd");
    add->setToolTip(tr("Add the typed path to the list"));
    add->setAutoDefault(false);
    path_->installEventFilter(this);
    connect(add, &QPushButton::clicked, this, [this] { addTyped(); });
    typed->addWidget(path_, 1);
    typed->addWidget(add);
    layout->addLayout(typed);
    auto* row = new QHBoxLayout;
    auto* browse = new QPushButton(tr("Add files..."));
    browse->setObjectName("lensPhotoBrowse");
    browse->setAutoDefault(false);
    browse->setToolTip(tr("Choose photos of the board"));
    connect(browse, &QPushButton::clicked, this, [this] {
        addPhotos(QFileDialog::getOpenFileNames(
            this, tr("Photos of the chessboard"), QString(),
            tr("Images (*.exr *.hdr *.png *.jpg *.jpeg *.tif *.tiff)")));
    });
    auto* remove = new QPushButton(tr("Remove"));
    remove->setObjectName("lensPhotoRemove");
    remove->setAutoDefault(false);
    remove->setToolTip(tr("Take the selected photos out of the list"));
    connect(remove, &QPushButton::clicked, this, [this] {
        qDeleteAll(list_->selectedItems());
        updateCount();
    });
    row->addWidget(browse);
    row->addWidget(remove);
    row->addStretch(1);
    layout->addLayout(row);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    QPushButton* ok = buttons->button(QDialogButtonBox::Ok);
    ok->setText(tr("Calibrate"));
    ok->setObjectName("lensCalibrate");
    ok->setAutoDefault(false);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    layout->addWidget(buttons);
    updateCount();
}

QStringList LensPhotosDialog::photos() const {
    QStringList out;
    for (int i = 0; i < list_->count(); ++i) out << list_->item(i)->text();
    return out;
}

void LensPhotosDialog::addPhotos(const QStringList& paths) {
    const QStringList have = photos();
    for (const QString& p : paths)
        if (!p.isEmpty() && !have.contains(p) && list_->findItems(p, Qt::MatchExactly).isEmpty())
            list_->addItem(p);
    updateCount();
}

void LensPhotosDialog::addTyped() {
    addPhotos({path_->text().trimmed()});
    path_->clear();
}

void LensPhotosDialog::updateCount() {
    count_->setText(tr("%n photo(s) besides the project's", "", list_->count()));
}

bool LensPhotosDialog::eventFilter(QObject* watched, QEvent* e) {
    if (watched == path_ && e->type() == QEvent::KeyPress) {
        const int key = static_cast<QKeyEvent*>(e)->key();
        if (key == Qt::Key_Return || key == Qt::Key_Enter) {
            addTyped();
            return true;
        }
    }
    return QDialog::eventFilter(watched, e);
}

void LensPhotosDialog::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void LensPhotosDialog::dropEvent(QDropEvent* e) {
    QStringList files;
    for (const QUrl& url : e->mimeData()->urls()) files << url.toLocalFile();
    addPhotos(files);
}

}  // namespace dp::ui
