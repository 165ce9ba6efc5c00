#include "ui/properties/property_panel.h"

#include "core/graph/graph.h"
#include "core/post_effects.h"
#include "ui/document_controller.h"
#include "ui/models/graph_model.h"
#include "ui/properties/color_param_editor.h"
#include "ui/properties/graph_driven_rows.h"
#include "ui/properties/param_editor.h"
#include "ui/properties/texture_slot_editor.h"

#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QScrollArea>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QStackedWidget>
#include <QToolButton>
#include <QUndoStack>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <map>
#include <vector>

namespace velvet::ui {
namespace {

QString fromView(std::string_view s) {
    return QString::fromUtf8(s.data(), static_cast<qsizetype>(s.size()));
}

/// A node input described as a parameter, so it gets the same editors as material parameters.
ParamMeta inputMeta(const graph::InputSpec& in) {
    // A colour input in [0, 1] gets a swatch; everything else (vectors, HDR colours) sliders.
    if (in.type == graph::PortType::Color && in.min >= 0.0f && in.max <= 1.0f)
        return colorParam(in.name, in.label, "Node", in.min, in.max, glm::vec3(in.defaultValue),
                          in.tooltip);
    ParamMeta m = floatParam(in.name, in.label, "Node", in.min, in.max, in.defaultValue.x, in.unit,
                             in.tooltip, in.softMax);
    m.defaultValue = glm::vec3(in.defaultValue); // a vector input keeps every component
    return m;
}

/// Components an input's editor shows: 1 for a slider or a swatch, else one spin box each.
int editorComponents(const graph::InputSpec& in, const ParamMeta& meta) {
    if (meta.type == ParamType::Color || in.type == graph::PortType::Float)
        return 1;
    return graph::portTypeComponents(in.type);
}

/// The colour space names offered for image nodes ("" follows the config's file rules).
const QStringList& colorSpaceChoices() {
    static const QStringList names = {QString(), QStringLiteral("sRGB texture"),
                                      QStringLiteral("Linear Rec.709"), QStringLiteral("Raw")};
    return names;
}

} // namespace

PropertyPanel::PropertyPanel(DocumentController* controller, QWidget* parent)
    : QWidget(parent), m_controller(controller), m_editors(kParamCount, nullptr),
      m_textureEditors(kTextureSlotCount, nullptr) {
    setObjectName(QStringLiteral("propertyPanel"));
    auto* outer = new QVBoxLayout(this);

    // Header: what is shown, and the way back to the material.
    auto* header = new QHBoxLayout;
    m_title = new QLabel(this);
    m_title->setObjectName(QStringLiteral("propertiesTitle"));
    QFont bold = m_title->font();
    bold.setBold(true);
    m_title->setFont(bold);
    m_materialButton = new QToolButton(this);
    m_materialButton->setObjectName(QStringLiteral("propertiesMaterialButton"));
    m_materialButton->setText(tr("Material"));
    m_materialButton->setToolTip(tr("Show the material's parameters"));
    m_materialButton->setAutoRaise(true);
    connect(m_materialButton, &QToolButton::clicked, this, &PropertyPanel::showMaterial);
    header->addWidget(m_title, 1);
    header->addWidget(m_materialButton);
    outer->addLayout(header);

    m_stack = new QStackedWidget(this);
    outer->addWidget(m_stack);
    outer->addStretch(1);
    // A QStackedWidget is as large as its largest page: a node's three inputs would sit on top
    // of the material page's height (a screen of blank space, issue 17 item 1) and inherit its
    // minimum width (cut off under a scroll area without a horizontal bar). Only the page shown
    // counts (QStackedLayout ignores an Ignored page's size hints).
    connect(m_stack, &QStackedWidget::currentChanged, this, &PropertyPanel::fitStackToPage);
    m_materialPage = new QWidget(m_stack);
    m_materialPage->setObjectName(QStringLiteral("materialPage"));
    m_stack->addWidget(m_materialPage);
    auto* layout = new QVBoxLayout(m_materialPage);
    layout->setContentsMargins(0, 0, 0, 0);

    m_driven = new GraphDrivenRows(this);
    connect(m_driven, &GraphDrivenRows::nodeRequested, this, &PropertyPanel::graphNodeRequested);
    // Groups appear in the order their first parameter has in the metadata table.
    std::map<std::string_view, QFormLayout*> groups;
    std::vector<QLabel*> labels;
    for (int i = 0; i < kParamCount; ++i) {
        const auto id = static_cast<ParamId>(i);
        const ParamMeta& meta = paramMeta(id);
        QFormLayout*& form = groups[meta.group];
        if (!form) {
            const QString group = QString::fromUtf8(meta.group);
            auto* box = new QGroupBox(group, m_materialPage);
            box->setObjectName(QStringLiteral("group:") + group);
            form = new QFormLayout(box);
            form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
            layout->addWidget(box);
        }
        ParamEditor* editor = ParamEditor::create(id, m_materialPage);
        auto* label = new QLabel(QString::fromUtf8(meta.label), m_materialPage);
        label->setToolTip(QString::fromUtf8(meta.tooltip));
        label->setBuddy(editor);
        form->addRow(label, editor);
        m_driven->add(id, form, editor); // "Driven by <node>" under it while a graph feeds it
        labels.push_back(label);
        m_editors[static_cast<size_t>(i)] = editor;

        connect(editor, &ParamEditor::edited, this,
                [this, id](glm::vec4 value, int key) { onEdited(id, glm::vec3(value), key); });
        connect(editor, &ParamEditor::resetRequested, this,
                [this, id] { m_controller->resetParam(id); });
    }
    // The emissive colour's picker offers the emission's strength as its intensity (beyond 1).
    if (auto* emissive = qobject_cast<ColorParamEditor*>(editor(ParamId::EmissiveColor))) {
        emissive->setIntensity(paramMeta(ParamId::EmissiveStrength),
                               m_controller->param(ParamId::EmissiveStrength).x);
        connect(emissive, &ColorParamEditor::intensityEdited, this, [this](float v, int key) {
            if (!m_refreshing)
                m_controller->editParam(ParamId::EmissiveStrength, glm::vec3(v), key);
        });
        connect(m_controller, &DocumentController::paramChanged, emissive,
                [this, emissive](ParamId id) {
                    if (id == ParamId::EmissiveStrength)
                        emissive->setIntensityValue(m_controller->param(id).x);
                });
    }

    // Textures: one row per slot (thumbnail, file, Browse…, Clear, colour space; drops).
    {
        auto* box = new QGroupBox(tr("Textures"), m_materialPage);
        box->setObjectName(QStringLiteral("group:Textures"));
        auto* form = new QFormLayout(box);
        form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
        // Each slot's name above its row, the row the panel's full width: beside a label column
        // as wide as "Specular / roughness / metallic" the rows made the panel wider than its
        // dock, cutting every value box and reset button at the right (issue 17 item 2).
        form->setRowWrapPolicy(QFormLayout::WrapAllRows);
        for (const TextureSlotMeta& meta : textureSlotMetas()) {
            const auto slot = static_cast<TextureSlot>(&meta - textureSlotMetas().data());
            auto* row = new TextureSlotEditor(m_controller, slot, box);
            auto* label = new QLabel(fromView(meta.label), box);
            label->setToolTip(fromView(meta.tooltip));
            label->setBuddy(row);
            form->addRow(label, row);
            m_textureEditors[static_cast<size_t>(slot)] = row;
            connect(row, &TextureSlotEditor::message, this, &PropertyPanel::reportMessage);
        }
        layout->addWidget(box);
    }

    // One label column width for every parameter group, so sliders line up from group to group.
    int labelWidth = 0;
    for (QLabel* label : labels)
        labelWidth = std::max(labelWidth, label->sizeHint().width());
    for (QLabel* label : labels)
        label->setMinimumWidth(labelWidth);

    connect(m_controller, &DocumentController::paramChanged, this, &PropertyPanel::refresh);
    // Texture slots change through sceneChanged (edit, undo, redo, open); rows skip unchanged.
    connect(m_controller, &DocumentController::sceneChanged, this, [this](ScenePart parts) {
        if (touches(parts, ScenePart::Graph))
            m_driven->refresh(m_controller->material());
        if (!touches(parts, ScenePart::MaterialStructure))
            return;
        for (TextureSlotEditor* row : m_textureEditors)
            row->refresh();
    });
    connect(m_controller, &DocumentController::documentReplaced, this, [this] {
        refreshAll();
        showMaterial(); // the old document's effects and nodes are gone
    });
    connect(m_controller, &DocumentController::postChainChanged, this, [this] {
        if (m_subject != Subject::Effect)
            return;
        const int index = effectIndex();
        if (index < 0) // removed (or its addition undone)
            showMaterial();
        else if (m_controller->scene().post.effects[size_t(index)].type != m_effectType)
            showEffect(m_effectId);
        else
            refreshEffect(); // the title names the effect's position, which a move changes
    });
    refreshAll();
    setSubject(Subject::Material, tr("Material"));
}

QString PropertyPanel::title() const {
    return m_title->text();
}

ParamEditor* PropertyPanel::subjectEditor(const QString& id) const {
    const auto it = m_subjectEditors.find(id);
    return it == m_subjectEditors.end() ? nullptr : it->second;
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
    m_space = space;
    applyColorSpace(this);
    if (space.colorManagement)
        for (TextureSlotEditor* row : m_textureEditors)
            row->setColorManagement(space.colorManagement);
}

void PropertyPanel::reportMessage(const QString& text) {
    emit message(text); // the main window shows it in the status bar and the Log
}

void PropertyPanel::applyColorSpace(QWidget* root) {
    for (ColorParamEditor* color : root->findChildren<ColorParamEditor*>())
        color->setColorSpace(m_space);
}

void PropertyPanel::setSubject(Subject subject, const QString& title) {
    m_subject = subject;
    m_title->setText(title);
    m_materialButton->setVisible(subject != Subject::Material);
    m_stack->setCurrentWidget(subject == Subject::Material ? m_materialPage : m_subjectPage);
    fitStackToPage();
    // A new subject starts at its top, wherever the material page had been scrolled to.
    for (QWidget* w = parentWidget(); w; w = w->parentWidget())
        if (auto* area = qobject_cast<QScrollArea*>(w)) {
            area->verticalScrollBar()->setValue(0);
            break;
        }
    emit subjectChanged();
}

void PropertyPanel::fitStackToPage() {
    for (int i = 0; i < m_stack->count(); ++i) {
        QWidget* page = m_stack->widget(i);
        const auto policy =
            page == m_stack->currentWidget() ? QSizePolicy::Preferred : QSizePolicy::Ignored;
        page->setSizePolicy(policy, policy);
    }
    m_stack->updateGeometry();
}

QWidget* PropertyPanel::newSubjectPage(const QString& title, const QString& description) {
    if (m_subjectPage) {
        m_stack->removeWidget(m_subjectPage);
        m_subjectPage->hide();
        m_subjectPage->deleteLater();
    }
    m_subjectEditors.clear();
    m_subjectPage = new QWidget(m_stack);
    m_subjectPage->setObjectName(QStringLiteral("subjectPage"));
    auto* layout = new QVBoxLayout(m_subjectPage);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* text = new QLabel(description, m_subjectPage);
    text->setObjectName(QStringLiteral("subjectDescription"));
    text->setWordWrap(true);
    layout->addWidget(text);
    auto* box = new QGroupBox(title, m_subjectPage);
    box->setObjectName(QStringLiteral("subjectParameters"));
    auto* form = new QFormLayout(box);
    form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    layout->addWidget(box);
    m_stack->addWidget(m_subjectPage);
    return box;
}

void PropertyPanel::showMaterial() {
    if (m_graph)
        disconnect(m_graphConnection), disconnect(m_graphResetConnection);
    m_graph = nullptr;
    m_node = graph::kInvalidNodeId;
    m_effectId = 0;
    m_effectType.clear();
    if (m_subject != Subject::Material || m_title->text().isEmpty())
        setSubject(Subject::Material, tr("Material"));
}

// ---- Post effects -------------------------------------------------------------------------------

int PropertyPanel::effectIndex() const {
    return m_subject == Subject::Effect
               ? int(findEffectIndex(m_controller->scene().post, m_effectId))
               : -1;
}

void PropertyPanel::showEffect(EffectId effect) {
    const auto& effects = m_controller->scene().post.effects;
    const long index = effect ? findEffectIndex(m_controller->scene().post, effect) : -1;
    const EffectMeta* meta = index >= 0 ? findPostEffect(effects[size_t(index)].type) : nullptr;
    if (!meta) {
        showMaterial();
        return;
    }
    if (m_graph)
        disconnect(m_graphConnection), disconnect(m_graphResetConnection);
    m_graph = nullptr;
    m_node = graph::kInvalidNodeId;
    m_effectId = effect;
    m_effectType = effects[size_t(index)].type;
    const QString label = fromView(meta->label);
    QWidget* box =
        newSubjectPage(tr("%1 parameters").arg(label),
                       tr("%1 Stage: %2; reads %3.")
                           .arg(fromView(meta->description), fromView(postStageName(meta->stage)),
                                QString::fromStdString(describeReads(meta->reads))));
    auto* form = static_cast<QFormLayout*>(box->layout());
    for (const ParamMeta& p : meta->params) {
        const QString id = fromView(p.id);
        ParamEditor* editor = ParamEditor::create(p, QStringLiteral("effectParam:") + id, box);
        auto* labelWidget = new QLabel(fromView(p.label), box);
        labelWidget->setToolTip(fromView(p.tooltip));
        labelWidget->setBuddy(editor);
        form->addRow(labelWidget, editor);
        m_subjectEditors[id] = editor;
        const std::string stdId(p.id);
        connect(editor, &ParamEditor::edited, this, [this, stdId](glm::vec4 value, int key) {
            editEffectParam(stdId, value, key, false);
        });
        connect(editor, &ParamEditor::resetRequested, this,
                [this, stdId] { editEffectParam(stdId, glm::vec4(0.0f), 0, true); });
    }
    if (meta->params.empty())
        form->addRow(new QLabel(tr("This effect has no parameters."), box));
    applyColorSpace(m_subjectPage);
    setSubject(Subject::Effect, tr("%1 (post effect %2)").arg(label).arg(index + 1));
    refreshEffect();
}

void PropertyPanel::refreshEffect() {
    const int index = effectIndex();
    if (index < 0)
        return;
    const EffectInstance& effect = m_controller->scene().post.effects[size_t(index)];
    const EffectMeta* meta = findPostEffect(effect.type);
    if (!meta)
        return;
    m_title->setText(tr("%1 (post effect %2)").arg(fromView(meta->label)).arg(index + 1));
    const bool was = m_refreshing;
    m_refreshing = true;
    for (const ParamMeta& p : meta->params)
        if (ParamEditor* editor = subjectEditor(fromView(p.id)))
            editor->setValue(effectValue(effect, p));
    m_refreshing = was;
}

void PropertyPanel::editEffectParam(const std::string& id, glm::vec4 value, int mergeKey,
                                    bool reset) {
    // The controller applies core's value rules and builds the undo command.
    if (m_refreshing || m_subject != Subject::Effect)
        return;
    if (reset)
        m_controller->resetEffectParam(m_effectId, id);
    else
        m_controller->editEffectParam(m_effectId, id, glm::vec3(value), mergeKey);
}

// ---- Graph nodes --------------------------------------------------------------------------------

void PropertyPanel::showGraphNode(GraphModel* model, graph::NodeId id) {
    const graph::Node* node = model ? model->graph().node(id) : nullptr;
    if (!node) { // the graph's selection was cleared: only a shown node gives way
        if (m_subject == Subject::GraphNode)
            showMaterial();
        return;
    }
    if (node->type->isOutput) {
        showMaterial(); // the material output's inputs are the material's parameters
        return;
    }
    if (m_graph != model) {
        if (m_graph)
            disconnect(m_graphConnection), disconnect(m_graphResetConnection);
        m_graph = model;
        m_graphConnection =
            connect(model, &GraphModel::changed, this, &PropertyPanel::onGraphChanged);
        m_graphResetConnection = connect(model, &GraphModel::reset, this, [this] {
            if (m_subject == Subject::GraphNode)
                showGraphNode(m_graph, m_node);
        });
    }
    m_effectId = 0;
    m_effectType.clear();
    m_node = id;
    const graph::NodeType& type = *node->type;
    const QString label = fromView(type.label);
    QWidget* box = newSubjectPage(tr("%1 inputs").arg(label), fromView(type.tooltip));
    auto* form = static_cast<QFormLayout*>(box->layout());
    for (size_t i = 0; i < type.inputs.size(); ++i) {
        const graph::InputSpec& in = type.inputs[i];
        const QString name = fromView(in.name);
        auto* labelWidget = new QLabel(fromView(in.label), box);
        labelWidget->setToolTip(fromView(in.tooltip));
        if (in.fallback != graph::Fallback::Value) {
            auto* note = new QLabel(tr("the mesh's UVs unless a link feeds it"), box);
            note->setObjectName(QStringLiteral("nodeInput:") + name);
            note->setEnabled(false);
            form->addRow(labelWidget, note);
            continue;
        }
        const ParamMeta meta = inputMeta(in);
        const int components = editorComponents(in, meta);
        ParamEditor* editor =
            components == 1
                ? ParamEditor::create(meta, QStringLiteral("nodeInput:") + name, box)
                : new VectorParamEditor(meta, QStringLiteral("nodeInput:") + name, components, box);
        labelWidget->setBuddy(editor);
        form->addRow(labelWidget, editor);
        m_subjectEditors[name] = editor;
        const int input = int(i);
        connect(editor, &ParamEditor::edited, this, [this, input](glm::vec4 value, int key) {
            editNodeInput(input, value, key, false);
        });
        connect(editor, &ParamEditor::resetRequested, this,
                [this, input] { editNodeInput(input, glm::vec4(0.0f), 0, true); });
    }
    for (const graph::SettingSpec& s : type.settings) {
        const QString name = fromView(s.name);
        const std::string stdName(s.name);
        auto* labelWidget = new QLabel(fromView(s.label), box);
        labelWidget->setToolTip(fromView(s.tooltip));
        auto* field = new QWidget(box);
        auto* row = new QHBoxLayout(field);
        row->setContentsMargins(0, 0, 0, 0);
        if (s.name == "colorSpace") {
            auto* combo = new QComboBox(field);
            combo->setObjectName(QStringLiteral("nodeSetting:") + name);
            combo->setEditable(true);
            combo->addItems(colorSpaceChoices());
            combo->setItemText(0, QString());
            combo->setToolTip(fromView(s.tooltip));
            combo->lineEdit()->setPlaceholderText(tr("from the file rules"));
            row->addWidget(combo, 1);
            connect(combo, &QComboBox::activated, this,
                    [this, combo, stdName] { editNodeSetting(stdName, combo->currentText()); });
            connect(combo->lineEdit(), &QLineEdit::editingFinished, this,
                    [this, combo, stdName] { editNodeSetting(stdName, combo->currentText()); });
        } else {
            auto* edit = new QLineEdit(field);
            edit->setObjectName(QStringLiteral("nodeSetting:") + name);
            edit->setToolTip(fromView(s.tooltip));
            row->addWidget(edit, 1);
            connect(edit, &QLineEdit::editingFinished, this,
                    [this, edit, stdName] { editNodeSetting(stdName, edit->text()); });
            if (s.name == "file") {
                auto* browse = new QToolButton(field);
                browse->setObjectName(QStringLiteral("nodeSetting:") + name +
                                      QStringLiteral("/browse"));
                browse->setText(QStringLiteral("…"));
                browse->setToolTip(tr("Choose an image file"));
                row->addWidget(browse);
                connect(browse, &QToolButton::clicked, this, [this, edit, stdName] {
                    const QString path = QFileDialog::getOpenFileName(
                        this, tr("Image"), QFileInfo(edit->text()).absolutePath(),
                        tr("Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.hdr *.tga *.bmp)"));
                    if (!path.isEmpty())
                        editNodeSetting(stdName, path);
                });
            }
        }
        form->addRow(labelWidget, field);
    }
    applyColorSpace(m_subjectPage);
    refreshNode();
    setSubject(Subject::GraphNode, tr("%1 (node %2)").arg(label).arg(id));
}

void PropertyPanel::refreshNode() {
    const graph::Node* node = m_graph ? m_graph->graph().node(m_node) : nullptr;
    if (!node || !m_subjectPage)
        return;
    const bool was = m_refreshing;
    m_refreshing = true;
    const graph::NodeType& type = *node->type;
    for (size_t i = 0; i < type.inputs.size(); ++i) {
        ParamEditor* editor = subjectEditor(fromView(type.inputs[i].name));
        if (!editor)
            continue;
        editor->setVector(node->inputValues[i]);
        const graph::Connection* link = m_graph->graph().connectionTo(m_node, graph::PortIndex(i));
        const graph::Node* from = link ? m_graph->graph().node(link->outNode) : nullptr;
        editor->setEnabled(!link);
        editor->setToolTip(from ? tr("Fed by %1 (node %2): disconnect to edit the value")
                                      .arg(fromView(from->type->label))
                                      .arg(from->id)
                                : fromView(type.inputs[i].tooltip));
    }
    for (size_t i = 0; i < type.settings.size(); ++i) {
        const QString name = QStringLiteral("nodeSetting:") + fromView(type.settings[i].name);
        const QString value = QString::fromStdString(node->settings[i]);
        if (auto* edit = m_subjectPage->findChild<QLineEdit*>(name)) {
            const QSignalBlocker block(edit);
            edit->setText(value);
        } else if (auto* combo = m_subjectPage->findChild<QComboBox*>(name)) {
            const QSignalBlocker block(combo);
            combo->setCurrentText(value);
        }
    }
    m_refreshing = was;
}

void PropertyPanel::onGraphChanged(const graph::Change& change) {
    if (m_subject != Subject::GraphNode)
        return;
    using What = graph::Change::What;
    switch (change.what) {
    case What::NodeRemoved:
        if (change.node == m_node)
            showMaterial();
        break;
    case What::ValueSet:
    case What::SettingSet:
        if (change.node == m_node)
            refreshNode();
        break;
    case What::Connected:
    case What::Disconnected:
        if (change.connection.inNode == m_node)
            refreshNode();
        break;
    case What::NodeAdded:
    case What::Moved:
        break;
    }
}

void PropertyPanel::editNodeInput(int input, glm::vec4 value, int mergeKey, bool reset) {
    // The graph model applies core's value rules and builds the undo command.
    if (m_refreshing || m_subject != Subject::GraphNode || !m_graph || input < 0)
        return;
    m_graph->editNodeInput(m_node, graph::PortIndex(input), value, mergeKey, reset);
}

void PropertyPanel::editNodeSetting(const std::string& name, const QString& value) {
    if (m_refreshing || m_subject != Subject::GraphNode || !m_graph)
        return;
    m_graph->editNodeSetting(m_node, name, value.toStdString());
}

} // namespace velvet::ui
