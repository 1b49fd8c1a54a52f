#include "proxy_panel.h"

#include <QApplication>
#include <QComboBox>
#include <QPointer>
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
#include "number_field.h"
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

NumberField* metres(double value, const char* name, const QString& tip) {
    auto* s = new NumberField;
    s->setRange(0.01, 1000);
    s->setDecimals(3);
    s->setValue(value);
    s->setSuffix(QObject::tr(" m"));
    s->setObjectName(name);
    s->setToolTip(tip);
    return s;
}

/// Gloss presets: reflectance at normal incidence and roughness of common real surfaces.
struct GlossPreset {
    const char* name;
    float specular, roughness;
};
constexpr GlossPreset kGlossPresets[] = {{"Matte", 0.0f, 0.1f},           {"Satin paint", 0.04f, 0.35f},
                                         {"Varnished wood", 0.04f, 0.15f}, {"Polished stone", 0.05f, 0.05f},
                                         {"Glazed tiles", 0.04f, 0.03f},   {"Wet street", 0.03f, 0.08f}};

NumberField* unit_field(const char* name, const QString& tip) {
    auto* s = new NumberField;
    s->setRange(0, 1);
    s->setDecimals(3);
    s->setSingleStep(0.01);
    s->setObjectName(name);
    s->setToolTip(tip);
    s->setKeyboardTracking(false);
    return s;
}

QPushButton* button(const char* name, const QString& text, const QString& tip) {
    auto* b = new QPushButton(text);
    b->setObjectName(name);
    b->setToolTip(tip);
    return b;
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

    // The selected proxy's size, typed: a ground too small or a box a little off is fixed here.
    auto* size = new QGroupBox(tr("Size"));
    auto* sizeForm = new QFormLayout(size);
    const char* sizeNames[] = {"proxySizeX", "proxySizeY", "proxySizeZ"};
    const QString sizeLabels[] = {tr("Width (x)"), tr("Height (y)"), tr("Depth (z)")};
    for (int k = 0; k < 3; ++k) {
        size_[k] = metres(1.0, sizeNames[k], tr("Size of the selected proxy along its own axis"));
        size_[k]->setRange(0.001, 1e6);
        size_[k]->setKeyboardTracking(false);
        connect(size_[k], &QDoubleSpinBox::valueChanged, this, [this] { applySize(); });
        sizeForm->addRow(sizeLabels[k], size_[k]);
    }
    // Where its base stands: a desk top, a shelf, the ground under a raised floor; live, one
    // undo step per stroke of the field.
    base_ = metres(0.0, "proxyBase", tr("Height of the selected proxy's lowest point (a plane's own height), "
                                        "in metres above y = 0"));
    base_->setRange(-1e5, 1e5);
    base_->setKeyboardTracking(false);
    connect(base_, &QDoubleSpinBox::valueChanged, this, [this] { applyBase(); });
    // One undo step while the field keeps the focus (arrow presses, typed values): a spin box
    // also finishes editing at each arrow press.
    connect(qApp, &QApplication::focusChanged, this, [this](QWidget* old, QWidget*) {
        if (old && (old == base_ || base_->isAncestorOf(old))) baseKey_ = -1;
    });
    sizeForm->addRow(tr("Base height"), base_);
    layout->addWidget(size);
    connect(list_, &QListWidget::currentRowChanged, this, [this] { showSize(); });

    // The selected proxy's gloss: what a polished table or a wet street reflects of the objects.
    auto* gloss = new QGroupBox(tr("Gloss"));
    auto* glossForm = new QFormLayout(gloss);
    glossPreset_ = new QComboBox;
    glossPreset_->setObjectName("proxyGlossPreset");
    glossPreset_->setToolTip(tr("A typical surface: fills in the reflectance and roughness"));
    glossPreset_->addItem(tr("Custom"));
    for (const GlossPreset& g : kGlossPresets) glossPreset_->addItem(tr(g.name));
    connect(glossPreset_, &QComboBox::activated, this, [this](int i) { applyGlossPreset(i); });
    glossSpecular_ = unit_field("proxyGlossSpecular",
                                tr("Reflectance at normal incidence: 0 matte, 0.04 varnish, tiles or water"));
    glossRoughness_ = unit_field("proxyGlossRoughness", tr("0 a mirror-like polish, 1 a dull sheen"));
    connect(glossSpecular_, &QDoubleSpinBox::valueChanged, this, [this] { applyGloss(); });
    connect(glossRoughness_, &QDoubleSpinBox::valueChanged, this, [this] { applyGloss(); });
    glossForm->addRow(tr("Preset"), glossPreset_);
    glossForm->addRow(tr("Reflectance"), glossSpecular_);
    glossForm->addRow(tr("Roughness"), glossRoughness_);
    layout->addWidget(gloss);
    connect(list_, &QListWidget::currentRowChanged, this, [this] { showGloss(); });

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
    estimate_ = button("albedoEstimate", tr("Estimate albedo"),
                                   tr("Estimate the selected proxy's albedo texture from the "
                                      "photo and the probe (written next to the project)"));
    connect(estimate_, &QPushButton::clicked, this, [this] { estimateAlbedo(list_->currentRow()); });
    albedoForm->addRow(estimate_);
    layout->addWidget(albedo);
    status_ = new QLabel;
    status_->setWordWrap(true);
    status_->setObjectName("proxyStatus");
    layout->addWidget(status_);
    // The last project's result is not this one's.
    connect(doc_, &Document::reloaded, status_, &QLabel::clear);
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
    {
        // Quietly: the emptied list's "no selection" disabled the fields for a moment, and the
        // field being typed in lost the focus at each edit.
        QSignalBlocker quiet(list_);
        list_->clear();
        for (const RealProxy& r : doc_->project().real) {
            QString text = QStringLiteral("%1 (%2)").arg(QString::fromStdString(r.name),
                                                        shape_kind_name(r.shape.kind));
            if (r.albedo.kind == Albedo::Kind::Texture) text += tr(", textured");
            list_->addItem(text);
        }
        list_->setCurrentRow(std::min(row, list_->count() - 1));
    }
    showSize();
    showGloss();
}

