#include "ui/scene/scene_panel.h"

#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"
#include "ui/scene/scene_choosers.h"
#include "ui/scene/scene_widgets.h"
#include "ui/scene/stage_group.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QMenu>
#include <QPushButton>
#include <QSignalBlocker>
#include <QToolButton>
#include <QVBoxLayout>
#include <cmath>

// The dock's frame, the mesh and environment group and the refresh; the lights' list and editor
// are in scene_light_editor.cpp.

namespace velvet::ui {

ScenePanel::ScenePanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_controller(controller) {
    setObjectName(QStringLiteral("scenePanel"));
    auto* layout = new QVBoxLayout(this);

    auto* envBox = new QGroupBox(tr("Mesh and environment"), this);
    auto* envForm = new QFormLayout(envBox);
    buildEnvironmentGroup(envForm);
    layout->addWidget(envBox);
    layout->addWidget(new StageGroup(m_controller, this));

    auto* lightsBox = new QGroupBox(tr("Lights"), this);
    auto* lightsLayout = new QVBoxLayout(lightsBox);
    auto* rigRow = new QHBoxLayout;
    rigRow->addWidget(new QLabel(tr("Rig"), lightsBox));
    m_rig = new QComboBox(lightsBox);
    m_rig->setObjectName(QStringLiteral("sceneLightRig"));
    m_rig->setToolTip(tr("Replace the lights with a rig (one undoable step)"));
    rigRow->addWidget(m_rig, 1);
    lightsLayout->addLayout(rigRow);

    m_lights = new QListWidget(lightsBox);
    m_lights->setObjectName(QStringLiteral("lightList"));
    m_lights->setToolTip(tr("The scene's lights; Delete removes the selected one"));
    m_lights->installEventFilter(this);
    lightsLayout->addWidget(m_lights, 1);

    auto* buttons = new QHBoxLayout;
    m_add = new QToolButton(lightsBox);
    m_add->setObjectName(QStringLiteral("addLightButton"));
    m_add->setText(tr("Add"));
    m_add->setPopupMode(QToolButton::InstantPopup);
    auto* addMenu = new QMenu(m_add);
    addMenu->setObjectName(QStringLiteral("addLightMenu"));
    const struct {
        LightType type;
        AreaShape shape;
        const char* label;
    } kinds[] = {{LightType::Directional, AreaShape::Sphere, "Directional"},
                 {LightType::Point, AreaShape::Sphere, "Point"},
                 {LightType::Spot, AreaShape::Sphere, "Spot"},
                 {LightType::Area, AreaShape::Sphere, "Area (sphere)"},
                 {LightType::Area, AreaShape::Rectangle, "Area (rectangle)"},
                 {LightType::Ambient, AreaShape::Sphere, "Ambient"}};
    for (const auto& kind : kinds)
        addMenu->addAction(tr(kind.label), this, [this, kind] { addLight(kind.type, kind.shape); });
    m_add->setMenu(addMenu);
    m_duplicate = new QPushButton(tr("Duplicate"), lightsBox);
    m_duplicate->setObjectName(QStringLiteral("duplicateLightButton"));
    m_remove = new QPushButton(tr("Remove"), lightsBox);
    m_remove->setObjectName(QStringLiteral("removeLightButton"));
    buttons->addWidget(m_add);
    buttons->addWidget(m_duplicate);
    buttons->addWidget(m_remove);
    buttons->addStretch(1);
    lightsLayout->addLayout(buttons);

    m_editor = new QWidget(lightsBox);
    m_editorForm = new QFormLayout(m_editor);
    m_editorForm->setContentsMargins(0, 0, 0, 0);
    buildLightEditor(m_editorForm);
    lightsLayout->addWidget(m_editor);
    layout->addWidget(lightsBox, 1);

    connect(m_rig, &QComboBox::activated, this,
            [this](int index) { applyLightRigChoice(m_controller, m_rig, index); });
    connect(m_lights, &QListWidget::currentRowChanged, this, &ScenePanel::refreshLightEditor);
    connect(m_duplicate, &QPushButton::clicked, this, &ScenePanel::duplicateSelectedLight);
    connect(m_remove, &QPushButton::clicked, this, &ScenePanel::removeSelectedLight);
    connect(m_controller, &DocumentController::sceneChanged, this, &ScenePanel::refresh);
    refresh(ScenePart::All);
}

void ScenePanel::buildEnvironmentGroup(QFormLayout* form) {
    m_mesh = new QComboBox(this);
    m_mesh->setObjectName(QStringLiteral("sceneMesh"));
    m_mesh->setToolTip(tr("Preview mesh (built-in, or a file through Assimp)"));
    form->addRow(tr("Mesh"), m_mesh);
    // A refused mesh file stays said here (and in the Log) until the mesh changes.
    m_meshError = new QLabel(this);
    m_meshError->setObjectName(QStringLiteral("sceneMeshError"));
    m_meshError->setWordWrap(true);
    m_meshError->setStyleSheet(QStringLiteral("color: #e07070"));
    m_meshError->hide();
    form->addRow(m_meshError);
    connect(m_controller, &DocumentController::meshRefused, m_meshError, [this](const QString& m) {
        m_meshError->setText(m);
        m_meshError->show();
    });
    m_hdri = new QComboBox(this);
    m_hdri->setObjectName(QStringLiteral("sceneHdri"));
    m_hdri->setToolTip(tr("Environment (HDRI) lighting the scene"));
    form->addRow(tr("HDRI"), m_hdri);
    m_envIntensity = makeSpin(QStringLiteral("sceneEnvironmentIntensity"), 0.0, 100.0, 0.1, 2,
                              tr("Multiplier on the environment's radiance"), this);
    form->addRow(tr("Intensity"), m_envIntensity);
    m_envRotation =
        makeSpin(QStringLiteral("sceneEnvironmentRotation"), 0.0, 360.0, 5.0, 1,
                 tr("Rotation about +Y (also Shift + right drag in the viewport)"), this);
    m_envRotation->setSuffix(tr("°"));
    m_envRotation->setWrapping(true);
    form->addRow(tr("Rotation"), m_envRotation);
    m_background = new QComboBox(this);
    m_background->setObjectName(QStringLiteral("sceneBackground"));
    m_background->addItem(tr("Sharp HDRI"), int(BackgroundMode::Sharp));
    m_background->addItem(tr("Blurred HDRI"), int(BackgroundMode::Blurred));
    m_background->addItem(tr("Solid colour"), int(BackgroundMode::SolidColor));
    m_background->addItem(tr("Procedural (FBM)"), int(BackgroundMode::ProceduralFbm));
    m_background->setToolTip(tr("What is seen behind the mesh (the lighting is unchanged)"));
    form->addRow(tr("Background"), m_background);
    m_backgroundColor = new QPushButton(this);
    m_backgroundColor->setObjectName(QStringLiteral("sceneBackgroundColor"));
    form->addRow(tr("Background colour"), m_backgroundColor);

    connect(m_mesh, &QComboBox::activated, this,
            [this](int index) { applyMeshChoice(m_controller, m_mesh, index, this); });
    connect(m_hdri, &QComboBox::activated, this,
            [this](int index) { applyHdriChoice(m_controller, m_hdri, index, this); });
    // Each box changes its own field only (the other keeps the scene's exact value).
    connect(m_envIntensity, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (m_updating)
            return;
        Environment env = m_controller->scene().environment;
        env.intensity = float(v);
        m_controller->editEnvironment(env, tr("Environment intensity"), m_envKey);
    });
    connect(m_envRotation, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (m_updating)
            return;
        Environment env = m_controller->scene().environment;
        env.rotationDeg = float(v);
        m_controller->editEnvironment(env, tr("Rotate environment"), m_envKey);
    });
    for (QDoubleSpinBox* spin : {m_envIntensity, m_envRotation})
        connect(spin, &QDoubleSpinBox::editingFinished, this,
                [this] { m_envKey = SetEnvironmentCommand::nextMergeKey(); });
    connect(m_background, &QComboBox::activated, this, [this](int index) {
        editBackground(BackgroundMode(m_background->itemData(index).toInt()),
                       m_controller->scene().environment.backgroundColor);
    });
    connect(m_backgroundColor, &QPushButton::clicked, this, [this] {
        const Environment& env = m_controller->scene().environment;
        if (auto color = pickLinearColor(this, env.backgroundColor, tr("Background colour")))
            editBackground(BackgroundMode::SolidColor, *color);
    });
    m_envKey = SetEnvironmentCommand::nextMergeKey();
}

