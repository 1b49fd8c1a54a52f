#include "calibration_panel.h"

#include <cmath>

#include <algorithm>

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QStackedWidget>
#include <QVBoxLayout>

#include "base/error.h"
#include "calibration/correspondences.h"
#include "calibration/vanishing.h"
#include "camera_panel.h"
#include "document.h"
#include "number_field.h"
#include "panel_widgets.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "project_edit.h"
#include "reconstruction/proxies.h"
#include "viewport.h"

namespace dp::ui {

namespace {

const QColor kAxisColour[3] = {QColor(240, 70, 70), QColor(70, 220, 70), QColor(80, 140, 255)};

}  // namespace

CalibrationPanel::CalibrationPanel(Document* doc, Viewport* viewport, CameraPanel* camera,
                                   ErrorReporter* reporter, QWidget* parent)
    : QWidget(parent), doc_(doc), viewport_(viewport), camera_(camera), reporter_(reporter) {
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    method_ = new QComboBox;
    method_->setObjectName("calibrationMethod");
    method_->addItems({tr("Chessboard (auto-detect)"), tr("Known rectangle (click corners)"),
                       tr("Vanishing lines (draw)")});
    method_->setToolTip(tr("How to match the camera to the photo"));
    pages_ = new QStackedWidget;
    pages_->addWidget(makeChessboardPage());
    pages_->addWidget(makeRectanglePage());
    pages_->addWidget(makeVanishingPage());
    connect(method_, &QComboBox::currentIndexChanged, this, [this](int i) {
        if (target_ != Target::None) viewport_->pickTool()->stop();
        pages_->setCurrentIndex(i);
        refreshMarks();
    });
    layout->addWidget(method_);
    layout->addWidget(pages_);
    QPushButton* ground = make_named_button("addGroundPlane", tr("Add ground plane"),
                                 tr("Add the ground (y = 0) as a real proxy, sized to what "
                                    "the matched camera sees of it"));
    connect(ground, &QPushButton::clicked, this, [this] { addGroundPlane(); });
    layout->addWidget(ground);
    status_ = new QLabel;
    status_->setObjectName("calibrationStatus");
    status_->setWordWrap(true);
    layout->addWidget(status_);

    PickTool* pick = viewport_->pickTool();
    connect(pick, &PickTool::pointPicked, this, [this](QPointF p) { onPoint(p); });
    connect(pick, &PickTool::segmentDrawn, this, [this](QPointF a, QPointF b) { onSegment(a, b); });
    connect(pick, &PickTool::finished, this, [this](bool cancelled) {
        if (target_ == Target::None) return;  // another tool's run
        // Esc drops an unfinished set of corners; drawn lines stay (each is complete).
        if (cancelled && target_ == Target::Corners && corners_.size() < 4) corners_.clear();
        target_ = Target::None;
        refreshMarks();
    });
    connect(doc_, &Document::reloaded, this, [this] {
        boardOrigin_.reset();
        boardFit_.reset();
        clearPicks();
        status_->clear();  // the last project's result is not this one's
    });
    setMethod(Method::Rectangle);
}

void CalibrationPanel::setMethod(Method m) {
    method_->setCurrentIndex(int(m));
}

QWidget* CalibrationPanel::makeRectanglePage() {
    auto* page = new QWidget;
    auto* form = new QFormLayout(page);
    rectWidth_ = make_number_field(0.001, 1000, 0.297, 3, tr(" m"), tr("Length of the edge from corner 1 to 2"));
    rectHeight_ = make_number_field(0.001, 1000, 0.210, 3, tr(" m"), tr("Length of the edge from corner 2 to 3"));
    rectFocal_ = make_number_field(0, 1e5, 0, 1, tr(" px"),
                      tr("Focal length in pixels of the photo; 0 estimates it from the "
                         "rectangle's perspective (it must be seen at an angle)"));
    rectFocal_->setSpecialValueText(tr("estimate"));
    rectWidth_->setObjectName("rectangleWidth");
    rectHeight_->setObjectName("rectangleHeight");
    rectFocal_->setObjectName("rectangleFocal");
    form->addRow(tr("Width"), rectWidth_);
    form->addRow(tr("Height"), rectHeight_);
    form->addRow(tr("Focal length"), rectFocal_);
    auto* row = new QHBoxLayout;
    QPushButton* pick = make_named_button("rectanglePick", tr("Click corners"),
                               tr("Click the rectangle's four corners in the photo, in order "
                                  "around it; corner 1 becomes the world origin"));
    QPushButton* apply = make_named_button("rectangleApply", tr("Apply"),
                                tr("Match the camera to the clicked corners"));
    connect(pick, &QPushButton::clicked, this, [this] { startPicking(Target::Corners); });
    connect(apply, &QPushButton::clicked, this, [this] { applyRectangle(); });
    row->addWidget(pick);
    row->addWidget(apply);
    form->addRow(row);
    cornerCount_ = new QLabel;
    form->addRow(cornerCount_);
    return page;
}

QWidget* CalibrationPanel::makeVanishingPage() {
    auto* page = new QWidget;
    auto* form = new QFormLayout(page);
    const char* names[3] = {"vanishingX", "vanishingY", "vanishingZ"};
    const QString texts[3] = {tr("X lines"), tr("Vertical"), tr("Z lines")};
    const QString tips[3] = {
        tr("Drag two or more segments along one ground direction (world X)"),
        tr("Drag two or more segments along vertical edges (world Y)"),
        tr("Drag two or more segments along the ground direction at right angles to X")};
    auto* row = new QHBoxLayout;
    for (int axis : {0, 2, 1}) {
        QPushButton* b = make_named_button(names[axis], texts[axis], tips[axis]);
        b->setStyleSheet(QStringLiteral("color: %1").arg(kAxisColour[axis].name()));
        connect(b, &QPushButton::clicked, this, [this, axis] {
            startPicking(axis == 0 ? Target::X : axis == 1 ? Target::Y : Target::Z);
        });
        row->addWidget(b);
    }
    form->addRow(row);
    auto* row2 = new QHBoxLayout;
    QPushButton* origin = make_named_button("vanishingOrigin", tr("Click origin"),
                                 tr("Click a point on the ground: the world origin"));
    QPushButton* clear = make_named_button("vanishingClear", tr("Clear"), tr("Remove the drawn lines"));
    connect(origin, &QPushButton::clicked, this, [this] { startPicking(Target::Origin); });
    connect(clear, &QPushButton::clicked, this, [this] { clearPicks(); });
    row2->addWidget(origin);
    row2->addWidget(clear);
    form->addRow(row2);
    auto* row3 = new QHBoxLayout;
    detectButton_ = make_named_button("vanishingDetect", tr("Detect lines"),
                                      tr("Find the photo's lines and propose them as X, Z and vertical lines with an "
                                         "origin; drop the wrong ones, add missing ones, then Apply"));
    QPushButton* drop = make_named_button("vanishingDrop", tr("Drop lines"),
                                          tr("Click drawn lines to remove them (Esc ends)"));
    connect(detectButton_, &QPushButton::clicked, this, [this] { detectLines(); });
    connect(drop, &QPushButton::clicked, this, [this] { startPicking(Target::Drop); });
    row3->addWidget(detectButton_);
    row3->addWidget(drop);
    form->addRow(row3);
    cameraHeight_ = make_number_field(0.01, 1000, 1.6, 3, tr(" m"), tr("Camera height above the ground (scale)"));
    cameraHeight_->setObjectName("vanishingHeight");
    form->addRow(tr("Camera height"), cameraHeight_);
    distance_ = make_number_field(0, 1e4, 0, 3, tr(" m"),
                     tr("Scale from a known distance between two ground points instead of the "
                        "camera height (0: use the camera height)"));
    distance_->setSpecialValueText(tr("use camera height"));
    distance_->setObjectName("vanishingDistance");
    QPushButton* ends = make_named_button("vanishingDistanceEnds", tr("Click ends"),
                               tr("Click the two ground points the known distance separates"));
    connect(ends, &QPushButton::clicked, this, [this] { startPicking(Target::Distance); });
    auto* distRow = new QHBoxLayout;
    distRow->addWidget(distance_, 1);
    distRow->addWidget(ends);
    form->addRow(tr("Or distance"), distRow);
    vertical_ = make_number_field(0, 1e4, 0, 3, tr(" m"),
                     tr("Scale from a known vertical length (a box edge, a door frame, a "
                        "person) instead of the camera height (0: not used)"));
    vertical_->setSpecialValueText(tr("not used"));
    vertical_->setObjectName("vanishingVertical");
    QPushButton* footTop = make_named_button("vanishingVerticalEnds", tr("Click foot, top"),
                                  tr("Click the vertical length's foot on the ground, then its "
                                     "top straight above it"));
    connect(footTop, &QPushButton::clicked, this, [this] { startPicking(Target::Vertical); });
    auto* vertRow = new QHBoxLayout;
    vertRow->addWidget(vertical_, 1);
    vertRow->addWidget(footTop);
    form->addRow(tr("Or vertical"), vertRow);
    freePrincipal_ = new QCheckBox(tr("Estimate the principal point"));
    freePrincipal_->setObjectName("vanishingFreePrincipal");
    freePrincipal_->setToolTip(tr("Needs lines along all three directions that pin it down; "
                                  "otherwise it stays at the image centre"));
    form->addRow(freePrincipal_);
    vanFocal_ = make_number_field(0, 1e5, 0, 1, tr(" px"),
                     tr("Focal length in pixels; 0 takes it from two vanishing points"));
    vanFocal_->setSpecialValueText(tr("from the lines"));
    vanFocal_->setObjectName("vanishingFocal");
    form->addRow(tr("Focal length"), vanFocal_);
    QPushButton* apply = make_named_button("vanishingApply", tr("Apply"),
                                tr("Match the camera to the drawn lines"));
    connect(apply, &QPushButton::clicked, this, [this] { applyVanishing(); });
    form->addRow(apply);
    lineCount_ = new QLabel;
    form->addRow(lineCount_);
    return page;
}

void CalibrationPanel::startPicking(Target target) {
    PickTool* pick = viewport_->pickTool();
    pick->stop();
    target_ = target;
    switch (target) {
        case Target::Corners:
            corners_.clear();
            pick->start(PickTool::Kind::Point, 4,
                        tr("Click the rectangle's 4 corners in order around it"));
            break;
        case Target::Origin:
            origin_.clear();
            pick->start(PickTool::Kind::Point, 1, tr("Click the world origin on the ground"));
            break;
        case Target::Distance:
            distanceEnds_.clear();
            pick->start(PickTool::Kind::Point, 2,
                        tr("Click the two ground points of the known distance"));
            break;
        case Target::Vertical:
            verticalEnds_.clear();
            pick->start(PickTool::Kind::Point, 2,
                        tr("Click the vertical length's foot on the ground, then its top"));
            break;
        case Target::BoardFoot:
            pick->start(PickTool::Kind::Point, 1,
                        tr("Click a point of the board that touches the floor (a corner on its lower edge)"));
            break;
        case Target::Drop:
            pick->start(PickTool::Kind::Point, 0, tr("Click the lines to drop; Esc ends"));
            break;
        case Target::Horizon:
            horizon_.clear();
            pick->start(PickTool::Kind::Segment, 1,
                        tr("Drag along the horizon, as far across the photo as it shows"));
            break;
        case Target::X:
        case Target::Y:
        case Target::Z:
            pick->start(PickTool::Kind::Segment, 0,
                        tr("Drag segments along %1 edges")
                            .arg(target == Target::X   ? tr("X")
                                 : target == Target::Y ? tr("vertical")
                                                       : tr("Z")));
            break;
        case Target::None:
            break;
    }
    viewport_->setFocus();
    refreshMarks();
}

void CalibrationPanel::onPoint(QPointF px) {
    if (target_ == Target::Corners) corners_.push_back(px);
    if (target_ == Target::Origin) origin_ = {px};
    if (target_ == Target::Distance) distanceEnds_.push_back(px);
    if (target_ == Target::Vertical) verticalEnds_.push_back(px);
    if (target_ == Target::BoardFoot) boardHeightFromClick(px);
    if (target_ == Target::Drop) dropLineNear(px);
    refreshMarks();
}

void CalibrationPanel::onSegment(QPointF a, QPointF b) {
    const int axis = target_ == Target::X ? 0 : target_ == Target::Y ? 1 : target_ == Target::Z ? 2 : -1;
    if (axis >= 0) lines_[axis].push_back({a, b});
    if (target_ == Target::Horizon) horizon_ = {a, b};
    refreshMarks();
}

void CalibrationPanel::clearPicks() {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    corners_.clear();
    origin_.clear();
    distanceEnds_.clear();
    verticalEnds_.clear();
    horizon_.clear();
    for (auto& l : lines_) l.clear();
    refreshMarks();
}

void CalibrationPanel::refreshMarks() {
    QVector<PickTool::Mark> marks;
    const int page = method_->currentIndex();
    if (page == int(Method::Chessboard)) {
        if (horizon_.size() == 2)
            marks.push_back({horizon_[0], horizon_[1], true, QColor(120, 200, 255), tr("horizon")});
        if (boardOrigin_ && viewport_->renderSize().isValid() && !boardPhoto_.isEmpty()) {
            const QPointF o = toRender(*boardOrigin_, boardPhoto_);
            marks.push_back({o, o, false, QColor(255, 255, 255), "O"});
        }
    } else if (page == int(Method::Rectangle)) {
        for (int i = 0; i < corners_.size(); ++i)
            marks.push_back({corners_[i], corners_[i], false, QColor(255, 200, 0),
                             QString::number(i + 1)});
    } else if (page == int(Method::Vanishing)) {
        static const char* axis[3] = {"X", "Y", "Z"};
        for (int a = 0; a < 3; ++a)
            for (const auto& s : lines_[a])
                marks.push_back({s.first, s.second, true, kAxisColour[a], axis[a]});
        for (QPointF o : origin_) marks.push_back({o, o, false, QColor(255, 255, 255), "O"});
        if (distanceEnds_.size() == 2)
            marks.push_back({distanceEnds_[0], distanceEnds_[1], true, QColor(255, 200, 0), "d"});
        if (verticalEnds_.size() == 2)
            marks.push_back({verticalEnds_[0], verticalEnds_[1], true, QColor(255, 200, 0), "h"});
    }
    viewport_->pickTool()->setMarks(marks);
    cornerCount_->setText(tr("Corners: %1 / 4").arg(corners_.size()));
    lineCount_->setText(tr("Lines: X %1, Z %2, vertical %3; origin %4")
                            .arg(lines_[0].size())
                            .arg(lines_[2].size())
                            .arg(lines_[1].size())
                            .arg(origin_.isEmpty() ? tr("not set") : tr("set")));
}

bool CalibrationPanel::guarded(const QString& title, const std::function<void()>& f) {
    return run_reporting_errors(reporter_, window(), title, f);
}

const Image& CalibrationPanel::photo(std::string* name) {
    const Project& p = doc_->project();
    const std::string path = p.resolve(p.photo.path).string();
    if (path != photoPath_ || photo_.empty()) {
        photo_ = load_image(path, "photo.path");
        photoPath_ = path;
    }
    if (name) *name = path;
    return photo_;
}

ImagePoint CalibrationPanel::toPhoto(QPointF r) {
    const QSize rs = viewport_->renderSize();
    const Image& img = photo();
    if (!rs.isValid()) throw InputError("", "", "no photo is shown in the viewport");
    const double sx = double(img.width()) / rs.width(), sy = double(img.height()) / rs.height();
    return ImagePoint((r.x() + 0.5) * sx - 0.5, (r.y() + 0.5) * sy - 0.5);
}

QPointF CalibrationPanel::toRender(ImagePoint p, QSize photo) const {
    const QSize rs = viewport_->renderSize();
    const double sx = double(rs.width()) / photo.width(), sy = double(rs.height()) / photo.height();
    return QPointF((p.x + 0.5) * sx - 0.5, (p.y + 0.5) * sy - 0.5);
}

double CalibrationPanel::clickSigma() {
    const QSize rs = viewport_->renderSize();
    const double scale = rs.isValid() ? double(photo().width()) / rs.width() : 1.0;
    return 0.5 * std::max(1.0, scale);
}

void CalibrationPanel::apply(const QString& method, const CalibrationResult& r,
                             const QString& more) {
    camera_->applyCalibration(method, r.camera_spec(), r.rms_px);
    QString text = tr("Matched (%1): horizontal field of view %2°\nUncertainty (1 sigma): %3")
                       .arg(method)
                       .arg(r.intrinsics.hfov_deg(), 0, 'f', 1)
                       .arg(QString::fromStdString(uncertainty_text(r)));
    if (!more.isEmpty()) text += "\n" + more;
    for (const std::string& w : r.warnings)
        text += "\n" + tr("Warning: ") + QString::fromStdString(w);
    status_->setText(text);
}

bool CalibrationPanel::applyRectangle() {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    return guarded(tr("Rectangle calibration failed"), [this] {
        std::vector<ImagePoint> px;
        for (QPointF c : corners_) px.push_back(toPhoto(c));
        std::string path;
        const Image& img = photo(&path);
        std::optional<Intrinsics> k;
        if (rectFocal_->value() > 0)
            k = Intrinsics::centred(img.width(), img.height(), rectFocal_->value());
        const CalibrationResult r = calibrate_rectangle(px, rectWidth_->value(),
                                                        rectHeight_->value(), img.width(),
                                                        img.height(), k, "rectangle",
                                                        clickSigma());
        apply(tr("rectangle"), r);
    });
}

bool CalibrationPanel::applyVanishing() {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    return guarded(tr("Vanishing-line calibration failed"), [this] {
        VanishingInput in;
        std::vector<LineSegment>* lists[3] = {&in.x, &in.y, &in.z};
        for (int a = 0; a < 3; ++a)
            for (const auto& s : lines_[a])
                lists[a]->push_back({toPhoto(s.first), toPhoto(s.second)});
        if (origin_.isEmpty())
            throw InputError("vanishing lines", "origin",
                             "click the world origin on the ground (\"Click origin\")");
        in.origin = toPhoto(origin_[0]);
        if (distance_->value() > 0) {
            if (distanceEnds_.size() != 2)
                throw InputError("vanishing lines", "distance",
                                 "click the two ends of the known distance (\"Click ends\")");
            in.distance = VanishingInput::Distance{toPhoto(distanceEnds_[0]),
                                                   toPhoto(distanceEnds_[1]), distance_->value()};
        } else if (vertical_->value() > 0) {
            if (verticalEnds_.size() != 2)
                throw InputError("vanishing lines", "vertical",
                                 "click the foot and the top of the known vertical length "
                                 "(\"Click foot, top\")");
            in.vertical = VanishingInput::Distance{toPhoto(verticalEnds_[0]),
                                                   toPhoto(verticalEnds_[1]), vertical_->value()};
        } else {
            in.camera_height = cameraHeight_->value();
        }
        if (vanFocal_->value() > 0) in.focal_px = vanFocal_->value();
        in.free_principal_point = freePrincipal_->isChecked();
        in.click_sigma_px = clickSigma();
        const Image& img = photo();
        apply(tr("vanishing lines"),
              calibrate_vanishing(in, img.width(), img.height(), "vanishing lines"));
    });
}

bool CalibrationPanel::addGroundPlane() {
    return guarded(tr("Ground plane failed"), [this] {
        const Image& img = photo();
        Project p = doc_->project();
        // One ground: a flat plane at y = 0 already there is refitted to what the camera sees
        // (keeping its name and albedo), not covered by a second one.
        for (RealProxy& r : p.real) {
            const bool flat = r.transform.rotation_deg == vec3(0) ||
                              (std::abs(r.transform.rotation_deg.x) < 1e-3f && std::abs(r.transform.rotation_deg.z) < 1e-3f);
            if (r.shape.kind != Shape::Kind::Plane || !flat || std::abs(r.transform.translation.y) > 1e-4f) continue;
            const ProxyFit fit = ground_proxy(p.camera.build(img.width(), img.height()), 0, r.name);
            r.shape = fit.proxy.shape;
            r.transform = fit.proxy.transform;
            doc_->edit(tr("Refit ground plane"), p);
            return;
        }
        ProxyFit fit = ground_proxy(p.camera.build(img.width(), img.height()), 0,
                                    unique_real_name(p, "ground"));
        p.real.push_back(fit.proxy);
        doc_->edit(tr("Add ground plane"), p);
    });
}

}  // namespace dp::ui