void ProxyPanel::showGloss() {
    const int row = list_->currentRow();
    const auto& real = doc_->project().real;
    const RealProxy* r = row >= 0 && size_t(row) < real.size() ? &real[size_t(row)] : nullptr;
    showingSize_ = true;
    for (QWidget* w : {static_cast<QWidget*>(glossPreset_), static_cast<QWidget*>(glossSpecular_),
                       static_cast<QWidget*>(glossRoughness_)})
        w->setEnabled(r != nullptr);
    const Gloss g = r ? r->gloss : Gloss{};
    glossSpecular_->setValue(g.specular);
    glossRoughness_->setValue(g.roughness);
    int preset = 0;
    for (size_t k = 0; k < std::size(kGlossPresets); ++k)
        if (kGlossPresets[k].specular == g.specular && (g.specular == 0 || kGlossPresets[k].roughness == g.roughness))
            preset = int(k) + 1;
    glossPreset_->setCurrentIndex(preset);
    showingSize_ = false;
}

void ProxyPanel::applyGloss() {
    const int row = list_->currentRow();
    Project p = doc_->project();
    if (showingSize_ || row < 0 || size_t(row) >= p.real.size()) return;
    RealProxy& r = p.real[size_t(row)];
    r.gloss.specular = float(glossSpecular_->value());
    r.gloss.roughness = float(glossRoughness_->value());
    if (p.real == doc_->project().real) return;
    doc_->tryEdit(tr("Gloss of %1").arg(QString::fromStdString(r.name)), p);
}

void ProxyPanel::applyGlossPreset(int index) {
    const int row = list_->currentRow();
    Project p = doc_->project();
    if (index < 1 || size_t(index) > std::size(kGlossPresets) || row < 0 || size_t(row) >= p.real.size()) return;
    const GlossPreset& g = kGlossPresets[size_t(index - 1)];
    RealProxy& r = p.real[size_t(row)];
    r.gloss = Gloss{g.specular, g.roughness};
    if (p.real == doc_->project().real) return;
    doc_->tryEdit(tr("%1 gloss on %2").arg(tr(g.name), QString::fromStdString(r.name)), p);
}

