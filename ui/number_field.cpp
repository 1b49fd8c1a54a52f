#include "number_field.h"

#include <QRegularExpression>
#include <cmath>

namespace dp::ui {

namespace {

/// Text on its way to a number: a sign, digits with one decimal point, an exponent being
/// written, or the start of "nan" / "inf" (typed so that they can be refused with a message).
bool could_become_number(const QString& s) {
    static const QRegularExpression partial(
        QStringLiteral("^[+-]?(\\d*[.,]?\\d*([eE][+-]?\\d*)?|n|na|nan|i|in|inf)$"),
        QRegularExpression::CaseInsensitiveOption);
    return partial.match(s).hasMatch();
}

bool parse(const QString& s, double& v) {
    bool ok = false;
    QString t = s;
    t.replace(QLatin1Char(','), QLatin1Char('.'));
    v = t.toDouble(&ok);  // C locale: accepts "1e20", "nan", "inf"
    return ok;
}

}  // namespace

NumberField::NumberField(QWidget* parent) : QDoubleSpinBox(parent) {
    setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
}

QString NumberField::numberPart(const QString& text) const {
    QString t = text;
    if (!prefix().isEmpty() && t.startsWith(prefix())) t.remove(0, prefix().size());
    if (!suffix().isEmpty() && t.endsWith(suffix())) t.chop(suffix().size());
    return t.trimmed();
}

QValidator::State NumberField::validate(QString& text, int&) const {
    if (!specialValueText().isEmpty() && text == specialValueText()) return QValidator::Acceptable;
    const QString t = numberPart(text);
    if (!could_become_number(t)) return QValidator::Invalid;
    // Anything that is or may become a number can be typed; only a value this field can take
    // is Acceptable, the rest is refused (with a reason) when the user confirms it.
    return problem(text).isEmpty() ? QValidator::Acceptable : QValidator::Intermediate;
}

QString NumberField::problem(const QString& text) const {
    if (!specialValueText().isEmpty() && text == specialValueText()) return {};
    const QString t = numberPart(text);
    double v = 0;
    if (t.isEmpty() || !parse(t, v)) return tr("'%1' is not a number").arg(t);
    if (!std::isfinite(v)) return tr("%1 is not a finite number").arg(t);
    if (v < minimum() || v > maximum())
        return tr("%1 is outside %2 to %3").arg(t, locale().toString(minimum(), 'g', 6),
                                               locale().toString(maximum(), 'g', 6));
    return {};
}

void NumberField::fixup(QString& text) const {
    // Called when the user confirms text that is not a value of this field: the spin box then
    // keeps its previous value (CorrectToPreviousValue); the user hears why.
    const QString why = problem(text);
    if (why.isEmpty()) return;
    const QString label = toolTip().section(QLatin1Char('\n'), 0, 0);
    auto* self = const_cast<NumberField*>(this);
    Q_EMIT self->refused(label.isEmpty() ? why : tr("%1: %2").arg(label, why));
}

double NumberField::valueFromText(const QString& text) const {
    double v = 0;
    if (!parse(numberPart(text), v) || !std::isfinite(v)) return value();
    return v;
}

}  // namespace dp::ui
