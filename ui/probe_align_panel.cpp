#include "probe_align_panel.h"

#include <QApplication>
#include <QCheckBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>
#include <cmath>
#include <filesystem>

#include "base/error.h"
#include "document.h"
#include "number_field.h"
#include "error_reporter.h"
#include "panel_widgets.h"
#include "photo_geometry.h"
#include "reconstruction/probe_align.h"
#include "reconstruction/sun_from_shadow.h"
#include "viewport.h"

namespace dp::ui {

ProbeAlignPanel::ProbeAlignPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter,
                                 QWidget* parent)
    : QWidget(parent), doc_(doc), viewport_(viewport), reporter_(reporter) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* sun = new QGroupBox(tr("Sun from a shadow"));
    auto* sunForm = new QFormLayout(sun);
    height_ = new NumberField;
    height_->setRange(0.001, 1000);
    height_->setDecimals(3);
    height_->setValue(0.5);
    height_->setSuffix(tr(" m"));
    height_->setObjectName("cueHeight");
    height_->setToolTip(tr("Height above the ground of the object point you click"));
    sunForm->addRow(tr("Point height"), height_);
    base_ = new QCheckBox(tr("Click its foot instead"));
    base_->setObjectName("cueBase");
    base_->setToolTip(tr("Click the ground point directly below the object point (e.g. the "
                         "foot of a pole) rather than the point itself"));
    sunForm->addRow(base_);
    auto* pickSun = new QPushButton(tr("Click point, then shadow tip"));
    pickSun->setObjectName("sunCue");
    pickSun->setToolTip(tr("Turn the probe so its sun casts the shadow seen in the photo"));
    connect(pickSun, &QPushButton::clicked, this, [this] { startPicking(Target::Sun); });
    sunForm->addRow(pickSun);
    layout->addWidget(sun);

    auto* strength = new QGroupBox(tr("Sun strength from a shadow"));
    auto* strengthLayout = new QVBoxLayout(strength);
    auto* pickStrength = new QPushButton(tr("Click a sunlit patch, then a shadowed one"));
    pickStrength->setObjectName("sunStrength");
    pickStrength->setToolTip(tr("Two patches of one surface, one in sunlight and one in shadow: the "
                                "probe's sun is scaled so that it gives them the photo's contrast "
                                "(for a probe whose sun was clipped when it was shot)"));
    connect(pickStrength, &QPushButton::clicked, this, [this] { startPicking(Target::SunStrength); });
    strengthLayout->addWidget(pickStrength);
    layout->addWidget(strength);

    auto* card = new QGroupBox(tr("Exposure and colour from a grey card"));
    auto* cardForm = new QFormLayout(card);
    reflectance_ = new NumberField;
    reflectance_->setRange(0.01, 1);
    reflectance_->setDecimals(3);
    reflectance_->setValue(0.18);
    reflectance_->setObjectName("cardReflectance");
    reflectance_->setToolTip(tr("The card's reflectance (0.18 for a standard grey card)"));
    cardForm->addRow(tr("Reflectance"), reflectance_);
    colour_ = new QCheckBox(tr("Match colour too"));
    colour_->setObjectName("cardColour");
    colour_->setToolTip(tr("Also set the probe's white balance so the card comes out as grey as "
                           "in the photo (for a probe shot with another camera or setting)"));
    cardForm->addRow(colour_);
    auto* pickCard = new QPushButton(tr("Drag over the card"));
    pickCard->setObjectName("greyCard");
    pickCard->setToolTip(tr("Drag a rectangle inside the card (it must lie on a real proxy)"));
    connect(pickCard, &QPushButton::clicked, this, [this] { startPicking(Target::Card); });
    cardForm->addRow(pickCard);
    layout->addWidget(card);
    status_ = new QLabel;
    status_->setWordWrap(true);
    status_->setObjectName("probeAlignStatus");
    layout->addWidget(status_);
    // The last project's result is not this one's.
    connect(doc_, &Document::reloaded, status_, &QLabel::clear);

    PickTool* pick = viewport_->pickTool();
    connect(pick, &PickTool::pointPicked, this, [this](QPointF p) {
        if (target_ != Target::Sun && target_ != Target::SunStrength) return;
        points_.push_back(p);
        const bool cue = target_ == Target::Sun;
        QVector<PickTool::Mark> marks;
        for (int i = 0; i < points_.size(); ++i)
            marks.push_back({points_[i], points_[i], false, QColor(255, 220, 60),
                             i == 0 ? (cue ? tr("object") : tr("sunlit")) : tr("shadow")});
        viewport_->pickTool()->setMarks(marks);
    });
    connect(pick, &PickTool::segmentDrawn, this, [this](QPointF a, QPointF b) {
        if (target_ == Target::Card) points_ = {a, b};
    });
    connect(pick, &PickTool::finished, this, [this](bool cancelled) {
        const Target t = target_;
        target_ = Target::None;
        if (t == Target::None) return;
        const QVector<QPointF> pts = points_;
        points_.clear();
        viewport_->pickTool()->setMarks({});
        if (cancelled || pts.size() != 2) return;
        if (t == Target::Sun) alignSun(pts[0], pts[1]);
        if (t == Target::Card) matchGreyCard(pts[0], pts[1]);
        if (t == Target::SunStrength) restoreSun(pts[0], pts[1]);
    });
}

