#include "settings_panel.h"

#include <QFormLayout>
#include <QSignalBlocker>
#include <QSpinBox>

#include "document.h"
#include "number_field.h"

namespace dp::ui {

SettingsPanel::SettingsPanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    auto* form = new QFormLayout(this);
    photons_ = new QSpinBox;
    photons_->setRange(1000, 100000000);
    photons_->setSingleStep(50000);
    photons_->setGroupSeparatorShown(true);
    photons_->setToolTip(
        tr("Photons traced per pass: more means less noise per pass, slower passes"));
    form->addRow(tr("Photons per pass"), photons_);
    passes_ = new QSpinBox;
    passes_->setRange(1, 100000);
    passes_->setToolTip(
        tr("Passes of `diffphoton render` (ignored with a time budget); the studio refines until "
           "its noise target"));
    form->addRow(tr("Passes"), passes_);
    noise_ = new NumberField;
    noise_->setObjectName("noiseTarget");
    noise_->setRange(0, 50);
    noise_->setDecimals(2);
    noise_->setSingleStep(0.25);
    noise_->setSuffix(tr(" %"));
    noise_->setSpecialValueText(tr("invisible"));
    noise_->setToolTip(
        tr("The studio refines until the estimated noise of the changed pixels is below this; "
           "'invisible': below half an 8-bit step at the display exposure"));
    noise_->setKeyboardTracking(false);
    connect(noise_, &NumberField::valueChanged, this,
            [this](double v) { Q_EMIT noiseTargetChanged(v / 100.0); });
    form->addRow(tr("Stop at noise"), noise_);
    budget_ = new NumberField;
    budget_->setRange(0, 86400);
    budget_->setSuffix(tr(" s"));
    budget_->setSpecialValueText(tr("none (use passes)"));
    budget_->setToolTip(tr("Render for this many seconds instead of a number of passes"));
    form->addRow(tr("Time budget"), budget_);
    radius_ = new NumberField;
    radius_->setRange(0, 100);
    radius_->setDecimals(4);
    radius_->setSingleStep(0.005);
    radius_->setSpecialValueText(tr("automatic"));
    radius_->setToolTip(tr("Initial gather radius in world units; it shrinks with every pass"));
    form->addRow(tr("Initial radius"), radius_);
    seed_ = new QSpinBox;
    seed_->setRange(0, 1 << 30);
    seed_->setToolTip(tr("Random seed: the same seed and scene give the same image"));
    form->addRow(tr("Seed"), seed_);
    for (QSpinBox* s : {photons_, passes_, seed_}) {
        s->setKeyboardTracking(false);
        connect(s, &QSpinBox::valueChanged, this, [this] { apply(); });
    }
    for (NumberField* s : {budget_, radius_}) {
        s->setKeyboardTracking(false);
        connect(s, &NumberField::valueChanged, this, [this] { apply(); });
    }
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    refresh();
}

void SettingsPanel::setNoiseTarget(double relError) {
    QSignalBlocker block(noise_);
    noise_->setValue(relError * 100.0);
}

void SettingsPanel::refresh() {
    refreshing_ = true;
    const RenderSettings& r = doc_->project().render;
    photons_->setValue(int(std::min<int64_t>(r.photons_per_pass, photons_->maximum())));
    passes_->setValue(r.passes);
    budget_->setValue(r.time_budget_s);
    radius_->setValue(r.initial_radius ? double(*r.initial_radius) : 0.0);
    seed_->setValue(int(r.seed));
    refreshing_ = false;
}

void SettingsPanel::apply() {
    if (refreshing_) return;
    Project p = doc_->project();
    RenderSettings& r = p.render;
    r.photons_per_pass = photons_->value();
    r.passes = passes_->value();
    r.time_budget_s = budget_->value();
    if (radius_->value() > 0)
        r.initial_radius = float(radius_->value());
    else
        r.initial_radius.reset();
    r.seed = uint64_t(seed_->value());
    doc_->tryEdit(tr("Change render settings"), p);
}

}  // namespace dp::ui
