#include "ui/scene/scene_choosers.h"

#include "core/default_stage.h"
#include "core/light_rigs.h"
#include "core/resources.h"
#include "core/scene.h"
#include "ui/document_controller.h"
#include "ui/hdri_thumbnail.h"

#include <QComboBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QSignalBlocker>
#include <QUndoStack>
#include <filesystem>

namespace velvet::ui {
namespace {

QString fromView(std::string_view text) {
    return QString::fromUtf8(text.data(), static_cast<qsizetype>(text.size()));
}

/// "rounded-cube" -> "Rounded cube".
QString prettyName(std::string_view name) {
    QString text = fromView(name).replace(QLatin1Char('-'), QLatin1Char(' '));
    if (!text.isEmpty())
        text[0] = text[0].toUpper();
    return text;
}

} // namespace

static_assert(kComboRoleAction == Qt::UserRole + 1);

QString normalPath(const QString& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path p(path.toStdString());
    const fs::path abs = fs::absolute(p, ec);
    return QString::fromStdString((ec ? p : abs).lexically_normal().generic_string());
}

void fillMeshCombo(QComboBox* combo, const Scene& scene) {
    const QSignalBlocker block(combo);
    combo->clear();
    const auto names = previewMeshKindNames();
    for (size_t i = 0; i < names.size(); ++i) {
        const auto kind = static_cast<PreviewMeshKind>(i);
        if (kind != PreviewMeshKind::Custom)
            combo->addItem(prettyName(names[i]), static_cast<int>(kind));
    }
    if (scene.mesh.kind == PreviewMeshKind::Custom)
        combo->addItem(QFileInfo(QString::fromStdString(scene.mesh.file)).fileName(),
                       static_cast<int>(PreviewMeshKind::Custom));
    combo->addItem(QObject::tr("Custom mesh…"), static_cast<int>(PreviewMeshKind::Custom));
    combo->setItemData(combo->count() - 1, true, kComboRoleAction);
    combo->setCurrentIndex(std::max(0, combo->findData(static_cast<int>(scene.mesh.kind))));
}

void fillHdriCombo(QComboBox* combo, const Scene& scene) {
    const QSignalBlocker block(combo);
    combo->clear();
    // Every shipped environment (resources/hdri, CC0) with a thumbnail of the panorama, so the
    // artist sees what a name lights the scene with before choosing it.
    combo->setIconSize(kHdriThumbnailSize);
    combo->addItem(QObject::tr("Uniform white"), QString());
    const QDir dir(QString::fromStdString(resources::path("hdri").string()));
    for (const QFileInfo& file : dir.entryInfoList(
             {QStringLiteral("*.exr"), QStringLiteral("*.hdr")}, QDir::Files, QDir::Name)) {
        const QString path = normalPath(file.absoluteFilePath());
        combo->addItem(hdriThumbnail(path), file.completeBaseName(), path);
        combo->setItemData(combo->count() - 1, path, Qt::ToolTipRole);
    }
    const QString current = scene.environment.hdri.empty()
                                ? QString()
                                : normalPath(QString::fromStdString(scene.environment.hdri));
    int index = combo->findData(current);
    if (index < 0) {
        combo->addItem(hdriThumbnail(current), QFileInfo(current).fileName(), current);
        combo->setItemData(combo->count() - 1, current, Qt::ToolTipRole);
        index = combo->count() - 1;
    }
    combo->addItem(QObject::tr("Other HDRI…"), QString());
    combo->setItemData(combo->count() - 1, true, kComboRoleAction);
    combo->setCurrentIndex(index);
}

void applyMeshChoice(DocumentController* controller, QComboBox* combo, int index,
                     QWidget* dialogParent) {
    MeshRef mesh;
    mesh.kind = static_cast<PreviewMeshKind>(combo->itemData(index).toInt());
    if (mesh.kind == PreviewMeshKind::Custom) {
        if (combo->itemData(index, kComboRoleAction).toBool()) {
            const QString file = QFileDialog::getOpenFileName(
                dialogParent, QObject::tr("Preview mesh"), QString(),
                QObject::tr("Meshes (*.obj *.fbx *.gltf *.glb *.ply *.stl *.dae)"));
            if (file.isEmpty()) {
                fillMeshCombo(combo, controller->scene());
                return;
            }
            mesh.file = normalPath(file).toStdString();
        } else {
            mesh.file = controller->scene().mesh.file;
        }
    }
    // The new mesh's stage (core/scene.h, applyStageDefaults: the drape and the shader ball on
    // a shadow-catching ground with occlusion) comes with it in one undo step, unless the artist
    // has set the ground or the occlusion by hand (they differ from the old mesh's defaults).
    const Scene& scene = controller->scene();
    Environment env = scene.environment;
    const bool followStage = mesh != scene.mesh && hasStageDefaults(env, scene.mesh.kind);
    applyStageDefaults(env, mesh.kind);
    if (followStage && env != scene.environment) {
        controller->undoStack()->beginMacro(QObject::tr("Preview mesh"));
        controller->editMesh(mesh);
        controller->editEnvironment(env, QObject::tr("Ground and occlusion"));
        controller->undoStack()->endMacro();
    } else {
        controller->editMesh(mesh);
    }
    fillMeshCombo(combo, controller->scene()); // a no-op choice sends no signal
}

void applyHdriChoice(DocumentController* controller, QComboBox* combo, int index,
                     QWidget* dialogParent) {
    Environment env = controller->scene().environment;
    QString path = combo->itemData(index).toString();
    if (combo->itemData(index, kComboRoleAction).toBool()) {
        path = QFileDialog::getOpenFileName(dialogParent, QObject::tr("Environment"), QString(),
                                            QObject::tr("HDR images (*.exr *.hdr)"));
        if (path.isEmpty()) {
            fillHdriCombo(combo, controller->scene());
            return;
        }
        path = normalPath(path);
    }
    env.hdri = path.toStdString();
    if (path.isEmpty())
        env.color = glm::vec3(1.0f);
    else // its bright side behind the mesh (core/default_stage.h), in the same undo step
        env.rotationDeg = hdriDefaultRotationDeg(env.hdri).value_or(env.rotationDeg);
    controller->editEnvironment(env, path.isEmpty()
                                         ? QObject::tr("Uniform white environment")
                                         : QObject::tr("HDRI %1").arg(QFileInfo(path).fileName()));
    fillHdriCombo(combo, controller->scene());
}

void fillLightRigCombo(QComboBox* combo, const Scene& scene) {
    const QSignalBlocker block(combo);
    combo->clear();
    for (const LightRig& rig : lightRigs()) {
        combo->addItem(fromView(rig.label), fromView(rig.id));
        combo->setItemData(combo->count() - 1, fromView(rig.description), Qt::ToolTipRole);
    }
    const auto match = matchingLightRig(scene.lights);
    if (match) {
        combo->setCurrentIndex(combo->findData(fromView(*match)));
    } else {
        combo->addItem(QObject::tr("Custom (%n light(s))", nullptr, int(scene.lights.size())),
                       QString());
        combo->setCurrentIndex(combo->count() - 1);
    }
}

void applyLightRigChoice(DocumentController* controller, QComboBox* combo, int index) {
    const QString id = combo->itemData(index).toString();
    if (const auto lights = lightRigLights(id.toStdString()))
        controller->editLights(*lights, QObject::tr("Light rig: %1").arg(combo->itemText(index)));
    fillLightRigCombo(combo, controller->scene());
}

} // namespace velvet::ui
