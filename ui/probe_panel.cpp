#include "probe_panel.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <algorithm>
#include <cmath>

#include "display.h"
#include "document.h"
#include "image/image_io.h"
#include "assets/scene_builder.h"
#include "stroke_slider.h"

namespace dp::ui {

namespace {

/// The exposure slider's position for `intensity`: tenths of a stop.
int exposure_ticks(float intensity) {
    const float stops = intensity > 0 ? std::log2(intensity) : -6.0f;
    return int(std::lround(stops * 10));
}

}  // namespace

ProbePanel::ProbePanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    auto* form = new QFormLayout(this);
    preview_ = new QLabel;
    preview_->setMinimumSize(256, 128);
    preview_->setAlignment(Qt::AlignCenter);
    preview_->setToolTip(
        tr("The light probe (lat-long); the ring marks its brightest point, the sun. Drag "
           "across it to turn the probe until the shadows fall as in the photo."));
    preview_->installEventFilter(this);
    form->addRow(preview_);
    auto slider = [&](const QString& label, const QString& tip, int lo, int hi, QLabel** value) {
        return add_stroke_slider(
            form, label, tip, lo, hi, 48, value, this,
            [this] {
                strokeKey_ = doc_->newMergeKey();
                Q_EMIT strokeStarted();
            },
            [this] {
                strokeKey_ = -1;
                Q_EMIT strokeFinished();
            },
            [this](QSlider*) { applySliders(); });
    };
    rotation_ = slider(tr("Rotation"), tr("Turn the probe about the vertical axis (degrees)"), -180,
                       180, &rotationValue_);
    // A probe shot with the camera not quite level, or a map with another horizon: tilt it.
    tiltX_ = slider(tr("Tilt (x)"), tr("Tilt the probe about the x axis (degrees)"), -90, 90, &tiltXValue_);
    tiltZ_ = slider(tr("Tilt (z)"), tr("Tilt the probe about the z axis (degrees)"), -90, 90, &tiltZValue_);
    tiltX_->setObjectName("probeTiltX");
    tiltZ_->setObjectName("probeTiltZ");
    exposure_ = slider(tr("Exposure"), tr("Probe brightness in stops (intensity 2^stops)"), -60, 60,
                       &exposureValue_);
    auto* balanceRow = new QWidget;
    auto* balance = new QHBoxLayout(balanceRow);
    balance->setContentsMargins(0, 0, 0, 0);
    whiteBalance_ = new QLabel;
    whiteBalance_->setObjectName("probeWhiteBalance");
    whiteBalance_->setToolTip(tr("Red, green and blue scale on the probe's light, matched to the "
                                 "photo by the grey card's \"Match colour too\""));
    balance->addWidget(whiteBalance_, 1);
    resetWhiteBalance_ = new QPushButton(tr("Reset"));
    resetWhiteBalance_->setObjectName("resetWhiteBalance");
    resetWhiteBalance_->setToolTip(tr("Light with the probe's own colours again"));
    connect(resetWhiteBalance_, &QPushButton::clicked, this, [this] { resetWhiteBalance(); });
    balance->addWidget(resetWhiteBalance_);
    form->addRow(tr("White balance"), balanceRow);
    maxWidth_ = new QSpinBox;
    maxWidth_->setObjectName("probeMaxWidth");
    maxWidth_->setRange(0, kMaxProbeMaxWidth);
    maxWidth_->setSingleStep(1024);
    maxWidth_->setSuffix(tr(" px"));
    maxWidth_->setSpecialValueText(tr("automatic"));
    maxWidth_->setKeyboardTracking(false);  // one edit (and one reload) per value, not per digit
    maxWidth_->setToolTip(tr("The widest the probe is kept: a wider one is shrunk on load with its light "
                             "kept. Automatic: 8192, less on a machine with little memory"));
    connect(maxWidth_, &QSpinBox::valueChanged, this, [this] { applyMaxWidth(); });
    form->addRow(tr("Max width"), maxWidth_);
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    refresh();
}

void ProbePanel::loadPreview() {
    const Project& p = doc_->project();
    // The probe as the renderer sees it: a mirror ball unwrapped with its field of view.
    const QString key = QString::fromStdString(p.resolve(p.probe.path).string()) + "|" +
                        QString::number(int(p.probe.format)) + "|" + QString::number(p.probe.mirror_ball_fov_deg) +
                        "|" + QString::number(p.probe.max_width);
    if (key == previewKey_) return;
    previewKey_ = key;
    previewImage_ = QImage();
    if (p.probe.path.empty()) return;
    try {
        const Image& probe = *doc_->assets().probe(p);
        const int w = 256, h = std::max(1, w * probe.height() / std::max(1, probe.width()));
        previewImage_ = to_display(resample(probe, w, h), 0.0f);
        // The brightest pixel stands for the sun: marked so it can be dragged into place.
        size_t brightest = 0;
        for (size_t i = 1; i < probe.size(); ++i)
            if (luminance(probe[i]) > luminance(probe[brightest])) brightest = i;
        sun_ = QPointF((double(brightest % size_t(probe.width())) + 0.5) / probe.width(),
                       (double(brightest / size_t(probe.width())) + 0.5) / probe.height());
    } catch (const std::exception&) {
        // The render reports unreadable probes; the preview just stays empty.
    }
}

