#include "ui/scene/scene_panel.h"

#include "core/color_management.h"
#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"
#include "ui/scene/scene_choosers.h"
#include "ui/scene/stage_group.h"

#include <QCheckBox>
#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QMenu>
#include <QPushButton>
#include <QSignalBlocker>
#include <QToolButton>
#include <QVBoxLayout>
#include <functional>
#include <glm/geometric.hpp>

namespace velvet::ui {

/// Three spin boxes for a vector (position or direction); calls back on every change.
class Vec3Editor : public QWidget {
public:
    Vec3Editor(const QString& name, double range, QWidget* parent) : QWidget(parent) {
        setObjectName(name);
        auto* row = new QHBoxLayout(this);
        row->setContentsMargins(0, 0, 0, 0);
        const char* axes[] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i) {
            m_boxes[i] = new QDoubleSpinBox(this);
            m_boxes[i]->setObjectName(name + QLatin1Char('.') + QLatin1String(axes[i]));
            m_boxes[i]->setRange(-range, range);
            m_boxes[i]->setDecimals(2);
            m_boxes[i]->setSingleStep(0.1);
            m_boxes[i]->setPrefix(QLatin1String(axes[i]) + QLatin1Char(' '));
            m_boxes[i]->setKeyboardTracking(false); // a typed "2.5" is one value, not 2 then 25
            row->addWidget(m_boxes[i]);
            connect(m_boxes[i], &QDoubleSpinBox::valueChanged, this, [this, i](double v) {
                if (onChanged)
                    onChanged(i, float(v));
            });
            connect(m_boxes[i], &QDoubleSpinBox::editingFinished, this, [this] {
                if (onFinished)
                    onFinished();
            });
        }
    }
    glm::vec3 value() const {
        return {float(m_boxes[0]->value()), float(m_boxes[1]->value()), float(m_boxes[2]->value())};
    }
    void setValue(glm::vec3 v) {
        for (int i = 0; i < 3; ++i) {
            const QSignalBlocker block(m_boxes[i]);
            m_boxes[i]->setValue(double(v[i]));
        }
    }
    /// One component changed (@p axis 0..2): the others keep the light's own values (the boxes
    /// round to two decimals and clamp to their range).
    std::function<void(int axis, float value)> onChanged;
    std::function<void()> onFinished;

private:
    QDoubleSpinBox* m_boxes[3];
};

namespace {

QString typeLabel(LightType type) {
    switch (type) {
    case LightType::Directional:
        return QObject::tr("Directional");
    case LightType::Point:
        return QObject::tr("Point");
    case LightType::Spot:
        return QObject::tr("Spot");
    case LightType::Area:
        return QObject::tr("Area");
    case LightType::Ambient:
        return QObject::tr("Ambient");
    }
    return {};
}

/// The unit of Light::intensity for @p type (docs/units.md).
QString intensityUnit(LightType type) {
    switch (type) {
    case LightType::Directional:
        return QObject::tr(" lx");
    case LightType::Point:
    case LightType::Spot:
        return QObject::tr(" cd");
    case LightType::Area:
        return QObject::tr(" nt");
    case LightType::Ambient:
        return QObject::tr(" ×");
    }
    return {};
}

QColor swatchColor(glm::vec3 linear) {
    return QColor::fromRgbF(linearToSrgb(std::clamp(linear.r, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.g, 0.0f, 1.0f)),
                            linearToSrgb(std::clamp(linear.b, 0.0f, 1.0f)));
}

void showSwatch(QPushButton* button, glm::vec3 linear) {
    const QColor c = swatchColor(linear);
    button->setStyleSheet(QStringLiteral("background-color: %1;").arg(c.name()));
    button->setToolTip(QObject::tr("Linear Rec.709 %1, %2, %3 (shown sRGB encoded); click to pick")
                           .arg(double(linear.r), 0, 'f', 3)
                           .arg(double(linear.g), 0, 'f', 3)
                           .arg(double(linear.b), 0, 'f', 3));
}

/// Opens the colour dialog on @p linear; the picked sRGB colour as scene-linear, or nullopt.
std::optional<glm::vec3> pickLinearColor(QWidget* parent, glm::vec3 linear, const QString& title) {
    const QColor picked = QColorDialog::getColor(swatchColor(linear), parent, title);
    if (!picked.isValid())
        return std::nullopt;
    return glm::vec3(srgbToLinear(float(picked.redF())), srgbToLinear(float(picked.greenF())),
                     srgbToLinear(float(picked.blueF())));
}

QDoubleSpinBox* makeSpin(const QString& name, double min, double max, double step, int decimals,
                         const QString& tip, QWidget* parent) {
    auto* spin = new QDoubleSpinBox(parent);
    spin->setObjectName(name);
    spin->setRange(min, max);
    spin->setSingleStep(step);
    spin->setDecimals(decimals);
    spin->setToolTip(tip);
    // Edits on Return, focus loss, arrows and wheel, not per keystroke: a refresh between
    // keystrokes would rewrite the text being typed.
    spin->setKeyboardTracking(false);
    return spin;
}

/// A new light of @p type placed in front of the mesh, upper right, aimed at the origin.
Light newLight(LightType type, AreaShape shape) {
    Light light;
    light.type = type;
    light.shape = shape;
    light.position = {1.5f, 1.5f, 1.5f};
    light.direction = glm::normalize(-light.position);
    switch (type) {
    case LightType::Directional:
        light.intensity = 3.0f;
        break;
    case LightType::Point:
    case LightType::Spot:
        light.intensity = 10.0f;
        light.range = 10.0f;
        break;
    case LightType::Area:
        light.intensity = 2.0f;
        light.size = shape == AreaShape::Sphere ? glm::vec2(0.25f) : glm::vec2(1.0f, 0.6f);
        break;
    case LightType::Ambient:
        light.intensity = 0.1f;
        break;
    }
    return light;
}

} // namespace

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

