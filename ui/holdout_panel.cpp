#include "holdout_panel.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSpinBox>
#include <QToolButton>
#include <QApplication>
#include <QPointer>
#include <QVBoxLayout>
#include <algorithm>

#include "assets/asset_library.h"
#include "base/error.h"
#include "document.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "panel_widgets.h"
#include "placement.h"
#include "reconstruction/holdout_matte.h"
#include "viewport.h"

namespace dp::ui {

namespace {

constexpr const char* kModeNames[] = {"holdoutBrush", "holdoutErase", "holdoutPolygon", "holdoutCut"};

/// The bytes of a Grayscale8 image, one per pixel (scan lines are padded).
std::vector<uint8_t> mask_bytes(const QImage& mask) {
    std::vector<uint8_t> out(size_t(mask.width()) * size_t(mask.height()));
    for (int y = 0; y < mask.height(); ++y) {
        const uchar* row = mask.constScanLine(y);
        for (int x = 0; x < mask.width(); ++x) out[size_t(y) * mask.width() + x] = row[x] >= 128;
    }
    return out;
}

/// A holdout name no other holdout has: `base`, then "base 2", "base 3"...
std::string unique_holdout_name(const Project& p, const std::string& base) {
    for (int n = 1;; ++n) {
        const std::string name = n == 1 ? base : base + " " + std::to_string(n);
        if (std::none_of(p.holdouts.begin(), p.holdouts.end(), [&](const Holdout& h) { return h.name == name; }))
            return name;
    }
}

}  // namespace

HoldoutPanel::HoldoutPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter, QWidget* parent)
    : QWidget(parent), doc_(doc), viewport_(viewport), reporter_(reporter) {
    auto* layout = new QVBoxLayout(this);
    auto* intro = new QLabel(tr("Paint the parts of the photo that stand in front of the objects: "
                                "what lies beyond the holdout's depth is hidden there."));
    intro->setWordWrap(true);
    layout->addWidget(intro);
    list_ = new QListWidget;
    list_->setObjectName("holdoutList");
    list_->setToolTip(tr("The holdouts: real occluders painted over the photo"));
    layout->addWidget(list_);
    auto* row = new QHBoxLayout;
    QPushButton* add = make_named_button("holdoutNew", tr("New"), tr("A new holdout with an empty mask"));
    QPushButton* remove = make_named_button("holdoutRemove", tr("Remove"), tr("Remove the selected holdout"));
    row->addWidget(add);
    row->addWidget(remove);
    layout->addLayout(row);
    connect(add, &QPushButton::clicked, this, [this] { addHoldout(); });
    connect(remove, &QPushButton::clicked, this, [this] {
        const int i = list_->currentRow();
        if (i < 0 || i >= int(doc_->project().holdouts.size())) return;
        Project p = doc_->project();
        p.holdouts.erase(p.holdouts.begin() + i);
        viewport_->matteTool()->stop();
        doc_->tryEdit(tr("Remove holdout"), p);
    });

    auto* form = new QFormLayout;
    depth_ = make_number_field(0.001, double(kMaxHoldoutDepth), 1.0, 3, tr(" m"),
                               tr("How far the occluder stands from the camera, along its view axis: "
                                  "objects beyond it are hidden by the mask"));
    depth_->setObjectName("holdoutDepth");
    depth_->setKeyboardTracking(false);
    connect(depth_, &QDoubleSpinBox::valueChanged, this, [this](double v) { setDepth(v, tr("Holdout depth")); });
    form->addRow(tr("Depth"), depth_);
    QPushButton* depthClick = make_named_button("holdoutDepthClick", tr("Depth from a click"),
                                                tr("Click a real surface where the occluder stands (its foot "
                                                   "on the floor, the wall it leans on)"));
    connect(depthClick, &QPushButton::clicked, this, [this] {
        if (list_->currentRow() < 0) return;
        viewport_->matteTool()->stop();
        picking_ = true;
        viewport_->pickTool()->start(PickTool::Kind::Point, 1, tr("Click where the occluder stands"));
    });
    form->addRow(depthClick);
    layout->addLayout(form);

    auto* tools = new QHBoxLayout;
    const QString labels[] = {tr("Brush"), tr("Erase"), tr("Polygon"), tr("Cut")};
    const QString tips[] = {tr("Paint the occluder (Shift erases)"), tr("Erase from the mask"),
                            tr("Click the occluder's corners; Enter, a double click or the first corner closes it"),
                            tr("Drag a rectangle around the occluder: GrabCut cuts it out of the photo")};
    for (int m = 0; m < 4; ++m) {
        auto* b = new QToolButton;
        b->setText(labels[m]);
        b->setToolTip(tips[m]);
        b->setObjectName(kModeNames[m]);
        b->setCheckable(true);
        connect(b, &QToolButton::clicked, this, [this, m] { startTool(m); });
        modes_[m] = b;
        tools->addWidget(b);
    }
    layout->addLayout(tools);
    auto* brushForm = new QFormLayout;
    radius_ = new QSpinBox;
    radius_->setObjectName("holdoutRadius");
    radius_->setRange(1, 500);
    radius_->setValue(12);
    radius_->setSuffix(tr(" px"));
    radius_->setToolTip(tr("The brush's radius in pixels of the render"));
    connect(radius_, &QSpinBox::valueChanged, this, [this](int r) { viewport_->matteTool()->setBrushRadius(r); });
    brushForm->addRow(tr("Brush radius"), radius_);
    layout->addLayout(brushForm);
    auto* after = new QHBoxLayout;
    recut_ = make_named_button("holdoutRecut", tr("Cut again"),
                               tr("Cut the last rectangle again, taking the strokes since as sure occluder "
                                  "(Brush) or background (Erase)"));
    done_ = make_named_button("holdoutDone", tr("Done"), tr("Stop painting (Esc)"));
    after->addWidget(recut_);
    after->addWidget(done_);
    layout->addLayout(after);
    connect(recut_, &QPushButton::clicked, this, [this] { cut(viewport_->matteTool()->cutRect()); });
    connect(done_, &QPushButton::clicked, this, [this] { viewport_->matteTool()->stop(); });
    status_ = new QLabel;
    status_->setObjectName("holdoutStatus");
    status_->setWordWrap(true);
    layout->addWidget(status_);
    layout->addStretch(1);

    MatteTool* matte = viewport_->matteTool();
    matte->setBrushRadius(radius_->value());
    connect(matte, &MatteTool::strokeFinished, this, [this] { commit(tr("Paint holdout")); });
    connect(matte, &MatteTool::cutRequested, this, [this](QRect r) { cut(r); });
    connect(matte, &MatteTool::finished, this, [this] {
        for (QToolButton* b : modes_) b->setChecked(false);
        refresh();
    });
    PickTool* pick = viewport_->pickTool();
    connect(pick, &PickTool::pointPicked, this, [this](QPointF px) {
        if (!picking_) return;
        guarded(tr("Holdout depth failed"), [&] {
            const Camera camera = viewport_->viewCamera();
            SurfaceHit hit;
            if (!cast_real(doc_->project(), camera.generate_ray(float(px.x()), float(px.y())), hit))
                throw InputError("", "holdouts.depth", "no real surface there: click the floor or a proxy");
            setDepth(glm::dot(hit.point - camera.position(), camera.forward()), tr("Holdout depth from a click"));
        });
    });
    connect(pick, &PickTool::finished, this, [this](bool) { picking_ = false; });
    connect(list_, &QListWidget::currentRowChanged, this, [this] {
        viewport_->matteTool()->stop();
        refresh();
        showSelected();
    });
    connect(doc_, &Document::changed, this, [this] {
        refresh();
        // An undo brings back another version of the mask: show it.
        const int i = list_->currentRow();
        if (i >= 0 && QString::fromStdString(doc_->project().holdouts[size_t(i)].mask) != shownMask_) showSelected();
    });
    connect(doc_, &Document::reloaded, this, [this] {
        viewport_->matteTool()->stop();
        status_->clear();
        list_->setCurrentRow(-1);
        refresh();
        showSelected();
    });
    refresh();
}

