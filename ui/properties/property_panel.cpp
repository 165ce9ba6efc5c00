#include "ui/properties/property_panel.h"

#include "ui/document_controller.h"
#include "ui/properties/color_param_editor.h"
#include "ui/properties/param_editor.h"

#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QVBoxLayout>
#include <algorithm>
#include <map>
#include <vector>

namespace velvet::ui {

PropertyPanel::PropertyPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_controller(controller), m_editors(kParamCount, nullptr) {
    setObjectName(QStringLiteral("propertyPanel"));
    auto* layout = new QVBoxLayout(this);

    // Groups appear in the order their first parameter has in the metadata table.
    std::map<std::string_view, QFormLayout*> groups;
    std::vector<QLabel*> labels;
    for (int i = 0; i < kParamCount; ++i) {
        const auto id = static_cast<ParamId>(i);
        const ParamMeta& meta = paramMeta(id);
        QFormLayout*& form = groups[meta.group];
        if (!form) {
            const QString group = QString::fromUtf8(meta.group);
            auto* box = new QGroupBox(group, this);
            box->setObjectName(QStringLiteral("group:") + group);
            form = new QFormLayout(box);
            form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
            layout->addWidget(box);
        }
        ParamEditor* editor = ParamEditor::create(id, this);
        auto* label = new QLabel(QString::fromUtf8(meta.label), this);
        label->setToolTip(QString::fromUtf8(meta.tooltip));
        label->setBuddy(editor);
        form->addRow(label, editor);
        labels.push_back(label);
        m_editors[static_cast<size_t>(i)] = editor;

        connect(editor, &ParamEditor::edited, this, &PropertyPanel::onEdited);
        connect(editor, &ParamEditor::resetRequested, m_controller,
                &DocumentController::resetParam);
    }
    layout->addStretch(1);

    // One label column width for every group, so sliders line up from group to group.
    int labelWidth = 0;
    for (QLabel* label : labels)
        labelWidth = std::max(labelWidth, label->sizeHint().width());
    for (QLabel* label : labels)
        label->setMinimumWidth(labelWidth);

    connect(m_controller, &DocumentController::paramChanged, this, &PropertyPanel::refresh);
    connect(m_controller, &DocumentController::documentReplaced, this, &PropertyPanel::refreshAll);
    refreshAll();
}

void PropertyPanel::refresh(ParamId id) {
    const bool was = m_refreshing;
    m_refreshing = true;
    editor(id)->setValue(m_controller->param(id));
    m_refreshing = was;
}

void PropertyPanel::refreshAll() {
    for (int i = 0; i < kParamCount; ++i)
        refresh(static_cast<ParamId>(i));
}

void PropertyPanel::onEdited(ParamId id, glm::vec3 value, int mergeKey) {
    if (m_refreshing)
        return; // a value coming from the document, not from the artist
    m_controller->editParam(id, value, mergeKey);
}

void PropertyPanel::setPickerColorSpace(const PickerColorSpace& space) {
    for (ParamEditor* editor : m_editors)
        if (auto* color = qobject_cast<ColorParamEditor*>(editor))
            color->setColorSpace(space);
}

} // namespace velvet::ui