void ProxyPanel::showSize() {
    const int row = list_->currentRow();
    const auto& real = doc_->project().real;
    const RealProxy* r = row >= 0 && size_t(row) < real.size() ? &real[size_t(row)] : nullptr;
    const Shape::Kind kind = r ? r->shape.kind : Shape::Kind::Mesh;
    const bool has[3] = {kind == Shape::Kind::Box || kind == Shape::Kind::Plane || kind == Shape::Kind::Sphere,
                         kind == Shape::Kind::Box, kind == Shape::Kind::Box || kind == Shape::Kind::Plane};
    showingSize_ = true;
    for (int k = 0; k < 3; ++k) {
        size_[k]->setEnabled(has[k]);
        if (!has[k]) continue;
        // A sphere's one size is its radius.
        size_[k]->setValue(kind == Shape::Kind::Sphere ? r->shape.radius : r->shape.size[k]);
    }
    size_[0]->setToolTip(kind == Shape::Kind::Sphere ? tr("Radius of the selected sphere")
                                                     : tr("Size of the selected proxy along its own x"));
    base_->setEnabled(r != nullptr);
    if (row != shownRow_) baseKey_ = -1;  // another proxy: another stroke
    shownRow_ = row;
    if (r) base_->setValue(double(proxy_base(*r)));
    showingSize_ = false;
}

float ProxyPanel::proxy_base(const RealProxy& r) {
    const float y = r.transform.translation.y;
    switch (r.shape.kind) {
        case Shape::Kind::Box: return y - 0.5f * r.shape.size.y * std::abs(r.transform.scale.y);
        case Shape::Kind::Sphere: return y - r.shape.radius * std::abs(r.transform.scale.y);
        default: return y;  // a plane's height; a mesh's origin
    }
}

void ProxyPanel::applyBase() {
    const int row = list_->currentRow();
    Project p = doc_->project();
    if (showingSize_ || row < 0 || size_t(row) >= p.real.size()) return;
    RealProxy& r = p.real[size_t(row)];
    r.transform.translation.y += float(base_->value()) - proxy_base(r);
    if (p.real == doc_->project().real) return;
    if (baseKey_ < 0) baseKey_ = doc_->newMergeKey();
    doc_->tryEdit(tr("Raise %1").arg(QString::fromStdString(r.name)), p, baseKey_);
}

void ProxyPanel::applySize() {
    const int row = list_->currentRow();
    Project p = doc_->project();
    if (showingSize_ || row < 0 || size_t(row) >= p.real.size()) return;
    RealProxy& r = p.real[size_t(row)];
    switch (r.shape.kind) {
        case Shape::Kind::Sphere: r.shape.radius = float(size_[0]->value()); break;
        case Shape::Kind::Plane:
            r.shape.size.x = float(size_[0]->value());
            r.shape.size.z = float(size_[2]->value());
            break;
        case Shape::Kind::Box: {
            // Boxes stand on something: a new height keeps the base where it was.
            const float old_height = r.shape.size.y * r.transform.scale.y;
            for (int k = 0; k < 3; ++k) r.shape.size[k] = float(size_[k]->value());
            r.transform.translation.y += 0.5f * (r.shape.size.y * r.transform.scale.y - old_height);
            break;
        }
        case Shape::Kind::Mesh: return;
    }
    if (p.real == doc_->project().real) return;
    doc_->tryEdit(tr("Resize %1").arg(QString::fromStdString(r.name)), p);
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
        const QSize ps = photo_size(doc_->assets(), p);
        std::vector<vec2> px;
        for (QPointF c : corners) px.push_back(render_to_photo(c, viewport_->renderSize(), ps));
        ProxyFit fit = box_proxy(photo_camera(doc_->assets(), p), px, float(boxHeight_->value()),
                                 unique_real_name(p, "box"));
        p.real.push_back(fit.proxy);
        doc_->tryEdit(tr("Add box proxy"), p);
        status_->setText(tr("Box added; footprint fit %1 px").arg(fit.rms_error_px, 0, 'f', 2));
    });
}

