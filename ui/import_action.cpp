#include "ui/import_action.h"

#include "core/material_import.h"
#include "ui/commands/apply_preset_command.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"

#include <QCryptographicHash>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMessageBox>
#include <QSettings>
#include <QStandardPaths>
#include <QUndoStack>

namespace velvet::ui {
namespace {

constexpr const char* kLastImportDirKey = "import/lastDir";

/// imports/<stem>_<8 hex digits of the path's SHA-1>: one folder per source file, so a second
/// import of the same file replaces its own images and no other file's.
QString imageFolderFor(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    const QByteArray hash =
        QCryptographicHash::hash(absolute.toUtf8(), QCryptographicHash::Sha1).toHex().left(8);
    const QString stem =
        QString::fromStdString(sanitizeFileStem(QFileInfo(path).completeBaseName().toStdString()));
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
           QStringLiteral("/imports/") + stem + QLatin1Char('_') + QString::fromLatin1(hash);
}

} // namespace

QString importFilter() {
    return QObject::tr("glTF and MaterialX (*.gltf *.glb *.mtlx)");
}

bool isImportableFile(const QString& path) {
    return velvet::isImportableFile(std::filesystem::path(path.toStdString()));
}

bool importFile(QWidget* parent, DocumentController& controller, const QString& path, LogPanel* log,
                bool withMesh, QString* error, const QString& material) {
    const std::filesystem::path file =
        QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString();
    QString chosen = material;
    if (chosen.isEmpty()) {
        std::vector<std::string> names;
        std::string listError;
        if (!listImportableMaterials(file, names, &listError)) {
            *error = QString::fromStdString(listError);
            return false;
        }
        if (names.size() > 1) {
            QStringList items;
            for (size_t i = 0; i < names.size(); ++i)
                items << QStringLiteral("%1: %2").arg(i).arg(
                    names[i].empty() ? QObject::tr("(unnamed)") : QString::fromStdString(names[i]));
            QInputDialog dialog(parent);
            dialog.setObjectName(QStringLiteral("importMaterialChooser"));
            dialog.setWindowTitle(QObject::tr("Import material"));
            dialog.setLabelText(QObject::tr("%1 holds %2 materials; import which?")
                                    .arg(QFileInfo(path).fileName())
                                    .arg(names.size()));
            dialog.setComboBoxItems(items);
            dialog.setComboBoxEditable(false);
            if (dialog.exec() != QDialog::Accepted) {
                *error = QObject::tr("%1: import cancelled").arg(path);
                return false;
            }
            chosen = QString::number(items.indexOf(dialog.textValue()));
        }
    }
    ImportOptions options;
    options.material = chosen.toStdString();
    options.imageFolder = imageFolderFor(path).toStdString();
    options.force = true; // this file's own folder: a re-import replaces its images
    ImportOutcome outcome = importMaterialFile(file, options);
    for (const std::string& w : outcome.warnings)
        if (log)
            log->warning(QStringLiteral("%1: %2").arg(QFileInfo(path).fileName(),
                                                      QString::fromStdString(w)));
    if (!outcome.ok()) {
        *error = QString::fromStdString(outcome.error);
        return false;
    }
    const QString name = QString::fromStdString(outcome.material.name);
    QUndoStack* stack = controller.undoStack();
    stack->beginMacro(QObject::tr("Import %1").arg(name));
    stack->push(new ApplyPresetCommand(&controller, std::move(outcome.material), std::string()));
    if (withMesh && outcome.hasMesh)
        controller.editMesh(MeshRef{PreviewMeshKind::Custom, file.string()});
    stack->endMacro();
    if (log)
        log->info(QObject::tr("Imported the material %1 from %2 (%3 warnings)")
                      .arg(name, path)
                      .arg(outcome.warnings.size()));
    return true;
}

bool importFileInteractively(QWidget* parent, DocumentController& controller, LogPanel* log) {
    QSettings settings;
    const QString path = QFileDialog::getOpenFileName(
        parent, QObject::tr("Import material"), settings.value(kLastImportDirKey).toString(),
        importFilter() + QStringLiteral(";;") + QObject::tr("All files (*)"));
    if (path.isEmpty())
        return false;
    settings.setValue(kLastImportDirKey, QFileInfo(path).absolutePath());
    QString error;
    if (importFile(parent, controller, path, log, /*withMesh=*/false, &error))
        return true;
    if (log)
        log->error(QObject::tr("Import failed: %1").arg(error));
    QMessageBox::warning(parent, QObject::tr("Import failed"), error);
    return false;
}

} // namespace velvet::ui