void ProbePanel::refresh() {
    refreshing_ = true;
    loadPreview();
    const ProbeSpec& probe = doc_->project().probe;
    rotation_->setValue(int(std::lround(probe.rotation_deg.y)));
    tiltX_->setValue(int(std::lround(probe.rotation_deg.x)));
    tiltZ_->setValue(int(std::lround(probe.rotation_deg.z)));
    tiltXValue_->setText(QString::fromUtf8("%1\u00b0").arg(tiltX_->value()));
    tiltZValue_->setText(QString::fromUtf8("%1\u00b0").arg(tiltZ_->value()));
    exposure_->setValue(exposure_ticks(probe.intensity));
    rotationValue_->setText(QString::fromUtf8("%1\u00b0").arg(rotation_->value()));
    exposureValue_->setText(QString::number(exposure_->value() / 10.0, 'f', 1));
    const vec3 wb = probe.white_balance;
    const bool neutral = wb == vec3(1.0f);
    whiteBalance_->setText(neutral ? tr("neutral")
                                   : QStringLiteral("%1, %2, %3")
                                         .arg(double(wb.x), 0, 'f', 3)
                                         .arg(double(wb.y), 0, 'f', 3)
                                         .arg(double(wb.z), 0, 'f', 3));
    resetWhiteBalance_->setEnabled(!neutral);
    maxWidth_->setValue(probe.max_width);
    if (!previewImage_.isNull()) {
        // The probe's rotation turns the map: show it shifted by the same angle.
        QImage shown(previewImage_.size(), previewImage_.format());
        const int shift = int(std::lround(-probe.rotation_deg.y / 360.0 * shown.width()));
        QPainter painter(&shown);
        for (int k = -1; k <= 1; ++k)
            painter.drawImage(shift + k * shown.width(), 0, previewImage_);
        const double w = shown.width();
        const double x = std::fmod(sun_.x() * w + shift + 2 * w, w);
        painter.setRenderHint(QPainter::Antialiasing);
        painter.setPen(QPen(QColor(255, 200, 0), 2));
        painter.drawEllipse(QPointF(x, sun_.y() * shown.height()), 6, 6);
        preview_->setPixmap(QPixmap::fromImage(shown));
    } else {
        preview_->setText(tr("(no probe)"));
    }
    refreshing_ = false;
}

void ProbePanel::applySliders() {
    if (refreshing_) return;
    Project p = doc_->project();
    // Only what a slider changed: a fractional angle from a tool stays unless its slider moved.
    vec3& r = p.probe.rotation_deg;
    const QSlider* sliders[3] = {tiltX_, rotation_, tiltZ_};
    for (int k = 0; k < 3; ++k)
        if (sliders[k]->value() != int(std::lround(r[k]))) r[k] = float(sliders[k]->value());
    // Likewise the intensity: a grey card's exact figure stays while the probe is only turned.
    const int shown = std::clamp(exposure_ticks(p.probe.intensity), exposure_->minimum(),
                                 exposure_->maximum());
    if (exposure_->value() != shown)
        p.probe.intensity = std::exp2(float(exposure_->value()) / 10.0f);
    doc_->edit(tr("Adjust probe"), p, strokeKey_);
}

void ProbePanel::applyMaxWidth() {
    if (refreshing_) return;
    Project p = doc_->project();
    // Between "automatic" (0) and the narrowest width the format takes, the narrowest.
    const int value = maxWidth_->value();
    const int width = value == 0 ? 0 : std::max(value, kMinProbeMaxWidth);
    if (width == p.probe.max_width) return;
    p.probe.max_width = width;
    doc_->edit(tr("Set probe max width"), p);
}

void ProbePanel::resetWhiteBalance() {
    Project p = doc_->project();
    p.probe.white_balance = vec3(1.0f);
    doc_->edit(tr("Reset probe white balance"), p);
}

bool ProbePanel::eventFilter(QObject* watched, QEvent* event) {
    if (watched != preview_) return false;
    if (event->type() == QEvent::MouseButtonPress) {
        dragX_ = int(static_cast<QMouseEvent*>(event)->position().x());
        dragStartValue_ = rotation_->value();
        strokeKey_ = doc_->newMergeKey();
        Q_EMIT strokeStarted();
        return true;
    }
    if (event->type() == QEvent::MouseMove && strokeKey_ >= 0) {
        const int dx = int(static_cast<QMouseEvent*>(event)->position().x()) - dragX_;
        int v = dragStartValue_ - dx * 360 / std::max(1, preview_->width());
        v = ((v + 180) % 360 + 360) % 360 - 180;
        rotation_->setValue(v);
        return true;
    }
    if (event->type() == QEvent::MouseButtonRelease && strokeKey_ >= 0) {
        strokeKey_ = -1;
        Q_EMIT strokeFinished();
        return true;
    }
    return false;
}

}  // namespace dp::ui
