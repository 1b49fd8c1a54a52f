#include "proxy_panel.h"

#include <QApplication>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>

#include "base/error.h"
#include "document.h"
#include "error_reporter.h"
#include "image/image_io.h"
#include "photo_geometry.h"
#include "project_edit.h"
#include "reconstruction/albedo.h"
#include "reconstruction/proxies.h"
#include "viewport.h"

namespace dp::ui {

namespace fs = std::filesystem;

namespace {

QDoubleSpinBox* metres(double value, const char* name, const QString& tip) {
    auto* s = new QDoubleSpinBox;
    s->setRange(0.01, 1000);
    s->setDecimals(3);
    s->setValue(value);
    s->setSuffix(QObject::tr(" m"));
    s->setObjectName(name);
    s->setToolTip(tip);
    return s;
}

QPushButton* button(const char* name, const QString& text, const QString& tip) {
    auto* b = new QPushButton(text);
    b->setObjectName(name);
    b->setToolTip(tip);
    return b;
}

/// A file-name-safe form of a proxy's name.
std::string file_stem(const std::string& name, int index) {
    std::string s;
    for (char c : name)
        s += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return s.empty() ? "real" + std::to_string(index) : s;
}

}  // namespace

ProxyPanel::ProxyPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter,
                       QWidget* parent)
    : QWidget(parent), doc_(doc), viewport_(viewport), reporter_(reporter) {
    auto* layout = new QVBoxLayout(this);
    list_ = new QListWidget;
    list_->setObjectName("proxyList");
    list_->setToolTip(tr("The real proxies: geometry standing in for the photo's surfaces"));
    layout->addWidget(list_);
    QPushButton* remove = button("proxyRemove", tr("Remove"), tr("Remove the selected proxy"));
    connect(remove, &QPushButton::clicked, this, [this] { removeSelected(); });
    layout->addWidget(remove);

    auto* box = new QGroupBox(tr("Box"));
    auto* boxForm = new QFormLayout(box);
    boxHeight_ = metres(0.5, "boxHeight", tr("Height of the box above the ground"));
    boxForm->addRow(tr("Height"), boxHeight_);
    QPushButton* pickBox = button("proxyBox", tr("Click footprint"),
                                  tr("Click the box's four corners on the ground, in order "
                                     "around it"));
    connect(pickBox, &QPushButton::clicked, this, [this] { startPicking(Target::Box); });
    boxForm->addRow(pickBox);
    layout->addWidget(box);

    auto* wall = new QGroupBox(tr("Wall"));
    auto* wallForm = new QFormLayout(wall);
    wallHeight_ = metres(2.5, "wallHeight", tr("Height of the wall"));
    wallThickness_ = metres(0.2, "wallThickness", tr("Depth behind the clicked line"));
    wallForm->addRow(tr("Height"), wallHeight_);
    wallForm->addRow(tr("Thickness"), wallThickness_);
    QPushButton* pickWall = button("proxyWall", tr("Click base"),
                                   tr("Click two points where the wall meets the ground"));
    connect(pickWall, &QPushButton::clicked, this, [this] { startPicking(Target::Wall); });
    wallForm->addRow(pickWall);
    layout->addWidget(wall);

    auto* albedo = new QGroupBox(tr("Albedo"));
    auto* albedoForm = new QFormLayout(albedo);
    resolution_ = new QSpinBox;
    resolution_->setRange(8, 2048);
    resolution_->setValue(128);
    resolution_->setObjectName("albedoResolution");
    resolution_->setToolTip(tr("Texture size along the longer side"));
    samples_ = new QSpinBox;
    samples_->setRange(16, 8192);
    samples_->setValue(256);
    samples_->setObjectName("albedoSamples");
    samples_->setToolTip(tr("Probe samples per texel (more: less noise, slower)"));
    albedoForm->addRow(tr("Resolution"), resolution_);
    albedoForm->addRow(tr("Samples"), samples_);
    QPushButton* estimate = button("albedoEstimate", tr("Estimate albedo"),
                                   tr("Estimate the selected proxy's albedo texture from the "
                                      "photo and the probe (written next to the project)"));
    connect(estimate, &QPushButton::clicked, this, [this] { estimateAlbedo(list_->currentRow()); });
    albedoForm->addRow(estimate);
    layout->addWidget(albedo);
    status_ = new QLabel;
    status_->setWordWrap(true);
    status_->setObjectName("proxyStatus");
    layout->addWidget(status_);
    layout->addStretch(1);

    PickTool* pick = viewport_->pickTool();
    connect(pick, &PickTool::pointPicked, this, [this](QPointF p) {
        if (target_ == Target::None) return;
        points_.push_back(p);
        QVector<PickTool::Mark> marks;
        for (QPointF q : points_) marks.push_back({q, q, false, QColor(80, 200, 255), {}});
        viewport_->pickTool()->setMarks(marks);
    });
    connect(pick, &PickTool::finished, this, [this](bool cancelled) {
        const Target t = target_;
        target_ = Target::None;
        if (t == Target::None) return;
        const QVector<QPointF> pts = points_;
        points_.clear();
        viewport_->pickTool()->setMarks({});
        if (cancelled) return;
        if (t == Target::Box) addBox(pts);
        if (t == Target::Wall) addWall(pts);
    });
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    refresh();
}

