#include "scene_panel.h"

#include <QAction>
#include <QCheckBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QPainter>
#include <QPixmap>
#include <QToolButton>
#include <QVBoxLayout>

#include "document.h"
#include "number_field.h"
#include "placement.h"
#include "project_edit.h"

namespace dp::ui {

namespace {

/// A small glyph of the light's kind for the list: a bulb with rays, a cone, a square, a disk.
QIcon light_icon(VirtualLight::Kind kind) {
    QPixmap pm(16, 16);
    pm.fill(Qt::transparent);
    QPainter p(&pm);
    p.setRenderHint(QPainter::Antialiasing);
    p.setPen(QPen(QColor(230, 170, 20), 1.5));
    p.setBrush(QColor(255, 220, 90));
    switch (kind) {
        case VirtualLight::Kind::Point:
            p.drawEllipse(QPointF(8, 8), 3.5, 3.5);
            for (int i = 0; i < 8; ++i) {
                const double a = i * kPi / 4;
                p.drawLine(QPointF(8 + 5 * std::cos(a), 8 + 5 * std::sin(a)),
                           QPointF(8 + 7.5 * std::cos(a), 8 + 7.5 * std::sin(a)));
            }
            break;
        case VirtualLight::Kind::Spot:
            p.drawPolygon(QPolygonF({QPointF(8, 1.5), QPointF(2, 14), QPointF(14, 14)}));
            break;
        case VirtualLight::Kind::Rect:
            p.drawRect(QRectF(2.5, 4.5, 11, 7));
            break;
        case VirtualLight::Kind::Disk:
            p.drawEllipse(QPointF(8, 8), 6, 4);
            break;
    }
    return QIcon(pm);
}

}  // namespace

ScenePanel::ScenePanel(Document* doc, const QList<QAction*>& actions, QMenu* lightMenu,
                       QWidget* parent)
    : QWidget(parent), doc_(doc) {
    auto* layout = new QVBoxLayout(this);
    list_ = new QListWidget;
    list_->setToolTip(tr("Virtual objects, then lights. Click to select, untick to hide."));
    layout->addWidget(list_, 1);

    auto* buttons = new QGridLayout;
    for (int i = 0; i < actions.size(); ++i) {
        auto* b = new QToolButton;
        b->setDefaultAction(actions[i]);
        b->setToolButtonStyle(Qt::ToolButtonTextOnly);
        b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        buttons->addWidget(b, i / 3, i % 3);
    }
    if (lightMenu) {
        addLight_ = new QToolButton;
        addLight_->setObjectName("addLightButton");
        addLight_->setText(tr("Add Light"));
        addLight_->setToolTip(tr("Add a point, spot or area light above the view's centre"));
        addLight_->setMenu(lightMenu);
        addLight_->setPopupMode(QToolButton::InstantPopup);
        addLight_->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
        const int n = int(actions.size());
        buttons->addWidget(addLight_, n / 3, n % 3);
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
        if (refreshing_) return;
        const int objects = int(doc_->project().objects.size());
        if (row >= objects)
            doc_->selectLight(row - objects);
        else
            doc_->select(row);
    });
    connect(list_, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
        const int row = list_->row(item);
        if (!refreshing_ && row < int(doc_->project().objects.size()))
            applyVisibility(row, item->checkState() == Qt::Checked);
    });
    connect(name_, &QLineEdit::editingFinished, this, [this] { rename(); });
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    connect(doc_, &Document::selectionChanged, this, [this] { refresh(); });
    refresh();
}

int ScenePanel::lightRow(int i) const {
    return int(doc_->project().objects.size()) + i;
}

void ScenePanel::rename() {
    if (refreshing_) return;
    const std::string name = name_->text().toStdString();
    Project p = doc_->project();
    if (const int sel = doc_->selected(); sel >= 0) {
        if (p.objects[size_t(sel)].name == name) return;
        p.objects[size_t(sel)].name = name;
        doc_->edit(tr("Rename object"), p);
    } else if (const int light = doc_->selectedLight(); light >= 0) {
        if (p.lights[size_t(light)].name == name) return;
        p.lights[size_t(light)].name = name;
        doc_->edit(tr("Rename light"), p);
    }
}

void ScenePanel::refresh() {
    refreshing_ = true;
    const Project& p = doc_->project();
    const int objects = int(p.objects.size());
    if (list_->count() != objects + int(p.lights.size())) {
        list_->clear();
        for (int i = 0; i < objects + int(p.lights.size()); ++i) list_->addItem(QString());
    }
    for (int i = 0; i < objects; ++i) {
        QListWidgetItem* item = list_->item(i);
        item->setText(QString::fromStdString(p.objects[size_t(i)].name));
        item->setIcon(QIcon());
        item->setToolTip(QString());
        item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
        item->setCheckState(p.objects[size_t(i)].visible ? Qt::Checked : Qt::Unchecked);
    }
    for (size_t i = 0; i < p.lights.size(); ++i) {
        // A light has no hide tick: it is on while it is in the scene.
        QListWidgetItem* item = list_->item(objects + int(i));
        const VirtualLight& l = p.lights[i];
        item->setFlags(item->flags() & ~Qt::ItemIsUserCheckable);
        item->setData(Qt::CheckStateRole, QVariant());
        item->setText(QString::fromStdString(l.name));
        item->setIcon(light_icon(l.kind));
        item->setToolTip(tr("%1 light, %2 W").arg(tr(light_kind_label(l.kind))).arg(double(l.power_w)));
    }
    const int sel = doc_->selected(), light = doc_->selectedLight();
    list_->setCurrentRow(sel >= 0 ? sel : light >= 0 ? objects + light : -1);
    const bool has = sel >= 0 || light >= 0;
    name_->setEnabled(has);
    for (NumberField* f : fields_) f->setEnabled(has);
    if (light >= 0) {
        const VirtualLight& l = p.lights[size_t(light)];
        name_->setText(QString::fromStdString(l.name));
        // A point has no size or facing that its scale could change.
        const bool area = l.kind == VirtualLight::Kind::Rect || l.kind == VirtualLight::Kind::Disk;
        for (int i = 3; i < 9; ++i) fields_[i]->setEnabled(i < 6 ? l.kind != VirtualLight::Kind::Point : area);
        const vec3* v[3] = {&l.transform.translation, &l.transform.rotation_deg, &l.transform.scale};
        for (int i = 0; i < 9; ++i) {
            QSignalBlocker block(fields_[i]);
            fields_[i]->setValue((*v[i / 3])[i % 3]);
        }
    } else if (sel >= 0) {
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

void ScenePanel::applyLightTransform(int index) {
    const int light = doc_->selectedLight();
    if (light < 0 || refreshing_) return;
    Project p = doc_->project();
    VirtualLight& l = p.lights[size_t(light)];
    vec3* v[3] = {&l.transform.translation, &l.transform.rotation_deg, &l.transform.scale};
    const float value = float(fields_[index]->value());
    if (index >= 6 && uniform_->isChecked()) {
        l.transform.scale *= value / l.transform.scale[index - 6];
        l.transform.scale[index - 6] = value;
    } else {
        (*v[index / 3])[index % 3] = value;
    }
    doc_->tryEdit(tr("Transform %1").arg(QString::fromStdString(l.name)), p);
}

void ScenePanel::applyTransform(int index) {
    if (doc_->selectedLight() >= 0) {
        applyLightTransform(index);
        return;
    }
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
