#include "material_panel.h"

#include <QColorDialog>
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QToolButton>
#include <QLabel>
#include <QPushButton>
#include <QSlider>
#include <algorithm>
#include <cmath>

#include "assets/material_presets.h"
#include "document.h"
#include "number_field.h"
#include "panel_widgets.h"
#include "image/image_io.h"
#include "scene/relink.h"
#include "stroke_slider.h"

namespace dp::ui {

namespace {
const char* const kTextureTips[MaterialPanel::kTextureSlots] = {
    "An image for the colour, mapped by the object's UVs (sRGB images are decoded to linear)",
    "glTF's metallic-roughness texture: green times the roughness, blue times the metallic; read as data",
    "A tangent-space normal map (OpenGL's and glTF's convention: +Y towards the image's top); read as data"};
}  // namespace

MaterialPanel::MaterialPanel(Document* doc, QWidget* parent) : QWidget(parent), doc_(doc) {
    auto* form = new QFormLayout(this);
    form_ = form;
    source_ = new QComboBox;
    source_->addItems({tr("This material"), tr("The mesh file's")});
    source_->setToolTip(tr("Draw the mesh with the materials of its file, or with this one"));
    form->addRow(tr("Materials"), source_);
    sourceNote_ =
        new QLabel(tr("Triangles with a material in the file are drawn with it; the material "
                      "below covers the others."));
    sourceNote_->setWordWrap(true);
    form->addRow(sourceNote_);
    kind_ = new QComboBox;
    kind_->addItems({tr("Diffuse"), tr("Mirror"), tr("Glass"), tr("Principled")});
    kind_->setToolTip(tr("Kind of material of the selected object"));
    form->addRow(tr("Material"), kind_);
    preset_ = new QComboBox;
    preset_->addItem(tr("Preset..."));
    for (const MaterialPreset& preset : material_presets()) preset_->addItem(tr(preset.name));
    preset_->setToolTip(tr("Make the material a principled preset, then adjust it; plastic, rubber and "
                           "ceramic keep the colour"));
    form->addRow(QString(), preset_);
    colour_ = new QPushButton;
    colour_->setToolTip(tr("Diffuse colour (albedo), or the principled base colour: click to pick"));
    form->addRow(tr("Colour"), colour_);
    reflectance_ = addSlider(form, tr("Reflectance"), tr("Mirror reflectance (grey), 0 to 1"), 0,
                             100, &reflectanceValue_);
    ior_ = addSlider(form, tr("IOR"), tr("Glass index of refraction, 1.0 to 2.5"), 100, 250,
                     &iorValue_);
    tint_ = new QPushButton;
    tint_->setToolTip(tr("Glass tint: transmittance per crossing; click to pick"));
    form->addRow(tr("Tint"), tint_);
    addPrincipledFields(form);
    addTextureSlots(form);

    connect(kind_, &QComboBox::currentIndexChanged, this, [this](int k) {
        const int sel = doc_->selected();
        if (refreshing_ || sel < 0) return;
        Project p = doc_->project();
        p.objects[size_t(sel)].material.kind = Material::Kind(k);
        doc_->edit(tr("Change material"), p);
    });
    connect(preset_, &QComboBox::activated, this, [this](int k) {
        const int sel = doc_->selected();
        if (refreshing_ || sel < 0 || k <= 0) return;
        const MaterialPreset& preset = material_presets()[size_t(k - 1)];
        Project p = doc_->project();
        Material& m = p.objects[size_t(sel)].material;
        m = with_preset(m, preset);
        doc_->edit(tr("Material preset: %1").arg(tr(preset.name)), p);
        preset_->setCurrentIndex(0);
    });
    connect(source_, &QComboBox::currentIndexChanged, this, [this](int k) {
        const int sel = doc_->selected();
        if (refreshing_ || sel < 0) return;
        Project p = doc_->project();
        p.objects[size_t(sel)].material_source = MaterialSource(k);
        doc_->edit(tr("Change material source"), p);
    });
    connect(colour_, &QPushButton::clicked, this, [this] { pickColour(false); });
    connect(tint_, &QPushButton::clicked, this, [this] { pickColour(true); });
    connect(doc_, &Document::changed, this, [this] { refresh(); });
    connect(doc_, &Document::selectionChanged, this, [this] { refresh(); });
    refresh();
}

void MaterialPanel::addPrincipledFields(QFormLayout* form) {
    struct Row {
        const char *label, *tip;
        double lo, hi;
    };
    static const Row rows[kPrincipledFields] = {
        {"Metallic", "0: a dielectric (plastic, glass), 1: a metal whose colour is the base colour", 0, 1},
        {"Roughness", "Perceptual roughness, 0 (polished) to 1 (matte); alpha = roughness squared", 0, 1},
        {"IOR", "Index of refraction of the dielectric, 1.01 to 5", kMinPrincipledIor, kMaxPrincipledIor},
        {"Specular", "Strength of the dielectric's reflection, 0 to 1", 0, 1},
        {"Transmission", "Share of the base that lets light through (rough glass), 0 to 1", 0, 1},
        {"Emission", "Emitted radiance (grey), linear; it lights the scene like a lamp", 0, 1e6},
        {"Normal strength", "How far the normal map tilts the surface: its X and Y times this, 0 to 10", 0, 10},
    };
    for (int i = 0; i < kPrincipledFields; ++i) {
        auto* f = new NumberField;
        f->setRange(rows[i].lo, rows[i].hi);
        f->setDecimals(3);
        f->setSingleStep(0.05);
        f->setKeyboardTracking(false);
        f->setToolTip(tr(rows[i].tip));
        form->addRow(tr(rows[i].label), f);
        principled_[i] = f;
        connect(f, &NumberField::valueChanged, this,
                [this, i](double v) { principledEdited(PrincipledField(i), v); });
    }
}

void MaterialPanel::principledEdited(PrincipledField field, double value) {
    const int sel = doc_->selected();
    if (refreshing_ || sel < 0) return;
    Project p = doc_->project();
    PrincipledMaterial& m = p.objects[size_t(sel)].material.principled;
    const float v = float(value);
    switch (field) {
        case Metallic: m.metallic = v; break;
        case Roughness: m.roughness = v; break;
        case Ior: m.ior = v; break;
        case Specular: m.specular = v; break;
        case Transmission: m.transmission = v; break;
        case Emission: m.emission = vec3(v); break;
        case NormalStrength: m.normal_scale = v; break;
        case kPrincipledFields: return;
    }
    if (!doc_->tryEdit(tr("Adjust material"), p)) refresh();
}

void MaterialPanel::addTextureSlots(QFormLayout* form) {
    static const char* const labels[kTextureSlots] = {"Colour map", "Metal/rough map", "Normal map"};
    static const char* const names[kTextureSlots] = {"BaseColour", "MetallicRoughness", "Normal"};
    for (int i = 0; i < kTextureSlots; ++i) {
        auto* row = new QWidget;
        auto* layout = new QHBoxLayout(row);
        layout->setContentsMargins(0, 0, 0, 0);
        auto* choose = new QPushButton;
        choose->setObjectName(QString("textureSlot%1").arg(names[i]));
        choose->setToolTip(tr(kTextureTips[i]));
        auto* clear = new QToolButton;
        clear->setObjectName(QString("textureClear%1").arg(names[i]));
        clear->setText(QString::fromUtf8("\u2715"));
        clear->setToolTip(tr("No texture"));
        layout->addWidget(choose, 1);
        layout->addWidget(clear);
        form->addRow(tr(labels[i]), row);
        textureButtons_[i] = choose;
        textureClears_[i] = clear;
        textureRows_[i] = row;
        const auto slot = TextureSlot(i);
        connect(choose, &QPushButton::clicked, this, [this, slot] {
            const QString dir = QString::fromStdString(doc_->project().base_dir.string());
            const QString f = QFileDialog::getOpenFileName(
                this, tr("Choose a texture"), dir,
                tr("Images (*.png *.jpg *.jpeg *.exr *.hdr *.tif *.tiff *.bmp)"));
            if (!f.isEmpty()) setTexture(slot, f);
        });
        connect(clear, &QToolButton::clicked, this, [this, slot] { setTexture(slot, QString()); });
    }
}

void MaterialPanel::setTexture(TextureSlot slot, const QString& path) {
    const int sel = doc_->selected();
    if (refreshing_ || sel < 0) return;
    Project p = doc_->project();
    Material& m = p.objects[size_t(sel)].material;
    // Stored as projects store paths: relative inside the project's folder.
    const std::string stored =
        path.isEmpty() ? std::string() : path_for_project(p.base_dir, QFileInfo(path).absoluteFilePath().toStdString());
    switch (slot) {
        case BaseColourMap:
            m.albedo.kind = stored.empty() ? Albedo::Kind::Constant : Albedo::Kind::Texture;
            m.albedo.texture_path = stored;
            break;
        case MetallicRoughnessMap: m.principled.metallic_roughness_texture = stored; break;
        case NormalMap: m.principled.normal_texture = stored; break;
        case kTextureSlots: return;
    }
    doc_->edit(stored.empty() ? tr("Clear texture") : tr("Choose texture"), p);
}

QSlider* MaterialPanel::addSlider(QFormLayout* form, const QString& label, const QString& tip,
                                  int lo, int hi, QLabel** value) {
    return add_stroke_slider(
        form, label, tip, lo, hi, 40, value, this,
        [this] {
            strokeKey_ = doc_->newMergeKey();
            Q_EMIT strokeStarted();
        },
        [this] {
            strokeKey_ = -1;
            Q_EMIT strokeFinished();
        },
        [this](QSlider* s) { sliderMoved(s); });
}

void MaterialPanel::sliderMoved(QSlider* moved) {
    const int sel = doc_->selected();
    if (refreshing_ || sel < 0) return;
    Project p = doc_->project();
    Material& m = p.objects[size_t(sel)].material;
    if (moved == reflectance_) m.reflectance = vec3(float(reflectance_->value()) / 100.0f);
    if (moved == ior_) m.ior = float(ior_->value()) / 100.0f;
    reflectanceValue_->setText(QString::number(reflectance_->value() / 100.0, 'f', 2));
    iorValue_->setText(QString::number(ior_->value() / 100.0, 'f', 2));
    // While the slider is held all moves fold into one undo step (a new step otherwise).
    doc_->edit(tr("Adjust material"), p, strokeKey_);
}

void MaterialPanel::setDiffuseColour(const QColor& colour) {
    const int sel = doc_->selected();
    if (sel < 0 || !colour.isValid()) return;
    Project p = doc_->project();
    p.objects[size_t(sel)].material.albedo.rgb = to_linear(colour);
    doc_->edit(tr("Change colour"), p);
}

void MaterialPanel::pickColour(bool tint) {
    const int sel = doc_->selected();
    if (sel < 0) return;
    const Material& m = doc_->project().objects[size_t(sel)].material;
    const QColor c = QColorDialog::getColor(to_qcolor(tint ? m.tint : m.albedo.rgb), this,
                                            tint ? tr("Glass tint")
                                            : m.kind == Material::Kind::Principled ? tr("Base colour")
                                                                                   : tr("Diffuse colour"));
    if (!c.isValid()) return;
    if (!tint) {
        setDiffuseColour(c);
        return;
    }
    Project p = doc_->project();
    p.objects[size_t(sel)].material.tint = to_linear(c);
    doc_->edit(tr("Change tint"), p);
}

void MaterialPanel::refresh() {
    refreshing_ = true;
    const int sel = doc_->selected();
    setEnabled(sel >= 0);
    form_->setRowVisible(source_, false);
    form_->setRowVisible(sourceNote_, false);
    for (NumberField* f : principled_) form_->setRowVisible(f, false);
    for (QWidget* row : textureRows_) form_->setRowVisible(row, false);
    if (sel >= 0) {
        const VirtualObject& o = doc_->project().objects[size_t(sel)];
        const Material& m = o.material;
        // Only a mesh has a file to take materials from.
        const bool mesh = o.shape.kind == Shape::Kind::Mesh;
        form_->setRowVisible(source_, mesh);
        form_->setRowVisible(sourceNote_, mesh && o.material_source == MaterialSource::File);
        source_->setCurrentIndex(int(o.material_source));
        kind_->setCurrentIndex(int(m.kind));
        paint_swatch(colour_, to_qcolor(m.albedo.rgb));
        paint_swatch(tint_, to_qcolor(m.tint));
        reflectance_->setValue(int(std::lround(luminance(m.reflectance) * 100)));
        ior_->setValue(int(std::lround(m.ior * 100)));
        reflectanceValue_->setText(QString::number(reflectance_->value() / 100.0, 'f', 2));
        iorValue_->setText(QString::number(ior_->value() / 100.0, 'f', 2));
        const bool principled = m.kind == Material::Kind::Principled;
        const PrincipledMaterial& pm = m.principled;
        const float values[kPrincipledFields] = {pm.metallic, pm.roughness,    pm.ior,
                                                 pm.specular, pm.transmission, luminance(pm.emission),
                                                 pm.normal_scale};
        for (int i = 0; i < kPrincipledFields; ++i) {
            principled_[i]->setValue(double(values[i]));
            form_->setRowVisible(principled_[i], principled);
        }
        const bool diffuse = m.kind == Material::Kind::Diffuse;
        const std::string paths[kTextureSlots] = {
            m.albedo.kind == Albedo::Kind::Texture ? m.albedo.texture_path : std::string(),
            pm.metallic_roughness_texture, pm.normal_texture};
        for (int i = 0; i < kTextureSlots; ++i) {
            const QString path = QString::fromStdString(paths[i]);
            textureButtons_[i]->setText(path.isEmpty() ? tr("Choose...") : QFileInfo(path).fileName());
            textureButtons_[i]->setToolTip(tr(kTextureTips[i]) + (path.isEmpty() ? QString() : "\n" + path));
            textureClears_[i]->setEnabled(!path.isEmpty());
            form_->setRowVisible(textureRows_[i], i == BaseColourMap ? diffuse || principled : principled);
        }
        colour_->setEnabled(diffuse || principled);
        reflectance_->setEnabled(m.kind == Material::Kind::Mirror);
        ior_->setEnabled(m.kind == Material::Kind::Glass);
        tint_->setEnabled(m.kind == Material::Kind::Glass);
    }
    refreshing_ = false;
}

}  // namespace dp::ui
