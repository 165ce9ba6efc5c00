#pragma once
/// @file property_panel.h
/// The Properties panel. It shows one subject at a time, always generated from metadata:
/// - the material (paramMetas()): one group box per ParamMeta::group, one ParamEditor each,
///   then a "Textures" group with one TextureSlotEditor per slot (textureSlotMetas());
/// - the effect selected in the Post chain panel (its EffectMeta::params);
/// - the node selected in the Material graph (its type's inputs described as ParamMeta, and its
///   string settings: an image file, a colour space). Selecting the material output node, or the
///   "Material" button in the header, shows the material again.
/// The panel builds no command and applies no value rule itself: it asks the DocumentController
/// (material parameters, effects by id: editParam, editEffectParam) or the GraphModel (node
/// inputs and settings: editNodeInput, editNodeSetting) for each edit, which core's rules
/// constrain and which becomes one undo command (slider drags merge into one); document changes
/// (undo, redo, open) refresh the editors without creating commands.

#include "core/graph/graph_types.h"
#include "core/material.h"
#include "core/post_chain.h"
#include "ui/color_picking.h"

#include <QPointer>
#include <QString>
#include <QWidget>
#include <glm/vec4.hpp>
#include <map>
#include <string>
#include <vector>

class QLabel;
class QStackedWidget;
class QToolButton;

namespace velvet::graph {
struct Change;
}

namespace velvet::ui {

class DocumentController;
class GraphDrivenRows;
class GraphModel;
class ParamEditor;
class TextureSlotEditor;

class PropertyPanel : public QWidget {
    Q_OBJECT
public:
    enum class Subject { Material, Effect, GraphNode };

    PropertyPanel(DocumentController* controller, QWidget* parent = nullptr);

    /// The material page's editor of @p id (never null).
    ParamEditor* editor(ParamId id) const { return m_editors[static_cast<size_t>(id)]; }
    /// The material page's row of texture slot @p slot in the "Textures" group (never null).
    TextureSlotEditor* textureEditor(TextureSlot slot) const {
        return m_textureEditors[static_cast<size_t>(slot)];
    }
    /// The material page's "Driven by <node>" links (parameters a graph feeds).
    GraphDrivenRows* drivenRows() const { return m_driven; }
    /// How colour swatches and pickers show and pick values (the viewport's display / view).
    void setPickerColorSpace(const PickerColorSpace& space);

    Subject subject() const { return m_subject; }
    /// The id of the effect shown (EffectInstance::id), or 0.
    EffectId effectId() const { return m_subject == Subject::Effect ? m_effectId : 0; }
    /// Where the effect shown is in the scene's chain now (it follows the effect through
    /// reorders), or -1.
    int effectIndex() const;
    /// The graph node shown, or kInvalidNodeId.
    graph::NodeId graphNode() const {
        return m_subject == Subject::GraphNode ? m_node : graph::kInvalidNodeId;
    }
    /// The editor of effect parameter / node input @p id on the effect or node page, or null.
    /// Named "effectParam:<id>" and "nodeInput:<id>"; node settings are QLineEdit / QComboBox
    /// children named "nodeSetting:<id>".
    ParamEditor* subjectEditor(const QString& id) const;
    /// The header's title ("Material", "Bloom (post effect)", "Image texture (node 3)").
    QString title() const;

public slots:
    void showMaterial();
    /// Shows the parameters of the effect with id @p effect (0, or an id not in the scene's
    /// chain: the material). Edits go to that effect wherever it moves.
    void showEffect(velvet::EffectId effect);
    /// Shows node @p id of @p model. The material output shows the material; no node (the
    /// graph's selection was cleared) shows the material when a node was shown.
    void showGraphNode(velvet::ui::GraphModel* model, velvet::graph::NodeId id);

signals:
    /// The subject changed (the window raises the Properties dock).
    void subjectChanged();
    /// The artist clicked "Driven by <node>" under a material parameter: show node @p id.
    void graphNodeRequested(velvet::graph::NodeId id);
    /// A refused edit (e.g. a file that is not an image dropped onto a texture slot). Also shown
    /// in the window's status bar and Log.
    void message(const QString& text);

private:
    void refresh(ParamId id);
    void refreshAll();
    void onEdited(ParamId id, glm::vec3 value, int mergeKey);
    /// Replaces the subject page (the old one is deleted later: a signal of one of its editors
    /// may be what led here).
    QWidget* newSubjectPage(const QString& title, const QString& description);
    void setSubject(Subject subject, const QString& title);
    /// Only the page shown sizes the stack (see the constructor).
    void fitStackToPage();
    void applyColorSpace(QWidget* root);
    void reportMessage(const QString& text);

    void editEffectParam(const std::string& id, glm::vec4 value, int mergeKey, bool reset);
    void refreshEffect();
    void editNodeInput(int input, glm::vec4 value, int mergeKey, bool reset);
    void editNodeSetting(const std::string& name, const QString& value);
    void onGraphChanged(const graph::Change& change);
    void refreshNode();

    DocumentController* m_controller;
    std::vector<ParamEditor*> m_editors;              ///< material page, indexed by ParamId
    std::vector<TextureSlotEditor*> m_textureEditors; ///< material page, indexed by TextureSlot
    GraphDrivenRows* m_driven = nullptr;              ///< the material page's "driven by" links
    QLabel* m_title = nullptr;
    QToolButton* m_materialButton = nullptr;
    QStackedWidget* m_stack = nullptr;
    QWidget* m_materialPage = nullptr;
    QWidget* m_subjectPage = nullptr;
    std::map<QString, ParamEditor*> m_subjectEditors; ///< by effect parameter / node input id
    PickerColorSpace m_space;
    Subject m_subject = Subject::Material;
    EffectId m_effectId = 0;
    std::string m_effectType;
    QPointer<GraphModel> m_graph;
    graph::NodeId m_node = graph::kInvalidNodeId;
    QMetaObject::Connection m_graphConnection, m_graphResetConnection;
    bool m_refreshing = false; ///< set while document values flow into the editors
};

} // namespace velvet::ui
