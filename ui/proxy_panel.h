#pragma once
#include <QPointF>
#include <QVector>
#include <QWidget>
#include <functional>
#include <thread>

#include "scene/project.h"

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;
class QListWidget;
class QSpinBox;

namespace dp::ui {

class Document;
class ErrorReporter;
class Viewport;

/// The real proxies that stand in for the photo's surfaces: a list (select, remove), boxes
/// from their clicked footprint (four corners on the ground, in order) and a height, walls from
/// two clicked points at their base, and the albedo texture of the selected proxy estimated
/// from the photo and the probe on demand (written next to the project file), and its gloss
/// (reflectance and roughness, or a preset: a polished table, a wet street). Every change is
/// one undo step; bad input is reported and changes nothing.
class ProxyPanel : public QWidget {
    Q_OBJECT
public:
    ProxyPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter,
               QWidget* parent = nullptr);

    QListWidget* list() const { return list_; }
    /// A box from four footprint corners / a wall from two base points (render pixels).
    bool addBox(const QVector<QPointF>& corners);
    bool addWall(const QVector<QPointF>& base);
    /// Estimates the albedo texture of real proxy `index` on a worker thread (seconds of work)
    /// and points the proxy at it when done; false if the request is refused at once.
    bool estimateAlbedo(int index);
    ~ProxyPanel() override;

private:
    enum class Target { None, Box, Wall };
    void refresh();
    /// The size fields show the selected proxy's (enabled where its shape has that size).
    void showSize();
    /// Applies the size fields to the selected proxy (a box keeps its base where it was).
    void applySize();
    /// Moves the selected proxy up or down so that its lowest point is at the base field's height.
    void applyBase();
    /// The height of a proxy's lowest point (a plane's own height, a mesh's origin).
    static float proxy_base(const RealProxy& r);
    /// The gloss fields show / set the selected proxy's gloss (a preset fills both fields).
    void showGloss();
    void applyGloss();
    void applyGlossPreset(int index);
    void startPicking(Target target);
    void removeSelected();
    bool guarded(const QString& title, const std::function<void()>& f);

    Document* doc_;
    Viewport* viewport_;
    ErrorReporter* reporter_;
    QListWidget* list_;
    QDoubleSpinBox *boxHeight_, *wallHeight_, *wallThickness_;
    QDoubleSpinBox* size_[3] = {};  ///< the selected proxy's size along its x, y, z
    QDoubleSpinBox* base_ = nullptr;  ///< the selected proxy's lowest point's height
    int baseKey_ = -1;                ///< merge key of the base field's stroke
    int shownRow_ = -1;               ///< the proxy the fields show
    bool showingSize_ = false;
    QComboBox* glossPreset_ = nullptr;
    QDoubleSpinBox *glossSpecular_ = nullptr, *glossRoughness_ = nullptr;
    QSpinBox *resolution_, *samples_;
    QLabel* status_;
    QPushButton* estimate_;  ///< disabled while an estimate runs
    Target target_ = Target::None;
    QVector<QPointF> points_;
    std::thread worker_;  ///< the albedo estimate in flight, if any
};

}  // namespace dp::ui
