#include "ui/scene/stage_group.h"

#include "core/color_management.h"
#include "core/scene.h"
#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QPushButton>
#include <QSignalBlocker>
#include <algorithm>
#include <functional>

namespace velvet::ui {
namespace {

QColor srgbSwatch(glm::vec3 linear) {
    return QColor::fromRgbF(linearToSrgb(std::clamp(linear.r, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.g, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.b, 0.0f, 1.0f)));
}

} // namespace

StageGroup::StageGroup(DocumentController* controller, QWidget* parent)
    : QGroupBox(tr("Ground and occlusion"), parent), m_controller(controller) {
    setObjectName(QStringLiteral("sceneStageGroup"));
    auto* form = new QFormLayout(this);
    m_ground = new QComboBox(this);
    m_ground->setObjectName(QStringLiteral("sceneGround"));
    m_ground->addItem(tr("Off"), int(GroundMode::Off));
    m_ground->addItem(tr("Shadow catcher"), int(GroundMode::ShadowCatcher));
    m_ground->addItem(tr("Plain"), int(GroundMode::Plain));
    m_ground->setToolTip(tr("A floor at the mesh's lowest point: a shadow catcher shows the "
                            "background darkened by shadows and occlusion; plain is a material "
                            "that fades into it"));
    form->addRow(tr("Ground"), m_ground);
    m_groundColor = new QPushButton(this);
    m_groundColor->setObjectName(QStringLiteral("sceneGroundColor"));
    form->addRow(tr("Ground colour"), m_groundColor);
    m_groundRoughness = new QDoubleSpinBox(this);
    m_groundRoughness->setObjectName(QStringLiteral("sceneGroundRoughness"));
    m_groundRoughness->setRange(0.0, 1.0);
    m_groundRoughness->setSingleStep(0.05);
    m_groundRoughness->setKeyboardTracking(false);
    m_groundRoughness->setToolTip(tr("Perceptual roughness of the plain ground"));
    form->addRow(tr("Ground roughness"), m_groundRoughness);
    m_occlusion = new QCheckBox(tr("Ambient occlusion"), this);
    m_occlusion->setObjectName(QStringLiteral("sceneAmbientOcclusion"));
    m_occlusion->setToolTip(tr("Screen-space ambient occlusion (GTAO) on the environment's "
                               "light, times the material's occlusion map"));
    form->addRow(m_occlusion);
    m_occlusionRadius = new QDoubleSpinBox(this);
    m_occlusionRadius->setObjectName(QStringLiteral("sceneOcclusionRadius"));
    m_occlusionRadius->setRange(0.01, 10.0);
    m_occlusionRadius->setSingleStep(0.05);
    m_occlusionRadius->setDecimals(2);
    m_occlusionRadius->setSuffix(tr(" m"));
    m_occlusionRadius->setKeyboardTracking(false);
    m_occlusionRadius->setToolTip(tr("How far the occlusion search reaches, in metres"));
    form->addRow(tr("Occlusion radius"), m_occlusionRadius);

    const auto edit = [this](const QString& text, const std::function<void(Environment&)>& change,
                             int mergeKey) {
        if (m_updating)
            return;
        Environment env = m_controller->scene().environment;
        change(env);
        m_controller->editEnvironment(env, text, mergeKey);
    };
    connect(m_ground, &QComboBox::activated, this, [this, edit](int index) {
        const auto mode = GroundMode(m_ground->itemData(index).toInt());
        edit(
            tr("Ground"), [mode](Environment& e) { e.ground = mode; }, 0);
    });
    connect(m_groundColor, &QPushButton::clicked, this, [this, edit] {
        const QColor picked = QColorDialog::getColor(
            srgbSwatch(m_controller->scene().environment.groundColor), this, tr("Ground colour"));
        if (!picked.isValid())
            return;
        const glm::vec3 c(srgbToLinear(float(picked.redF())), srgbToLinear(float(picked.greenF())),
                          srgbToLinear(float(picked.blueF())));
        edit(
            tr("Ground colour"), [c](Environment& e) { e.groundColor = c; }, 0);
    });
    connect(m_groundRoughness, &QDoubleSpinBox::valueChanged, this, [this, edit](double v) {
        edit(
            tr("Ground roughness"), [v](Environment& e) { e.groundRoughness = float(v); }, m_key);
    });
    connect(m_occlusion, &QCheckBox::toggled, this, [edit](bool on) {
        edit(
            on ? tr("Ambient occlusion on") : tr("Ambient occlusion off"),
            [on](Environment& e) { e.ambientOcclusion = on; }, 0);
    });
    connect(m_occlusionRadius, &QDoubleSpinBox::valueChanged, this, [this, edit](double v) {
        edit(
            tr("Occlusion radius"), [v](Environment& e) { e.occlusionRadius = float(v); }, m_key);
    });
    for (QDoubleSpinBox* spin : {m_groundRoughness, m_occlusionRadius})
        connect(spin, &QDoubleSpinBox::editingFinished, this,
                [this] { m_key = SetEnvironmentCommand::nextMergeKey(); });
    m_key = SetEnvironmentCommand::nextMergeKey();
    connect(m_controller, &DocumentController::sceneChanged, this, &StageGroup::refresh);
    refresh(ScenePart::All);
}

void StageGroup::refresh(ScenePart parts) {
    if (!touches(parts, ScenePart::Environment))
        return;
    const Environment& env = m_controller->scene().environment;
    m_updating = true;
    {
        const QSignalBlocker a(m_ground), b(m_groundRoughness), c(m_occlusion),
            d(m_occlusionRadius);
        m_ground->setCurrentIndex(std::max(0, m_ground->findData(int(env.ground))));
        m_groundRoughness->setValue(double(env.groundRoughness));
        m_occlusion->setChecked(env.ambientOcclusion);
        m_occlusionRadius->setValue(double(env.occlusionRadius));
    }
    m_groundColor->setStyleSheet(
        QStringLiteral("background-color: %1;").arg(srgbSwatch(env.groundColor).name()));
    const bool plain = env.ground == GroundMode::Plain;
    m_groundColor->setEnabled(plain);
    m_groundRoughness->setEnabled(plain);
    m_occlusionRadius->setEnabled(env.ambientOcclusion);
    m_updating = false;
}

} // namespace velvet::ui
