#pragma once
// Small widget factories the panels share.
#include <QPushButton>
#include <QString>

#include "number_field.h"

namespace dp::ui {

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

/// A push button with an object name (tests find it by that) and a tooltip.
inline QPushButton* make_named_button(const QString& name, const QString& text, const QString& tip) {
    auto* b = new QPushButton(text);
    b->setObjectName(name);
    b->setToolTip(tip);
    return b;
}

}  // namespace dp::ui