bool HoldoutPanel::guarded(const QString& title, const std::function<void()>& f) {
    return run_reporting_errors(reporter_, window(), title, f);
}

void HoldoutPanel::refresh() {
    const Project& p = doc_->project();
    const int row = std::min(list_->currentRow(), int(p.holdouts.size()) - 1);
    {
        QSignalBlocker block(list_);
        list_->clear();
        for (const Holdout& h : p.holdouts)
            list_->addItem(tr("%1 (%2 m)").arg(QString::fromStdString(h.name)).arg(double(h.depth), 0, 'g', 4));
        list_->setCurrentRow(row);
    }
    const bool selected = row >= 0;
    {
        QSignalBlocker block(depth_);
        if (selected) depth_->setValue(double(p.holdouts[size_t(row)].depth));
    }
    depth_->setEnabled(selected);
    const MatteTool* matte = viewport_->matteTool();
    recut_->setEnabled(selected && !matte->cutRect().isEmpty());
    done_->setEnabled(matte->active());
    if (!selected && matte->shown()) showSelected();
}

void HoldoutPanel::showSelected() {
    MatteTool* matte = viewport_->matteTool();
    const int i = list_->currentRow();
    const QSize size = viewport_->renderSize();
    if (i < 0 || i >= int(doc_->project().holdouts.size()) || !size.isValid()) {
        matte->setShown(false);
        shownMask_.clear();
        return;
    }
    const Project& p = doc_->project();
    const Holdout& h = p.holdouts[size_t(i)];
    QImage mask(size, QImage::Format_Grayscale8);
    mask.fill(0);
    try {
        // Data, as the renderer reads it: white is the occluder.
        ImageLoadOptions linear;
        linear.colorspace = "linear";
        const Image m = load_image(p.resolve(h.mask).string(), "holdouts[" + std::to_string(i) + "].mask", nullptr, linear);
        QImage read(m.width(), m.height(), QImage::Format_Grayscale8);
        for (int y = 0; y < m.height(); ++y)
            for (int x = 0; x < m.width(); ++x) read.scanLine(y)[x] = luminance(m.at(x, y)) >= 0.5f ? 255 : 0;
        mask = read.size() == size ? read : read.scaled(size, Qt::IgnoreAspectRatio, Qt::FastTransformation);
    } catch (const InputError& e) {
        status_->setText(tr("The mask cannot be read (%1); painting starts from an empty one.")
                             .arg(QString::fromStdString(e.what())));
    }
    matte->setMask(mask);
    matte->setShown(true);
    shownMask_ = QString::fromStdString(h.mask);
}

