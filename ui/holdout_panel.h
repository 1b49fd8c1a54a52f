#pragma once
#include <QImage>
#include <QWidget>
#include <functional>
#include <string>
#include <thread>
#include <vector>

class QLabel;
class QListWidget;
class QPushButton;
class QSpinBox;
class QToolButton;

namespace dp::ui {

class Document;
class ErrorReporter;
class NumberField;
class Viewport;

/// Holdouts: the real occluders the proxies do not model (a board, a plant), painted over the
/// photo so that virtual objects behind them are hidden (docs/holdouts.md). A list (new,
/// remove); the selected one's mask shown over the picture and painted with the viewport's
/// matte tool (brush, erase, polygon, or a rectangle cut out by GrabCut and cut again after
/// strokes); its depth typed or taken from a click on a real surface. Every stroke, cut and
/// depth is one undo step; masks are written beside the project (a saved project is needed).
class HoldoutPanel : public QWidget {
    Q_OBJECT
public:
    HoldoutPanel(Document* doc, Viewport* viewport, ErrorReporter* reporter, QWidget* parent = nullptr);
    ~HoldoutPanel() override;
    QListWidget* list() const { return list_; }
    /// Adds a holdout with an empty mask and selects it; false (reported) if it cannot.
    bool addHoldout();
    /// Cuts the occluder inside `rect` (render pixels) out of the photo, with the strokes made
    /// since the last rectangle as sure labels, into the selected holdout's mask: GrabCut runs on
    /// a worker and the result is one undo step when it is done. False if refused at once.
    bool cut(QRect rect);

private:
    void refresh();
    /// Shows the selected holdout's mask in the viewport (read from its file).
    void showSelected();
    /// Writes the matte tool's mask for the selected holdout and records it as one step.
    bool commit(const QString& text);
    void startTool(int mode);
    void setDepth(double metres, const QString& text);
    /// Lays a finished cut into the mask of holdout `row` (if it is still the one shown).
    void applyCut(QRect rect, int row, int W, int H, const std::vector<uint8_t>& cut, const std::string& error);
    bool guarded(const QString& title, const std::function<void()>& f);

    Document* doc_;
    Viewport* viewport_;
    ErrorReporter* reporter_;
    QListWidget* list_;
    NumberField* depth_;
    QSpinBox* radius_;
    QToolButton* modes_[4] = {};
    QPushButton *recut_, *done_;
    QLabel* status_;
    bool picking_ = false;  ///< the pick tool is taking this panel's depth click
    QString shownMask_;     ///< the mask file the matte tool holds
    std::thread cutter_;    ///< the GrabCut in flight, if any
};

}  // namespace dp::ui
