#include "ui/export_action.h"

#include "core/material_export.h"
#include "core/mtlx_export.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"

#include <QApplication>
#include <QCoreApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QGuiApplication>
#include <QMessageBox>
#include <QSettings>
#include <array>

namespace velvet::ui {
namespace {

constexpr const char* kLastExportDirKey = "export/lastDir";

QString tr(const char* text) {
    return QCoreApplication::translate("velvet::ui::ExportAction", text);
}

struct WayOut {
    const char* label;
    ExportFormat format;
    MtlxShader shader;
};

// glTF first (what engines read), then MaterialX per shader node, then the native preset.
constexpr std::array kWaysOut{
    WayOut{"glTF 2.0 binary", ExportFormat::Glb, MtlxShader::StandardSurface},
    WayOut{"glTF 2.0 with separate files", ExportFormat::Gltf, MtlxShader::StandardSurface},
    WayOut{"MaterialX, standard_surface", ExportFormat::Mtlx, MtlxShader::StandardSurface},
    WayOut{"MaterialX, open_pbr_surface", ExportFormat::Mtlx, MtlxShader::OpenPbrSurface},
    WayOut{"MaterialX, gltf_pbr", ExportFormat::Mtlx, MtlxShader::GltfPbr},
    WayOut{"Velvet preset", ExportFormat::Preset, MtlxShader::StandardSurface},
};

QString filterOf(const WayOut& way) {
    const std::string_view ext = exportFormatExtension(way.format);
    return QStringLiteral("%1 (*%2)")
        .arg(tr(way.label), QString::fromUtf8(ext.data(), qsizetype(ext.size())));
}

/// The way out @p filter names, else the first whose extension @p path has.
const WayOut* wayOutFor(const QString& filter, const QString& path) {
    for (const WayOut& way : kWaysOut)
        if (filterOf(way) == filter)
            return &way;
    const QString suffix = QLatin1Char('.') + QFileInfo(path).suffix().toLower();
    for (const WayOut& way : kWaysOut)
        if (QString::fromUtf8(exportFormatExtension(way.format).data()) == suffix)
            return &way;
    return nullptr;
}

} // namespace

QStringList exportFilters() {
    QStringList filters;
    for (const WayOut& way : kWaysOut)
        filters << filterOf(way);
    return filters;
}

bool exportDocument(const DocumentController& controller, const QString& path,
                    const QString& filter, LogPanel* log, QString* error) {
    const WayOut* way = wayOutFor(filter, path);
    if (!way) {
        if (error)
            *error = tr("%1: not a format Velvet exports (.glb, .gltf, .mtlx, .json)").arg(path);
        return false;
    }
    QString target = path;
    const QString ext = QString::fromUtf8(exportFormatExtension(way->format).data());
    if (!target.endsWith(ext, Qt::CaseInsensitive))
        target += ext;
    const QFileInfo info(target);
    ExportOptions options;
    options.format = way->format;
    options.shader = way->shader;
    options.force = true; // the save dialog asked before replacing
    // Texture decoding and baking can take a moment: say so rather than look frozen.
    QGuiApplication::setOverrideCursor(Qt::WaitCursor);
    const ExportOutcome outcome =
        exportMaterial(controller.scene(), info.absolutePath().toStdString(),
                       info.completeBaseName().toStdString(), options);
    QGuiApplication::restoreOverrideCursor();
    for (const std::string& warning : outcome.warnings)
        if (log)
            log->warning(tr("Export %1: %2").arg(info.fileName(), QString::fromStdString(warning)));
    if (!outcome.ok()) {
        if (error)
            *error = QString::fromStdString(outcome.error);
        return false;
    }
    if (log)
        log->info(tr("Exported %1 (%2 files)").arg(target).arg(outcome.written.size()));
    return true;
}

bool exportDocumentInteractively(QWidget* parent, const DocumentController& controller,
                                 LogPanel* log) {
    QSettings settings;
    const QString stem = QString::fromStdString(controller.material().name).trimmed().isEmpty()
                             ? QStringLiteral("material")
                             : QString::fromStdString(controller.material().name);
    const QString start = settings.value(kLastExportDirKey).toString();
    QString filter = exportFilters().front();
    const QString path = QFileDialog::getSaveFileName(
        parent, tr("Export material"), start.isEmpty() ? stem : start + QLatin1Char('/') + stem,
        exportFilters().join(";;"), &filter);
    if (path.isEmpty())
        return false;
    settings.setValue(kLastExportDirKey, QFileInfo(path).absolutePath());
    QString error;
    if (exportDocument(controller, path, filter, log, &error))
        return true;
    if (log)
        log->error(tr("Export failed: %1").arg(error));
    QMessageBox::warning(parent, tr("Export failed"), error);
    return false;
}

} // namespace velvet::ui
