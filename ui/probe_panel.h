#pragma once
#include <QImage>
#include <QPointF>
#include <QWidget>

class QLabel;
class QPushButton;
class QSlider;
class QSpinBox;

namespace dp::ui {

class Document;

/// The light probe: a preview of the lat-long map (drag across it to turn the probe), rotation
/// about the vertical axis, exposure (the probe's intensity in stops) and its white balance
/// (set by the grey card's "Match colour too", shown here with a reset) and the widest the probe
/// is kept (probe.max_width, automatic by default).
class ProbePanel : public QWidget {
    Q_OBJECT
public:
    explicit ProbePanel(Document* doc, QWidget* parent = nullptr);

    /// Sets the probe's white balance back to neutral (one undo step).
    void resetWhiteBalance();

Q_SIGNALS:
    void strokeStarted();
    void strokeFinished();

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void refresh();
    void loadPreview();
    void applySliders();
    void applyMaxWidth();

    Document* doc_;
    QLabel* preview_;
    QSlider *rotation_, *tiltX_, *tiltZ_, *exposure_;
    QLabel *rotationValue_, *tiltXValue_, *tiltZValue_, *exposureValue_;
    QLabel* whiteBalance_;
    QPushButton* resetWhiteBalance_;
    QSpinBox* maxWidth_;  ///< 0 shows "automatic"
    QString previewKey_;
    QImage previewImage_;
    QPointF sun_;  ///< brightest point of the probe, as fractions of its width and height
    int strokeKey_ = -1;
    int dragX_ = 0, dragStartValue_ = 0;
    bool refreshing_ = false;
};

}  // namespace dp::ui