void ScenePanel::buildLightEditor(QFormLayout* form) {
    m_name = new QLineEdit(m_editor);
    m_name->setObjectName(QStringLiteral("lightName"));
    form->addRow(tr("Name"), m_name);
    m_type = new QComboBox(m_editor);
    m_type->setObjectName(QStringLiteral("lightType"));
    for (int t = 0; t <= int(LightType::Ambient); ++t)
        m_type->addItem(typeLabel(LightType(t)), t);
    form->addRow(tr("Type"), m_type);
    m_shape = new QComboBox(m_editor);
    m_shape->setObjectName(QStringLiteral("lightShape"));
    m_shape->addItem(tr("Sphere"), int(AreaShape::Sphere));
    m_shape->addItem(tr("Rectangle"), int(AreaShape::Rectangle));
    form->addRow(tr("Shape"), m_shape);
    m_color = new QPushButton(m_editor);
    m_color->setObjectName(QStringLiteral("lightColor"));
    form->addRow(tr("Colour"), m_color);
    m_intensity = makeSpin(QStringLiteral("lightIntensity"), 0.0, 100000.0, 0.1, 3,
                           tr("Directional: lux; point and spot: candela; area: nits; ambient: a "
                              "multiplier of white (docs/units.md)"),
                           m_editor);
    form->addRow(tr("Intensity"), m_intensity);
    m_position = new Vec3Editor(QStringLiteral("lightPosition"), 1000.0, m_editor);
    form->addRow(tr("Position (m)"), m_position);
    m_direction = new Vec3Editor(QStringLiteral("lightDirection"), 1.0, m_editor);
    m_direction->setToolTip(tr("The way the light travels (normalised when drawn)"));
    form->addRow(tr("Direction"), m_direction);
    m_range =
        makeSpin(QStringLiteral("lightRange"), 0.01, 1000.0, 0.1, 2,
                 tr("Influence radius in metres: the light is exactly 0 from here on"), m_editor);
    form->addRow(tr("Range (m)"), m_range);
    m_inner = makeSpin(QStringLiteral("lightInnerCone"), 0.0, 89.0, 1.0, 1,
                       tr("Full intensity inside this half-angle"), m_editor);
    m_inner->setSuffix(tr("°"));
    form->addRow(tr("Inner cone"), m_inner);
    m_outer = makeSpin(QStringLiteral("lightOuterCone"), 0.1, 89.9, 1.0, 1,
                       tr("No light outside this half-angle"), m_editor);
    m_outer->setSuffix(tr("°"));
    form->addRow(tr("Outer cone"), m_outer);
    m_sizeX = makeSpin(QStringLiteral("lightSizeX"), 0.001, 100.0, 0.05, 3,
                       tr("Sphere: radius; rectangle: width (m)"), m_editor);
    form->addRow(tr("Radius / width"), m_sizeX);
    m_sizeY = makeSpin(QStringLiteral("lightSizeY"), 0.001, 100.0, 0.05, 3,
                       tr("Rectangle height (m)"), m_editor);
    form->addRow(tr("Height"), m_sizeY);
    m_castShadows = new QCheckBox(tr("Casts shadows"), m_editor);
    m_castShadows->setObjectName(QStringLiteral("lightCastShadows"));
    m_castShadows->setToolTip(tr("Shadows from the preview mesh (the %1 strongest such lights at "
                                 "the mesh cast them; docs/shadows.md)")
                                  .arg(4));
    form->addRow(m_castShadows);
    m_sourceSize = makeSpin(QStringLiteral("lightSourceSize"), 0.0, 20.0, 0.1, 2,
                            tr("The source's size for soft shadows: a directional light's angular "
                               "diameter, a point or spot light's radius"),
                            m_editor);
    form->addRow(tr("Source size"), m_sourceSize);

    // Every field edits a copy of the selected light; one gesture (typing, arrows, a wheel
    // session) is one command.
    // Spin-box gestures merge by m_lightKey; discrete edits (rename, type, shape, colour) are one
    // command each (key 0).
    const auto edit = [this](const QString& text, const std::function<void(Light&)>& change,
                             int mergeKey = 0) {
        if (m_updating || selectedLight() < 0)
            return;
        Light light = m_controller->scene().lights[size_t(selectedLight())];
        change(light);
        editSelected(light, text, mergeKey);
    };
    const auto gesture = [this, edit](const QString& text,
                                      const std::function<void(Light&)>& change) {
        edit(text, change, m_lightKey);
    };
    const auto nextGesture = [this] { m_lightKey = SetLightsCommand::nextMergeKey(); };
    connect(m_name, &QLineEdit::editingFinished, this, [this, edit] {
        edit(tr("Rename light"), [this](Light& l) { l.name = m_name->text().toStdString(); });
        m_name->setModified(false);
    });
    connect(m_type, &QComboBox::activated, this, [this, edit](int index) {
        edit(tr("Light type"),
             [this, index](Light& l) { l.type = LightType(m_type->itemData(index).toInt()); });
    });
    connect(m_shape, &QComboBox::activated, this, [this, edit](int index) {
        edit(tr("Area light shape"),
             [this, index](Light& l) { l.shape = AreaShape(m_shape->itemData(index).toInt()); });
    });
    connect(m_color, &QPushButton::clicked, this, [this, edit] {
        if (selectedLight() < 0)
            return;
        const glm::vec3 old = m_controller->scene().lights[size_t(selectedLight())].color;
        if (auto color = pickLinearColor(this, old, tr("Light colour")))
            edit(tr("Light colour"), [color](Light& l) { l.color = *color; });
    });
    const auto spinEdit = [this, gesture, nextGesture](QDoubleSpinBox* spin, const QString& text,
                                                       float Light::*field) {
        connect(spin, &QDoubleSpinBox::valueChanged, this, [gesture, text, field](double v) {
            gesture(text, [field, v](Light& l) { l.*field = float(v); });
        });
        connect(spin, &QDoubleSpinBox::editingFinished, this, nextGesture);
    };
    spinEdit(m_intensity, tr("Light intensity"), &Light::intensity);
    spinEdit(m_range, tr("Light range"), &Light::range);
    // The cones stay ordered (the loader refuses inner > outer): moving one past the other
    // pushes the other along.
    connect(m_inner, &QDoubleSpinBox::valueChanged, this, [gesture](double v) {
        gesture(tr("Spot inner cone"), [v](Light& l) {
            l.innerConeDeg = float(v);
            l.outerConeDeg = std::max(l.outerConeDeg, l.innerConeDeg);
        });
    });
    connect(m_outer, &QDoubleSpinBox::valueChanged, this, [gesture](double v) {
        gesture(tr("Spot outer cone"), [v](Light& l) {
            l.outerConeDeg = float(v);
            l.innerConeDeg = std::min(l.innerConeDeg, l.outerConeDeg);
        });
    });
    for (QDoubleSpinBox* spin : {m_inner, m_outer})
        connect(spin, &QDoubleSpinBox::editingFinished, this, nextGesture);
    connect(m_sizeX, &QDoubleSpinBox::valueChanged, this, [gesture](double v) {
        gesture(tr("Area light size"), [v](Light& l) { l.size.x = float(v); });
    });
    connect(m_sizeY, &QDoubleSpinBox::valueChanged, this, [gesture](double v) {
        gesture(tr("Area light size"), [v](Light& l) { l.size.y = float(v); });
    });
    for (QDoubleSpinBox* spin : {m_sizeX, m_sizeY})
        connect(spin, &QDoubleSpinBox::editingFinished, this, nextGesture);
    connect(m_castShadows, &QCheckBox::toggled, this, [edit](bool on) {
        edit(on ? tr("Light casts shadows") : tr("Light casts no shadows"),
             [on](Light& l) { l.castShadows = on; });
    });
    connect(m_sourceSize, &QDoubleSpinBox::valueChanged, this, [gesture](double v) {
        gesture(tr("Light source size"), [v](Light& l) {
            (l.type == LightType::Directional ? l.sourceAngleDeg : l.sourceRadius) = float(v);
        });
    });
    connect(m_sourceSize, &QDoubleSpinBox::editingFinished, this, nextGesture);
    m_position->onChanged = [gesture](int axis, float v) {
        gesture(tr("Move light"), [axis, v](Light& l) { l.position[axis] = v; });
    };
    m_direction->onChanged = [this, gesture](int axis, float v) {
        gesture(tr("Aim light"), [axis, v](Light& l) {
            glm::vec3 d = l.direction;
            d[axis] = v;
            if (glm::dot(d, d) > 1e-12f) // a zero direction aims nowhere (the loader refuses it)
                l.direction = d;
        });
        refreshLightEditor(); // a refused zero shows the kept direction again
    };
    m_position->onFinished = m_direction->onFinished = nextGesture;
    connect(m_lights, &QListWidget::currentRowChanged, this, nextGesture);
}