bool HoldoutPanel::addHoldout() {
    return guarded(tr("New holdout failed"), [&] {
        if (doc_->path().isEmpty()) throw InputError("", "", "save the project first: the mask is written next to it");
        const QSize size = viewport_->renderSize();
        if (!size.isValid()) throw InputError("", "photo.path", "the photo is not shown yet");
        Project p = doc_->project();
        Holdout h;
        h.name = unique_holdout_name(p, "holdout");
        h.mask = save_holdout_mask(std::vector<uint8_t>(size_t(size.width()) * size.height(), 0), size.width(),
                                   size.height(), doc_->path().toStdString(), h.name);
        // Halfway to what the view centre shows: in front of the objects, which stand there.
        const Camera camera = viewport_->viewCamera();
        const vec3 centre = view_centre_point(p, camera);
        h.depth = std::clamp(0.5f * glm::dot(centre - camera.position(), camera.forward()), 0.01f, kMaxHoldoutDepth);
        p.holdouts.push_back(h);
        if (!doc_->tryEdit(tr("Add holdout"), p)) return;
        list_->setCurrentRow(int(p.holdouts.size()) - 1);
        status_->setText(tr("Paint the occluder, or drag a rectangle around it with Cut."));
    });
}

bool HoldoutPanel::commit(const QString& text) {
    return guarded(tr("Holdout failed"), [&] {
        const int i = list_->currentRow();
        if (i < 0 || i >= int(doc_->project().holdouts.size())) throw InputError("", "holdouts", "select a holdout first");
        if (doc_->path().isEmpty()) throw InputError("", "", "save the project first: the mask is written next to it");
        const QImage& mask = viewport_->matteTool()->mask();
        Project p = doc_->project();
        Holdout& h = p.holdouts[size_t(i)];
        h.mask = save_holdout_mask(mask_bytes(mask), mask.width(), mask.height(), doc_->path().toStdString(), h.name);
        shownMask_ = QString::fromStdString(h.mask);  // what the tool holds: no need to read it back
        doc_->tryEdit(text, p);
    });
}

