#include "ui/properties/choice_param_editor.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QSignalBlocker>
#include <QToolButton>
#include <cmath>

namespace velvet::ui {

ChoiceParamEditor::ChoiceParamEditor(const ParamMeta& spec, const QString& name, QWidget* parent)
    : ParamEditor(spec, name, parent), m_combo(new QComboBox(this)) {
    m_combo->setObjectName(partName("combo"));
    m_combo->setToolTip(QString::fromUtf8(meta().tooltip));
    for (std::string_view name : meta().choices)
        m_combo->addItem(QString::fromUtf8(name.data(), static_cast<qsizetype>(name.size())));

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(m_combo, 1);
    layout->addWidget(makeResetButton());

    connect(m_combo, &QComboBox::currentIndexChanged, this, [this](int index) {
        if (index >= 0)
            emitEdited(glm::vec3(static_cast<float>(index)), 0);
    });
    setValue(meta().defaultValue);
}

void ChoiceParamEditor::setValue(glm::vec3 value) {
    const QSignalBlocker block(m_combo);
    m_combo->setCurrentIndex(static_cast<int>(std::lround(value.x)));
}

} // namespace velvet::ui