bool ProxyPanel::addWall(const QVector<QPointF>& base) {
    return guarded(tr("Wall proxy failed"), [&] {
        if (base.size() != 2)
            throw InputError("", "wall", "a wall takes two points at its base, got " +
                                             std::to_string(base.size()));
        Project p = doc_->project();
        const QSize ps = photo_size(doc_->assets(), p);
        const vec2 a = render_to_photo(base[0], viewport_->renderSize(), ps);
        const vec2 b = render_to_photo(base[1], viewport_->renderSize(), ps);
        ProxyFit fit = wall_proxy(photo_camera(doc_->assets(), p), a, b, float(wallHeight_->value()),
                                  float(wallThickness_->value()), unique_real_name(p, "wall"));
        p.real.push_back(fit.proxy);
        doc_->tryEdit(tr("Add wall proxy"), p);
        status_->setText(tr("Wall added"));
    });
}

bool ProxyPanel::estimateAlbedo(int index) {
    Project p = doc_->project();
    AlbedoTextureOptions o;
    const bool ok = guarded(tr("Albedo estimate failed"), [&] {
        if (worker_.joinable()) throw InputError("", "", "an albedo estimate is already running");
        if (index < 0 || index >= int(p.real.size())) throw InputError("", "real", "select a real proxy first");
        if (doc_->path().isEmpty())
            throw InputError("", "", "save the project first: the texture is written next to it");
        o.max_resolution = resolution_->value();
        o.probe_samples = samples_->value();
        o.clip_level = doc_->assets().photo_clip_level(p);
    });
    if (!ok) return false;
    // Seconds of work: on a worker thread, the result applied on the UI thread to the project as
    // it is then (only the proxy's albedo changes).
    const std::string projectFile = doc_->path().toStdString();
    const std::shared_ptr<AssetLibrary> assets = doc_->assetLibrary();
    const QString name = QString::fromStdString(p.real[size_t(index)].name);
    QPointer<ProxyPanel> self(this);
    status_->setText(tr("Estimating the albedo of %1…").arg(name));
    estimate_->setEnabled(false);
    worker_ = std::thread([=]() mutable {
        std::string error;
        Albedo albedo;
        AlbedoTexture t;
        try {
            t = estimate_albedo_texture(*build_scene(*assets, p), index, o);
            Project q = p;
            attach_albedo_texture(q, index, t, projectFile);
            albedo = q.real[size_t(index)].albedo;
        } catch (const std::exception& e) {
            error = e.what();
        }
        QMetaObject::invokeMethod(qApp, [self, index, name, albedo, t = std::move(t), error] {
            if (!self) return;
            self->worker_.join();
            self->estimate_->setEnabled(true);
            if (!error.empty()) {
                run_reporting_errors(self->reporter_, self->window(), tr("Albedo estimate failed"),
                                     [&] { throw std::runtime_error(error); });
                return;
            }
            Project now = self->doc_->project();
            if (index >= int(now.real.size()) || QString::fromStdString(now.real[size_t(index)].name) != name) return;
            now.real[size_t(index)].albedo = albedo;
            self->doc_->edit(tr("Estimate albedo of %1").arg(name), now);
            const double n = double(t.albedo.size()) / 100.0;
            self->status_->setText(tr("Albedo: %1 x %2 texels, %3% estimated, mean %4")
                                       .arg(t.albedo.width())
                                       .arg(t.albedo.height())
                                       .arg(double(t.valid) / n, 0, 'f', 1)
                                       .arg(double(luminance(t.mean_albedo)), 0, 'f', 3));
        }, Qt::QueuedConnection);
    });
    return true;
}

ProxyPanel::~ProxyPanel() {
    if (worker_.joinable()) worker_.join();
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
