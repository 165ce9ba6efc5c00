#pragma once
/// @file post_chain_panel.h
/// The Post chain panel (issue 5): the scene's effects in a list with enable check boxes, drag
/// to reorder (or Ctrl+Up / Ctrl+Down), add from a menu grouped by stage, remove (Delete),
/// duplicate (Ctrl+D), chain presets loaded and saved, stage conflicts explained inline (a
/// warning icon and tooltip on the offending row, the explanations under the list). The selected
/// effect's parameters are edited in the Properties panel (effectSelected; PropertyPanel builds
/// them from the effect's ParamMeta). Every change is a QUndoCommand
/// (ui/commands/post_chain_commands.h).

#include "core/post_chain.h"

#include <QListView>
#include <QString>
#include <QStringList>
#include <QWidget>
#include <memory>
#include <string>
#include <vector>

class QLabel;
class QMenu;
class QToolButton;

namespace velvet::ui {

class DocumentController;
class PostChainModel;

/// The effect list. Drops of its own rows become one MoveEffectCommand whatever the drag's
/// source (so a QDropEvent sent by a test takes the same path as a real drag); Ctrl+Up and
/// Ctrl+Down move the current effect, the keyboard alternative to dragging.
class PostChainListView : public QListView {
    Q_OBJECT
public:
    explicit PostChainListView(QWidget* parent = nullptr);
    /// The insert position (0..rows) a drop at viewport point @p pos means.
    int insertPositionAt(const QPoint& pos) const;

signals:
    /// Ctrl+Up / Ctrl+Down: move the current row by @p delta.
    void moveRequested(int delta);
    void removeRequested();
    void duplicateRequested();

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dragMoveEvent(QDragMoveEvent* event) override;
    void dropEvent(QDropEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
};

class PostChainPanel : public QWidget {
    Q_OBJECT
public:
    explicit PostChainPanel(DocumentController* controller, QWidget* parent = nullptr);
    ~PostChainPanel() override;

    PostChainListView* list() const { return m_list; }
    PostChainModel* model() const { return m_model; }
    /// The Add menu: one section per stage, one action per effect type (data: the type id).
    QMenu* addMenu() const { return m_addMenu; }
    /// The explanations of every stage conflict, under the list (hidden when there is none).
    QLabel* issueLabel() const { return m_issueLabel; }

    /// The selected row, or -1.
    int currentRow() const;
    void setCurrentRow(int row);

    /// Adds an effect of @p type where its stage belongs (after the effects of its stage or
    /// earlier ones; stage-free effects after the selection, else at the end). One command.
    bool addEffect(const QString& type);
    void removeCurrent();
    void duplicateCurrent();
    /// Moves the current effect by @p delta rows (one command) and keeps it selected.
    void moveCurrent(int delta);

    /// Replaces the chain with the preset in @p path (one command). On failure the chain is
    /// untouched and @p problems gets "file: path: message" lines.
    bool loadPreset(const QString& path, QStringList* problems);
    /// Saves the scene's chain as a preset named @p name. False + @p error on failure.
    bool savePreset(const QString& path, const QString& name, QString* error);

public slots:
    /// File dialog, then loadPreset; problems go to a message box and problemsReported.
    void loadPresetDialog();
    void savePresetDialog();

signals:
    /// Errors for the Log (a failed load or save), already formatted.
    void problemsReported(const QString& text);
    /// The artist selected (or clicked) the effect with id @p effect (EffectInstance::id); 0 when
    /// nothing is selected. The window shows that effect's parameters in Properties, which keeps
    /// following it by id through reorders.
    void effectSelected(velvet::EffectId effect);

private:
    /// The id of the effect on @p row, 0 for no row.
    EffectId effectAt(int row) const;
    void buildAddMenu();
    void updateActions();
    void updateIssues();
    DocumentController* m_controller;
    PostChainModel* m_model;
    PostChainListView* m_list;
    QMenu* m_addMenu = nullptr;
    QToolButton* m_addButton = nullptr;
    QToolButton* m_removeButton = nullptr;
    QToolButton* m_duplicateButton = nullptr;
    QToolButton* m_upButton = nullptr;
    QToolButton* m_downButton = nullptr;
    QLabel* m_issueLabel = nullptr;
};

} // namespace velvet::ui
