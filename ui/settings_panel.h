#pragma once
#include <QWidget>

class QDoubleSpinBox;
class QSpinBox;

namespace dp::ui {

class Document;

/// The project's render settings: photons per pass, passes, time budget, radius, seed.
class SettingsPanel : public QWidget {
    Q_OBJECT
public:
    explicit SettingsPanel(Document* doc, QWidget* parent = nullptr);

private:
    void refresh();
    void apply();

    Document* doc_;
    QSpinBox *photons_, *passes_, *seed_;
    QDoubleSpinBox *budget_, *radius_;
    bool refreshing_ = false;
};

}  // namespace dp::ui
