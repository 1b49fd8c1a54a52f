#pragma once
#include <QDoubleSpinBox>

namespace dp::ui {

/// A number the user types, refused rather than bent: the text may be written as the user
/// thinks of it ("1.5", "2e-3", "1e20"), and a value outside the field's range, or not a number
/// at all ("nan", "inf"), is not clamped to the nearest bound but left unapplied: the field
/// goes back to its last value and refused() says why.
class NumberField : public QDoubleSpinBox {
    Q_OBJECT
public:
    explicit NumberField(QWidget* parent = nullptr);

    QValidator::State validate(QString& text, int& pos) const override;
    void fixup(QString& text) const override;
    double valueFromText(const QString& text) const override;

    /// Why `text` cannot be this field's value, or an empty string if it can.
    QString problem(const QString& text) const;

Q_SIGNALS:
    /// A typed value was not applied; `reason` names the value and the range.
    void refused(const QString& reason);

private:
    QString numberPart(const QString& text) const;
};

}  // namespace dp::ui
