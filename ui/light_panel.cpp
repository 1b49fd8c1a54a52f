#include "light_panel.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <algorithm>
#include <cmath>

#include "document.h"
#include "number_field.h"
#include "panel_widgets.h"
#include "project_edit.h"

namespace dp::ui {

int LightPanel::powerToSlider(double watts) {
    if (!(watts > 0)) return 0;
    return std::clamp(int(std::lround(100.0 * (std::log10(watts) + 1.0))), 0, 800);
}

double LightPanel::sliderToPower(int position) {
    const double w = std::pow(10.0, position / 100.0 - 1.0);
    const double unit = std::pow(10.0, std::floor(std::log10(w)) - 2);  // three digits
    return std::round(w / unit) * unit;
}

LightPanel::LightPanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    form_ = new QFormLayout(this);
    form_->addRow(new QLabel(tr("<b>Light</b>")));
    kind_ = new QComboBox;
    kind_->setObjectName("lightKind");
    for (int k = 0; k < 4; ++k) kind_->addItem(tr(light_kind_label(VirtualLight::Kind(k))));
    kind_->setToolTip(tr("Point: a bulb; spot: a bulb cut to a cone; area: a glowing rectangle or "
                         "disk (softer shadows)"));
    form_->addRow(tr("Kind"), kind_);
    colour_ = make_named_button("lightColour", QString(), tr("Colour of the light: click to pick"));
    form_->addRow(tr("Colour"), colour_);

    power_ = make_number_field(0, kMaxLightPower, 100, 1, tr(" W"),
                               tr("Radiant power in watts, as Blender's lights have it"));
    power_->setObjectName("lightPower");
    power_->setKeyboardTracking(false);
    powerSlider_ = addSliderRow(tr("Power"), tr("Power, a tenfold step every fifth of the slider"),
                                0, 800, power_);
    angle_ = make_number_field(1, 180, 45, 1, tr(" deg"), tr("Full angle of the spot's cone"));
    angle_->setObjectName("spotAngle");
    angle_->setKeyboardTracking(false);
    angleSlider_ = addSliderRow(tr("Spot angle"), tr("Full angle of the spot's cone"), 1, 180, angle_);
    blendValue_ = new QLabel;
    blendValue_->setMinimumWidth(40);
    blend_ = addSliderRow(tr("Spot blend"),
                          tr("Soft share of the cone's edge: 0 a hard edge, 1 soft from the axis"), 0,
                          100, blendValue_);
    for (int i = 0; i < 2; ++i) {
        size_[i] = make_number_field(0.001, 1e4, 0.5, 3, tr(" m"),
                                     i == 0 ? tr("Width of the area light (its local x); a disk's diameter")
                                            : tr("Depth of the rectangle (its local z)"));
        size_[i]->setObjectName(i == 0 ? "lightSizeX" : "lightSizeZ");
        size_[i]->setKeyboardTracking(false);
        form_->addRow(i == 0 ? tr("Size") : tr("Depth"), size_[i]);
        connect(size_[i], &NumberField::valueChanged, this, [this, i] { fieldEdited(size_[i]); });
    }
    visible_ = new QCheckBox(tr("Visible to camera"));
    visible_->setObjectName("lightVisible");
    visible_->setToolTip(tr("The camera and mirrors see the area light's glowing face"));
    form_->addRow(QString(), visible_);

    connect(kind_, &QComboBox::currentIndexChanged, this, [this](int k) {
        editLight(tr("Light kind"), [k](VirtualLight& l) { l.kind = VirtualLight::Kind(k); });
    });
    connect(colour_, &QPushButton::clicked, this, [this] {
        const int sel = doc_->selectedLight();
        if (sel < 0) return;
        const QColor c = QColorDialog::getColor(to_qcolor(doc_->project().lights[size_t(sel)].colour),
                                                this, tr("Light colour"));
        setColour(c);
    });
    connect(power_, &NumberField::valueChanged, this, [this] { fieldEdited(power_); });
    connect(angle_, &NumberField::valueChanged, this, [this] { fieldEdited(angle_); });
    connect(visible_, &QCheckBox::toggled, this, [this](bool on) {
        editLight(on ? tr("Show light's face") : tr("Hide light's face"),
                  [on](VirtualLight& l) { l.visible = on; });
    });
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    connect(doc_, &Document::selectionChanged, this, [this] { refresh(); });
    refresh();
}

