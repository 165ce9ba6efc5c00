#include "ui/viewport_toolbar.h"

#include "core/color_management.h"
#include "core/resources.h"
#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"
#include "ui/scene/scene_choosers.h"
#include "ui/viewport_widget.h"

#include <QAction>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QSettings>
#include <QSignalBlocker>
#include <QSlider>
#include <QToolButton>
#include <cmath>
#include <filesystem>

namespace velvet::ui {
namespace {

using render::DebugView;

/// Keep in step with render::DebugView (renderer.h): one row per value, in enum order.
constexpr DebugViewEntry kDebugViews[] = {
    {DebugView::Final, "Final"},
    {DebugView::Albedo, "Albedo"},
    {DebugView::Normal, "Normal"},
    {DebugView::Depth, "Depth"},
    {DebugView::Roughness, "Roughness"},
    {DebugView::Metallic, "Metallic"},
    {DebugView::Position, "Position"},
    {DebugView::Specular, "Specular"},
    {DebugView::Clearcoat, "Clearcoat"},
    {DebugView::Sheen, "Sheen"},
    {DebugView::Occlusion, "Occlusion"},
    {DebugView::Emissive, "Emissive"},
    {DebugView::MaterialId, "Material ID"},
    {DebugView::LightsPerPixel, "Lights per pixel"},
    {DebugView::DiffuseOnly, "Diffuse only"},
    {DebugView::SpecularOnly, "Specular only"},
    {DebugView::BaseSpecular, "Base specular"},
    {DebugView::SheenOnly, "Sheen only"},
    {DebugView::ClearcoatOnly, "Clearcoat only"},
    {DebugView::Anisotropy, "Anisotropy"},
    {DebugView::SpecularOcclusion, "Specular occlusion"},
};

const char* const kDebugViewKey = "viewport/debugView";
const char* const kDisplayKey = "viewport/display";
const char* const kViewKey = "viewport/view";
const char* const kLookKey = "viewport/look";
const char* const kExposureKey = "viewport/exposureEv";
const char* const kOverlayKey = "viewport/timingOverlay";
const char* const kAntialiasKey = "viewport/progressiveAntialias";
const char* const kReducedKey = "viewport/reducedWhileMoving";

constexpr double kMaxExposure = 10.0;
constexpr int kExposureSliderSteps = 10; // slider units per EV

/// A checkable action of @p bar, checked or not, named for the tests and settings.
QAction* addToggle(QToolBar* bar, const QString& text, const QString& name, bool checked,
                   const QString& tip) {
    QAction* action = bar->addAction(text);
    action->setObjectName(name);
    action->setCheckable(true);
    action->setChecked(checked);
    action->setToolTip(tip);
    return action;
}

QComboBox* makeCombo(const QString& name, const QString& tip, QWidget* parent) {
    auto* combo = new QComboBox(parent);
    combo->setObjectName(name);
    combo->setToolTip(tip);
    combo->setSizeAdjustPolicy(QComboBox::AdjustToContents);
    return combo;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// ViewportToolbar

ViewportToolbar::ViewportToolbar(std::shared_ptr<const ColorManagement> colorManagement,
                                 QWidget* parent)
    : QToolBar(tr("View toolbar"), parent), m_colorManagement(std::move(colorManagement)) {
    setObjectName(QStringLiteral("viewportToolbar"));

    m_debugView = makeCombo(QStringLiteral("debugViewCombo"),
                            tr("What the viewport shows: the final image or one G-buffer or "
                               "lighting channel"),
                            this);
    for (const DebugViewEntry& entry : kDebugViews)
        m_debugView->addItem(tr(entry.label), static_cast<int>(entry.view));
    addWidget(m_debugView);
    addSeparator();

    m_display = makeCombo(QStringLiteral("displayCombo"),
                          tr("OpenColorIO display, or the built-in PBR Neutral tone mapper"), this);
    m_display->addItem(tr("Built-in (PBR Neutral)"), QString());
    const bool haveOcio = m_colorManagement && m_colorManagement->isLoaded();
    if (haveOcio)
        for (const std::string& display : m_colorManagement->displays())
            m_display->addItem(QString::fromStdString(display), QString::fromStdString(display));
    m_view = makeCombo(QStringLiteral("viewCombo"), tr("OpenColorIO view of the display"), this);
    m_look = makeCombo(QStringLiteral("lookCombo"), tr("OpenColorIO look"), this);
    addWidget(m_display);
    addWidget(m_view);
    addWidget(m_look);
    addSeparator();

    auto* evLabel = new QLabel(tr(" EV "), this);
    addWidget(evLabel);
    m_exposureSlider = new QSlider(Qt::Horizontal, this);
    m_exposureSlider->setObjectName(QStringLiteral("exposureSlider"));
    m_exposureSlider->setRange(int(-kMaxExposure * kExposureSliderSteps),
                               int(kMaxExposure * kExposureSliderSteps));
    m_exposureSlider->setMaximumWidth(100);
    m_exposureSlider->setToolTip(tr("Exposure in stops (scene-linear × 2^EV)"));
    addWidget(m_exposureSlider);
    m_exposure = new QDoubleSpinBox(this);
    m_exposure->setObjectName(QStringLiteral("exposureSpin"));
    m_exposure->setRange(-kMaxExposure, kMaxExposure);
    m_exposure->setSingleStep(0.1);
    m_exposure->setDecimals(1);
    m_exposure->setToolTip(m_exposureSlider->toolTip());
    addWidget(m_exposure);
    addSeparator();

    m_antialias = addToggle(
        this, tr("Refine"), QStringLiteral("progressiveAntialiasAction"), true,
        tr("Anti-alias the still view: once nothing changes, average %1 frames offset by a "
           "fraction of a pixel (smooth silhouettes, highlights and threads)")
            .arg(ViewportWidget::kProgressiveSamples));
    m_reduced = addToggle(
        this, tr("Half while moving"), QStringLiteral("reducedWhileMovingAction"), true,
        tr("Draw the view at half size while it moves (a drag, a slider) and at full size once it "
           "rests. Off: full size while moving too, the shadows and contact occlusion drawn "
           "coarser while the camera moves"));
    m_overlay = addToggle(this, tr("Timings"), QStringLiteral("timingOverlayAction"), false,
                          tr("Show per-pass GPU timings over the viewport"));

    fillViews();

    connect(m_debugView, &QComboBox::currentIndexChanged, this, &ViewportToolbar::onChanged);
    connect(m_display, &QComboBox::currentIndexChanged, this, [this] {
        fillViews();
        onChanged();
    });
    connect(m_view, &QComboBox::currentIndexChanged, this, &ViewportToolbar::onChanged);
    connect(m_look, &QComboBox::currentIndexChanged, this, &ViewportToolbar::onChanged);
    connect(m_exposure, &QDoubleSpinBox::valueChanged, this, [this](double ev) {
        const QSignalBlocker block(m_exposureSlider);
        m_exposureSlider->setValue(int(std::lround(ev * kExposureSliderSteps)));
        onChanged();
    });
    connect(m_exposureSlider, &QSlider::valueChanged, this, [this](int steps) {
        m_exposure->setValue(double(steps) / kExposureSliderSteps); // emits valueChanged
    });
    connect(m_antialias, &QAction::toggled, this, [this](bool on) {
        if (!m_updating) // restoreSettings(): nothing new to save
            saveSettings();
        emit progressiveAntialiasToggled(on);
    });
    connect(m_reduced, &QAction::toggled, this, [this](bool on) {
        if (!m_updating)
            saveSettings();
        emit reducedWhileMovingToggled(on);
    });
    connect(m_overlay, &QAction::toggled, this, [this](bool on) {
        if (!m_updating)
            saveSettings();
        emit timingOverlayToggled(on);
    });
}

std::span<const DebugViewEntry> ViewportToolbar::debugViews() {
    return kDebugViews;
}

void ViewportToolbar::fillViews() {
    const QSignalBlocker blockView(m_view);
    const QSignalBlocker blockLook(m_look);
    const QString previousView = m_view->currentText();
    const QString previousLook = m_look->currentData().toString();
    m_view->clear();
    m_look->clear();
    const std::string display = m_display->currentData().toString().toStdString();
    const bool builtIn = display.empty();
    m_view->setEnabled(!builtIn);
    m_look->setEnabled(!builtIn);
    m_look->addItem(tr("No look"), QString());
    if (builtIn) {
        m_view->addItem(tr("Built-in"));
        return;
    }
    for (const std::string& view : m_colorManagement->views(display))
        m_view->addItem(QString::fromStdString(view));
    for (const std::string& look : m_colorManagement->looks())
        m_look->addItem(QString::fromStdString(look), QString::fromStdString(look));
    // Switching display keeps the view and look where the new display has them.
    int index = m_view->findText(previousView);
    if (index < 0)
        index = m_view->findText(QString::fromStdString(m_colorManagement->defaultView(display)));
    m_view->setCurrentIndex(std::max(0, index));
    m_look->setCurrentIndex(std::max(0, m_look->findData(previousLook)));
}

void ViewportToolbar::onChanged() {
    if (m_updating)
        return;
    saveSettings();
    emit viewStateChanged();
}

render::FrameSettings ViewportToolbar::frameSettings() const {
    render::FrameSettings fs;
    fs.view = static_cast<DebugView>(m_debugView->currentData().toInt());
    fs.exposureEv = static_cast<float>(m_exposure->value());
    const QString display = m_display->currentData().toString();
    if (!display.isEmpty()) {
        fs.display = display.toStdString();
        fs.displayView = m_view->currentText().toStdString();
        fs.look = m_look->currentData().toString().toStdString();
    }
    return fs;
}

PickerColorSpace ViewportToolbar::pickerColorSpace() const {
    const render::FrameSettings fs = frameSettings();
    PickerColorSpace space;
    if (fs.usesColorManagement()) {
        space.colorManagement = m_colorManagement;
        space.display = DisplaySettings{fs.display, fs.displayView, fs.look, 0.0f};
    }
    return space;
}

bool ViewportToolbar::timingOverlay() const {
    return m_overlay->isChecked();
}

bool ViewportToolbar::progressiveAntialias() const {
    return m_antialias->isChecked();
}

bool ViewportToolbar::reducedWhileMoving() const {
    return m_reduced->isChecked();
}

void ViewportToolbar::restoreSettings() {
    QSettings settings;
    m_updating = true;
    const int debugIndex = m_debugView->findText(settings.value(kDebugViewKey).toString());
    m_debugView->setCurrentIndex(std::max(0, debugIndex));
    m_display->setCurrentIndex(
        std::max(0, m_display->findData(settings.value(kDisplayKey).toString())));
    fillViews();
    if (const int i = m_view->findText(settings.value(kViewKey).toString()); i >= 0)
        m_view->setCurrentIndex(i);
    if (const int i = m_look->findData(settings.value(kLookKey).toString()); i >= 0)
        m_look->setCurrentIndex(i);
    m_exposure->setValue(settings.value(kExposureKey, 0.0).toDouble());
    // Both read before either is set: each toggle saves the whole toolbar, which would write the
    // other's not yet restored state over the stored one.
    const bool overlay = settings.value(kOverlayKey, false).toBool();
    const bool antialias = settings.value(kAntialiasKey, true).toBool();
    const bool reduced = settings.value(kReducedKey, true).toBool();
    m_overlay->setChecked(overlay);
    m_antialias->setChecked(antialias);
    m_reduced->setChecked(reduced);
    m_updating = false;
    emit viewStateChanged();
}

void ViewportToolbar::saveSettings() const {
    QSettings settings;
    settings.setValue(kDebugViewKey, m_debugView->currentText());
    settings.setValue(kDisplayKey, m_display->currentData().toString());
    settings.setValue(kViewKey, m_view->isEnabled() ? m_view->currentText() : QString());
    settings.setValue(kLookKey, m_look->currentData().toString());
    settings.setValue(kExposureKey, m_exposure->value());
    settings.setValue(kOverlayKey, m_overlay->isChecked());
    settings.setValue(kAntialiasKey, m_antialias->isChecked());
    settings.setValue(kReducedKey, m_reduced->isChecked());
}

// ---------------------------------------------------------------------------------------------
// SceneToolbar

SceneToolbar::SceneToolbar(DocumentController* controller, QWidget* parent)
    : QToolBar(tr("Scene toolbar"), parent), m_controller(controller) {
    setObjectName(QStringLiteral("sceneToolbar"));

    m_mesh = makeCombo(QStringLiteral("meshCombo"), tr("Preview mesh"), this);
    addWidget(m_mesh);
    m_hdri =
        makeCombo(QStringLiteral("hdriCombo"), tr("Environment (HDRI) lighting the scene"), this);
    addWidget(m_hdri);

    addWidget(new QLabel(tr(" Intensity "), this));
    m_intensity = new QDoubleSpinBox(this);
    m_intensity->setObjectName(QStringLiteral("environmentIntensity"));
    m_intensity->setRange(0.0, 100.0);
    m_intensity->setSingleStep(0.1);
    m_intensity->setDecimals(2);
    m_intensity->setToolTip(tr("Multiplier on the environment's radiance"));
    addWidget(m_intensity);

    addWidget(new QLabel(tr(" Rotation "), this));
    m_rotation = new QSlider(Qt::Horizontal, this);
    m_rotation->setObjectName(QStringLiteral("environmentRotation"));
    m_rotation->setRange(0, 360);
    m_rotation->setMaximumWidth(120);
    m_rotation->setToolTip(tr("Environment rotation about +Y in degrees (also Shift + right drag "
                              "in the viewport)"));
    addWidget(m_rotation);

    addWidget(new QLabel(tr(" Lights "), this));
    m_lightRig = makeCombo(QStringLiteral("lightRigCombo"),
                           tr("Light rig: a set of lights to judge the material under (edit "
                              "single lights in the Scene panel)"),
                           this);
    addWidget(m_lightRig);

    m_ground = new QToolButton(this);
    m_ground->setObjectName(QStringLiteral("groundToggle"));
    m_ground->setText(tr("Ground"));
    m_ground->setCheckable(true);
    m_ground->setToolTip(tr("A shadow-catching ground under the mesh (its look and the ambient "
                            "occlusion: Scene panel)"));
    addWidget(m_ground);
    connect(m_ground, &QToolButton::toggled, this, [this](bool on) {
        if (m_updating)
            return;
        Environment env = m_controller->scene().environment;
        env.ground = on ? GroundMode::ShadowCatcher : GroundMode::Off;
        m_controller->editEnvironment(env, on ? tr("Ground on") : tr("Ground off"));
    });

    m_intensityKey = SetEnvironmentCommand::nextMergeKey();
    refresh(ScenePart::All);
    connect(m_lightRig, &QComboBox::activated, this,
            [this](int index) { applyLightRigChoice(m_controller, m_lightRig, index); });

    connect(m_mesh, &QComboBox::activated, this, &SceneToolbar::onMeshChosen);
    connect(m_hdri, &QComboBox::activated, this, &SceneToolbar::onHdriChosen);
    connect(m_intensity, &QDoubleSpinBox::valueChanged, this, [this](double value) {
        if (!m_updating)
            editEnvironment(tr("Environment intensity"), m_intensityKey, float(value),
                            m_controller->scene().environment.rotationDeg);
    });
    // One typing or arrow session is one command; the next starts a new one.
    connect(m_intensity, &QDoubleSpinBox::editingFinished, this,
            [this] { m_intensityKey = SetEnvironmentCommand::nextMergeKey(); });
    connect(m_rotation, &QSlider::sliderPressed, this,
            [this] { m_rotationKey = SetEnvironmentCommand::nextMergeKey(); });
    connect(m_rotation, &QSlider::valueChanged, this, [this](int degrees) {
        if (!m_updating)
            editEnvironment(tr("Rotate environment"),
                            m_rotation->isSliderDown() ? m_rotationKey : 0,
                            m_controller->scene().environment.intensity, float(degrees));
    });
    connect(m_controller, &DocumentController::sceneChanged, this, &SceneToolbar::refresh);
}

void SceneToolbar::refresh(ScenePart parts) {
    // Every material edit emits sceneChanged too: refill only for the parts shown here.
    if (!touches(parts, ScenePart::Mesh | ScenePart::Environment | ScenePart::Lights))
        return;
    const Scene& scene = m_controller->scene();
    m_updating = true;
    if (touches(parts, ScenePart::Mesh))
        fillMeshCombo(m_mesh, scene);
    if (touches(parts, ScenePart::Environment))
        fillHdriCombo(m_hdri, scene);
    {
        const QSignalBlocker block(m_intensity);
        m_intensity->setValue(scene.environment.intensity);
    }
    {
        const QSignalBlocker block(m_rotation);
        float degrees = std::fmod(scene.environment.rotationDeg, 360.0f);
        if (degrees < 0.0f)
            degrees += 360.0f;
        m_rotation->setValue(int(std::lround(degrees)));
    }
    if (touches(parts, ScenePart::Lights))
        fillLightRigCombo(m_lightRig, scene);
    {
        const QSignalBlocker block(m_ground);
        m_ground->setChecked(scene.environment.ground != GroundMode::Off);
    }
    m_updating = false;
}

void SceneToolbar::onMeshChosen(int index) {
    applyMeshChoice(m_controller, m_mesh, index, this);
}

void SceneToolbar::onHdriChosen(int index) {
    applyHdriChoice(m_controller, m_hdri, index, this);
}

void SceneToolbar::editEnvironment(const QString& text, int mergeKey, float intensity,
                                   float rotationDeg) {
    Environment env = m_controller->scene().environment;
    env.intensity = intensity;
    env.rotationDeg = rotationDeg;
    m_controller->editEnvironment(env, text, mergeKey);
}

} // namespace velvet::ui
