#include "mesh_files.h"

#include <QCoreApplication>
#include <QFileInfo>
#include <QStringList>

#include "geometry/mesh.h"

namespace dp::ui {

QString mesh_file_filter() {
    QStringList patterns;
    for (const std::string& e : mesh_file_extensions())
        patterns << "*." + QString::fromStdString(e);
    return QCoreApplication::translate("dp::ui::MeshFiles", "Meshes (%1)").arg(patterns.join(' '));
}

bool is_mesh_file(const QString& path) {
    const std::string suffix = QFileInfo(path).suffix().toLower().toStdString();
    for (const std::string& e : mesh_file_extensions())
        if (e == suffix) return true;
    return false;
}

}  // namespace dp::ui