void ProxyPanel::refresh() {
    const int row = list_->currentRow();
    list_->clear();
    static const char* kinds[] = {"plane", "box", "sphere", "mesh"};
    for (const RealProxy& r : doc_->project().real) {
        QString text = QStringLiteral("%1 (%2)").arg(QString::fromStdString(r.name),
                                                    kinds[int(r.shape.kind)]);
        if (r.albedo.kind == Albedo::Kind::Texture) text += tr(", textured");
        list_->addItem(text);
    }
    list_->setCurrentRow(std::min(row, list_->count() - 1));
}

void ProxyPanel::startPicking(Target target) {
    target_ = Target::None;  // an unfinished run of ours is dropped, not applied
    points_.clear();
    viewport_->pickTool()->stop();
    target_ = target;
    viewport_->pickTool()->setMarks({});
    viewport_->pickTool()->start(PickTool::Kind::Point, target == Target::Box ? 4 : 2,
                                 target == Target::Box
                                     ? tr("Click the box's 4 footprint corners in order")
                                     : tr("Click 2 points at the wall's base"));
    viewport_->setFocus();
}

bool ProxyPanel::guarded(const QString& title, const std::function<void()>& f) {
    return run_reporting_errors(reporter_, window(), title, f);
}

bool ProxyPanel::addBox(const QVector<QPointF>& corners) {
    return guarded(tr("Box proxy failed"), [&] {
        Project p = doc_->project();
        const QSize ps = photo_size(p);
        std::vector<vec2> px;
        for (QPointF c : corners) px.push_back(render_to_photo(c, viewport_->renderSize(), ps));
        ProxyFit fit = box_proxy(photo_camera(p), px, float(boxHeight_->value()),
                                 unique_real_name(p, "box"));
        p.real.push_back(fit.proxy);
        doc_->edit(tr("Add box proxy"), p);
        status_->setText(tr("Box added; footprint fit %1 px").arg(fit.rms_error_px, 0, 'f', 2));
    });
}

bool ProxyPanel::addWall(const QVector<QPointF>& base) {
    return guarded(tr("Wall proxy failed"), [&] {
        if (base.size() != 2)
            throw InputError("", "wall", "a wall takes two points at its base, got " +
                                             std::to_string(base.size()));
        Project p = doc_->project();
        const QSize ps = photo_size(p);
        const vec2 a = render_to_photo(base[0], viewport_->renderSize(), ps);
        const vec2 b = render_to_photo(base[1], viewport_->renderSize(), ps);
        ProxyFit fit = wall_proxy(photo_camera(p), a, b, float(wallHeight_->value()),
                                  float(wallThickness_->value()), unique_real_name(p, "wall"));
        p.real.push_back(fit.proxy);
        doc_->edit(tr("Add wall proxy"), p);
        status_->setText(tr("Wall added"));
    });
}

bool ProxyPanel::estimateAlbedo(int index) {
    return guarded(tr("Albedo estimate failed"), [&] {
        Project p = doc_->project();
        if (index < 0 || index >= int(p.real.size()))
            throw InputError("", "real", "select a real proxy first");
        if (doc_->path().isEmpty())
            throw InputError("", "", "save the project first: the texture is written next to it");
        QApplication::setOverrideCursor(Qt::WaitCursor);
        RenderScene scene(p, load_assets(p));
        AlbedoTextureOptions o;
        o.max_resolution = resolution_->value();
        o.probe_samples = samples_->value();
        // An 8-bit photo clips at its top values; EXR and HDR photos do not clip.
        const std::string ext = fs::path(p.photo.path).extension().string();
        if (ext != ".exr" && ext != ".hdr" && ext != ".EXR" && ext != ".HDR")
            o.clip_level = 0.99f * std::exp2(p.photo.exposure);
        const AlbedoTexture t = estimate_albedo_texture(scene, index, o);
        const QFileInfo project(doc_->path());
        const std::string name = project.completeBaseName().toStdString() + "_" +
                                 file_stem(p.real[size_t(index)].name, index) + "_albedo.exr";
        const fs::path folder = project.absolutePath().toStdString();
        save_exr((folder / name).string(), {{"", &t.albedo}});
        RealProxy& r = p.real[size_t(index)];
        r.albedo.kind = Albedo::Kind::Texture;
        // Relative to the project's folder when it is the file's; absolute otherwise.
        std::error_code ec;
        r.albedo.texture_path =
            fs::equivalent(p.base_dir, folder, ec) ? name : (folder / name).string();
        doc_->edit(tr("Estimate albedo of %1").arg(QString::fromStdString(r.name)), p);
        QApplication::restoreOverrideCursor();
        const double n = double(t.albedo.size()) / 100.0;
        status_->setText(tr("Albedo: %1 x %2 texels, %3% estimated, mean %4")
                             .arg(t.albedo.width())
                             .arg(t.albedo.height())
                             .arg(double(t.valid) / n, 0, 'f', 1)
                             .arg(double(luminance(t.mean_albedo)), 0, 'f', 3));
    });
}

void ProxyPanel::removeSelected() {
    const int row = list_->currentRow();
    Project p = doc_->project();
    if (row < 0 || row >= int(p.real.size())) return;
    const QString name = QString::fromStdString(p.real[size_t(row)].name);
    p.real.erase(p.real.begin() + row);
    doc_->edit(tr("Remove proxy %1").arg(name), p);
}

}  // namespace dp::ui
