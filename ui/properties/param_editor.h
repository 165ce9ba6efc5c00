#pragma once
/// @file param_editor.h
/// One row of the property panel: the editing widgets of one parameter, built from its ParamMeta
/// (a material parameter, a post effect's parameter, or a graph node input described as one).
/// Editors only report what the artist did; the panel turns that into undo commands and pushes
/// document values back with setValue (which never re-emits edited()).

#include "core/material.h"

#include <QString>
#include <QWidget>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

class QDoubleSpinBox;
class QToolButton;

namespace velvet::ui {

class ParamEditor : public QWidget {
    Q_OBJECT
public:
    /// A key no other gesture has used (process-wide; the colour picker's gestures too).
    static int nextGestureKey();
    /// The editor for @p meta's type, named @p name ("param:lobes.base.roughness",
    /// "effectParam:intensity", "nodeInput:factor"); child widgets are "<name>/<part>".
    /// @p meta's strings and spans must outlive the editor (they are static tables).
    static ParamEditor* create(const ParamMeta& meta, const QString& name,
                               QWidget* parent = nullptr);
    /// A material parameter's editor, named "param:<id>".
    static ParamEditor* create(ParamId id, QWidget* parent = nullptr);

    const ParamMeta& meta() const { return m_meta; }
    /// Shows @p value (from the document). Emits nothing.
    virtual void setValue(glm::vec3 value) = 0;
    /// Vector editors show all four components; the others ignore w.
    virtual void setVector(glm::vec4 value) { setValue(glm::vec3(value)); }

signals:
    /// The artist changed the value. Edits with the same non-zero @p mergeKey belong to one
    /// gesture (a slider drag) and become one undo command. Vector editors fill w as well.
    void edited(glm::vec4 value, int mergeKey);
    /// The artist asked for the metadata default.
    void resetRequested();

protected:
    /// Sets the objectName, the tooltip and the reset context menu.
    ParamEditor(const ParamMeta& meta, const QString& name, QWidget* parent);
    /// A small reset button (objectName "<name>/reset") for the row's layout.
    QToolButton* makeResetButton();
    /// objectName for a child widget: "<name>/<part>".
    QString partName(const char* part) const;
    void emitEdited(glm::vec3 value, int mergeKey) {
        emit edited(glm::vec4(value, 0.0f), mergeKey);
    }

private:
    ParamMeta m_meta;
};

/// Values with 2 to 4 components that are not colours (a UV scale, an atlas rectangle, a colour
/// outside [0, 1]): one spin box per component, in the metadata's hard range.
class VectorParamEditor : public ParamEditor {
    Q_OBJECT
public:
    VectorParamEditor(const ParamMeta& meta, const QString& name, int components,
                      QWidget* parent = nullptr);
    void setValue(glm::vec3 value) override;
    void setVector(glm::vec4 value) override;
    int components() const { return m_count; }

private:
    QDoubleSpinBox* m_spins[4] = {};
    int m_count;
    glm::vec4 m_value{0.0f};
};

} // namespace velvet::ui