int ScenePanel::selectedLight() const {
    const int row = m_lights->currentRow();
    return row >= 0 && size_t(row) < m_controller->scene().lights.size() ? row : -1;
}

void ScenePanel::selectLight(int index) {
    m_lights->setCurrentRow(index);
}

void ScenePanel::addLight(LightType type, AreaShape shape) {
    std::vector<Light> lights = m_controller->scene().lights;
    Light light = newLight(type, shape);
    light.name =
        (typeLabel(type) + QLatin1Char(' ') + QString::number(lights.size() + 1)).toStdString();
    lights.push_back(light);
    m_controller->editLights(lights, tr("Add %1 light").arg(typeLabel(type).toLower()));
    selectLight(int(lights.size()) - 1);
}

void ScenePanel::duplicateSelectedLight() {
    const int index = selectedLight();
    if (index < 0)
        return;
    std::vector<Light> lights = m_controller->scene().lights;
    Light copy = lights[size_t(index)];
    copy.name += " copy";
    lights.insert(lights.begin() + index + 1, copy);
    m_controller->editLights(lights, tr("Duplicate light"));
    selectLight(index + 1);
}

void ScenePanel::removeSelectedLight() {
    const int index = selectedLight();
    if (index < 0)
        return;
    std::vector<Light> lights = m_controller->scene().lights;
    const QString name = QString::fromStdString(lights[size_t(index)].name);
    lights.erase(lights.begin() + index);
    m_controller->editLights(lights, tr("Remove light %1").arg(name));
    selectLight(std::min(index, int(lights.size()) - 1));
}

