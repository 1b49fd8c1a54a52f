#pragma once
// Small widget factories the panels share.
#include <QApplication>
#include <QColor>
#include <QPushButton>
#include <QString>
#include <algorithm>
#include <cmath>

#include "base/math.h"
#include "image/image_io.h"
#include "number_field.h"

namespace dp::ui {

/// The wait cursor for as long as it lives, taken back however the scope ends (a match that
/// throws left the cursor waiting).
class WaitCursor {
public:
    WaitCursor() { QApplication::setOverrideCursor(Qt::WaitCursor); }
    ~WaitCursor() { QApplication::restoreOverrideCursor(); }
    WaitCursor(const WaitCursor&) = delete;
    WaitCursor& operator=(const WaitCursor&) = delete;
};

/// A number field with its range, decimals, value, unit suffix and tooltip set.
inline NumberField* make_number_field(double lo, double hi, double value, int decimals,
                                      const QString& suffix, const QString& tip) {
    auto* s = new NumberField;
    s->setRange(lo, hi);
    s->setDecimals(decimals);
    s->setValue(value);
    s->setSuffix(suffix);
    s->setToolTip(tip);
    return s;
}

/// A linear colour as the screen shows it (sRGB, clamped to [0, 1]): colours are linear in the
/// project and sRGB in the colour dialog.
inline QColor to_qcolor(const vec3& linear) {
    auto c = [](float v) { return int(std::lround(linear_to_srgb(std::clamp(v, 0.0f, 1.0f)) * 255)); };
    return QColor(c(linear.x), c(linear.y), c(linear.z));
}

/// The linear colour of an sRGB one.
inline vec3 to_linear(const QColor& c) {
    return vec3(srgb_to_linear(float(c.redF())), srgb_to_linear(float(c.greenF())),
                srgb_to_linear(float(c.blueF())));
}

/// Shows `c` as the button's face (a colour button).
inline void paint_swatch(QPushButton* b, const QColor& c) {
    b->setStyleSheet(QStringLiteral("background-color: %1; min-height: 1.4em;").arg(c.name()));
}

/// A push button with an object name (tests find it by that) and a tooltip.
inline QPushButton* make_named_button(const QString& name, const QString& text, const QString& tip) {
    auto* b = new QPushButton(text);
    b->setObjectName(name);
    b->setToolTip(tip);
    return b;
}

}  // namespace dp::ui
