#include "stroke_slider.h"

#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSlider>

namespace dp::ui {

QSlider* add_stroke_slider(QFormLayout* form, const QString& label, const QString& tip, int lo, int hi,
                           int label_width, QLabel** value, QObject* context,
                           const std::function<void()>& pressed, const std::function<void()>& released,
                           const std::function<void(QSlider*)>& moved) {
    auto* s = new QSlider(Qt::Horizontal);
    s->setRange(lo, hi);
    s->setToolTip(tip);
    *value = new QLabel;
    (*value)->setMinimumWidth(label_width);
    auto* row = new QHBoxLayout;
    row->addWidget(s, 1);
    row->addWidget(*value);
    form->addRow(label, row);
    QObject::connect(s, &QSlider::sliderPressed, context, pressed);
    QObject::connect(s, &QSlider::sliderReleased, context, released);
    QObject::connect(s, &QSlider::valueChanged, context, [s, moved] { moved(s); });
    return s;
}

}  // namespace dp::ui