QSlider* LightPanel::addSliderRow(const QString& label, const QString& tip, int lo, int hi,
                                  QWidget* beside) {
    auto* s = new QSlider(Qt::Horizontal);
    s->setRange(lo, hi);
    s->setToolTip(tip);
    auto* row = new QWidget;
    auto* box = new QHBoxLayout(row);
    box->setContentsMargins(0, 0, 0, 0);
    box->addWidget(s, 1);
    box->addWidget(beside);
    form_->addRow(label, row);
    // Press and release bracket one undo step, as the material's sliders do.
    connect(s, &QSlider::sliderPressed, this, [this] {
        strokeKey_ = doc_->newMergeKey();
        Q_EMIT strokeStarted();
    });
    connect(s, &QSlider::sliderReleased, this, [this] {
        strokeKey_ = -1;
        Q_EMIT strokeFinished();
    });
    connect(s, &QSlider::valueChanged, this, [this, s] { sliderMoved(s); });
    return s;
}

template <class F>
void LightPanel::editLight(const QString& text, F change, int mergeKey, bool typed) {
    const int sel = doc_->selectedLight();
    if (refreshing_ || sel < 0) return;
    Project p = doc_->project();
    change(p.lights[size_t(sel)]);
    if (!typed) {
        doc_->edit(text, p, mergeKey);
    } else if (!doc_->tryEdit(text, p, mergeKey)) {
        refresh();
    }
}

void LightPanel::sliderMoved(QSlider* moved) {
    const int v = moved->value();
    if (moved == powerSlider_) {
        editLight(tr("Light power"), [v](VirtualLight& l) { l.power_w = float(sliderToPower(v)); },
                  strokeKey_);
    } else if (moved == angleSlider_) {
        editLight(tr("Spot angle"), [v](VirtualLight& l) { l.spot_angle_deg = float(v); }, strokeKey_);
    } else if (moved == blend_) {
        editLight(tr("Spot blend"), [v](VirtualLight& l) { l.spot_blend = float(v) / 100.0f; },
                  strokeKey_);
    }
}

void LightPanel::fieldEdited(NumberField* field) {
    const float v = float(field->value());
    if (field == power_) {
        editLight(tr("Light power"), [v](VirtualLight& l) { l.power_w = v; }, -1, true);
    } else if (field == angle_) {
        editLight(tr("Spot angle"), [v](VirtualLight& l) { l.spot_angle_deg = v; }, -1, true);
    } else {
        const int i = field == size_[0] ? 0 : 1;
        editLight(tr("Light size"), [v, i](VirtualLight& l) { l.size[i] = v; }, -1, true);
    }
}

void LightPanel::setColour(const QColor& colour) {
    if (!colour.isValid()) return;
    const vec3 c = to_linear(colour);
    editLight(tr("Light colour"), [c](VirtualLight& l) { l.colour = c; });
}

void LightPanel::refresh() {
    const int sel = doc_->selectedLight();
    setVisible(sel >= 0);
    if (sel < 0) return;
    refreshing_ = true;
    const VirtualLight& l = doc_->project().lights[size_t(sel)];
    const bool spot = l.kind == VirtualLight::Kind::Spot;
    const bool rect = l.kind == VirtualLight::Kind::Rect;
    const bool area = rect || l.kind == VirtualLight::Kind::Disk;
    kind_->setCurrentIndex(int(l.kind));
    paint_swatch(colour_, to_qcolor(l.colour));
    power_->setValue(double(l.power_w));
    powerSlider_->setValue(powerToSlider(l.power_w));
    angle_->setValue(double(l.spot_angle_deg));
    angleSlider_->setValue(int(std::lround(l.spot_angle_deg)));
    blend_->setValue(int(std::lround(l.spot_blend * 100)));
    blendValue_->setText(QString::number(double(l.spot_blend), 'f', 2));
    for (int i = 0; i < 2; ++i) size_[i]->setValue(double(l.size[i]));
    visible_->setChecked(l.visible);
    form_->setRowVisible(angleSlider_->parentWidget(), spot);
    form_->setRowVisible(blend_->parentWidget(), spot);
    form_->setRowVisible(size_[0], area);
    form_->setRowVisible(size_[1], rect);
    form_->setRowVisible(visible_, area);
    if (auto* label = qobject_cast<QLabel*>(form_->labelForField(size_[0])))
        label->setText(rect ? tr("Width") : tr("Diameter"));
    refreshing_ = false;
}

}  // namespace dp::ui