void ProbeAlignPanel::startPicking(Target target) {
    target_ = Target::None;  // an unfinished run of ours is dropped, not applied
    points_.clear();
    viewport_->pickTool()->stop();
    viewport_->pickTool()->setMarks({});
    target_ = target;
    if (target == Target::Sun)
        viewport_->pickTool()->start(PickTool::Kind::Point, 2,
                                     tr("Click the object point, then the tip of its shadow"));
    else if (target == Target::SunStrength)
        viewport_->pickTool()->start(PickTool::Kind::Point, 2,
                                     tr("Click a sunlit patch, then a shadowed patch of the same surface"));
    else
        viewport_->pickTool()->start(PickTool::Kind::Segment, 1,
                                     tr("Drag from corner to corner inside the grey card"));
    viewport_->setFocus();
}

bool ProbeAlignPanel::guarded(const QString& title, const std::function<void()>& f) {
    return run_reporting_errors(reporter_, window(), title, f);
}

bool ProbeAlignPanel::alignSun(QPointF object, QPointF shadowTip) {
    return guarded(tr("Sun alignment failed"), [&] {
        Project p = doc_->project();
        const QSize ps = photo_size(doc_->assets(), p);
        ShadowCue cue;
        cue.object_px = render_to_photo(object, viewport_->renderSize(), ps);
        cue.shadow_px = render_to_photo(shadowTip, viewport_->renderSize(), ps);
        cue.height = float(height_->value());
        cue.object_is_base = base_->isChecked();
        const vec3 sun = sun_direction_from_shadow(photo_camera(doc_->assets(), p), cue);
        const vec3 bright = brightest_direction(*doc_->assets().probe(p));
        const ProbeYaw yaw = align_probe_yaw(bright, p.probe.rotation_deg, sun);
        p.probe.rotation_deg = yaw.rotation_deg;
        doc_->tryEdit(tr("Align probe to the shadow"), p);
        status_->setText(tr("Probe turned %1° about the vertical; sun elevation differs by %2°")
                             .arg(yaw.yaw_deg, 0, 'f', 1)
                             .arg(yaw.elevation_mismatch_deg, 0, 'f', 1));
    });
}

bool ProbeAlignPanel::matchGreyCard(QPointF a, QPointF b) {
    return guarded(tr("Grey card failed"), [&] {
        Project p = doc_->project();
        const QSize ps = photo_size(doc_->assets(), p);
        const vec2 pa = render_to_photo(a, viewport_->renderSize(), ps);
        const vec2 pb = render_to_photo(b, viewport_->renderSize(), ps);
        GreyCard card;
        card.x0 = int(std::lround(std::min(pa.x, pb.x)));
        card.y0 = int(std::lround(std::min(pa.y, pb.y)));
        card.x1 = int(std::lround(std::max(pa.x, pb.x)));
        card.y1 = int(std::lround(std::max(pa.y, pb.y)));
        card.reflectance = float(reflectance_->value());
        const float clip = doc_->assets().photo_clip_level(p);
        const bool colour = colour_->isChecked();
        ExposureMatch m;
        WhiteBalanceMatch wb;
        {
            const WaitCursor wait;
            const std::shared_ptr<RenderScene> scene = build_scene(doc_->assets(), p);
            if (colour)
                m = wb = match_white_balance_grey_card(*scene, card, clip);
            else
                m = match_exposure_grey_card(*scene, card, clip);
        }
        p.probe.intensity = m.intensity;
        QString text = tr("Probe intensity x%1").arg(m.scale, 0, 'f', 3);
        if (colour) {
            p.probe.white_balance = wb.white_balance;
            text += tr(", white balance %1, %2, %3")
                        .arg(wb.white_balance.x, 0, 'f', 3)
                        .arg(wb.white_balance.y, 0, 'f', 3)
                        .arg(wb.white_balance.z, 0, 'f', 3);
        }
        doc_->tryEdit(colour ? tr("Probe exposure and colour from the grey card")
                             : tr("Probe exposure from the grey card"),
                      p);
        status_->setText(text + tr(" (from %1 card pixels, spread %2)")
                                    .arg(m.pixels)
                                    .arg(m.spread, 0, 'f', 3));
    });
}

bool ProbeAlignPanel::restoreSun(QPointF lit, QPointF shadow) {
    return guarded(tr("Sun strength failed"), [&] {
        Project p = doc_->project();
        const QSize ps = photo_size(doc_->assets(), p);
        SunShadowPatches patches;
        patches.lit = render_to_photo(lit, viewport_->renderSize(), ps);
        patches.shadow = render_to_photo(shadow, viewport_->renderSize(), ps);
        SunFromShadow m;
        {
            const WaitCursor wait;
            m = match_sun_to_shadow(*build_scene(doc_->assets(), p), patches);
        }
        if (!(m.sun_scale <= kMaxSunScale))
            throw InputError("", "sun_from_shadow", tr("the sun would need more light than it can be given; is the "
                                                       "shadowed patch lit by the sky at all?").toStdString());
        p.probe.sun_scale = m.sun_scale;
        doc_->tryEdit(tr("Sun strength from the shadow"), p);
        status_->setText(tr("Sun x%1: the patches' contrast is %2 in the photo, the probe gave %3")
                             .arg(m.scale, 0, 'g', 4)
                             .arg(m.photo_contrast, 0, 'f', 2)
                             .arg(m.probe_contrast, 0, 'f', 2));
    });
}

}  // namespace dp::ui
