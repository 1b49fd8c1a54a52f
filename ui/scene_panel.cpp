#include "scene_panel.h"

#include <QAction>
#include <QCheckBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include "document.h"
#include "number_field.h"
#include "placement.h"

namespace dp::ui {

ScenePanel::ScenePanel(Document* doc, const QList<QAction*>& actions, QWidget* parent)
    : QWidget(parent), doc_(doc) {
    auto* layout = new QVBoxLayout(this);
    list_ = new QListWidget;
    list_->setToolTip(tr("Virtual objects. Click to select, untick to hide."));
    layout->addWidget(list_, 1);

    auto* buttons = new QGridLayout;
    for (int i = 0; i < actions.size(); ++i) {
        auto* b = new QToolButton;
        b->setDefaultAction(actions[i]);
        b->setToolButtonStyle(Qt::ToolButtonTextOnly);
        b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        buttons->addWidget(b, i / 3, i % 3);
    }
    layout->addLayout(buttons);

    auto* form = new QFormLayout;
    name_ = new QLineEdit;
    name_->setToolTip(tr("Name of the selected object"));
    form->addRow(tr("Name"), name_);
    const char* rows[] = {"Position (m)", "Rotation (deg)", "Scale"};
    const char* tips[] = {"Position of the object's origin in world units (y is up)",
                          "Euler rotation in degrees, applied X then Y then Z",
                          "Scale along the object's local axes"};
    for (int r = 0; r < 3; ++r) {
        auto* row = new QHBoxLayout;
        for (int c = 0; c < 3; ++c) {
            auto* f = new NumberField;
            f->setDecimals(r == 1 ? 1 : 3);
            f->setRange(r == 2 ? 0.001 : -1e4, 1e4);
            f->setSingleStep(r == 1 ? 5.0 : 0.05);
            f->setKeyboardTracking(false);
            f->setToolTip(tr(tips[r]) + QStringLiteral(" (%1)").arg(QChar('x' + c)));
            fields_[r * 3 + c] = f;
            row->addWidget(f);
            connect(f, &NumberField::valueChanged, this, [this, i = r * 3 + c] { applyTransform(i); });
        }
        if (r == 2) {
            uniform_ = new QCheckBox(tr("Uniform"));
            uniform_->setObjectName("uniformScale");
            uniform_->setToolTip(tr("Editing one scale field scales all three alike"));
            row->addWidget(uniform_);
        }
        form->addRow(tr(rows[r]), row);
    }
    layout->addLayout(form);

    connect(list_, &QListWidget::currentRowChanged, this, [this](int row) {
        if (!refreshing_) doc_->select(row);
    });
    connect(list_, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
        if (!refreshing_) applyVisibility(list_->row(item), item->checkState() == Qt::Checked);
    });
    connect(name_, &QLineEdit::editingFinished, this, [this] {
        const int sel = doc_->selected();
        if (sel < 0 || refreshing_) return;
        Project p = doc_->project();
        if (p.objects[size_t(sel)].name == name_->text().toStdString()) return;
        p.objects[size_t(sel)].name = name_->text().toStdString();
        doc_->edit(tr("Rename object"), p);
    });
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    connect(doc_, &Document::selectionChanged, this, [this] { refresh(); });
    refresh();
}

void ScenePanel::refresh() {
    refreshing_ = true;
    const Project& p = doc_->project();
    if (list_->count() != int(p.objects.size())) {
        list_->clear();
        for (size_t i = 0; i < p.objects.size(); ++i) list_->addItem(QString());
    }
    for (size_t i = 0; i < p.objects.size(); ++i) {
        QListWidgetItem* item = list_->item(int(i));
        item->setText(QString::fromStdString(p.objects[i].name));
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(p.objects[i].visible ? Qt::Checked : Qt::Unchecked);
    }
    const int sel = doc_->selected();
    list_->setCurrentRow(sel);
    const bool has = sel >= 0;
    name_->setEnabled(has);
    for (NumberField* f : fields_) f->setEnabled(has);
    if (has) {
        const VirtualObject& o = p.objects[size_t(sel)];
        name_->setText(QString::fromStdString(o.name));
        const vec3* v[3] = {&o.transform.translation, &o.transform.rotation_deg,
                            &o.transform.scale};
        for (int i = 0; i < 9; ++i) {
            QSignalBlocker block(fields_[i]);
            fields_[i]->setValue((*v[i / 3])[i % 3]);
        }
    } else {
        name_->clear();
        for (int i = 0; i < 9; ++i) {  // neutral values, not the last selection's
            QSignalBlocker block(fields_[i]);
            fields_[i]->setValue(i < 6 ? 0.0 : 1.0);
        }
    }
    refreshing_ = false;
}

void ScenePanel::applyTransform(int index) {
    const int sel = doc_->selected();
    if (sel < 0 || refreshing_) return;
    Project p = doc_->project();
    Transform& t = p.objects[size_t(sel)].transform;
    vec3* v[3] = {&t.translation, &t.rotation_deg, &t.scale};
    const float value = float(fields_[index]->value());
    if (index >= 6 && uniform_->isChecked()) {
        const float k = value / t.scale[index - 6];  // the others by the same factor
        t.scale *= k;
        t.scale[index - 6] = value;  // exactly as typed
    } else {
        (*v[index / 3])[index % 3] = value;
    }
    if (index >= 6) t = kept_on_base(p, doc_->project().objects[size_t(sel)], t);
    doc_->tryEdit(tr("Transform %1").arg(QString::fromStdString(p.objects[size_t(sel)].name)), p);
}

void ScenePanel::applyVisibility(int row, bool visible) {
    Project p = doc_->project();
    if (row < 0 || row >= int(p.objects.size())) return;
    p.objects[size_t(row)].visible = visible;
    doc_->edit(visible ? tr("Show object") : tr("Hide object"), p);
}

}  // namespace dp::ui