void HoldoutPanel::startTool(int mode) {
    MatteTool* matte = viewport_->matteTool();
    if (list_->currentRow() < 0) {
        if (doc_->project().holdouts.empty()) {
            if (!addHoldout()) {
                modes_[mode]->setChecked(false);
                return;
            }
        } else {
            list_->setCurrentRow(int(doc_->project().holdouts.size()) - 1);
        }
    }
    for (int m = 0; m < 4; ++m) modes_[m]->setChecked(m == mode);
    if (matte->active())
        matte->setMode(MatteTool::Mode(mode));
    else
        matte->start(MatteTool::Mode(mode), matte->mask());
    viewport_->setFocus();
    refresh();
}

void HoldoutPanel::setDepth(double metres, const QString& text) {
    const int i = list_->currentRow();
    if (i < 0 || i >= int(doc_->project().holdouts.size())) return;
    Project p = doc_->project();
    p.holdouts[size_t(i)].depth = float(std::clamp(metres, 0.001, double(kMaxHoldoutDepth)));
    if (p.holdouts[size_t(i)].depth == doc_->project().holdouts[size_t(i)].depth) return;
    doc_->tryEdit(text, p);
}

bool HoldoutPanel::cut(QRect rect) {
    std::vector<MatteLabel> labels;
    int W = 0, H = 0;
    const bool ok = guarded(tr("Cut failed"), [&] {
        if (cutter_.joinable()) throw InputError("", "", "a cut is already running");
        MatteTool* matte = viewport_->matteTool();
        const QImage& mask = matte->mask();
        if (mask.isNull() || rect.isEmpty()) throw InputError("", "", "drag a rectangle around the occluder first");
        W = mask.width(), H = mask.height();
        labels = matte_labels_from_rect(W, H, rect.left(), rect.top(), rect.right() + 1, rect.bottom() + 1);
        if (rect == matte->cutRect()) {
            const QImage& strokes = matte->cutStrokes();
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const uchar s = strokes.constScanLine(y)[x];
                    if (s == 1) labels[size_t(y) * W + x] = MatteLabel::Occluder;
                    if (s == 2) labels[size_t(y) * W + x] = MatteLabel::Background;
                }
        }
    });
    if (!ok) return false;
    // GrabCut on a worker (its time grows with the photo), the result laid into the mask on the
    // UI thread.
    const std::shared_ptr<AssetLibrary> assets = doc_->assetLibrary();
    const Project project = doc_->project();
    const int row = list_->currentRow();
    QPointer<HoldoutPanel> self(this);
    status_->setText(tr("Cutting the occluder out of the photo…"));
    modes_[3]->setEnabled(false);
    recut_->setEnabled(false);
    cutter_ = std::thread([=, labels = std::move(labels)] {
        std::vector<uint8_t> cut;
        std::string error;
        try {
            cut = grabcut_matte(*assets->photo_at(project, W, H), labels);
        } catch (const std::exception& e) {
            error = e.what();
        }
        QMetaObject::invokeMethod(qApp, [self, rect, row, W, H, cut = std::move(cut), error] {
            if (!self) return;
            self->cutter_.join();
            self->modes_[3]->setEnabled(true);
            self->refresh();
            self->applyCut(rect, row, W, H, cut, error);
        }, Qt::QueuedConnection);
    });
    return true;
}

void HoldoutPanel::applyCut(QRect rect, int row, int W, int H, const std::vector<uint8_t>& cut, const std::string& error) {
    guarded(tr("Cut failed"), [&] {
        if (!error.empty()) throw InputError("", "", error);
        MatteTool* matte = viewport_->matteTool();
        QImage mask = matte->mask();
        // Another holdout chosen, or another project, while it ran: the cut is not this mask's.
        if (row != list_->currentRow() || mask.width() != W || mask.height() != H) {
            status_->clear();
            return;
        }
        size_t covered = 0;
        for (int y = std::max(rect.top(), 0); y <= std::min(rect.bottom(), H - 1); ++y)
            for (int x = std::max(rect.left(), 0); x <= std::min(rect.right(), W - 1); ++x) {
                mask.scanLine(y)[x] = cut[size_t(y) * W + x] ? 255 : 0;
                covered += cut[size_t(y) * W + x];
            }
        matte->setMask(mask);
        if (!commit(tr("Cut holdout"))) return;
        status_->setText(tr("Cut out %1 pixels. Brush or Erase strokes mark what it missed; then Cut again.")
                             .arg(covered));
        refresh();
    });
}

HoldoutPanel::~HoldoutPanel() {
    if (cutter_.joinable()) cutter_.join();
}

}  // namespace dp::ui
