#pragma once
#include <QString>

#include <functional>

class QFormLayout;
class QLabel;
class QObject;
class QSlider;

namespace dp::ui {

/// Adds a form row: a horizontal slider of range [lo, hi] and a label for its value (`*value`,
/// at least `label_width` pixels wide). Pressing and releasing the slider bracket one undo
/// stroke (`pressed`, `released`); `moved` runs on every value change. `context` owns the
/// connections.
QSlider* add_stroke_slider(QFormLayout* form, const QString& label, const QString& tip, int lo, int hi,
                           int label_width, QLabel** value, QObject* context,
                           const std::function<void()>& pressed, const std::function<void()>& released,
                           const std::function<void(QSlider*)>& moved);

}  // namespace dp::ui