void ScenePanel::editSelected(const Light& light, const QString& text, int mergeKey) {
    std::vector<Light> lights = m_controller->scene().lights;
    lights[size_t(selectedLight())] = light;
    m_controller->editLights(lights, text, mergeKey);
}

void ScenePanel::editBackground(BackgroundMode mode, glm::vec3 color) {
    Environment env = m_controller->scene().environment;
    env.background = mode;
    env.backgroundColor = color;
    m_controller->editEnvironment(env, tr("Background"));
}

bool ScenePanel::eventFilter(QObject* watched, QEvent* event) {
    if (watched == m_lights && event->type() == QEvent::KeyPress) {
        const auto* key = static_cast<QKeyEvent*>(event);
        if (key->key() == Qt::Key_Delete || key->key() == Qt::Key_Backspace) {
            removeSelectedLight();
            return true;
        }
    }
    return QWidget::eventFilter(watched, event);
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

void ScenePanel::refreshLightList() {
    const Scene& scene = m_controller->scene();
    const int row = m_lights->currentRow();
    const QSignalBlocker block(m_lights);
    // Rebuild only when the rows differ (a value edit keeps the list and its selection).
    QStringList labels;
    for (const Light& light : scene.lights)
        labels << tr("%1 — %2").arg(QString::fromStdString(light.name), typeLabel(light.type));
    bool same = m_lights->count() == labels.size();
    for (int i = 0; same && i < labels.size(); ++i)
        same = m_lights->item(i)->text() == labels[i];
    if (!same) {
        m_lights->clear();
        m_lights->addItems(labels);
    }
    m_lights->setCurrentRow(
        std::min(std::max(row, labels.isEmpty() ? -1 : 0), int(labels.size()) - 1));
}

void ScenePanel::refreshLightEditor() {
    const int index = selectedLight();
    m_editor->setEnabled(index >= 0);
    m_duplicate->setEnabled(index >= 0);
    m_remove->setEnabled(index >= 0);
    if (index < 0) {
        m_shownLight = -1;
        return;
    }
    const Light& light = m_controller->scene().lights[size_t(index)];
    m_updating = true;
    {
        const QSignalBlocker a(m_name), b(m_type), c(m_shape), d(m_intensity), e(m_range),
            f(m_inner), g(m_outer), h(m_sizeX), i(m_sizeY), j(m_castShadows), k(m_sourceSize);
        // Keep what is being typed into the name of the light shown, never another light's.
        if (index != m_shownLight || !m_name->isModified())
            m_name->setText(QString::fromStdString(light.name)); // clears isModified()
        m_shownLight = index;
        m_type->setCurrentIndex(m_type->findData(int(light.type)));
        m_shape->setCurrentIndex(m_shape->findData(int(light.shape)));
        m_intensity->setSuffix(intensityUnit(light.type));
        m_intensity->setValue(double(light.intensity));
        m_range->setValue(double(light.range));
        m_inner->setValue(double(light.innerConeDeg));
        m_outer->setValue(double(light.outerConeDeg));
        m_sizeX->setValue(double(light.size.x));
        m_sizeY->setValue(double(light.size.y));
        m_castShadows->setChecked(light.castShadows);
        const bool directional = light.type == LightType::Directional;
        m_sourceSize->setSuffix(directional ? tr("°") : tr(" m"));
        m_sourceSize->setValue(double(directional ? light.sourceAngleDeg : light.sourceRadius));
    }
    m_position->setValue(light.position);
    m_direction->setValue(light.direction);
    showSwatch(m_color, light.color);

    // Show the fields the type uses (docs/units.md).
    const bool positioned =
        light.type != LightType::Directional && light.type != LightType::Ambient;
    const bool aimed = light.type == LightType::Directional || light.type == LightType::Spot ||
                       (light.type == LightType::Area && light.shape == AreaShape::Rectangle);
    m_editorForm->setRowVisible(m_shape, light.type == LightType::Area);
    m_editorForm->setRowVisible(m_position, positioned);
    m_editorForm->setRowVisible(m_direction, aimed);
    m_editorForm->setRowVisible(m_range, positioned);
    m_editorForm->setRowVisible(m_inner, light.type == LightType::Spot);
    m_editorForm->setRowVisible(m_outer, light.type == LightType::Spot);
    m_editorForm->setRowVisible(m_sizeX, light.type == LightType::Area);
    m_editorForm->setRowVisible(m_sizeY, light.type == LightType::Area &&
                                             light.shape == AreaShape::Rectangle);
    m_editorForm->setRowVisible(m_castShadows, light.type != LightType::Ambient);
    // Area lights' penumbra comes from their own size.
    m_editorForm->setRowVisible(m_sourceSize, light.type == LightType::Directional ||
                                                  light.type == LightType::Point ||
                                                  light.type == LightType::Spot);
    m_updating = false;
}

} // namespace velvet::ui
