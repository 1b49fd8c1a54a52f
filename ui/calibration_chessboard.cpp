// The chessboard page of the calibration panel: one photo with a focal length, the plane the
// board lies on (the ground, or a wall with the ground chosen from the camera's up or a dragged
// horizon), the lens from several photos on a worker thread, and the undistorted photo.
#include <QApplication>
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPointer>
#include <QProgressDialog>
#include <QPushButton>
#include <QSpinBox>
#include <atomic>
#include <exception>

#include "base/error.h"
#include "calibration/exif.h"
#include "calibration/ground_frame.h"
#include "calibration/undistort.h"
#include "calibration_panel.h"

#include <optional>
#include "document.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "lens_photos_dialog.h"
#include "number_field.h"
#include "panel_widgets.h"
#include "viewport.h"

namespace dp::ui {

/// What the lens worker is given and what it leaves for the UI thread. The worker writes the
/// results before it posts finishLens; the UI thread reads them only after joining it.
struct CalibrationPanel::LensJob {
    std::vector<std::string> paths;  ///< the project's photo first
    ChessboardSpec spec;
    std::atomic<bool> cancel{false};
    std::vector<ChessboardView> views;
    ChessboardCalibration calibration;
    std::exception_ptr error;
    bool cancelled = false;
};

namespace {

QString file_name(const std::string& path) {
    return QFileInfo(QString::fromStdString(path)).fileName();
}

}  // namespace

QWidget* CalibrationPanel::makeChessboardPage() {
    auto* page = new QWidget;
    auto* form = new QFormLayout(page);
    cols_ = new QSpinBox;
    rows_ = new QSpinBox;
    for (QSpinBox* s : {cols_, rows_}) s->setRange(2, 50);
    cols_->setValue(9);
    rows_->setValue(6);
    cols_->setObjectName("boardCols");
    rows_->setObjectName("boardRows");
    cols_->setToolTip(tr("Inner corners along a row (squares - 1)"));
    rows_->setToolTip(tr("Inner corners along a column (squares - 1)"));
    auto* size = new QHBoxLayout;
    size->addWidget(cols_);
    size->addWidget(new QLabel(QStringLiteral("x")));
    size->addWidget(rows_);
    form->addRow(tr("Inner corners"), size);
    square_ = make_number_field(0.001, 10, 0.025, 4, tr(" m"), tr("Side of one square in metres"));
    square_->setObjectName("boardSquare");
    form->addRow(tr("Square size"), square_);
    focalSource_ = new QComboBox;
    focalSource_->setObjectName("boardFocalSource");
    focalSource_->addItems(
        {tr("From EXIF, else the board"), tr("Given focal length"), tr("Estimate from the board")});
    focalSource_->setToolTip(
        tr("Where the focal length comes from: the photo's EXIF data (the board's perspective "
           "where the photo has none), the field below, or the board's perspective (a tilted board)"));
    form->addRow(tr("Focal length"), focalSource_);
    boardFocal_ = make_number_field(0, 1e5, 1000, 1, tr(" px"), tr("Focal length in pixels of the photo"));
    boardFocal_->setObjectName("boardFocal");
    form->addRow(QString(), boardFocal_);

    boardPlane_ = new QComboBox;
    boardPlane_->setObjectName("boardPlane");
    boardPlane_->addItems(
        {tr("Ground"), tr("Wall (up from the camera)"), tr("Wall (clicked horizon)")});
    boardPlane_->setToolTip(
        tr("Where the board is: on the ground (its plane becomes the ground), or upright on a "
           "wall, with up from the camera (a photo taken without roll) or from the horizon "
           "dragged on the photo"));
    form->addRow(tr("Board lies on"), boardPlane_);
    boardHeight_ = make_number_field(0, 1000, 1.0, 3, tr(" m"),
                         tr("Height of the board's origin corner (its first inner corner, "
                            "marked O after Detect and apply) above the floor"));
    boardHeight_->setObjectName("boardHeight");
    boardHeight_->setKeyboardTracking(false);
    // Applied at once to the last board on a wall: no need to detect it again.
    connect(boardHeight_, &QDoubleSpinBox::valueChanged, this, [this] { applyBoardHeight(); });
    connect(boardHeight_, &QDoubleSpinBox::editingFinished, this, [this] { boardHeightKey_ = -1; });
    form->addRow(tr("Board height"), boardHeight_);
    boardFootButton_ = make_named_button("boardHeightClick", tr("Height from a click"),
                                         tr("Click a point of the board that touches the floor (a corner "
                                            "of its lower edge): the board height that puts it there"));
    connect(boardFootButton_, &QPushButton::clicked, this, [this] { startPicking(Target::BoardFoot); });
    form->addRow(QString(), boardFootButton_);
    horizonButton_ = make_named_button("boardHorizon", tr("Click horizon"),
                                  tr("Drag along the horizon in the photo (where the floor "
                                     "would meet the sky, or a level line at eye height)"));
    connect(horizonButton_, &QPushButton::clicked, this, [this] { startPicking(Target::Horizon); });
    form->addRow(QString(), horizonButton_);
    auto enable = [this](int plane) {
        boardHeight_->setEnabled(plane != int(BoardPlane::Ground));
        boardFootButton_->setEnabled(plane != int(BoardPlane::Ground));
        horizonButton_->setEnabled(plane == int(BoardPlane::WallHorizon));
    };
    connect(boardPlane_, &QComboBox::currentIndexChanged, this, enable);
    enable(boardPlane_->currentIndex());

    QPushButton* go = make_named_button("chessboardApply", tr("Detect and apply"),
                                   tr("Find the board in the photo and match the camera to it"));
    connect(go, &QPushButton::clicked, this, [this] { applyChessboard(); });
    form->addRow(go);
    lensButton_ = make_named_button("lensPhotos", tr("Lens from several photos..."),
                               tr("Calibrate the lens (focal length, principal point, "
                                  "distortion) from this photo and more photos of the board"));
    connect(lensButton_, &QPushButton::clicked, this, [this] { lensDialog()->open(); });
    form->addRow(lensButton_);
    QPushButton* undistort =
        make_named_button("exportUndistorted", tr("Export undistorted photo..."),
                     tr("Write the photo with the camera's lens distortion taken out"));
    connect(undistort, &QPushButton::clicked, this, [this] { exportUndistortedDialog(); });
    form->addRow(undistort);
    return page;
}

ChessboardSpec CalibrationPanel::boardSpec() const {
    return ChessboardSpec{cols_->value(), rows_->value(), square_->value()};
}

CalibrationResult CalibrationPanel::placeGround(const CalibrationResult& r, const std::string& source,
                                                QString* ground, glm::dvec3* upOut) {
    const auto plane = BoardPlane(boardPlane_->currentIndex());
    if (plane == BoardPlane::Ground) {
        *ground = tr("Ground (y = 0): the board's plane");
        return r;
    }
    glm::dvec3 up;
    if (plane == BoardPlane::WallCameraUp) {
        up = up_from_camera(r, source);
    } else {
        if (horizon_.size() != 2)
            throw InputError("chessboard", "horizon",
                             "drag along the horizon first (\"Click horizon\"), or choose "
                             "another plane for the board");
        up = up_from_horizon(r.intrinsics, toPhoto(horizon_[0]), toPhoto(horizon_[1]), source);
    }
    if (upOut) *upOut = up;
    const CalibrationResult g = with_ground_from_up(r, up, boardHeight_->value(), source);
    *ground = tr("Ground (y = 0): level, %1 m below the board's origin corner O (up from %2); "
                 "the board is on a wall, the camera %3 m above the ground")
                  .arg(boardHeight_->value(), 0, 'f', 3)
                  .arg(plane == BoardPlane::WallCameraUp ? tr("the camera") : tr("the horizon"))
                  .arg(g.pose.position().y, 0, 'f', 2);
    return g;
}

void CalibrationPanel::applyBoardHeight() {
    if (!boardFit_ || !(doc_->project().camera == boardFit_->applied)) {
        if (boardFit_) boardFit_.reset();  // another camera since: the board no longer says where the floor is
        return;
    }
    guarded(tr("Board height failed"), [this] {
        const CalibrationResult g =
            with_ground_from_up(boardFit_->pose, boardFit_->up, boardHeight_->value(), boardFit_->source);
        Project p = doc_->project();
        p.camera = g.camera_spec();
        if (boardHeightKey_ < 0) boardHeightKey_ = doc_->newMergeKey();
        if (!doc_->tryEdit(tr("Board height"), p, boardHeightKey_)) return;
        boardFit_->applied = p.camera;
        status_->setText(tr("Ground (y = 0): level, %1 m below the board's origin corner O; the camera %2 m "
                            "above the ground")
                             .arg(boardHeight_->value(), 0, 'f', 3)
                             .arg(g.pose.position().y, 0, 'f', 2));
    });
}

void CalibrationPanel::boardHeightFromClick(QPointF px) {
    guarded(tr("Board height failed"), [&] {
        if (!boardFit_ || !(doc_->project().camera == boardFit_->applied))
            throw InputError("chessboard", "board height",
                             "detect and apply the board on a wall first: the click is read on its plane");
        const CalibrationResult& r = boardFit_->pose;
        const ImagePoint q = toPhoto(px);
        const Ray ray = r.camera().generate_ray(float(q.x), float(q.y));
        // The board's plane, through its corners (first row and first column).
        const int cols = boardSpec().cols;
        if (r.world_points.size() <= size_t(cols)) throw InputError("chessboard", "board height", "no board corners");
        const glm::dvec3 o = r.world_points[0];
        const glm::dvec3 n = glm::cross(r.world_points[1] - o, r.world_points[size_t(cols)] - o);
        const glm::dvec3 org(ray.org), dir(ray.dir);
        const double denom = glm::dot(n, dir);
        if (std::abs(denom) < 1e-9 * glm::length(n)) throw InputError("chessboard", "board height", "the board is seen edge-on there");
        const double t = glm::dot(n, o - org) / denom;
        if (!(t > 0)) throw InputError("chessboard", "board height", "that point is not on the board's plane");
        const glm::dvec3 point = org + t * dir;
        const glm::dvec3 origin = r.world_points.empty() ? glm::dvec3(0.0) : r.world_points.front();
        const glm::dvec3 up = glm::normalize(glm::transpose(r.pose.R) * boardFit_->up);
        const double height = glm::dot(origin - point, up);
        if (height < 0)
            throw InputError("chessboard", "board height",
                             "that point is above the board's origin corner O: click where the board meets the floor");
        boardHeight_->setValue(height);  // applies it (applyBoardHeight)
        boardHeightKey_ = -1;
    });
}

bool CalibrationPanel::applyChessboard() {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    return guarded(tr("Chessboard calibration failed"), [this] {
        std::string path;
        const Image& img = photo(&path);
        const ChessboardSpec spec = boardSpec();
        const ChessboardView view = detect_chessboard(img, spec, path);
        CalibrationResult r;
        QString focalNote;
        switch (focalSource_->currentIndex()) {
            case 0: {
                // A photo without EXIF (a scan, a webcam's, an edited one) is not an error here: a
                // new user's first try should work. The board's perspective gives the focal length.
                std::optional<ExifFocal> e;
                try {
                    e = read_exif_focal(path);
                } catch (const InputError&) {
                    focalNote = tr("No EXIF focal length in the photo: estimated from the board.");
                }
                if (e) {
                    const double f = e->focal_px * double(img.width()) / e->width;
                    r = chessboard_pose(view, spec, Intrinsics::centred(img.width(), img.height(), f));
                } else {
                    r = chessboard_single(view, spec);
                }
                break;
            }
            case 1:
                check_focal(boardFocal_->value(), path, "focal length");
                r = chessboard_pose(
                    view, spec,
                    Intrinsics::centred(img.width(), img.height(), boardFocal_->value()));
                break;
            default:
                r = chessboard_single(view, spec);
        }
        QString ground;
        const CalibrationResult pose = r;
        glm::dvec3 up(0.0);
        r = placeGround(r, path, &ground, &up);
        boardOrigin_ = view.corners[0];
        boardPhoto_ = QSize(view.width, view.height);
        apply(tr("chessboard"), r, focalNote.isEmpty() ? ground : focalNote + "\n" + ground);
        boardFit_.reset();
        if (up != glm::dvec3(0.0)) boardFit_ = BoardFit{pose, up, path, doc_->project().camera};
        refreshMarks();
    });
}

LensPhotosDialog* CalibrationPanel::lensDialog() {
    if (!lensDialog_) {
        lensDialog_ = new LensPhotosDialog(this);
        connect(lensDialog_, &QDialog::accepted, this,
                [this] { calibrateLens(lensDialog_->photos()); });
    }
    return lensDialog_;
}

bool CalibrationPanel::calibrateLens(const QStringList& photos) {
    if (target_ != Target::None) viewport_->pickTool()->stop();
    auto job = std::make_shared<LensJob>();
    const bool ok = guarded(tr("Lens calibration failed"), [&] {
        if (lensWorker_.joinable())
            throw InputError("", "", "a lens calibration is already running");
        job->spec = boardSpec();
        std::string own;
        photo(&own);  // the project's photo must load
        job->paths.push_back(own);
        const QString ownCanonical = QFileInfo(QString::fromStdString(own)).canonicalFilePath();
        for (const QString& p : photos) {
            if (p.isEmpty() || QFileInfo(p).canonicalFilePath() == ownCanonical) continue;
            job->paths.push_back(p.toStdString());
        }
        if (job->paths.size() < 2)
            throw InputError("", "photos",
                             "add photos of the board besides the project's photo (10 or more, "
                             "tilted different ways, is best)");
    });
    if (!ok) return false;
    // Loading and searching full-size photos takes a good fraction of a second each: on a
    // worker, with a progress dialog whose Cancel stops it between photos.
    lensJob_ = job;
    const int total = int(job->paths.size());
    lensProgress_ = new QProgressDialog(tr("Finding the board in %1 photos...").arg(total),
                                        tr("Cancel"), 0, total + 1, this);
    lensProgress_->setObjectName("lensProgress");
    lensProgress_->setWindowModality(Qt::WindowModal);
    lensProgress_->setMinimumDuration(500);
    lensProgress_->setAutoClose(false);
    lensProgress_->setAutoReset(false);
    lensProgress_->setValue(0);
    connect(lensProgress_, &QProgressDialog::canceled, this, [job] { job->cancel = true; });
    lensButton_->setEnabled(false);
    status_->setText(tr("Calibrating the lens from %1 photos...").arg(total));
    QPointer<CalibrationPanel> self(this);
    lensWorker_ = std::thread([job, self, total] {
        // Runs `f` on the UI thread, unless the panel is gone by then.
        auto post = [self](auto f) {
            QMetaObject::invokeMethod(
                qApp,
                [self, f] {
                    if (self) f(*self);
                },
                Qt::QueuedConnection);
        };
        try {
            for (int i = 0; i < total; ++i) {
                if (job->cancel) {
                    job->cancelled = true;
                    break;
                }
                job->views.push_back(detect_chessboard(job->paths[size_t(i)], job->spec));
                post([i](CalibrationPanel& p) {
                    if (p.lensProgress_) p.lensProgress_->setValue(i + 1);
                });
            }
            if (!job->cancelled) job->calibration = calibrate_chessboard(job->views, job->spec);
        } catch (...) {
            job->error = std::current_exception();
        }
        post([](CalibrationPanel& p) { p.finishLens(); });
    });
    return true;
}

void CalibrationPanel::finishLens() {
    if (lensWorker_.joinable()) lensWorker_.join();
    const std::shared_ptr<LensJob> job = std::move(lensJob_);
    if (lensProgress_) {
        lensProgress_->deleteLater();
        lensProgress_ = nullptr;
    }
    lensButton_->setEnabled(true);
    if (!job) return;
    // Cancel pressed after the last photo still cancels: nothing is applied.
    if (job->cancelled || job->cancel) {
        status_->setText(tr("Lens calibration cancelled: the camera is unchanged"));
        return;
    }
    const bool ok = guarded(tr("Lens calibration failed"), [&] {
        if (job->error) std::rethrow_exception(job->error);
        const Project& p = doc_->project();
        if (p.resolve(p.photo.path).string() != job->paths[0])
            throw InputError(job->paths[0], "",
                             "the project's photo changed while the lens was calibrated; "
                             "nothing was applied");
        const ChessboardCalibration& c = job->calibration;
        QString ground;
        const CalibrationResult r = placeGround(c.for_view(0), job->paths[0], &ground);
        QStringList perPhoto;
        for (size_t i = 0; i < job->views.size(); ++i) {
            QString line =
                tr("%1 %2").arg(file_name(job->paths[i])).arg(c.view_rms_px[i], 0, 'f', 2);
            if (c.duplicate_of[i] >= 0)
                line +=
                    tr(" (duplicate of %1)").arg(file_name(job->paths[size_t(c.duplicate_of[i])]));
            perPhoto << line;
        }
        boardOrigin_ = job->views[0].corners[0];
        boardPhoto_ = QSize(job->views[0].width, job->views[0].height);
        apply(tr("chessboard, %1 photos").arg(job->views.size()), r,
              ground + "\n" +
                  tr("Lens: k1 %1 k2 %2 p1 %3 p2 %4; rms per photo (px): %5")
                      .arg(double(r.intrinsics.distortion.k1), 0, 'f', 4)
                      .arg(double(r.intrinsics.distortion.k2), 0, 'f', 4)
                      .arg(double(r.intrinsics.distortion.p1), 0, 'f', 5)
                      .arg(double(r.intrinsics.distortion.p2), 0, 'f', 5)
                      .arg(perPhoto.join(", ")));
        refreshMarks();
    });
    if (!ok) status_->setText(tr("Lens calibration failed: the camera is unchanged"));
}

CalibrationPanel::~CalibrationPanel() {
    if (lensJob_) lensJob_->cancel = true;
    if (lensWorker_.joinable()) lensWorker_.join();
    if (detector_.joinable()) detector_.join();
}

bool CalibrationPanel::exportUndistortedPhoto(const QString& path) {
    return guarded(tr("Export undistorted photo failed"), [&] {
        const std::string out = path.toStdString();
        const QString suffix = QFileInfo(path).suffix().toLower();
        if (suffix != "exr" && suffix != "png" && suffix != "jpg" && suffix != "jpeg")
            throw InputError(out, "", "write the undistorted photo as .exr, .png or .jpg");
        const Image& img = photo();
        const Camera camera = doc_->project().camera.build(img.width(), img.height());
        const Image ideal = undistort_image(img, camera);
        // The writers' own errors name the file and say what failed.
        if (suffix == "exr")
            save_exr(out, {{"", &ideal}});
        else
            save_ldr(out, ideal);
        status_->setText(camera.distortion().is_zero()
                             ? tr("Wrote %1: the camera has no lens distortion, so it is the "
                                  "photo as it is")
                                   .arg(QFileInfo(path).fileName())
                             : tr("Wrote %1: the photo as a pinhole camera of the same focal "
                                  "length would have taken it")
                                   .arg(QFileInfo(path).fileName()));
    });
}

void CalibrationPanel::exportUndistortedDialog() {
    const QString f =
        QFileDialog::getSaveFileName(this, tr("Export undistorted photo"), QString(),
                                     tr("PNG (*.png);;OpenEXR (*.exr);;JPEG (*.jpg)"));
    if (!f.isEmpty()) exportUndistortedPhoto(f);
}

}  // namespace dp::ui
