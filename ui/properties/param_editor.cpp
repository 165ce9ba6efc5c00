#include "ui/properties/param_editor.h"

#include "ui/properties/choice_param_editor.h"
#include "ui/properties/color_param_editor.h"
#include "ui/properties/float_param_editor.h"

#include <QAction>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QSignalBlocker>
#include <QToolButton>
#include <algorithm>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

} // namespace

ParamEditor* ParamEditor::create(const ParamMeta& meta, const QString& name, QWidget* parent) {
    switch (meta.type) {
    case ParamType::Float:
        return new FloatParamEditor(meta, name, parent);
    case ParamType::Color:
        return new ColorParamEditor(meta, name, parent);
    case ParamType::Choice:
        return new ChoiceParamEditor(meta, name, parent);
    }
    return nullptr;
}

ParamEditor* ParamEditor::create(ParamId id, QWidget* parent) {
    const ParamMeta& meta = paramMeta(id);
    return create(meta, QStringLiteral("param:") + fromView(meta.id), parent);
}

ParamEditor::ParamEditor(const ParamMeta& meta, const QString& name, QWidget* parent)
    : QWidget(parent), m_meta(meta) {
    setObjectName(name);
    setToolTip(fromView(m_meta.tooltip));
    auto* reset = new QAction(tr("Reset %1").arg(fromView(m_meta.label)), this);
    connect(reset, &QAction::triggered, this, [this] { emit resetRequested(); });
    addAction(reset);
    setContextMenuPolicy(Qt::ActionsContextMenu);
}

QToolButton* ParamEditor::makeResetButton() {
    auto* button = new QToolButton(this);
    button->setObjectName(partName("reset"));
    button->setText(QStringLiteral("\u21ba"));
    button->setAutoRaise(true);
    button->setFocusPolicy(Qt::NoFocus);
    button->setToolTip(tr("Reset to the default"));
    connect(button, &QToolButton::clicked, this, [this] { emit resetRequested(); });
    return button;
}

QString ParamEditor::partName(const char* part) const {
    return objectName() + QLatin1Char('/') + QLatin1String(part);
}

int ParamEditor::nextGestureKey() {
    static int last = 0;
    return ++last;
}

VectorParamEditor::VectorParamEditor(const ParamMeta& meta, const QString& name, int components,
                                     QWidget* parent)
    : ParamEditor(meta, name, parent), m_count(std::clamp(components, 1, 4)) {
    static const char* const kParts[4] = {"x", "y", "z", "w"};
    const QString tip = fromView(meta.tooltip);
    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    for (int i = 0; i < m_count; ++i) {
        auto* spin = new QDoubleSpinBox(this);
        spin->setObjectName(partName(kParts[i]));
        spin->setRange(meta.min, meta.max);
        spin->setDecimals(3);
        const float end = meta.softMax != 0.0f && meta.softMax > meta.min && meta.softMax < meta.max
                              ? meta.softMax
                              : meta.max;
        spin->setSingleStep(
            std::min(1.0, (double(end) - std::max(double(meta.min), -1.0)) / 100.0));
        spin->setKeyboardTracking(false); // typed text commits on Enter or focus out: one command
        spin->setToolTip(tip);
        if (!meta.unit.empty())
            spin->setSuffix(QLatin1Char(' ') + fromView(meta.unit));
        layout->addWidget(spin, 1);
        m_spins[i] = spin;
        connect(spin, &QDoubleSpinBox::valueChanged, this, [this, i](double v) {
            glm::vec4 next = m_value;
            next[i] = static_cast<float>(v);
            emit edited(next, 0);
        });
    }
    layout->addWidget(makeResetButton());
    setVector(glm::vec4(meta.defaultValue, 0.0f));
}

void VectorParamEditor::setValue(glm::vec3 value) {
    setVector(glm::vec4(value, m_value.w));
}

void VectorParamEditor::setVector(glm::vec4 value) {
    m_value = value;
    for (int i = 0; i < m_count; ++i) {
        const QSignalBlocker block(m_spins[i]);
        m_spins[i]->setValue(value[i]);
    }
}

} // namespace velvet::ui
