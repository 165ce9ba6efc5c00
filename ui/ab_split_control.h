#pragma once
/// @file ab_split_control.h
/// The viewport's A/B split as the artist drives it (issue 17, items 8 and 9): the toolbar's
/// "A/B" button, which names what B is ("A/B · B: gold"), its menu (B = a snapshot of A, A with
/// another BRDF term, B from a preset chosen in the Library's folder, swap sides), the swap
/// shortcut (X), and the split's state in the viewport (B's material and label). View state
/// only: nothing here is a document edit.

#include "core/material.h"

#include <QObject>
#include <QString>
#include <optional>

class QAction;
class QToolButton;
class QWidget;

namespace velvet::ui {

class DocumentController;
class LogPanel;
class ViewportWidget;

class AbSplitControl : public QObject {
    Q_OBJECT
public:
    /// @p window parents the button, the menu and the dialog, and carries the swap shortcut.
    AbSplitControl(QWidget* window, DocumentController* controller, ViewportWidget* viewport,
                   LogPanel* log);

    /// The toolbar button (the checkable action with the menu).
    QToolButton* button() const { return m_button; }
    /// The checkable A/B toggle.
    QAction* action() const { return m_action; }
    /// Swaps the sides (B left, A right); shortcut X.
    QAction* swapAction() const { return m_swap; }
    /// What B is, as the toolbar and B's label say it; empty while the split is off.
    QString description() const { return m_description; }
    /// The folder "B from preset…" opens: the shipped presets (the Library's folder).
    static QString presetFolder();

    /// On: B is @p b (a snapshot of the current material when unset), described as
    /// @p description; off: one material.
    void setSplit(bool on, std::optional<Material> b = std::nullopt,
                  const QString& description = {});
    /// B = the current material with BRDF term @p term set to @p choice.
    void setSplitTerm(ParamId term, int choice);
    /// B = the preset at @p path. False (and a Log line) when it could not be read.
    bool setSplitPreset(const QString& path);
    /// Asks for a preset in presetFolder(), then setSplitPreset.
    void choosePreset();

signals:
    /// A short message for the status bar.
    void status(const QString& text);

private:
    void showDescription();

    QWidget* m_window;
    DocumentController* m_controller;
    ViewportWidget* m_viewport;
    LogPanel* m_log;
    QAction* m_action = nullptr;
    QAction* m_swap = nullptr;
    QToolButton* m_button = nullptr;
    QString m_description;
};

} // namespace velvet::ui