void ScenePanel::editBackground(BackgroundMode mode, glm::vec3 color) {
    Environment env = m_controller->scene().environment;
    env.background = mode;
    env.backgroundColor = color;
    m_controller->editEnvironment(env, tr("Background"));
}

void ScenePanel::refresh(ScenePart parts) {
    // sceneChanged comes with every material edit too (each slider tick): only the parts this
    // dock shows refill anything.
    if (!touches(parts, ScenePart::Mesh | ScenePart::Environment | ScenePart::Lights))
        return;
    const Scene& scene = m_controller->scene();
    m_updating = true;
    if (touches(parts, ScenePart::Mesh)) {
        fillMeshCombo(m_mesh, scene);
        m_meshError->hide();
    }
    if (touches(parts, ScenePart::Environment))
        fillHdriCombo(m_hdri, scene);
    if (touches(parts, ScenePart::Lights))
        fillLightRigCombo(m_rig, scene);
    {
        const QSignalBlocker a(m_envIntensity), b(m_envRotation), c(m_background);
        m_envIntensity->setValue(double(scene.environment.intensity));
        float degrees = std::fmod(scene.environment.rotationDeg, 360.0f);
        m_envRotation->setValue(double(degrees < 0.0f ? degrees + 360.0f : degrees));
        m_background->setCurrentIndex(
            std::max(0, m_background->findData(int(scene.environment.background))));
    }
    showSwatch(m_backgroundColor, scene.environment.backgroundColor);
    m_backgroundColor->setEnabled(scene.environment.background == BackgroundMode::SolidColor);
    refreshLightList();
    m_updating = false;
    refreshLightEditor();
}

} // namespace velvet::ui
