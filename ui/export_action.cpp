#include "ui/export_action.h"

#include "core/material_export.h"
#include "core/mtlx_export.h"
#include "core/texture_set_export.h"
#include "render/baked_export.h"
#include "render/material_bake.h"
#include "ui/busy_work.h"
#include "ui/document_controller.h"
#include "ui/log_panel.h"
#include "ui/texture_set_dialog.h"

#include <QApplication>
#include <QCoreApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMessageBox>
#include <QSettings>
#include <array>
#include <cstring>
#include <optional>

namespace velvet::ui {
namespace {

constexpr const char* kLastExportDirKey = "export/lastDir";
constexpr const char* kLastExportFilterKey = "export/lastFilter";
constexpr const char* kLastBakeSizeKey = "export/lastBakeSize";
/// The main file of a texture set, the manifest: NAME_texture_set.json.
constexpr const char* kTextureSetSuffix = "_texture_set.json";

QString tr(const char* text) {
    return QCoreApplication::translate("velvet::ui::ExportAction", text);
}

struct WayOut {
    const char* label;
    ExportFormat format;
    MtlxShader shader;
    /// An engine texture set (render::exportTextureSet) instead of format.
    std::optional<TextureSetTarget> textureSet = std::nullopt;
};

// glTF first (what engines read), then MaterialX per shader node, then the native preset.
constexpr std::array kWaysOut{
    WayOut{"glTF 2.0 binary", ExportFormat::Glb, MtlxShader::StandardSurface},
    WayOut{"glTF 2.0 with separate files", ExportFormat::Gltf, MtlxShader::StandardSurface},
    WayOut{"MaterialX, standard_surface", ExportFormat::Mtlx, MtlxShader::StandardSurface},
    WayOut{"MaterialX, open_pbr_surface", ExportFormat::Mtlx, MtlxShader::OpenPbrSurface},
    WayOut{"MaterialX, gltf_pbr", ExportFormat::Mtlx, MtlxShader::GltfPbr},
    WayOut{"Velvet preset", ExportFormat::Preset, MtlxShader::StandardSurface},
    // Engine texture sets: the maps baked on the GPU, named and packed per engine, and the
    // manifest (the file the dialog names) beside them.
    WayOut{"Texture set for Unreal Engine", ExportFormat::Preset, MtlxShader::StandardSurface,
           TextureSetTarget::Unreal},
    WayOut{"Texture set for Unity HDRP", ExportFormat::Preset, MtlxShader::StandardSurface,
           TextureSetTarget::UnityHdrp},
    WayOut{"Texture set for Godot", ExportFormat::Preset, MtlxShader::StandardSurface,
           TextureSetTarget::Godot},
    WayOut{"Texture set for glTF", ExportFormat::Preset, MtlxShader::StandardSurface,
           TextureSetTarget::Gltf},
};

QString filterOf(const WayOut& way) {
    if (way.textureSet)
        return QStringLiteral("%1 (*%2)").arg(tr(way.label), QLatin1String(kTextureSetSuffix));
    const std::string_view ext = exportFormatExtension(way.format);
    return QStringLiteral("%1 (*%2)")
        .arg(tr(way.label), QString::fromUtf8(ext.data(), qsizetype(ext.size())));
}

/// Bakes and writes a texture set on a worker thread (the bake makes its own headless EGL
/// context there, leaving the viewport's context alone) while a busy dialog shows progress.
ExportOutcome exportTextureSetWithProgress(const Material& material, const QFileInfo& info,
                                           const TextureSetOptions& options) {
    QString base = info.fileName();
    if (base.endsWith(QLatin1String(kTextureSetSuffix), Qt::CaseInsensitive))
        base.chop(int(std::strlen(kTextureSetSuffix)));
    const std::string folder = info.absolutePath().toStdString();
    return runWithBusyDialog(tr("Baking the %1 texture set…").arg(base),
                             [material, folder, base = base.toStdString(), options] {
                                 return render::exportTextureSet(material, folder, base, options,
                                                                 /*force=*/true);
                             });
}

/// Exports the scene's material, its node graph baked, on a worker thread (the bake makes its
/// own headless EGL context there, as for texture sets) while a busy dialog shows progress.
ExportOutcome exportMaterialWithProgress(const Scene& scene, const QFileInfo& info,
                                         const ExportOptions& options) {
    const std::string folder = info.absolutePath().toStdString();
    return runWithBusyDialog(
        tr("Exporting %1…").arg(info.fileName()),
        [scene, folder, base = info.completeBaseName().toStdString(), options] {
            return render::exportMaterialBaked(scene, folder, base, options);
        });
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
                    const QString& filter, LogPanel* log, QString* error,
                    const TextureSetOptions* textureSet, int bakeSize) {
    const WayOut* way = wayOutFor(filter, path);
    if (!way) {
        if (error)
            *error = tr("%1: not a format Velvet exports (.glb, .gltf, .mtlx, .json)").arg(path);
        return false;
    }
    if (way->textureSet) {
        QString target = path;
        if (!target.endsWith(QLatin1String(kTextureSetSuffix), Qt::CaseInsensitive)) {
            if (target.endsWith(QLatin1String(".json"), Qt::CaseInsensitive))
                target.chop(5);
            target += QLatin1String(kTextureSetSuffix);
        }
        const QFileInfo info(target);
        TextureSetOptions options = textureSet ? *textureSet : TextureSetOptions{};
        options.target = *way->textureSet;
        if (const std::string problem = checkTextureSetOptions(options); !problem.empty()) {
            if (error)
                *error = tr("%1: %2").arg(target, QString::fromStdString(problem));
            return false;
        }
        const ExportOutcome outcome =
            exportTextureSetWithProgress(controller.material(), info, options);
        for (const std::string& warning : outcome.warnings)
            if (log)
                log->warning(
                    tr("Export %1: %2").arg(info.fileName(), QString::fromStdString(warning)));
        if (!outcome.ok()) {
            if (error)
                *error = QString::fromStdString(outcome.error);
            return false;
        }
        if (log)
            log->info(tr("Exported %1 (%2 files)")
                          .arg(QString::fromStdString(outcome.written.back().string()))
                          .arg(outcome.written.size()));
        return true;
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
    if (bakeSize > 0)
        options.bakeSize = bakeSize;
    // Texture decoding and the graph's bake (at the CLI's default size) can take a moment.
    const ExportOutcome outcome = exportMaterialWithProgress(controller.scene(), info, options);
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
    // The way out chosen last time is offered first again.
    QString filter = settings.value(kLastExportFilterKey).toString();
    if (!exportFilters().contains(filter))
        filter = exportFilters().front();
    const QString path = QFileDialog::getSaveFileName(
        parent, tr("Export material"), start.isEmpty() ? stem : start + QLatin1Char('/') + stem,
        exportFilters().join(";;"), &filter);
    if (path.isEmpty())
        return false;
    settings.setValue(kLastExportDirKey, QFileInfo(path).absolutePath());
    settings.setValue(kLastExportFilterKey, filter);
    // An engine's texture set: its size, file type, bits and normal convention first.
    std::optional<TextureSetOptions> textureSet;
    if (const WayOut* way = wayOutFor(filter, path); way && way->textureSet) {
        TextureSetDialog dialog(*way->textureSet, parent);
        if (dialog.exec() != QDialog::Accepted)
            return false;
        dialog.remember();
        textureSet = dialog.options();
    }
    // A node graph is baked to maps for glTF and MaterialX: at what size (as --bake-size).
    int bakeSize = 0;
    if (const WayOut* way = wayOutFor(filter, path); way && !way->textureSet &&
                                                     way->format != ExportFormat::Preset &&
                                                     controller.material().graph) {
        bool ok = false;
        bakeSize = QInputDialog::getInt(
            parent, tr("Bake the node graph"),
            tr("The node graph's maps are baked to textures for this format.\nSize (texels "
               "square):"),
            settings.value(kLastBakeSizeKey, 1024).toInt(), 1, 8192, 256, &ok);
        if (!ok)
            return false;
        settings.setValue(kLastBakeSizeKey, bakeSize);
    }
    QString error;
    if (exportDocument(controller, path, filter, log, &error, textureSet ? &*textureSet : nullptr,
                       bakeSize))
        return true;
    if (log)
        log->error(tr("Export failed: %1").arg(error));
    QMessageBox::warning(parent, tr("Export failed"), error);
    return false;
}

} // namespace velvet::ui
