#include "ui/commands/set_scene_command.h"
#include "ui/document_controller.h"
#include "ui/scene/scene_panel.h"
#include "ui/scene/scene_widgets.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QEvent>
#include <QFormLayout>
#include <QKeyEvent>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSignalBlocker>
#include <algorithm>
#include <functional>
#include <glm/geometric.hpp>

// The Scene dock's lights: the list (add, duplicate, remove, Delete) and the selected light's
// editor; the dock's frame is in scene_panel.cpp.

namespace velvet::ui {
namespace {

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
