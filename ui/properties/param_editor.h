#pragma once
/// @file param_editor.h
/// One row of the property panel: the editing widgets of one material parameter, built from its
/// ParamMeta. Editors only report what the artist did; the panel turns that into undo commands
/// and pushes document values back with setValue (which never re-emits edited()).

#include "core/material.h"

#include <QWidget>
#include <glm/vec3.hpp>
#include <memory>

class QToolButton;

namespace velvet::ui {

class ParamEditor : public QWidget {
    Q_OBJECT
public:
    /// The editor for @p id's ParamMeta::type.
    static ParamEditor* create(ParamId id, QWidget* parent = nullptr);

    ParamId param() const { return m_param; }
    const ParamMeta& meta() const { return paramMeta(m_param); }
    /// Shows @p value (from the document). Emits nothing.
    virtual void setValue(glm::vec3 value) = 0;

signals:
    /// The artist changed the value. Edits with the same non-zero @p mergeKey belong to one
    /// gesture (a slider drag) and become one undo command.
    void edited(velvet::ParamId id, glm::vec3 value, int mergeKey);
    /// The artist asked for the metadata default.
    void resetRequested(velvet::ParamId id);

protected:
    /// Sets objectName "param:<id>", the tooltip and the reset context menu.
    ParamEditor(ParamId id, QWidget* parent);
    /// A small reset button (objectName "param:<id>/reset") for the row's layout.
    QToolButton* makeResetButton();
    /// objectName for a child widget: "param:<id>/<part>".
    QString partName(const char* part) const;
    /// A key no other gesture has used (process-wide).
    static int nextGestureKey();

private:
    ParamId m_param;
};

} // namespace velvet::ui
