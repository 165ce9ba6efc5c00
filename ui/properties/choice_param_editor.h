#pragma once
/// @file choice_param_editor.h
/// A Choice parameter (a BRDF term): a combo box of the metadata's choice names.

#include "ui/properties/param_editor.h"

class QComboBox;

namespace velvet::ui {

class ChoiceParamEditor : public ParamEditor {
    Q_OBJECT
public:
    ChoiceParamEditor(const ParamMeta& meta, const QString& name, QWidget* parent = nullptr);
    void setValue(glm::vec3 value) override;

    QComboBox* comboBox() const { return m_combo; }

private:
    QComboBox* m_combo;
};

} // namespace velvet::ui
