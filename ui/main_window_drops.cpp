// MainWindow's drops (ui/main_window.h): what a file dropped on the window does. Split from
// main_window.cpp by job, as the menus are (main_window_menus.cpp).
#include "core/default_stage.h"
#include "core/document_io.h"
#include "core/texture_ref.h"
#include "ui/document_controller.h"
#include "ui/import_action.h"
#include "ui/library/library_panel.h"
#include "ui/log_panel.h"
#include "ui/main_window.h"
#include "ui/viewport_widget.h"

#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QMimeData>
#include <QStatusBar>
#include <QUrl>

namespace velvet::ui {
namespace {

/// What a file dropped on the window does: a scene opens, a preset is applied to the current
/// scene (undoable), a glTF or MaterialX file's material is imported (a glTF's mesh becomes the
/// preview mesh), an HDR image becomes the environment, a mesh the preview mesh, another image
/// the base colour texture.
enum class DropKind { None, Document, Hdri, Mesh, Image, Interchange };

DropKind dropKindOf(const QString& path) {
    const QString suffix = QFileInfo(path).suffix().toLower();
    if (suffix == QLatin1String("json"))
        return DropKind::Document;
    // glTF and MaterialX bring a material in (a glTF's mesh too): ui/import_action.h.
    if (isImportableFile(path))
        return DropKind::Interchange;
    if (suffix == QLatin1String("exr") || suffix == QLatin1String("hdr"))
        return DropKind::Hdri;
    static const QStringList images = {QStringLiteral("png"),  QStringLiteral("jpg"),
                                       QStringLiteral("jpeg"), QStringLiteral("tif"),
                                       QStringLiteral("tiff"), QStringLiteral("tga"),
                                       QStringLiteral("bmp")};
    if (images.contains(suffix))
        return DropKind::Image;
    static const QStringList meshes = {QStringLiteral("obj"), QStringLiteral("fbx"),
                                       QStringLiteral("ply"), QStringLiteral("stl"),
                                       QStringLiteral("dae")};
    if (meshes.contains(suffix))
        return DropKind::Mesh;
    return DropKind::None;
}

/// Absolute, normalised, '/'-separated: the form core stores resource paths in.
std::string documentPath(const QString& path) {
    return QDir::cleanPath(QFileInfo(path).absoluteFilePath()).toStdString();
}

} // namespace

bool MainWindow::openDroppedFile(const QString& path) {
    switch (dropKindOf(path)) {
    case DropKind::Document: {
        // A material preset dropped on the window is applied to the scene being judged (one
        // undoable step, like the Library); a scene replaces the document.
        if (detectDocumentKind(path.toStdString()) == DocumentKind::Material) {
            QString error;
            if (!m_library->applyPreset(path, &error)) {
                m_log->error(error);
                statusBar()->showMessage(tr("Could not apply %1 (see the Log)").arg(path), 10000);
                return false;
            }
            m_log->info(tr("Applied the preset %1").arg(path));
            return true;
        }
        return maybeSave() && openFile(path);
    }
    case DropKind::Image: {
        TextureRef ref;
        ref.file = documentPath(path);
        const bool factorReset = m_controller->assignTextureImage(
            TextureSlot::BaseColor, ref,
            tr("Set Base colour texture %1").arg(QFileInfo(path).fileName()));
        m_log->info(
            tr("Base colour texture: %1 (drop on a Properties slot for another one)").arg(path));
        if (factorReset)
            m_log->info(tr("Base colour factor set to white so the map shows as painted (it "
                           "multiplies the map; Ctrl+Z restores both)"));
        return true;
    }
    case DropKind::Hdri: {
        Environment env = m_controller->scene().environment;
        env.hdri = documentPath(path);
        // Its bright side behind the mesh (core/default_stage.h), in the same undo step.
        env.rotationDeg = hdriDefaultRotationDeg(env.hdri).value_or(env.rotationDeg);
        m_controller->editEnvironment(env, tr("HDRI %1").arg(QFileInfo(path).fileName()));
        m_log->info(tr("Environment: %1").arg(path));
        return true;
    }
    case DropKind::Mesh: {
        MeshRef mesh;
        mesh.kind = PreviewMeshKind::Custom;
        mesh.file = documentPath(path);
        if (!m_controller->editMesh(mesh))
            return false; // refused: said in the Log, the status bar and the Scene panel
        m_log->info(tr("Preview mesh: %1").arg(path));
        return true;
    }
    case DropKind::Interchange: {
        // The material, and a glTF's mesh as the preview mesh, as one undo step.
        QString error;
        if (importFile(this, *m_controller, path, m_log, /*withMesh=*/true, &error))
            return true;
        m_log->error(tr("Import failed: %1").arg(error));
        statusBar()->showMessage(tr("Could not import %1 (see the Log)").arg(path), 10000);
        return false;
    }
    case DropKind::None:
        break;
    }
    m_log->warning(tr("%1: not a scene, preset, HDRI, mesh or image; nothing done").arg(path));
    return false;
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    if (!event->mimeData()->hasUrls())
        return;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile() && dropKindOf(url.toLocalFile()) != DropKind::None) {
            event->acceptProposedAction();
            return;
        }
}

void MainWindow::dropEvent(QDropEvent* event) {
    if (!event->mimeData()->hasUrls())
        return;
    // A preset dropped on B's side of the A/B split becomes B (view state); anywhere else it is
    // applied to the document (one undo step), like a drag from the Library.
    const QPoint inViewport = m_viewport->mapFrom(this, event->position().toPoint());
    const bool onB =
        m_viewport->rect().contains(inViewport) && m_viewport->isOnSplitB(inViewport.x());
    bool handled = false;
    for (const QUrl& url : event->mimeData()->urls()) {
        if (!url.isLocalFile())
            continue;
        const QString path = url.toLocalFile();
        if (onB && dropKindOf(path) == DropKind::Document &&
            detectDocumentKind(path.toStdString()) == DocumentKind::Material)
            handled |= setAbSplitPreset(path);
        else
            handled |= openDroppedFile(path);
    }
    if (handled)
        event->acceptProposedAction();
}

} // namespace velvet::ui
